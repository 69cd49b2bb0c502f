//! Smoothing and refinement schemes as `Mesh` methods (`crate::schemes`).

use super::mesh::PyMesh;
use super::{big_int, levels};
use crate::budget::predict;
use crate::schemes;
use pyo3::prelude::*;

#[pymethods]
impl PyMesh {
    /// Catmull-Clark subdivision (Catmull & Clark 1978), original masks, with
    /// OpenSubdiv's boundary and crease rules.
    ///
    /// Every face (any size) becomes one quad per corner. Face point =
    /// centroid, edge point = (a + b + f1 + f2)/4, vertex point =
    /// (Q + 2R + (n-3)S)/n. Per level: V' = V + E + F, E' = 4E, F' = 2E
    /// (on open meshes F counts the faces and 2E the face corners; holes
    /// stay open). Boundary edges and creases (:meth:`with_creases`) follow
    /// the B-spline curve rule: edge point = midpoint, crease vertex =
    /// (a + 6v + b)/8; a semi-sharp crease of sharpness s blends into
    /// the smooth rule over s levels (DeRose, Kass & Truong 1998). The
    /// output carries the creases (decayed) and the attributes
    /// (:meth:`with_attributes`).
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    ///     Number of levels (0 returns an equal mesh).
    /// progress : bool, default False
    ///     Show a tqdm progress bar, one step per level.
    /// boundary : {"edge_and_corner", "edge_only"}, default "edge_and_corner"
    ///     OpenSubdiv's boundary interpolation: with "edge_and_corner" a
    ///     boundary vertex with one face is a corner and stays put.
    /// crease_method : {"uniform", "chaikin"}, default "uniform"
    ///     How semi-sharp creases decay (OpenSubdiv's creasing methods).
    /// corner_interpolation : {"all", "boundaries", "corners_only", "corners_plus1", "corners_plus2", "smooth"}, default "all"
    ///     Corner attributes (UVs): OpenSubdiv's face-varying choices,
    ///     linear everywhere ("all", its default), linear along seams and
    ///     boundaries, smooth with seam corners pinned ("corners_only"),
    ///     also junctions of three or more UV islands ("corners_plus1",
    ///     Blender's "Keep Corners, Junctions"), also concave corners and
    ///     seam ends ("corners_plus2", "… and Concave"), or smooth.
    /// correspondence : bool, default False
    ///     Also return a :class:`topomesh.Correspondence` (parent faces,
    ///     vertex origins, the subdivision matrix ``S``).
    ///
    /// Returns
    /// -------
    /// Mesh or tuple of (Mesh, Correspondence)
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     If ``iterations`` is negative, an option is unknown, or the output
    ///     would exceed 31-bit ids or the memory budget.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (iterations = 1, progress = false, *, boundary = "edge_and_corner", crease_method = "uniform", corner_interpolation = "all", correspondence = false))]
    fn catmull_clark<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = big_int)] iterations: i128,
        progress: bool,
        boundary: &str,
        crease_method: &str,
        corner_interpolation: &str,
        correspondence: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let spec = levels::Spec::with_rules("catmull_clark", predict::catmull_clark, boundary, crease_method, corner_interpolation, schemes::catmull_clark::catmull_clark_level_with)?;
        levels::run(py, self, iterations, progress, spec, correspondence, schemes::catmull_clark::catmull_clark_level)
    }

    /// Doo-Sabin subdivision (Doo & Sabin 1978) with Doo & Sabin's weights
    /// a_0 = 1/4 + 5/(4n), a_i = (3 + 2cos(2 pi i/n))/(4n).
    ///
    /// One new vertex per corner; faces for every old face, edge and vertex.
    /// Per level: V' = 2E, E' = 4E, F' = F + E + V. Zero-length self-loops
    /// open into tubes. Parameters, return and errors as :meth:`catmull_clark`.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn doo_sabin<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        levels::run(py, self, iterations, progress, levels::Spec::plain("doo_sabin", predict::doo_sabin).with_direct(schemes::doo_sabin::doo_sabin_level_with).with_corners(schemes::corner_direct::doo_sabin).with_large_corners(schemes::doo_sabin::open_large_corners_apply, schemes::doo_sabin::open_large_corners), correspondence, schemes::doo_sabin::doo_sabin_level)
    }

    /// Loop subdivision (Loop 1987) with Loop's original
    /// beta = (5/8 - (3/8 + cos(2 pi/n)/4)^2)/n (as trimesh, VTK, pymeshlab,
    /// OpenSubdiv), and OpenSubdiv's boundary and crease rules.
    ///
    /// Non-triangles (n != 3) are first fanned into n triangles around their
    /// centroid ("extended Loop"). Per level on triangles: V' = V + E,
    /// E' = 2E + 3F, F' = 4F; holes stay open. Boundaries, creases,
    /// parameters, return and errors as :meth:`catmull_clark`.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (iterations = 1, progress = false, *, boundary = "edge_and_corner", crease_method = "uniform", corner_interpolation = "all", correspondence = false))]
    fn r#loop<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = big_int)] iterations: i128,
        progress: bool,
        boundary: &str,
        crease_method: &str,
        corner_interpolation: &str,
        correspondence: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let spec = levels::Spec::with_rules("loop", predict::loop_subdivision, boundary, crease_method, corner_interpolation, schemes::loop_subdivision::loop_level_with)?;
        levels::run(py, self, iterations, progress, spec, correspondence, schemes::loop_subdivision::loop_level)
    }

    /// sqrt3 subdivision (Kobbelt 2000): a centroid per face, old edges
    /// flipped, old vertices smoothed with alpha_n = (4 - 2cos(2 pi/n))/9.
    ///
    /// n-gons are treated like triangles (centroid, spokes, flips). Per
    /// level: V' = V + F, E' = 3E, F' = 2E triangles. Open meshes follow
    /// Kobbelt's boundary rule: the boundary is trisected on every second
    /// level of one call (odd levels keep it), so ``iterations=2`` refines
    /// it and two calls of one level do not. Parameters, return and errors
    /// as :meth:`catmull_clark`.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn sqrt3<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        levels::run(py, self, iterations, progress, levels::Spec::plain("sqrt3", predict::sqrt3).with_direct(schemes::sqrt3::sqrt3_level_with).with_corners(schemes::corner_direct::sqrt3).with_owned(schemes::sqrt3::sqrt3_level_owned), correspondence, schemes::sqrt3::sqrt3_level)
    }

    /// The simplest subdivision scheme (Peters & Reif 1997): mid-edge
    /// subdivision, new vertices at edge midpoints, one face per old face
    /// and per old vertex.
    ///
    /// Per level: V' = E, E' = 2E, F' = F + V; every new vertex is
    /// 4-valent. Open meshes keep their boundary polyline (boundary
    /// vertices stay, boundary edges are split at their midpoints: V' = E +
    /// V_b, E' = 2E + E_b). Parameters, return and errors as
    /// :meth:`catmull_clark`.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn simplest<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        levels::run(py, self, iterations, progress, levels::Spec::plain("simplest", predict::simplest).with_direct(schemes::simplest::simplest_level_with).with_corners(schemes::corner_direct::simplest).with_owned(schemes::simplest::simplest_level_owned), correspondence, schemes::simplest::simplest_level)
    }

    /// Midpoint (linear) subdivision: triangles split 1 -> 4 at edge
    /// midpoints (as ``trimesh.remesh.subdivide``), other faces into one quad
    /// per corner around their centroid. Old vertices do not move.
    ///
    /// Per level: V' = V + E + F_(n!=3), F' = 4 F_3 + sum_(n!=3) n.
    /// Parameters, return and errors as :meth:`catmull_clark`.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn midpoint<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        levels::run(py, self, iterations, progress, levels::Spec::plain("midpoint", predict::midpoint).with_direct(schemes::midpoint::midpoint_level_with).with_corners(|i, o, rows, k| {
            schemes::corner_linear::level(i, o, schemes::corner_linear::Primal::Mixed, rows, k)
        }), correspondence, schemes::midpoint::midpoint_level)
    }

    /// The dual mesh: a vertex at every face centroid, a face around every
    /// vertex (V' = F, E' = E, F' = V). Orientation is kept. Parameters,
    /// return and errors as :meth:`catmull_clark`.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn dual<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        levels::run(py, self, iterations, progress, levels::Spec::plain("dual", predict::dual).with_direct(schemes::dual::dual_level_with).with_corners(schemes::corner_direct::dual).with_owned(schemes::dual::dual_level_owned), correspondence, schemes::dual::dual_level)
    }

    /// Limit positions and unit normals of the Catmull-Clark or Loop surface
    /// at every vertex (OpenSubdiv's limit masks), without subdividing
    /// further: place points on the limit surface, or shade a coarse mesh.
    ///
    /// The creases and the boundary rule apply as in the schemes. Semi-sharp
    /// creases are refined away first (1 + ceil(s) levels, internally).
    /// Normals are exact (unchanged by refining first) everywhere; at Loop's
    /// crease and boundary vertices with three or more interior edges the
    /// cross tangent is the one the plain crease rules make (an eigenvector
    /// of their local subdivision matrix), not OpenSubdiv's mask, which is
    /// made for Biermann, Levin & Zorin's modified rules.
    ///
    /// Parameters
    /// ----------
    /// scheme : {"catmull_clark", "loop"}, default "catmull_clark"
    /// boundary, crease_method : str
    ///     As in :meth:`catmull_clark`.
    ///
    /// Returns
    /// -------
    /// positions, normals : ndarray of float64, shape (V, 3)
    ///     Normals are unit length and point like the faces around the
    ///     vertex (zero for a point-sphere).
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     An unknown scheme or option.
    #[pyo3(signature = (scheme = "catmull_clark", *, boundary = "edge_and_corner", crease_method = "uniform"))]
    fn limit_points<'py>(&self, py: Python<'py>, scheme: &str, boundary: &str, crease_method: &str) -> PyResult<(Bound<'py, numpy::PyArray2<f64>>, Bound<'py, numpy::PyArray2<f64>>)> {
        use crate::schemes::limit::{limit_points, LimitScheme};
        let s = match scheme {
            "catmull_clark" => LimitScheme::CatmullClark,
            "loop" => LimitScheme::Loop,
            _ => return Err(super::arg_err(format!("limit_points: scheme = {scheme:?}; expected \"catmull_clark\" or \"loop\""))),
        };
        let options = levels::options("limit_points", boundary, crease_method)?;
        let creases = self.data.creases.clone();
        let m = &self.inner;
        let l = super::run_interruptible(py, || limit_points(m, s, creases.as_ref(), options))?;
        Ok((super::convert::vec3_array(py, &l.positions), super::convert::vec3_array(py, &l.normals)))
    }
}
