//! Python bindings of the high-level operators (dissertation ch. III),
//! multi-segment curved handles (ch. IV) and rind modeling (ch. V.3).
//! Faces are given by index and corners by position in their face (the
//! order of :attr:`Mesh.face_indices`); every method returns a new mesh.

use super::mesh::PyMesh;
use super::{arg_err, err};
use crate::mesh::{Corner, EdgeId, FaceId, HalfedgeId, Mesh};
use crate::ops::Rind;
use pyo3::prelude::*;

fn face_of(m: &Mesh, f: i64) -> PyResult<FaceId> {
    if f < 0 || f as usize >= m.n_faces() {
        return Err(arg_err(format!("face {f} out of range (mesh has {} faces)", m.n_faces())));
    }
    Ok(FaceId(f as u32))
}

fn corner_of(m: &Mesh, face: i64, position: i64) -> PyResult<Corner> {
    let f = face_of(m, face)?;
    if position < 0 {
        return Err(arg_err(format!("corner position {position} of face {face} is negative")));
    }
    m.corner(f, position as usize).map_err(err)
}

/// The half-edge leaving corner `position` of `face` (faces with edges only).
fn halfedge_of(m: &Mesh, face: i64, position: i64, what: &str) -> PyResult<HalfedgeId> {
    match corner_of(m, face, position)? {
        Corner::Halfedge(h) => Ok(h),
        Corner::Point(_) => Err(arg_err(format!("{what}: face {face} is a point-sphere (it has no edge)"))),
    }
}

fn edge_of(m: &Mesh, e: i64) -> PyResult<EdgeId> {
    if e < 0 || e as usize >= m.n_edges() {
        return Err(arg_err(format!("edge {e} out of range (mesh has {} edges)", m.n_edges())));
    }
    Ok(EdgeId(e as u32))
}

/// One face index or a sequence of them.
fn face_list(obj: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let raw: Vec<i64> = if let Ok(f) = obj.extract::<i64>() { vec![f] } else { obj.extract()? };
    raw.into_iter()
        .map(|f| if f < 0 { Err(arg_err(format!("face {f} is negative"))) } else { Ok(f as usize) })
        .collect()
}

#[pymethods]
impl PyMesh {
    /// DeleteEdgeWithCleanup(e) (dissertation ch. III.1): :meth:`delete_edge`,
    /// then every end vertex left without edges (a point-sphere) is deleted.
    ///
    /// E−1 and the effect of :meth:`delete_edge`; then V−k, F−k and
    /// components −k for the k ∈ {0, 1, 2} point-spheres removed. The last
    /// edge takes index ``edge``; a removed vertex's index goes to the last vertex.
    fn delete_edge_with_cleanup(&self, py: Python<'_>, #[pyo3(from_py_with = super::sat_i64)] edge: i64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "delete_edge_with_cleanup")?;
        let e = edge_of(&self.inner, edge)?;
        let mut m = self.inner.clone();
        super::detach(py, || m.delete_edge_with_cleanup(e)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// SubdivideEdge(e) (ch. III.2): a new vertex at ``(1 − t)·a + t·b`` on
    /// ``edge`` = (a, b) (the row of :attr:`edges`), by CreateVertex,
    /// two InsertEdge and DeleteEdge. Returns ``(mesh, vertex)``.
    ///
    /// V+1, E+1, F and genus unchanged; both faces beside the edge gain a
    /// corner. Self-loops split too (a one-gon becomes a two-gon). ``edge``
    /// now runs from the new vertex to b; the new last edge runs from a to it.
    #[pyo3(signature = (edge, t = 0.5))]
    fn subdivide_edge(&self, #[pyo3(from_py_with = super::sat_i64)] edge: i64, t: f64) -> PyResult<(PyMesh, usize)> {
        super::data::warn_dropped(&self.data, "subdivide_edge")?;
        let e = edge_of(&self.inner, edge)?;
        let mut m = self.inner.clone();
        let s = m.subdivide_edge(e, t).map_err(err)?;
        Ok((PyMesh::wrap(m), s.vertex.idx()))
    }

    /// CreatePipe(c1, c2) (ch. III.3): joins corner ``position1`` of
    /// ``face1`` to corner ``position2`` of ``face2``, and every further
    /// matching corner (one face forward, the other backward), making a pipe
    /// of quads in place of the two faces. A smaller face first has its
    /// longest edges subdivided until the sizes agree.
    ///
    /// With d splits and N corners: V+d, E+d+N, F+N−2; genus +1 on one
    /// component, components −1 across two.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Same face twice, a corner position not in its face, a
    ///     point-sphere against a larger face.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     When the pipe's faces cross the rest of the surface (the exact
    ///     crossing check ``menger`` uses), with the number of crossing
    ///     triangle pairs.
    fn create_pipe(&self, py: Python<'_>, #[pyo3(from_py_with = super::sat_i64)] face1: i64, #[pyo3(from_py_with = super::sat_i64)] position1: i64, #[pyo3(from_py_with = super::sat_i64)] face2: i64, #[pyo3(from_py_with = super::sat_i64)] position2: i64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "create_pipe")?;
        let c1 = corner_of(&self.inner, face1, position1)?;
        let c2 = corner_of(&self.inner, face2, position2)?;
        let mut m = self.inner.clone();
        super::detach(py, || m.create_pipe(c1, c2)).map_err(err)?;
        warn_new_crossings(py, "create_pipe", &self.inner, &m)?;
        Ok(PyMesh::wrap(m))
    }

    /// CreateFaceManifold(p0, …, pN−1) (ch. III.4): adds a sphere of two
    /// faces through ``points`` (N, 3): the front face in the given order,
    /// the back face reversed. Returns ``(mesh, front, back)``.
    ///
    /// V+N, E+N, F+2, components +1 (one point: a point-sphere, front = back).
    fn create_face_manifold(&self, py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<(PyMesh, usize, usize)> {
        super::data::warn_dropped(&self.data, "create_face_manifold")?;
        let pts = super::convert::positions(py, points)?;
        let mut m = self.inner.clone();
        let fm = m.create_face_manifold(&pts).map_err(err)?;
        Ok((PyMesh::wrap(m), fm.front.idx(), fm.back.idx()))
    }

    /// ConnectEdges (ch. III.5) on the side leaving corner ``position1`` of
    /// ``face1`` and the side leaving corner ``position2`` of ``face2``: an
    /// edge from where the first starts to where the second ends, and one
    /// from where the first ends to where the second starts, bounding a new
    /// face with both sides. Returns ``(mesh, new_face)``.
    ///
    /// E+2. One face: it splits in three (F+2). Two faces: F unchanged and
    /// genus +1 (one component) or components −1.
    fn connect_edges(&self, #[pyo3(from_py_with = super::sat_i64)] face1: i64, #[pyo3(from_py_with = super::sat_i64)] position1: i64, #[pyo3(from_py_with = super::sat_i64)] face2: i64, #[pyo3(from_py_with = super::sat_i64)] position2: i64) -> PyResult<(PyMesh, usize)> {
        super::data::warn_dropped(&self.data, "connect_edges")?;
        let h1 = halfedge_of(&self.inner, face1, position1, "connect_edges")?;
        let h2 = halfedge_of(&self.inner, face2, position2, "connect_edges")?;
        let mut m = self.inner.clone();
        let (_, _, f) = m.connect_edges(h1, h2).map_err(err)?;
        Ok((PyMesh::wrap(m), f.idx()))
    }

    /// CollapseEdge(e) (ch. III.6): merges the two ends of ``edge`` into one
    /// vertex at its midpoint. Returns ``(mesh, vertex)``.
    ///
    /// V−1, E−s, F−(s−1), genus unchanged, where s is 1 plus the number of
    /// two-gons on the edge (each vanishes; a triangle beside it becomes a
    /// two-gon). Raises :class:`MeshError` for a self-loop.
    fn collapse_edge(&self, py: Python<'_>, #[pyo3(from_py_with = super::sat_i64)] edge: i64) -> PyResult<(PyMesh, usize)> {
        super::data::warn_dropped(&self.data, "collapse_edge")?;
        let e = edge_of(&self.inner, edge)?;
        let mut m = self.inner.clone();
        let c = super::detach(py, || m.collapse_edge(e)).map_err(err)?;
        Ok((PyMesh::wrap(m), c.vertex.idx()))
    }

    /// A multi-segment curved handle (dissertation ch. IV) from ``face_a``
    /// to ``face_b``.
    ///
    /// Parameters
    /// ----------
    /// face_a, face_b : int
    ///     Two faces not sharing an edge.
    /// segments : int, default 4
    ///     Number of pipe segments k (k − 1 intermediate cross-sections).
    /// weights : (float, float), optional
    ///     Hermite tangent lengths (w1, w2) along the face normals, in model
    ///     units; both negative make a tunnel through the solid instead of
    ///     a handle. Default: the distance between the face centroids, twice.
    /// corners : (int, int or None), optional
    ///     Corner positions matched with each other in ``face_a`` and
    ///     ``face_b``; changing one twists the handle. A second entry of
    ///     ``None`` picks the corner of ``face_b`` giving the least twist.
    ///     Default: ``(0, None)``.
    ///
    /// Faces of different sizes are equalized by subdividing the smaller
    /// one's edges. With d splits and N corners: V + d + N(k−1),
    /// E + d + N(2k−1), F + Nk − 2; genus +1 on one component, components −1
    /// across two.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Same face, faces sharing an edge, a corner not in its face,
    ///     weights of opposite signs, segments < 1, coincident centroids.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     When the handle passes through the body (the exact crossing check
    ///     ``menger`` uses, on the handle's faces), with the number of
    ///     crossing triangle pairs.
    /// pinch, pinch_center, pinch_width : float, default 1.0, 0.5, 1.0
    ///     TopMod's pinch: sections scaled from 1 at the ends to ``pinch``
    ///     at ``pinch_center`` (in (0, 1)), by a quadratic Bézier whose
    ///     spread ``pinch_width`` (in [0.001, 10]) sets; ``pinch`` in (0, 10].
    /// extra_twists : int, default 0
    ///     Extra full turns of the sections from ``face_a`` to ``face_b``
    ///     (0 to 100).
    #[pyo3(signature = (face_a, face_b, segments = 4, weights = None, corners = None, pinch = 1.0, pinch_center = 0.5, pinch_width = 1.0, extra_twists = 0))]
    fn add_handle(
        &self,
        py: Python<'_>,
        #[pyo3(from_py_with = super::sat_i64)] face_a: i64,
        #[pyo3(from_py_with = super::sat_i64)] face_b: i64,
        #[pyo3(from_py_with = super::sat_i64)] segments: i64,
        weights: Option<(f64, f64)>,
        corners: Option<(i64, Option<i64>)>,
        pinch: f64,
        pinch_center: f64,
        pinch_width: f64,
        #[pyo3(from_py_with = super::big_int)] extra_twists: i128,
    ) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "add_handle")?;
        let extra_twists = super::usize_in("add_handle", "extra_twists", extra_twists, 0, 100)? as u32;
        let shape = crate::ops::HandleShape { pinch, center: pinch_center, width: pinch_width, extra_twists };
        let m0 = &self.inner;
        let corners = corners.unwrap_or((0, None));
        let c1 = halfedge_of(m0, face_a, corners.0, "add_handle")?;
        let c2 = halfedge_of(m0, face_b, corners.1.unwrap_or(0), "add_handle")?;
        if segments < 1 {
            return Err(arg_err(format!("add_handle: segments = {segments} must be at least 1")));
        }
        // every segment adds a ring of n quads (n = the larger face's size)
        let n = m0.face_degree(m0.face(c1)).max(m0.face_degree(m0.face(c2))) as u64;
        let ring = (segments as u64).saturating_mul(n);
        let c = crate::budget::Counts::plain(
            (m0.n_vertices() as u64).saturating_add(ring),
            (m0.n_edges() as u64).saturating_add(ring.saturating_mul(2)),
            (m0.n_faces() as u64).saturating_add(ring),
        );
        crate::budget::check("add_handle", &format!("segments = {segments}"), crate::budget::build_bytes(&c)).map_err(err)?;
        // in topomesh's pool, never rayon's global one (`pool` module docs)
        let (w1, w2) = match weights {
            Some(w) => w,
            None => {
                let c = super::pool::run(|| m0.face_centroids());
                let d = (c[face_a as usize] - c[face_b as usize]).length();
                (d, d)
            }
        };
        let c2 = if corners.1.is_none() { super::pool::run(|| m0.aligned_handle_corner(c1, c2, w1, w2)).map_err(err)? } else { c2 };
        let mut m = m0.clone();
        super::detach(py, || m.add_handle_shaped(c1, c2, segments as usize, w1, w2, shape)).map_err(err)?;
        warn_new_crossings(py, "add_handle", m0, &m)?;
        Ok(PyMesh::wrap(m))
    }

    /// Pairs of triangles of :meth:`triangulate` that intersect, int64 (K, 2),
    /// ``i < j``, sorted: an edge of one through the other's interior, or
    /// lying in the other's plane across it (coplanar overlap). Triangles
    /// sharing an edge never count; sharing a vertex, only when they meet
    /// away from it. The exact check ``menger``, ``add_handle`` and
    /// ``create_pipe`` use (``src/geometry/crossing/``): near-linear in the
    /// triangles. Triangles around a vertex of high valence are paired by
    /// their directions there (``conway("Y8000")``'s 8,000-valent apex:
    /// 0.02 s), and large convex faces are not fanned (see
    /// :meth:`triangulate`; the two 8,000-gons of ``conway("P8000")``: 0.05
    /// s). What stays quadratic is thousands of long triangles converging
    /// on one spot without a common vertex, or two such fans facing each
    /// other: their boxes all overlap there (benches/CATALOG.md, large faces).
    fn self_intersections<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<i64>>> {
        let pairs = super::run_interruptible(py, || {
            let (tris, p) = crate::geometry::triangles_with_points(&self.inner);
            crate::cancel::check()?;
            let pairs = crate::geometry::crossing::crossing_pairs(&p, &tris, None, true);
            crate::cancel::check().map(|()| pairs)
        })?;
        let rows: Vec<[u32; 2]> = pairs.iter().map(|&(i, j)| [i, j]).collect();
        Ok(super::convert::u32_rows(py, &rows))
    }

    /// The offset shell of this mesh for rind modeling (dissertation ch.
    /// V.3.1): a copy with reversed orientation, each vertex moved inward by
    /// ``thickness`` along its averaged normal. Returns a :class:`Rind`
    /// whose faces ``0..F`` are this mesh's faces (outer shell) and
    /// ``F..2F`` their inner twins.
    ///
    /// An open mesh gives the closed solid shell of its surface: the hole
    /// faces (among ``0..F``) are peeled at once, so each boundary loop
    /// becomes a strip of quads joining the outer and inner rims (listed in
    /// :attr:`Rind.punched`). The shell is the double of the open surface:
    /// χ = 2χ, genus 2g + b − 1 for a connected surface with b ≥ 1 loops.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A thickness that is not positive, or one that flips an inner face
    ///     (named); a mesh with point-spheres.
    fn rind(&self, py: Python<'_>, thickness: f64) -> PyResult<PyRind> {
        super::data::warn_dropped(&self.data, "rind")?;
        let r = super::detach(py, || self.inner.rind(thickness)).map_err(err)?;
        Ok(PyRind { inner: r })
    }
}

/// Crossing pairs a warning counts before it says "at least": a surface
/// folded through itself everywhere (a wireframe thicker than its edges)
/// has quadratically many, 88 M in 28 s for a prism's two 8,000-gons; a
/// million take about a tenth of a second to find.
pub(crate) const CROSSING_REPORT_LIMIT: usize = 1_000_000;

/// Runs the shared crossing check (`geometry::crossing`) on the faces an
/// operator made and raises a `GeometryWarning` with the count when they
/// pass through the rest of the surface (up to [`CROSSING_REPORT_LIMIT`]).
pub(crate) fn warn_new_crossings(py: Python<'_>, op: &str, before: &crate::Mesh, after: &crate::Mesh) -> PyResult<()> {
    let (n, stopped) = super::run_interruptible(py, || {
        let n = crate::geometry::crossing::crossings_of_new_faces_upto(before, after, CROSSING_REPORT_LIMIT);
        crate::cancel::check().map(|()| n)
    })?;
    if n > 0 {
        let count = if stopped { format!("at least {CROSSING_REPORT_LIMIT}") } else { n.to_string() };
        let msg = format!(
            "{op}: the new faces pass through the surface: {count} crossing triangle pairs (the mesh is a valid manifold but self-intersecting; choose other faces, weights or corners)"
        );
        super::warn_geometry(py, msg)?;
    }
    Ok(())
}

/// A rind: a mesh with its offset shell and the outer↔inner face table
/// (dissertation ch. V.3). Immutable; :meth:`punch` and :meth:`peel` return
/// new rinds. Faces are named by their index in the initial rind (outer
/// ``0..F``, inner ``F..2F``), whatever later operations renumber.
#[pyclass(name = "Rind", module = "topomesh", frozen)]
pub struct PyRind {
    pub(crate) inner: Rind,
}

#[pymethods]
impl PyRind {
    /// The rind surface as a :class:`Mesh`.
    #[getter]
    fn mesh(&self) -> PyMesh {
        PyMesh::wrap(self.inner.mesh().clone())
    }
    /// Number of outer faces F (the source mesh's faces).
    #[getter]
    fn n_outer_faces(&self) -> usize {
        self.inner.initial_face_count() / 2
    }
    /// Outer faces punched or peeled so far, increasing.
    #[getter]
    fn punched(&self) -> Vec<usize> {
        self.inner.punched_faces()
    }
    /// Current indices in :attr:`mesh` of outer face ``face`` and its inner
    /// twin, or ``None`` once punched.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``face`` outside ``0 .. n_outer_faces - 1``.
    fn face_pair(&self, #[pyo3(from_py_with = super::big_int)] face: i128) -> PyResult<Option<(usize, usize)>> {
        let n = self.inner.initial_face_count() / 2;
        if n == 0 {
            return Err(super::arg_err("face_pair: the rind has no outer faces"));
        }
        let f = super::usize_in("face_pair", "face", face, 0, n - 1)?;
        Ok(self.inner.face_pair(f).map(|(a, b)| (a.idx(), b.idx())))
    }
    /// Punch a hole through each outer face of ``faces`` (an int or a
    /// sequence): CreatePipe between the face and its inner twin.
    ///
    /// Per face E+N, F+N−2; the first punch of a fresh rind joins the two
    /// shells (components −1), each later one adds a handle (genus +1).
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A face out of range, on the inner shell, already punched, or
    ///     selected twice.
    fn punch(&self, py: Python<'_>, faces: &Bound<'_, PyAny>) -> PyResult<PyRind> {
        let fs = face_list(faces)?;
        let mut r = self.inner.clone();
        super::detach(py, || r.punch(&fs)).map_err(err)?;
        Ok(PyRind { inner: r })
    }
    /// Peel each outer face of ``faces``: punch it, then delete the
    /// infinitely thin walls it leaves against earlier holes and the
    /// two-gons at their ends (ch. V.3.2), so neighbouring holes open into
    /// one. Each wall removed cuts a handle (genus −1), or separates a piece
    /// when it closes a ring of holes. Same errors as :meth:`punch`.
    fn peel(&self, py: Python<'_>, faces: &Bound<'_, PyAny>) -> PyResult<PyRind> {
        let fs = face_list(faces)?;
        let mut r = self.inner.clone();
        super::detach(py, || r.peel(&fs)).map_err(err)?;
        Ok(PyRind { inner: r })
    }
    fn __repr__(&self) -> String {
        let m = self.inner.mesh();
        format!(
            "Rind(outer_faces={}, punched={}, V={}, E={}, F={}, genus={}, components={})",
            self.inner.initial_face_count() / 2,
            self.inner.punched_faces().len(),
            m.n_vertices(),
            m.n_edges(),
            m.n_faces(),
            m.genus(),
            m.n_components()
        )
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRind>()?;
    Ok(())
}
