//! The space beam element: section stiffness, co-rotational kinematics, finite rotations.

pub mod beam;
pub mod corotational;
pub mod rotation;
