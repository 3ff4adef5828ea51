//! Scene files (JSON).
