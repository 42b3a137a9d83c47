//! Contact between string and wall: the spatial multi-directional gap element with friction.

pub mod gap;
