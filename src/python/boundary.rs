//! Open meshes in Python: the boundary policy of the constructors
//! (`boundaries=` / legacy `close_boundaries=`) and the boundary queries of
//! `Mesh` (`src/mesh/boundary.rs`).

use super::arg_err;
use super::convert::{i64_array, u32_rows};
use super::mesh::PyMesh;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

/// Whether a constructor keeps boundary loops (as hole faces) or refuses
/// them, from its two keywords: `boundaries` ("keep", the default, or
/// "refuse") and the legacy `close_boundaries` (`None` by default; `True`
/// means "keep", `False` "refuse"). `call` names the constructor.
pub(crate) fn keep_boundaries(call: &str, close_boundaries: Option<bool>, boundaries: &str) -> PyResult<bool> {
    let keep = match boundaries {
        "keep" => true,
        "refuse" => false,
        other => {
            return Err(arg_err(format!(
                "{call}: boundaries = {other:?} is not an option; allowed: \"keep\" (accept open meshes, the default) or \"refuse\""
            )))
        }
    };
    match close_boundaries {
        None => Ok(keep),
        // the default "keep" gives way to the legacy strict spelling
        Some(false) => Ok(false),
        Some(true) if keep => Ok(true),
        Some(true) => Err(arg_err(format!(
            "{call}: close_boundaries=True (keep boundary loops) contradicts boundaries=\"refuse\"; pass only one of them"
        ))),
    }
}

/// The refusal of an open mesh rebuilt from `corner_twins` (which always
/// re-creates its holes) when boundaries are refused.
pub(crate) fn refuse_open(call: &str, m: &crate::Mesh) -> PyResult<()> {
    let b = m.n_boundary_loops();
    if b == 0 {
        return Ok(());
    }
    let e = m.boundary_edges()[0];
    Err(arg_err(format!(
        "{call}: the mesh is open ({b} boundary loop{}, e.g. boundary edge ({}, {})) and boundaries were refused \
         (boundaries=\"refuse\" or close_boundaries=False); keep boundaries=\"keep\" (the default) to accept it open",
        if b == 1 { "" } else { "s" },
        e[0],
        e[1]
    )))
}

#[pymethods]
impl PyMesh {
    /// Number of boundary loops of the open surface (the same as
    /// :attr:`n_holes`: each loop is stored as one hole face).
    #[getter]
    fn n_boundary_loops(&self) -> usize {
        self.inner.n_boundary_loops()
    }

    /// True when the mesh has no boundary loop (no hole face).
    #[getter]
    fn is_closed(&self) -> bool {
        self.inner.is_closed()
    }

    /// The boundary loops as vertex indices.
    ///
    /// Returns
    /// -------
    /// list of numpy.ndarray of int64
    ///     One array per loop, its vertices in the order the boundary edges
    ///     run in the faces: ``(loop[i], loop[i + 1])`` (and the last back to
    ///     the first) is a side of a face, traversed that way by the face, so
    ///     a loop runs clockwise seen from the side the face normals point to
    ///     (for an outward-oriented surface, the loop turns against the faces
    ///     beside it). Each loop starts at its lowest vertex index; the loops
    ///     are sorted by it. Empty for a closed mesh.
    fn boundary_loops<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray1<i64>>> {
        let loops = super::detach(py, || self.inner.boundary_loops());
        loops.iter().map(|l| i64_array(py, l.iter().map(|v| v.0 as i64))).collect()
    }

    /// The boundary edges, int64 (k, 2): ``[tail, head]`` as the edge runs
    /// in its face, loop after loop in the order of :meth:`boundary_loops`.
    /// ``(0, 2)`` for a closed mesh.
    fn boundary_edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let e = super::detach(py, || self.inner.boundary_edges());
        u32_rows(py, &e)
    }

    /// χ = V − E + F of each connected component, its boundary loops not
    /// counted as faces, so χ_c = 2 − 2 g_c − b_c with g_c from
    /// :attr:`component_genera` and b_c from :attr:`component_boundary_loops`
    /// (same component order).
    #[getter]
    fn component_euler_characteristics(&self) -> Vec<i64> {
        self.inner.component_euler_characteristics()
    }

    /// Number of boundary loops of each connected component (the order of
    /// :attr:`component_genera`).
    #[getter]
    fn component_boundary_loops(&self) -> Vec<i64> {
        self.inner.component_boundary_loops()
    }
}
