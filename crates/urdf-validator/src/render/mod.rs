//! Views of a [`crate::report::Report`]: each renderer reads the report and nothing else.

pub mod html;
pub mod text;

pub use text::{render_text, TextOptions};
