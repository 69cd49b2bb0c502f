//! Python bindings of the TopMod tools of issue 16 (`crate::ops::tools`):
//! object tools, wireframe, multi-face handle, rind by scaling, conical
//! cuts and convex hulls. Every method returns a new mesh; the input is
//! never modified.

use super::mesh::PyMesh;
use super::{arg_err, err};
use crate::budget::Counts;
use crate::mesh::Mesh;
use glam::DVec3;
use pyo3::prelude::*;

/// A non-negative index or a sequence of them.
fn index_list(call: &str, what: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let raw: Vec<i128> = if let Ok(x) = super::big_int(obj) {
        vec![x]
    } else {
        let items: Vec<Bound<'_, PyAny>> = obj.try_iter()?.collect::<PyResult<_>>()?;
        items.iter().map(super::big_int).collect::<PyResult<_>>()?
    };
    raw.into_iter()
        .map(|x| {
            if x < 0 || x > u32::MAX as i128 {
                Err(arg_err(format!("{call}: {what} {x} is out of range (indices are >= 0)")))
            } else {
                Ok(x as usize)
            }
        })
        .collect()
}

fn point(call: &str, name: &str, p: Option<(f64, f64, f64)>) -> PyResult<Option<DVec3>> {
    match p {
        None => Ok(None),
        Some((x, y, z)) if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Some(DVec3::new(x, y, z))),
        Some(p) => Err(arg_err(format!("{call}: {name} = {p:?} must be finite"))),
    }
}

fn sphere_center(obj: &Bound<'_, PyAny>) -> PyResult<Option<(f64, f64, f64)>> {
    if obj.is_none() {
        return Ok(None);
    }
    super::convert::point3(obj, "spherize", "center").map(|[x, y, z]| Some((x, y, z)))
}

/// Largest length or scale factor the tools accept (a bound that names the
/// parameter instead of building a mesh of 1e21-sized coordinates).
const MAX_LENGTH: f64 = 1e15;

#[pymethods]
impl PyMesh {
    /// Planarize all faces (TopMod's object tool, made iterative): each
    /// iteration fits every face's least-squares plane and moves every
    /// vertex to the mean of its projections onto its faces' planes.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 50
    ///     At most this many iterations (>= 0).
    /// tol : float, default 1e-9
    ///     Stop once the residual is at most this (>= 0, model units).
    ///
    /// Returns
    /// -------
    /// (Mesh, float)
    ///     The mesh (same topology) and the residual: the largest distance
    ///     of a vertex to the least-squares plane of one of its faces.
    #[pyo3(signature = (iterations = 50, tol = 1e-9))]
    fn planarize(&self, py: Python<'_>, #[pyo3(from_py_with = super::big_int)] iterations: i128, tol: f64) -> PyResult<(PyMesh, f64)> {
        let it = super::usize_in("planarize", "iterations", iterations, 0, 1_000_000)?;
        let mut m = self.inner.clone();
        let r = super::run_interruptible(py, || m.planarize(it, tol))?;
        // only positions move: every attribute and crease stays valid
        Ok((PyMesh::with_data(m, self.data.clone_ref(py)), r.residual))
    }

    /// The largest distance of a vertex to the least-squares plane of one
    /// of its faces (0 for triangles): the residual :meth:`planarize` reports.
    fn planarity_residual(&self, py: Python<'_>) -> f64 {
        super::detach(py, || self.inner.planarity_residual())
    }

    /// Spherize (TopMod's object tool): every vertex moved along the ray
    /// from ``center`` onto the sphere of ``radius`` about it. Defaults:
    /// the vertex centroid and the mean distance to it. Topology unchanged.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A radius that is not positive, a vertex at the centre.
    #[pyo3(signature = (radius = None, center = None))]
    fn spherize(&self, py: Python<'_>, radius: Option<f64>, #[pyo3(from_py_with = sphere_center)] center: Option<(f64, f64, f64)>) -> PyResult<PyMesh> {
        let c = point("spherize", "center", center)?;
        if let Some(r) = radius {
            super::finite_in("spherize", "radius", r, f64::MIN_POSITIVE, MAX_LENGTH)?;
        }
        let mut m = self.inner.clone();
        super::detach(py, || m.spherize(c, radius)).map_err(err)?;
        // only positions move: every attribute and crease stays valid
        Ok(PyMesh::with_data(m, self.data.clone_ref(py)))
    }

    /// Remove valence-2 vertices (TopMod's object tool): each vertex with
    /// two edges goes and its two edges become one (V−1, E−1 each; F and
    /// genus unchanged). Vertices on a self-loop, and those whose removal
    /// would empty a face (the two-gon sphere keeps one), stay.
    fn remove_valence2_vertices(&self, py: Python<'_>) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "remove_valence2_vertices")?;
        let (m, _) = super::detach(py, || self.inner.remove_valence2_vertices()).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Clean up two-gons (TopMod's object tool): every two-gon face goes,
    /// its two sides becoming one edge (E−1, F−1 each; V and genus
    /// unchanged). A component made only of two-gons keeps two of them.
    fn cleanup_two_gons(&self, py: Python<'_>) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "cleanup_two_gons")?;
        let (m, _) = super::detach(py, || self.inner.cleanup_two_gons()).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Split valence-2 vertices (TopMod's object tool): each vertex with
    /// two edges becomes two on a new edge (V+1, E+1 each), set apart by
    /// ``offset`` each along the difference of the edge directions, or by a
    /// tenth of each edge's length when ``offset`` is None.
    #[pyo3(signature = (offset = None))]
    fn split_valence2_vertices(&self, py: Python<'_>, offset: Option<f64>) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "split_valence2_vertices")?;
        let mut m = self.inner.clone();
        super::detach(py, || m.split_valence2_vertices(offset)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Subdivide all edges (TopMod's object tool): ``n`` evenly spaced new
    /// vertices on every edge. V + nE, E(n+1), F unchanged; a k-gon becomes
    /// a k(n+1)-gon. New vertex j of edge e is vertex V + e·n + j, from the
    /// edge's first vertex (the row of :attr:`edges`).
    #[pyo3(signature = (n = 1))]
    fn subdivide_all_edges(&self, py: Python<'_>, #[pyo3(from_py_with = super::big_int)] n: i128) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "subdivide_all_edges")?;
        let n = super::usize_in("subdivide_all_edges", "n", n, 1, 1 << 20)?;
        let m = super::detach(py, || self.inner.subdivide_all_edges(n)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Wireframe modelling (TopMod's two variants): a tube of four sides
    /// along every edge, strips ``width`` wide inside each face (default:
    /// the thickness, TopMod's first variant) and ``thickness`` deep.
    ///
    /// V' = 4E, E' = 10E, F' = 2V + 4E; a connected closed mesh of genus g
    /// gives genus E − V + 1 = 2g + F − 1.
    ///
    /// Parameters
    /// ----------
    /// thickness : float
    ///     Depth of the tubes (> 0).
    /// width : float or None, default None
    ///     Width of the strips inside each face (> 0); None uses the
    ///     thickness.
    /// check_crossings : bool, default True
    ///     Test the output for self-crossings and warn when there are any.
    ///     The test is exact and linear in the output, but it is almost all
    ///     of the call (on a 100k-quad torus, one thread: 2.3 s with it,
    ///     0.04 s without; `benches/CATALOG.md`). False skips it, for inputs and
    ///     parameters already known to give a crossing-free result
    ///     (:meth:`self_intersections` and :func:`topomesh.printing.printable`
    ///     test it when asked).
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A non-positive thickness or width, an open mesh, a point-sphere.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     When the tubes cross each other (strips too wide for the faces),
    ///     unless ``check_crossings`` is False.
    #[pyo3(signature = (thickness, width = None, check_crossings = true))]
    fn wireframe(&self, py: Python<'_>, thickness: f64, width: Option<f64>, check_crossings: bool) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "wireframe")?;
        super::finite_in("wireframe", "thickness", thickness, f64::MIN_POSITIVE, MAX_LENGTH)?;
        if let Some(w) = width {
            super::finite_in("wireframe", "width", w, f64::MIN_POSITIVE, MAX_LENGTH)?;
        }
        let m = super::detach(py, || self.inner.wireframe(thickness, width)).map_err(err)?;
        if check_crossings {
            super::ops::warn_new_crossings(py, "wireframe", &Mesh::new(), &m)?;
        }
        Ok(PyMesh::wrap(m))
    }

    /// Multi-face handle (TopMod's ``multiConnectFaces``, both algorithms).
    ///
    /// ``algorithm="convex_hull"``: the vertices of ``faces`` (at least two),
    /// each moved ``extrude`` along its face's normal and scaled by ``scale``
    /// about their centroid, span a convex hub, and every face is joined to
    /// its copy on the hub by a pipe. Faces that look at the hub give a solid
    /// hub; a hub behind them (negative ``extrude``, inside the solid) is a
    /// cavity. On one component the genus grows by k − 1 for k faces.
    ///
    /// ``algorithm="closest_edge"``: bridges (quads of two InsertEdges)
    /// between the nearest sides of different selected faces, nearest first,
    /// each side used once, kept only where the bridge is planar within 5°
    /// (and, for three or more faces, not facing along the normal of their
    /// centroids' plane); new edges between faces of one plane are deleted
    /// after (TopMod's ``edgeCleanup``). ``scale`` and ``extrude`` do not
    /// apply. Two facing squares give a tube of four quads.
    ///
    /// Parameters
    /// ----------
    /// faces : sequence of int
    /// scale : float, default 1.0
    /// extrude : float, default 0.5
    /// algorithm : {"convex_hull", "closest_edge"}, default "convex_hull"
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Fewer than two faces, repeats, out of range; a copy that is not a
    ///     face of the hub; faces on both sides of the hub; a flat hub; no
    ///     planar bridge (closest_edge); an unknown ``algorithm``.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     When the hub, the pipes or the bridges pass through the surface.
    #[pyo3(signature = (faces, scale = 1.0, extrude = 0.5, algorithm = "convex_hull"))]
    fn multi_face_handle(&self, py: Python<'_>, faces: &Bound<'_, PyAny>, scale: f64, extrude: f64, algorithm: &str) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "multi_face_handle")?;
        let fs = index_list("multi_face_handle", "face", faces)?;
        super::finite_in("multi_face_handle", "scale", scale, f64::MIN_POSITIVE, MAX_LENGTH)?;
        super::finite_in("multi_face_handle", "extrude", extrude, -MAX_LENGTH, MAX_LENGTH)?;
        let m = match algorithm {
            "convex_hull" => super::detach(py, || self.inner.multi_face_handle(&fs, scale, extrude))
                .map_err(|e| match e {
                    // the hub is built from the moved face corners: name the parameters that moved them
                    crate::MeshError::Interrupted => err(e),
                    e => arg_err(format!("multi_face_handle (scale = {}, extrude = {}): {e}", crate::error::num(scale), crate::error::num(extrude))),
                })?,
            "closest_edge" => super::detach(py, || self.inner.multi_face_handle_edges(&fs)).map_err(err)?.0,
            a => return Err(arg_err(format!("multi_face_handle: algorithm = {a:?} is not 'convex_hull' or 'closest_edge'"))),
        };
        super::ops::warn_new_crossings(py, "multi_face_handle", &self.inner, &m)?;
        Ok(PyMesh::wrap(m))
    }

    /// Column modelling (TopMod's ``makeWireframeWithColumns``): a prism of
    /// ``segments`` sides and radius ``thickness`` along every edge, joined
    /// at every vertex by strips between neighbouring columns and a top and
    /// a bottom cap (no cap at a valence-2 vertex; an n-gon closes a
    /// valence-1 vertex's column; for odd n the bottom cap is a fan of
    /// triangles around a centre, which keeps saddle joints from crossing). The columns end at TopMod's distance
    /// from each vertex plus a quarter of the thickness (TopMod's margin of
    /// a thousandth folded the joints between columns at right angles;
    /// ``docs/tools.md``).
    ///
    /// With V₁, V₂, V₃ the vertices of valence 1, 2, ≥ 3, n = ``segments``,
    /// m = n // 2, ε = 1 for even n (else 0) and S₃ = 2E − V₁ − 2V₂:
    /// V' = 2nE + (1 − ε)V₃,
    /// E' = 3nE + (m + 1)(2E − V₁) − (1 + ε)V₂ + 2(1 − ε)S₃,
    /// F' = nE + m(2E − V₁) + (1 + ε)V₃ + (1 − ε)(V₂ + 2S₃) + V₁; the genus
    /// of each component is E − V + 1 (the cycle rank of its edges).
    ///
    /// Parameters
    /// ----------
    /// thickness : float, default 0.25
    ///     The columns' radius (> 0; TopMod's UI: (0, 1]).
    /// segments : int, default 4
    ///     Sides of each column, in [3, 100] (TopMod's UI: [4, 100]).
    /// check_crossings : bool, default True
    ///     Test the output for self-crossings; where joints cross (strongly
    ///     curved vertices), move those vertices' rings further out along
    ///     their edges, 1.1× per round for up to 8 rounds, keeping the round
    ///     with the fewest crossings, and warn about any left. False skips
    ///     both (the plain construction, unchecked; the check is most of the
    ///     call on large inputs, see :meth:`wireframe`). Outputs without
    ///     crossings are the same either way.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A parameter out of range; a self-loop or zero-length edge; an edge
    ///     too short for the rings at its ends (use a smaller thickness); a
    ///     point-sphere.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     When the columns or joints still cross each other after the rings
    ///     were moved, unless ``check_crossings`` is False.
    #[pyo3(signature = (thickness = 0.25, segments = 4, check_crossings = true))]
    fn wireframe_columns(&self, py: Python<'_>, thickness: f64, #[pyo3(from_py_with = super::big_int)] segments: i128, check_crossings: bool) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "wireframe_columns")?;
        super::finite_in("wireframe_columns", "thickness", thickness, f64::MIN_POSITIVE, MAX_LENGTH)?;
        let n = super::usize_in("wireframe_columns", "segments", segments, 3, 100)?;
        // (odd n adds a fan centre per vertex; the edge and face bounds hold the fans' spokes and triangles)
        let out = Counts::plain(2 * n as u64 * self.inner.n_edges() as u64 + self.inner.n_vertices() as u64, 6 * n as u64 * self.inner.n_edges() as u64, 4 * n as u64 * self.inner.n_edges() as u64);
        let need = crate::budget::level_bytes(&Counts::of(&self.inner), &out);
        super::detach(py, || crate::budget::check("wireframe_columns", "the output", need)).map_err(err)?;
        if !check_crossings {
            let m = super::detach(py, || self.inner.wireframe_columns(thickness, n)).map_err(err)?;
            return Ok(PyMesh::wrap(m));
        }
        let c = super::run_interruptible(py, || self.inner.wireframe_columns_checked(thickness, n))?;
        if c.crossing_pairs > 0 {
            let moved = if c.moved_vertices > 0 {
                format!("{} before the rings of {} vertices were moved out", c.crossing_pairs_before, c.moved_vertices)
            } else {
                "the edges leave no room to move the crossing joints' rings out".to_string()
            };
            let msg = format!(
                "wireframe_columns: the columns and joints cross: {} crossing triangle pairs ({moved}; the mesh is a valid manifold but self-intersecting; try a smaller thickness or other segments)",
                c.crossing_pairs
            );
            super::warn_geometry(py, msg)?;
        }
        Ok(PyMesh::wrap(c.mesh))
    }

    /// Rind by scaling (TopMod's high-genus tool, beside :meth:`rind` by
    /// thickness): the offset shell is a copy scaled by ``scale`` about the
    /// vertex centroid, inside for 0 < scale < 1; for scale > 1 the scaled
    /// copy is the outer shell. Returns a :class:`Rind` (faces ``0..F``
    /// outer, ``F..2F`` inner, as :meth:`rind`).
    fn rind_by_scaling(&self, py: Python<'_>, scale: f64) -> PyResult<super::ops::PyRind> {
        super::data::warn_dropped(&self.data, "rind_by_scaling")?;
        super::finite_in("rind_by_scaling", "scale", scale, f64::MIN_POSITIVE, MAX_LENGTH)?;
        let r = super::detach(py, || self.inner.rind_by_scaling(scale)).map_err(err)?;
        Ok(super::ops::PyRind { inner: r })
    }

    /// Cut by vertex (TopMod's conical tool): each vertex of ``vertices``
    /// (an int or a sequence) cut off by the plane through the mean of the
    /// points at ``offset`` (a fraction in (0, 2]) along its edges, normal
    /// to its averaged normal; the part above the plane connected to the
    /// vertex is replaced by a cap face. A convex corner of valence k:
    /// V + k − 1, E + k, F + 1.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     An index out of range or repeated, an offset outside (0, 2], a
    ///     vertex on or below its plane, a cut that removes a whole component.
    #[pyo3(signature = (vertices, offset = 0.25))]
    fn cut_vertices(&self, py: Python<'_>, vertices: &Bound<'_, PyAny>, offset: f64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "cut_vertices")?;
        let vs = index_list("cut_vertices", "vertex", vertices)?;
        let (m, _) = super::detach(py, || self.inner.cut_vertices(&vs, offset)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Cut by edge (TopMod's conical tool): each edge of ``edges`` cut off
    /// by the plane through the mean of the points at ``offset`` along the
    /// other edges of its ends, normal to the sum of its faces' normals.
    /// Cuts that touch are made one after the other. Errors as
    /// :meth:`cut_vertices`.
    #[pyo3(signature = (edges, offset = 0.25))]
    fn cut_edges(&self, py: Python<'_>, edges: &Bound<'_, PyAny>, offset: f64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "cut_edges")?;
        let es = index_list("cut_edges", "edge", edges)?;
        let (m, _) = super::detach(py, || self.inner.cut_edges(&es, offset)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// Cut by face (TopMod's conical tool): each face of ``faces`` sliced
    /// off by a plane parallel to it, through the mean of the points at
    /// ``offset`` along the edges leaving its corners. Errors as
    /// :meth:`cut_vertices`.
    #[pyo3(signature = (faces, offset = 0.25))]
    fn cut_faces(&self, py: Python<'_>, faces: &Bound<'_, PyAny>, offset: f64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "cut_faces")?;
        let fs = index_list("cut_faces", "face", faces)?;
        let (m, _) = super::detach(py, || self.inner.cut_faces(&fs, offset)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }
}

fn hull_points(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    if let Ok(m) = obj.cast::<PyMesh>() {
        return Ok(m.borrow().inner.positions().to_vec());
    }
    super::convert::positions(py, obj)
}

/// The convex hull of a point set, float64 (N, 3), or of a :class:`Mesh`'s
/// vertices (TopMod's conical tool), as a closed convex polyhedron:
/// exact orientation predicates decide every side test, triangles in one
/// plane merge into one polygon face, and only extreme points are vertices.
///
/// Raises
/// ------
/// MeshError
///     Fewer than four distinct points, non-finite coordinates, all points
///     on one plane or line.
#[pyfunction]
pub fn convex_hull(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<PyMesh> {
    let p = hull_points(py, points)?;
    let (m, _) = super::detach(py, || crate::ops::tools::hull::convex_hull(&p)).map_err(err)?;
    Ok(PyMesh::wrap(m))
}

/// TopMod's dual convex hull of a point set or a :class:`Mesh`'s vertices:
/// the convex solid bounded by the plane through each vertex of the hull,
/// normal to its averaged normal (one face per hull vertex; TopMod also
/// clips by the bounding box, left out here). Errors as :func:`convex_hull`.
#[pyfunction]
pub fn dual_convex_hull(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<PyMesh> {
    let p = hull_points(py, points)?;
    let m = super::detach(py, || crate::ops::tools::hull::dual_convex_hull(&p)).map_err(err)?;
    Ok(PyMesh::wrap(m))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(convex_hull, m)?)?;
    m.add_function(wrap_pyfunction!(dual_convex_hull, m)?)?;
    Ok(())
}
