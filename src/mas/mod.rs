//! Multi-agent systems: the `.mas2g` model, launch policies, the scheduler, message routing, traces.
