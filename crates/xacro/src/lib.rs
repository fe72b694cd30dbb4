//! Native xacro expander: xacro 2.x (in-order processing) without Python, without code execution, with the
//! source location of every output element and attribute.

pub mod expr;
