//! topomesh: connected, orientable 2-manifold polygon meshes of any genus,
//! the high-genus modeling operators, and subdivision schemes.
//!
//! The core (everything but `python`) has no Python dependency; the PyO3
//! bindings are compiled only with the `python` cargo feature.

pub mod budget;
pub mod cancel;
pub mod error;
pub mod geometry;
pub mod io;
pub mod ifs;
pub mod mesh;
pub mod ops;
pub mod primitives;
pub mod repair;
pub mod schemes;
mod union_find;
#[cfg(test)]
mod test_rng;

#[cfg(feature = "python")]
mod python;

pub use error::{MeshError, Result};
pub use mesh::{Corner, EdgeId, FaceId, FaceStart, HalfedgeId, Mesh, PolygonFaces, VertexId};
pub use mesh::BuildOptions;
