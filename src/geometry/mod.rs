//! Geometry on a mesh's connectivity: the one triangulation every export,
//! peer check and scheme uses.

pub mod triangulate;

pub use triangulate::Triangulation;
