//! The GOAL agent: mental state, conditions, modules, rules, actions and the reasoning cycle.
