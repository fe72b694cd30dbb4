//! Differential tests against Python xacro (generated goldens).
