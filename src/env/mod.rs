//! The environment interface: entities, typed percepts, actions and their results.
