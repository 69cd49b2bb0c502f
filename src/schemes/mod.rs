//! Schemes: one file each. Every scheme is a free function taking a `&Mesh`
//! and returning a new `Mesh`; the mesh structure knows nothing about them.
pub mod sierpinski;
pub mod menger_sponge;
pub mod menger;
