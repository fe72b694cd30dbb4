//! The assets stage: every link's geometry turned, once, into what the analyses need (ground-contact
//! supports; meshes read and reduced to their convex hull through the shared mesh cache).

pub mod supports;
