//! Bindings of TopMod's remeshing menu and extrusions (`schemes::topmod`):
//! one `Mesh` method per scheme, each iterable, interruptible with the GIL
//! released and checked against the memory budget from its count formulas.

use super::mesh::PyMesh;
use super::{arg_err, big_int, err, finite_in, iterate_traced, run_interruptible};
use crate::budget::{self, Counts};
use crate::schemes::topmod::{checkerboard as cb, compose, corner_cutting as cc, doo_sabin_bc_new as dsn, extrude as ex, linear, loop_style as ls, pentagonal as pt, stellate as st, twelve_six_four as t64};
use pyo3::prelude::*;

fn plain(v: u64, e: u64, f: u64) -> Counts {
    Counts::plain(v, e, f)
}

// count formulas of the schemes' docs, saturating
macro_rules! predictor {
    ($name:ident, |$v:ident, $e:ident, $f:ident| $lo:expr, $hi:expr) => {
        fn $name(c: &Counts) -> (Counts, Counts) {
            let ($v, $e, $f) = (c.v, c.e, c.f);
            let lo: (u64, u64, u64) = $lo;
            let hi: (u64, u64, u64) = $hi;
            (plain(lo.0, lo.1, lo.2), plain(hi.0, hi.1, hi.2))
        }
    };
}
fn s(x: u64, k: u64) -> u64 {
    x.saturating_mul(k)
}
fn a(x: u64, y: u64) -> u64 {
    x.saturating_add(y)
}
predictor!(p_stellate, |v, e, f| (a(v, f), s(e, 3), s(e, 2)), (a(v, f), s(e, 3), s(e, 2)));
predictor!(p_double_stellate, |v, e, f| (a(a(v, f), s(e, 2)), s(e, 9), s(e, 6)), (a(a(v, f), s(e, 2)), s(e, 9), s(e, 6)));
predictor!(p_join, |v, e, f| (a(v, f), s(e, 2), e), (a(v, f), s(e, 2), e));
predictor!(p_linear, |v, e, f| (a(a(v, e), f), s(e, 4), s(e, 2)), (a(a(v, e), f), s(e, 4), s(e, 2)));
predictor!(p_dual_host, |v, e, f| (s(e, 2), s(e, 4), a(a(f, e), v)), (s(e, 2), s(e, 4), a(a(f, e), v)));
predictor!(p_loop_style, |v, e, f| (a(v, e), s(e, 4), a(f, s(e, 2))), (a(v, e), s(e, 4), a(f, s(e, 2))));
predictor!(p_root4, |v, e, f| (a(v, s(e, 2)), s(e, 4), a(f, e)), (a(v, s(e, 2)), s(e, 4), a(f, e)));
// dual Loop (closed meshes only): E' = 4·E_t with E ≤ E_t ≤ 3E, V' = 4·F_t
// = 8·E_t/3, F' = V_t + E_t with V_t ≥ F (compose::dual_loop's counts)
predictor!(p_dual_loop, |v, e, f| (s(e, 2), s(e, 4), a(f, e)), (s(e, 8), s(e, 12), a(a(v, f), s(e, 3))));
predictor!(p_pentagonal, |v, e, f| (a(a(v, s(e, 2)), f), s(e, 5), s(e, 2)), (a(a(v, s(e, 2)), f), s(e, 5), s(e, 2)));
predictor!(p_dual_pentagonal, |v, e, f| (s(e, 2), s(e, 5), a(a(v, f), s(e, 2))), (s(e, 2), s(e, 5), a(a(v, f), s(e, 2))));
predictor!(p_pentagon_preserving, |v, e, f| (a(v, e), s(e, 2), f), (a(v, s(e, 3)), s(e, 6), a(f, s(e, 2))));
predictor!(p_dual_pentagon_preserving, |v, e, f| (v, s(e, 2), a(f, e)), (a(v, s(e, 2)), s(e, 6), a(f, s(e, 3))));
predictor!(p_dual_1264, |v, e, f| (s(e, 4), s(e, 6), a(a(f, e), v)), (s(e, 4), s(e, 6), a(a(f, e), v)));
predictor!(p_1264, |v, e, f| (a(a(v, e), f), s(e, 6), s(e, 4)), (a(a(v, e), f), s(e, 6), s(e, 4)));
predictor!(p_checker, |v, e, f| (a(v, s(e, 4)), s(e, 9), a(f, s(e, 4))), (a(v, s(e, 4)), s(e, 9), a(f, s(e, 4))));
predictor!(p_dome, |v, e, f| (a(v, s(e, 59)), s(e, 116), a(f, s(e, 56))), (a(v, s(e, 59)), s(e, 116), a(f, s(e, 56))));
predictor!(p_fractal, |v, e, f| (a(a(v, e), f), s(e, 6), s(e, 4)), (a(a(v, e), f), s(e, 6), s(e, 4)));
predictor!(p_double_stellate_misc, |v, e, f| (a(a(v, f), s(e, 2)), s(e, 6), s(e, 3)), (a(a(v, f), s(e, 2)), s(e, 6), s(e, 3)));
predictor!(p_doo_sabin_bc_new, |v, e, f| (a(v, s(e, 4)), s(e, 7), a(f, s(e, 2))), (a(v, s(e, 4)), s(e, 7), a(f, s(e, 2))));
predictor!(p_doo_sabin_bc, |v, e, f| (s(e, 4), s(e, 8), a(a(f, s(e, 3)), v)), (s(e, 4), s(e, 8), a(a(f, s(e, 3)), v)));

fn unit(call: &str, name: &str, x: f64) -> PyResult<f64> {
    finite_in(call, name, x, 0.0, 1.0)
}

/// A face selection: one index or a sequence, checked in the core.
fn faces_arg(call: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let raw: Vec<i64> = if let Ok(f) = obj.extract::<i64>() {
        vec![f]
    } else {
        obj.extract().map_err(|_| arg_err(format!("{call}: faces must be a face index or a sequence of face indices")))?
    };
    raw.into_iter().map(|f| if f < 0 { Err(arg_err(format!("{call}: face {f} is negative"))) } else { Ok(f as usize) }).collect()
}

/// Budget check of a one-step operation with known output counts.
fn check_once(py: Python<'_>, call: &str, m: &crate::Mesh, out: Counts) -> PyResult<()> {
    let need = budget::level_bytes(&Counts::of(m), &out);
    super::detach(py, || budget::check(call, "the output", need)).map_err(err)
}

#[pymethods]
impl PyMesh {
    /// Stellate (TopMod's *Stellate*, the centroid fan): every n-gon becomes
    /// n triangles around a new vertex at its centroid, moved by ``offset``
    /// along the face's unit normal.
    ///
    /// Per iteration V' = V + F, E' = 3E, F' = 2E (all triangles); genus
    /// unchanged. Source: TopMod, ``subdivideAllFaces(obj, false)`` and
    /// ``stellateFace``.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    ///     Number of steps (>= 0).
    /// offset : float, default 0.0
    ///     Distance of each centre from its face's plane, outwards, in [0, 10].
    /// progress : bool, default False
    ///     Show a tqdm progress bar.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A parameter out of range, an open mesh, or the memory budget.
    #[pyo3(signature = (iterations = 1, offset = 0.0, progress = false))]
    fn stellate(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let d = finite_in("stellate", "offset", offset, 0.0, 10.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "stellate", p_stellate, |m| st::stellate(m, d))
    }

    /// Double stellate (TopMod's *Double Stellation*, ``starSubdivide``):
    /// stellate, stellate every triangle again, then move the first round's
    /// centres by ``offset`` along their face's unit normal.
    ///
    /// Per iteration V' = V + F + 2E, E' = 9E, F' = 6E (all triangles).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// offset : float, default 0.0
    ///     In [0, 10] (TopMod's UI: [0, 1]).
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, offset = 0.0, progress = false))]
    fn double_stellate(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let d = finite_in("double_stellate", "offset", offset, 0.0, 10.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "double_stellate", p_double_stellate, |m| st::double_stellate(m, d))
    }

    /// Double stellate, TopMod's second variant (*Double Stellate (Misc.)*,
    /// ``twostellateSubdivide``): stellate with the centres moved by
    /// ``height`` along the face normals, stellate every triangle with its
    /// centre moved by ``curve``, then delete every edge of the first
    /// stellation: the join of the stellation, :meth:`stellate_edge_removal`
    /// of :meth:`stellate`.
    ///
    /// Per iteration V' = V + F + 2E, E' = 6E, F' = 3E (all quads).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// height : float, default 0.0
    ///     In [-1, 1] (TopMod's UI).
    /// curve : float, default 0.0
    ///     In [-1, 1] (TopMod's UI).
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, height = 0.0, curve = 0.0, progress = false))]
    fn double_stellate_misc(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, height: f64, curve: f64, progress: bool) -> PyResult<PyMesh> {
        let h = finite_in("double_stellate_misc", "height", height, -1.0, 1.0)?;
        let c = finite_in("double_stellate_misc", "curve", curve, -1.0, 1.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "double_stellate_misc", p_double_stellate_misc, |m| st::double_stellate_misc(m, h, c))
    }

    /// Stellate with edge removal (TopMod's ``stellateSubdivide``): stellate,
    /// then delete every old edge, so each edge becomes the quad of its two
    /// ends and its two faces' centroids (Conway's *join* connectivity).
    ///
    /// Per iteration V' = V + F, E' = 2E, F' = E (all quads). The cube gives
    /// the rhombic dodecahedron.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, progress = false))]
    fn stellate_edge_removal(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool) -> PyResult<PyMesh> {
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "stellate_edge_removal", p_join, |m| st::stellate_edge_removal(m, 0.0))
    }

    /// Linear vertex insertion (TopMod's *Linear Vertex Insertion*,
    /// ``subdivideAllFaces(obj, true)``): edges split at their midpoints, each
    /// face's centroid joined to its midpoints; no smoothing.
    ///
    /// Per iteration V' = V + E + F, E' = 4E, F' = 2E (all quads).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, progress = false))]
    fn linear_vertex_insertion(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool) -> PyResult<PyMesh> {
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "linear_vertex_insertion", p_linear, linear::linear_vertex_insertion)
    }

    /// Corner cutting (TopMod's ``cornerCuttingSubdivide``): Doo-Sabin's
    /// connectivity with TopMod's weights, ``alpha`` on the corner itself and
    /// ``(1 − alpha)(3 + 2 cos(2π(k − j)/n))/(3n − 5)`` on the others.
    ///
    /// Per iteration V' = 2E, E' = 4E, F' = F + E + V (faces keep their size,
    /// edges give quads, valence-k vertices k-gons).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// alpha : float, default 0.5625
    ///     In [1/3, 1) (TopMod's range and default 9/16).
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, alpha = 0.5625, progress = false))]
    fn corner_cutting(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, alpha: f64, progress: bool) -> PyResult<PyMesh> {
        if !(alpha.is_finite() && alpha >= 1.0 / 3.0 && alpha < 1.0) {
            return Err(arg_err(format!("corner_cutting: alpha = {} is out of range; it must be a finite number in [1/3, 1)", crate::error::num(alpha))));
        }
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "corner_cutting", p_dual_host, |m| cc::corner_cutting(m, alpha))
    }

    /// Modified corner cutting (TopMod's ``modifiedCornerCuttingSubdivide``):
    /// Doo-Sabin's connectivity, each corner point at distance
    /// ``thickness / 2`` from both edges of its corner (on their bisector).
    ///
    /// Per iteration V' = 2E, E' = 4E, F' = F + E + V.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// thickness : float, default 0.25
    ///     In [0, 1].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, thickness = 0.25, progress = false))]
    fn modified_corner_cutting(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, thickness: f64, progress: bool) -> PyResult<PyMesh> {
        let t = unit("modified_corner_cutting", "thickness", thickness)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "modified_corner_cutting", p_dual_host, |m| cc::modified_corner_cutting(m, t))
    }

    /// Root-3 as TopMod composes it (``subdivideRoot3``: dual, honeycomb,
    /// dual).
    ///
    /// Per iteration V' = V + F, E' = 3E, F' = 2E (all triangles).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, progress = false))]
    fn root3(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool) -> PyResult<PyMesh> {
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "root3", p_stellate, compose::root3)
    }

    /// Loop-style remeshing (TopMod's ``loopStyleSubdivide``): edges split at
    /// their midpoints and every corner cut off between them (Loop's
    /// connectivity on any face); old vertices move to
    /// ``length·v + (1 − length)·mean(adjacent midpoints)``.
    ///
    /// Per iteration V' = V + E, E' = 4E, F' = F + 2E (the faces keep their
    /// size, 2E new triangles).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// length : float, default 1.0
    ///     In [0, 1].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, length = 1.0, progress = false))]
    fn loop_style(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, length: f64, progress: bool) -> PyResult<PyMesh> {
        let l = unit("loop_style", "length", length)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "loop_style", p_loop_style, |m| ls::loop_style(m, l))
    }

    /// Root-4 (TopMod's ``root4Subdivide``): an inner face per face from the
    /// twisted edge points, old vertices joined to it and old edges deleted
    /// (one hexagon per edge); old vertices move by ``weight`` towards the
    /// mean of their neighbours.
    ///
    /// Per iteration V' = V + 2E, E' = 4E, F' = F + E (faces keep their size,
    /// E hexagons).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// weight : float, default 0.0
    ///     In [0, 1].
    /// twist : float, default 0.0
    ///     In [0, 1]: the edge points ``(1 − twist) a + twist b``.
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, weight = 0.0, twist = 0.0, progress = false))]
    fn root4(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, weight: f64, twist: f64, progress: bool) -> PyResult<PyMesh> {
        let (w, t) = (unit("root4", "weight", weight)?, unit("root4", "twist", twist)?);
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "root4", p_root4, |m| ls::root4(m, w, t))
    }

    /// Dual Loop-style remeshing: TopMod's menu entry of that name runs
    /// root-4 (:meth:`root4`, same parameters and counts).
    #[pyo3(signature = (iterations = 1, weight = 0.0, twist = 0.0, progress = false))]
    fn dual_loop_style(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, weight: f64, twist: f64, progress: bool) -> PyResult<PyMesh> {
        let (w, t) = (unit("dual_loop_style", "weight", weight)?, unit("dual_loop_style", "twist", twist)?);
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_loop_style", p_root4, |m| ls::root4(m, w, t))
    }

    /// Hexagon preserving remeshing: TopMod's menu entry runs root-4
    /// (:meth:`root4`, same parameters and counts).
    #[pyo3(signature = (iterations = 1, weight = 0.0, twist = 0.0, progress = false))]
    fn hexagon_preserving(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, weight: f64, twist: f64, progress: bool) -> PyResult<PyMesh> {
        let (w, t) = (unit("hexagon_preserving", "weight", weight)?, unit("hexagon_preserving", "twist", twist)?);
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "hexagon_preserving", p_root4, |m| ls::root4(m, w, t))
    }

    /// Dual hexagon preserving (TopMod: dual, root-4, dual).
    ///
    /// Per iteration V' = V + E, E' = 4E, F' = F + 2E (faces keep their size,
    /// 2E triangles).
    #[pyo3(signature = (iterations = 1, weight = 0.0, twist = 0.0, progress = false))]
    fn dual_hexagon_preserving(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, weight: f64, twist: f64, progress: bool) -> PyResult<PyMesh> {
        let (w, t) = (unit("dual_hexagon_preserving", "weight", weight)?, unit("dual_hexagon_preserving", "twist", twist)?);
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_hexagon_preserving", p_loop_style, |m| compose::dual_hexagon_preserving(m, w, t))
    }

    /// Dual Loop (TopMod's ``subdivideDualLoop``: dual, Loop, dual); every
    /// output vertex is 3-valent. Counts: those of :meth:`loop` on the dual,
    /// dualised.
    #[pyo3(signature = (iterations = 1, progress = false))]
    fn dual_loop(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool) -> PyResult<PyMesh> {
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_loop", p_dual_loop, compose::dual_loop)
    }

    /// Pentagonalization (TopMod's ``pentagonalSubdivide``): edges trisected,
    /// each face's centroid joined to one trisection point per side, so each
    /// corner gives a pentagon; those points move by ``offset`` towards their
    /// face's centroid.
    ///
    /// Per iteration V' = V + 2E + F, E' = 5E, F' = 2E (all pentagons).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// offset : float, default 0.0
    ///     In [0, 1].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, offset = 0.0, progress = false))]
    fn pentagonalize(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let o = unit("pentagonalize", "offset", offset)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "pentagonalize", p_pentagonal, |m| pt::pentagonalize(m, o))
    }

    /// Cubic pentagonalization (TopMod: pentagonalization, dual, dual):
    /// :meth:`pentagonalize`'s counts, positions averaged twice.
    #[pyo3(signature = (iterations = 1, offset = 0.0, progress = false))]
    fn cubic_pentagonalize(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let o = unit("cubic_pentagonalize", "offset", offset)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "cubic_pentagonalize", p_pentagonal, |m| compose::cubic_pentagonalize(m, o))
    }

    /// Dual pentagonalization (TopMod: dual, pentagonalization, dual).
    ///
    /// Per iteration V' = 2E, E' = 5E, F' = V + F + 2E (the input's faces,
    /// one k-gon per valence-k vertex, 2E triangles).
    #[pyo3(signature = (iterations = 1, offset = 0.0, progress = false))]
    fn dual_pentagonalize(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let o = unit("dual_pentagonalize", "offset", offset)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_pentagonalize", p_dual_pentagonal, |m| compose::dual_pentagonalize(m, o))
    }

    /// Pentagon preserving remeshing (TopMod's ``pentagonalSubdivide2``):
    /// edges split at their midpoints, each face of n >= 3 sides gets its
    /// midpoints' n-gon scaled by ``scale`` and n pentagons around it.
    ///
    /// With H3 the corners of faces of 3 or more sides, per iteration
    /// V' = V + E + H3, E' = 2E + 2·H3, F' = F + H3. The dodecahedron gives 72
    /// pentagons.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// scale : float, default 0.75
    ///     In [0, 1].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, scale = 0.75, progress = false))]
    fn pentagon_preserving(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, scale: f64, progress: bool) -> PyResult<PyMesh> {
        let sc = unit("pentagon_preserving", "scale", scale)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "pentagon_preserving", p_pentagon_preserving, |m| pt::pentagon_preserving(m, sc))
    }

    /// Dual pentagon preserving (TopMod: dual, pentagon preserving, dual).
    ///
    /// With S the valence sum of the vertices of valence >= 3, per iteration
    /// V' = V + S, E' = 2E + 2S, F' = F + E + S.
    #[pyo3(signature = (iterations = 1, scale = 0.75, progress = false))]
    fn dual_pentagon_preserving(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, scale: f64, progress: bool) -> PyResult<PyMesh> {
        let sc = unit("dual_pentagon_preserving", "scale", scale)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_pentagon_preserving", p_dual_pentagon_preserving, |m| compose::dual_pentagon_preserving(m, sc))
    }

    /// Dual 12.6.4 (TopMod's ``dual1264Subdivide``): each n-gon becomes a
    /// 2n-gon through its sides' trisection points, scaled by ``scale``,
    /// each edge a quad, each valence-k vertex a 2k-gon; all vertices
    /// 3-valent.
    ///
    /// Per iteration V' = 4E, E' = 6E, F' = F + E + V.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// scale : float, default 0.7
    ///     In (0, 1] (at 1 the edge quads have zero width).
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, scale = 0.7, progress = false))]
    fn dual_12_6_4(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, scale: f64, progress: bool) -> PyResult<PyMesh> {
        let scale = finite_in("dual_12_6_4", "scale", scale, f64::MIN_POSITIVE, 1.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_12_6_4", p_dual_1264, |m| t64::dual_12_6_4(m, scale))
    }

    /// 12.6.4 remeshing (TopMod's ``subdivide1264``: dual, dual 12.6.4, dual).
    ///
    /// Per iteration V' = V + E + F, E' = 6E, F' = 4E (all triangles).
    #[pyo3(signature = (iterations = 1, scale = 0.7, progress = false))]
    fn remesh_12_6_4(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, scale: f64, progress: bool) -> PyResult<PyMesh> {
        // checked here, not by the dual 12.6.4 inside, so that the error names this call
        let scale = finite_in("remesh_12_6_4", "scale", scale, f64::MIN_POSITIVE, 1.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "remesh_12_6_4", p_1264, |m| compose::remesh_12_6_4(m, scale))
    }

    /// Checkerboard remeshing (TopMod's ``checkerBoardRemeshing``): each face
    /// inset by ``thickness``, each edge trisected at ``thickness`` from its
    /// ends, each corner and each side a quad.
    ///
    /// Per iteration V' = V + 4E, E' = 9E, F' = F + 4E (faces keep their
    /// size, 4E quads).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// thickness : float, default 0.33
    ///     In (0, 0.5].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, thickness = 0.33, progress = false))]
    fn checkerboard(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, thickness: f64, progress: bool) -> PyResult<PyMesh> {
        let thickness = finite_in("checkerboard", "thickness", thickness, f64::MIN_POSITIVE, 0.5)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "checkerboard", p_checker, |m| cb::checkerboard(m, thickness))
    }

    /// Dual checkerboard (TopMod: dual, checkerboard, dual).
    ///
    /// Per iteration V' = V + 4E, E' = 9E, F' = F + 4E.
    #[pyo3(signature = (iterations = 1, thickness = 0.33, progress = false))]
    fn dual_checkerboard(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, thickness: f64, progress: bool) -> PyResult<PyMesh> {
        // checked here, not by the checkerboard inside, so that the error names this call
        let thickness = finite_in("dual_checkerboard", "thickness", thickness, f64::MIN_POSITIVE, 0.5)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dual_checkerboard", p_checker, |m| compose::dual_checkerboard(m, thickness))
    }

    /// Doo-Sabin BC (TopMod's ``dooSabinSubdivideBC``: every edge split at its
    /// midpoint, then Doo-Sabin).
    ///
    /// Per iteration V' = 4E, E' = 8E, F' = F + 3E + V (2n-gons for the
    /// n-gons, 2E quads, E two-gons, one k-gon per valence-k vertex).
    #[pyo3(signature = (iterations = 1, progress = false))]
    fn doo_sabin_bc(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool) -> PyResult<PyMesh> {
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "doo_sabin_bc", p_doo_sabin_bc, compose::doo_sabin_bc)
    }

    /// Doo-Sabin BC New (TopMod's ``dooSabinSubdivideBCNew``): every edge
    /// halved, each face replaced by the Doo-Sabin mask of its halved
    /// polygon scaled by ``scale`` about its centroid, and each edge by two
    /// pentagons meeting at a new edge between its faces' rings; the old
    /// vertices move to ``length · v + (1 − length) ·`` (the mean of their
    /// ring points).
    ///
    /// Per iteration V' = V + 4E, E' = 7E, F' = F + 2E (a 2n-gon per n-gon,
    /// 2E pentagons); old vertices keep their valence.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// scale : float, default 1.0
    ///     In (0, 2].
    /// length : float, default 1.0
    ///     In [0, 1].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, scale = 1.0, length = 1.0, progress = false))]
    fn doo_sabin_bc_new(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, scale: f64, length: f64, progress: bool) -> PyResult<PyMesh> {
        let scale = finite_in("doo_sabin_bc_new", "scale", scale, f64::MIN_POSITIVE, 2.0)?;
        let l = finite_in("doo_sabin_bc_new", "length", length, 0.0, 1.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "doo_sabin_bc_new", p_doo_sabin_bc_new, |m| dsn::doo_sabin_bc_new(m, scale, l))
    }

    /// Dome remeshing (TopMod's ``domeSubdivide``): every edge cut in four,
    /// then seven Doo-Sabin extrusions of every face (lengths 0, 0.3, 0.18,
    /// 0.1, 0.05, 0.025, 0.01 × ``length``, scales 1.6, 1.7, 1.6, 1.4, 1.2,
    /// 1.1, 0.01 × ``scale``).
    ///
    /// Per iteration V' = V + 59E, E' = 116E, F' = F + 56E (an n-gon's top is
    /// a 4n-gon, 56E quads).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// length : float, default 1.0
    ///     In [0, 2].
    /// scale : float, default 1.0
    ///     In (0, 2].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, length = 1.0, scale = 1.0, progress = false))]
    fn dome(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, length: f64, scale: f64, progress: bool) -> PyResult<PyMesh> {
        let l = finite_in("dome", "length", length, 0.0, 2.0)?;
        let scale = finite_in("dome", "scale", scale, f64::MIN_POSITIVE, 2.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "dome", p_dome, |m| ex::dome(m, l, scale))
    }

    /// Fractal remeshing (TopMod's ``fractalSubdivide``): corners cut off at
    /// the edge midpoints, each face's midpoint polygon fanned to a centre
    /// raised along the normal by ``offset`` times TopMod's height.
    ///
    /// Per iteration V' = V + E + F, E' = 6E, F' = 4E (all triangles).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// offset : float, default 1.0
    ///     In [0, 2].
    /// progress : bool, default False
    ///
    /// Returns
    /// -------
    /// Mesh
    #[pyo3(signature = (iterations = 1, offset = 1.0, progress = false))]
    fn fractal(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, offset: f64, progress: bool) -> PyResult<PyMesh> {
        let o = finite_in("fractal", "offset", offset, 0.0, 2.0)?;
        iterate_traced(py, &self.inner, &self.data, iterations, progress, "fractal", p_fractal, |m| ls::fractal(m, o))
    }

    /// Subdivide the selected faces (TopMod's ``subdivideFaces``): into quads
    /// around their centroids with their edges split at the midpoints
    /// (``quads=True``; unselected neighbours gain those midpoints), or into
    /// centroid fans.
    ///
    /// With k selected faces of N corners in all and s edges with a
    /// selected side: quads V' = V + s + k, E' = E + s + N, F' = F − k + N;
    /// fans V' = V + k, E' = E + N, F' = F − k + N.
    ///
    /// Parameters
    /// ----------
    /// faces : int or sequence of int
    ///     Face indices (repeats ignored).
    /// quads : bool, default True
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A face out of range or a point-sphere, an open mesh.
    #[pyo3(signature = (faces, quads = true))]
    fn subdivide_faces(&self, py: Python<'_>, faces: &Bound<'_, PyAny>, quads: bool) -> PyResult<PyMesh> {
        let sel = faces_arg("subdivide_faces", faces)?;
        // upper bounds: N corners selected, at most N edges split, k <= N
        let c = Counts::of(&self.inner);
        let n: u64 = sel.iter().filter(|&&f| f < self.inner.n_faces()).map(|&f| self.inner.face_degree(crate::FaceId(f as u32)) as u64).sum();
        check_once(py, "subdivide_faces", &self.inner, plain(a(c.v, s(n, 2)), a(c.e, s(n, 2)), a(c.f, n)))?;
        let m = &self.inner;
        let r = run_interruptible(py, || super::data::build_traced(!self.data.face.is_empty(), m, || linear::subdivide_faces(m, &sel, quads)))?;
        super::data::inherited(py, &self.data, "subdivide_faces", m, r.0, r.1)
    }

    /// Extrude the selected faces (TopMod's extrusions, ``performExtrusion``).
    ///
    /// ``kind``: ``"cubical"`` (``extrudeFace``: ring scaled by ``scale``,
    /// rotated by ``twist`` degrees, moved by ``length`` along the normal),
    /// ``"doo_sabin"`` (``extrudeFaceDS``: Doo-Sabin mask over the twisted,
    /// moved ring, ``twist`` in [0, 1]), ``"octahedral"`` (``extrudeDualFace``:
    /// the edge midpoints, joined by 2n triangles), ``"stellate"``
    /// (``stellateFace``: a pyramid), ``"double_stellate"``
    /// (``doubleStellateFace``), ``"dome"`` (``extrudeFaceDome``: five
    /// Doo-Sabin rings and a pyramid; ``twist`` in [0, 5] is TopMod's rotation
    /// factor), ``"dodecahedral"`` (``extrudeFaceDodeca``: per step three
    /// rings and 2n pentagons, on a pentagon the dodecahedron's ring of ten)
    /// and ``"icosahedral"`` (``extrudeFaceIcosa``: three rings and 6n
    /// triangles, on a triangle the icosahedron's eighteen), these two shaped
    /// by ``angle`` and ``lengths`` instead of length, scale and twist. Per
    /// selected n-gon and ``segments`` s: cubical and doo_sabin add
    /// (V, E, F) = (s·n, 2s·n, s·n), octahedral (s·n, 3s·n, 2s·n), stellate
    /// (1, n, n − 1), double_stellate (n + 1, 4n, 3n − 1), dome
    /// (5n + 1, 11n, 6n − 1), dodecahedral (3s·n, 5s·n, 2s·n), icosahedral
    /// (3s·n, 9s·n, 6s·n). The genus is unchanged.
    ///
    /// Parameters
    /// ----------
    /// faces : int or sequence of int
    ///     Face indices (repeats ignored).
    /// kind : str, default "cubical"
    /// length : float or None, default None
    ///     Distance per step along the face normal; ``None`` is TopMod's
    ///     default (2, and 1 for ``"dome"``). In [0, 1e6].
    /// scale : float, default 1.0
    ///     Scale of each new ring about its centroid, in (0, 10].
    /// twist : float, default 0.0
    ///     Degrees per step in [0, 360] (cubical, octahedral; counter-clockwise about the normal), the twist in
    ///     [0, 1] (doo_sabin), the rotation factor in [0, 5] (dome); 0 for the
    ///     stellate kinds.
    /// segments : int, default 1
    ///     Steps (>= 1; only cubical, doo_sabin, octahedral, dodecahedral and
    ///     icosahedral take more).
    /// angle : float or None, default None
    ///     TopMod's angle in degrees, in [0, 180] (dodecahedral: 40,
    ///     icosahedral: 50 when None); other kinds refuse it.
    /// lengths : (float, float, float) or None, default None
    ///     TopMod's lengths 1–3 relative to the face's mean side, each in
    ///     [0, 100] (dodecahedral: (0.5, 1, 1), icosahedral: (0.5, 0.7, 0.8)
    ///     when None); other kinds refuse them.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Unknown ``kind``, a parameter out of range (named), a face out of
    ///     range or a point-sphere, an open mesh.
    #[pyo3(signature = (faces, kind = "cubical", length = None, scale = 1.0, twist = 0.0, segments = 1, angle = None, lengths = None))]
    #[allow(clippy::too_many_arguments)]
    fn extrude(&self, py: Python<'_>, faces: &Bound<'_, PyAny>, kind: &str, length: Option<f64>, scale: f64, twist: f64, #[pyo3(from_py_with = big_int)] segments: i128, angle: Option<f64>, lengths: Option<(f64, f64, f64)>) -> PyResult<PyMesh> {
        let k = ex::Kind::parse(kind).ok_or_else(|| arg_err(format!("extrude: kind = {kind:?} is not one of {}", ex::Kind::NAMES)))?;
        let segments = super::usize_in("extrude", "segments", segments, 1, 1 << 20)?;
        let length = finite_in("extrude", "length", length.unwrap_or(k.default_length()), 0.0, 1e6)?;
        let e = ex::Extrusion { kind: k, length, scale, twist, segments, angle, lengths: lengths.map(|(a, b, c)| [a, b, c]) };
        e.check().map_err(err)?;
        let sel = faces_arg("extrude", faces)?;
        let n: u64 = sel.iter().filter(|&&f| f < self.inner.n_faces()).map(|&f| self.inner.face_degree(crate::FaceId(f as u32)) as u64).sum();
        let c = Counts::of(&self.inner);
        let per = (segments as u64).saturating_mul(n).saturating_mul(9).saturating_add(n.saturating_mul(11));
        check_once(py, "extrude", &self.inner, plain(c.v.saturating_add(per), c.e.saturating_add(per), c.f.saturating_add(per)))?;
        let m = &self.inner;
        let r = run_interruptible(py, || super::data::build_traced(!self.data.face.is_empty(), m, || ex::extrude(m, &sel, &e)))?;
        super::data::inherited(py, &self.data, "extrude", m, r.0, r.1)
    }
}
