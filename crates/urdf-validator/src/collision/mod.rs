//! Self-collision with real geometry (work in progress: see issue 5).
