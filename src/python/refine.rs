//! Bindings of the refinement schemes of the honeycomb and vertex truncation
//! papers: `Mesh.honeycomb` and `Mesh.vertex_truncation`.

use super::mesh::PyMesh;
use super::{arg_err, err, big_int};
use crate::budget::predict;
use crate::schemes::honeycomb;
use crate::schemes::vertex_truncation::{self, Truncation};
use pyo3::prelude::*;

#[pymethods]
impl PyMesh {
    /// Honeycomb subdivision (Akleman & Srinivasan, "Honeycomb Subdivision").
    ///
    /// Each face's corners get new points by eq. (1)–(2) of the paper; each
    /// face keeps its size, each valence-k vertex becomes a 2k-gon and every
    /// new vertex is 3-valent. Per iteration V' = 2E, E' = 3E, F' = F + V
    /// (Remark 2); genus unchanged. The dodecahedron gives the truncated
    /// icosahedron (12 pentagons, 20 hexagons).
    ///
    /// Open meshes stay open: each boundary loop stays one loop (F counts
    /// real faces, so the counts hold and χ is kept), and its new vertices
    /// lie on the boundary edges, at ``t`` along each, instead of being
    /// averaged over the hole.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    ///     Number of steps (>= 0).
    /// t : float, default 0.5
    ///     Position of the point on each edge, in [0, 1] (eq. 1).
    /// tension : float or None, default None
    ///     The weight ``a`` of eq. (2), in [0, 1], for every face; ``None``
    ///     uses the paper's ``a = 0.45 + 1.25 / N`` for an N-gon (clamped to
    ///     1 for two-gons). One-gons always use 1.
    /// progress : bool, default False
    ///     Show a tqdm progress bar, one tick per iteration.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``iterations`` negative, ``t`` or ``tension`` outside [0, 1].
    #[pyo3(signature = (iterations = 1, t = 0.5, tension = None, progress = false, *, correspondence = false))]
    fn honeycomb<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = big_int)] iterations: i128,
        t: f64,
        tension: Option<f64>,
        progress: bool,
        correspondence: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        honeycomb::check_args(t, tension).map_err(err)?;
        let spec = super::levels::Spec::plain("honeycomb", predict::truncation)
            .with_direct(move |m, r, data| honeycomb::honeycomb_level_with(m, t, tension, r, data))
            .with_corners(move |i, o, rows, k| crate::schemes::corner_direct::honeycomb(i, o, t, tension, rows, k))
            .with_large_corners(honeycomb::large_corners_apply, move |i, o, rows, out, k| honeycomb::large_corners(i, o, t, tension, rows, out, k))
            .with_owned(move |m, r| honeycomb::honeycomb_level_owned(m, t, tension, r));
        super::levels::run(py, self, iterations, progress, spec, correspondence, |m, r| honeycomb::honeycomb_level(m, t, tension, r))
    }

    /// Vertex truncation (Akleman, Edmundson & Ozener, "A Generalized Vertex
    /// Truncation Scheme").
    ///
    /// Cuts every edge at ``ratio`` from each end and replaces every vertex
    /// by the polygon of its cut points: an n-gon becomes a 2n-gon, a
    /// valence-m vertex an m-gon, every new vertex is 3-valent; per
    /// iteration V' = 2E, E' = 3E, F' = F + V, genus unchanged. Planar faces
    /// with 3-valent vertices (and the octahedron and icosahedron) stay
    /// planar at every iteration.
    ///
    /// Open meshes stay open: a boundary loop is cut like a face (its
    /// corners cut off along the boundary edges) and stays one loop; the
    /// counts hold with F counting real faces, so χ is kept.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    ///     Number of steps (>= 0).
    /// mode : {"chaikin", "polyhedral"}, default "chaikin"
    ///     ``"chaikin"``: the paper's scheme, cuts at 1/4 and 3/4 of each
    ///     edge. ``"polyhedral"``: classic truncation at ``ratio``.
    /// ratio : float, default 0.25
    ///     Fraction of each edge cut off at each end, in (0, 0.5]; only
    ///     ``mode="polyhedral"`` accepts a value other than 0.25. At 0.5 the
    ///     two cuts of an edge coincide and are merged: the result is the
    ///     rectified mesh (cube → cuboctahedron; V' = E, E' = 2E,
    ///     F' = F + V, 4-valent vertices). ``1 / (2 + 2 cos(pi / n))`` turns
    ///     regular n-gons into regular 2n-gons (the Archimedean truncations).
    /// progress : bool, default False
    ///     Show a tqdm progress bar, one tick per iteration.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``iterations`` negative, unknown ``mode``, ``ratio`` outside
    ///     (0, 0.5] or not 0.25 with ``mode="chaikin"``.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (iterations = 1, mode = "chaikin", ratio = 0.25, progress = false, *, correspondence = false))]
    fn vertex_truncation<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = big_int)] iterations: i128,
        mode: &str,
        ratio: f64,
        progress: bool,
        correspondence: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let how = match mode {
            "chaikin" if ratio == 0.25 => Truncation::Chaikin,
            "chaikin" => {
                return Err(arg_err(format!(
                    "vertex_truncation: ratio = {} needs mode='polyhedral' (mode='chaikin' always cuts at 1/4 and 3/4)",
                    crate::error::num(ratio)
                )))
            }
            "polyhedral" => Truncation::Polyhedral { ratio },
            other => {
                return Err(arg_err(format!("vertex_truncation: mode = {other:?} is not one of 'chaikin', 'polyhedral'")))
            }
        };
        how.check().map_err(err)?;
        let ratio = how.ratio();
        let spec = super::levels::Spec::plain("vertex_truncation", predict::truncation)
            .with_corners(move |i, o, rows, k| crate::schemes::corner_direct::truncation(i, o, ratio, rows, k))
            .with_owned(move |m, r| vertex_truncation::vertex_truncation_level_owned(m, how, r));
        super::levels::run(py, self, iterations, progress, spec, correspondence, |m, r| vertex_truncation::vertex_truncation_level(m, how, r))
    }
}
