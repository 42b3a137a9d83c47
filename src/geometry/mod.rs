//! Well geometry: survey stations, minimum curvature, the borehole frame and hole size.

pub mod frame;
pub mod hole;
pub mod min_curvature;
pub mod survey;

pub use frame::{Frame, Vec3};
pub use hole::{HoleSection, HoleSize};
pub use min_curvature::{AxisPoint, WellPath};
pub use survey::{Station, Survey};
