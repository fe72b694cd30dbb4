//! The parse stage: URDF XML → a typed [`Robot`] that keeps the span of every value, plus parse findings.

pub mod parse;
pub mod robot;

pub use parse::parse_urdf;
pub use robot::Robot;
