//! Schemes: one file each. Every scheme is a free function taking a `&Mesh`
//! and returning a new `Mesh`; the mesh structure knows nothing about them.

pub mod honeycomb;
pub mod vertex_truncation;
pub(crate) mod hosts;
mod primal_columns;
mod primal_uniform;
pub(crate) mod face_vertex_columns;
mod fan_columns;
#[cfg(test)]
mod twin_reference;
pub(crate) mod corner_origins;
pub mod corner_transfer;
pub mod creases;
pub mod face_varying;
pub mod corner_linear;
pub mod corner_direct;
pub mod level;
pub mod limit;
pub mod stencil;
pub mod catmull_clark;
pub mod doo_sabin;
pub mod dual;
mod dual_in_place;
mod dual_open;
#[cfg(test)]
mod dual_open_reference;
pub(crate) mod dual_walk;
pub mod loop_subdivision;
pub mod midpoint;
pub mod simplest;
pub mod sqrt3;
pub mod sierpinski;
pub mod menger_sponge;
pub mod menger;
pub mod menger_level;
pub mod conway;
pub mod topmod;
pub(crate) mod keyed;
pub mod face_parents;
#[cfg(test)]
mod output_hashes;
