//! Geometry shared by several schemes, operators and exports: one
//! implementation each, called by all of them. The triangulation every
//! export, peer check and crossing check uses; the exact crossing checks.

pub mod crossing;
pub mod triangulate;

pub use triangulate::Triangulation;

use crate::mesh::Mesh;
use glam::DVec3;

/// The mesh's triangulation and the positions its triangles index: the
/// vertices, then the points the triangulation adds (owned by no vertex).
pub fn triangles_with_points(m: &Mesh) -> (Vec<[u32; 3]>, Vec<DVec3>) {
    let t = m.triangulate();
    let mut p = m.positions().to_vec();
    p.extend_from_slice(&t.points);
    (t.tris, p)
}
