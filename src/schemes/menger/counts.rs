//! The count formulas of the module docs of [`super`], evaluated on an input.

use super::check::build_reduced;
use super::offset::plan;
use super::{EdgeKind, MengerOptions};
use crate::error::Result;
use crate::mesh::Mesh;

/// Quantities of the count formulas (module docs), measured on the input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct MengerCounts {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub genus: i64,
    /// Edges collapsed, kept as strips, split by miter points.
    pub collapsed: usize,
    pub strips: usize,
    pub mitered: usize,
    /// `G + 2E_m` after welding: the inner surface's vertices.
    pub inner_vertices: usize,
    /// Strip and miter quads and vertex faces with at least three corners.
    pub inner_faces: usize,
    /// Faces added by splitting non-planar faces into planar pieces.
    pub planar_splits: usize,
}

/// The counts one [`menger`] iteration will produce on `m` (module docs):
/// `V' = V + 4E + inner vertices`, `F' = 6E + inner faces`,
/// `genus' = 2g + F − 1` per component, `E' = V' + F' − χ'`.
pub fn menger_counts(m: &Mesh, o: &MengerOptions) -> Result<MengerCounts> {
    let pl = plan(m, o, &vec![false; m.n_vertices()], None)?;
    let (e, f) = (m.n_edges(), m.n_faces());
    let n_miter = pl.kind.iter().filter(|&&k| k == EdgeKind::Miter).count();
    let n_coll = pl.kind.iter().filter(|&&k| k == EdgeKind::Collapse).count();
    let built = build_reduced(m, o, true)?.0 .0;
    let inner_vertices = built.inner_vertices;
    let inner_faces = built.sizes.len() - built.split_extra - 3 * m.n_halfedges();
    let chi2 = 2 * m.euler_characteristic() - 2 * f as i64;
    let vertices = m.n_vertices() + 4 * e + inner_vertices;
    let faces = 6 * e + inner_faces + built.split_extra;
    Ok(MengerCounts {
        vertices,
        edges: (vertices as i64 + faces as i64 - chi2) as usize,
        faces,
        genus: (m.n_components() as i64 * 2 - chi2) / 2,
        collapsed: n_coll,
        strips: e - n_coll - n_miter,
        mitered: n_miter,
        inner_vertices,
        inner_faces,
        planar_splits: built.split_extra,
    })
}
