//! `topomesh.Mesh`: an immutable Python view of the core `Mesh`. Operations
//! return new meshes. Interop and file methods delegate to the pure-Python
//! `topomesh._interop` / `topomesh.io` modules.

use super::convert::{faces, i64_array, indices_1d, positions, u32_rows, vec3_array};
use super::{arg_err, err};
use crate::mesh::{BuildOptions, Corner, EdgeId, FaceId, Mesh, VertexId};
use glam::DVec3;
use numpy::ndarray::{ArrayView1, ArrayView2};
use numpy::{PyArray1, PyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::sync::OnceLock;

/// An orientable 2-manifold polygon mesh, closed or open (immutable).
///
/// Build one with :meth:`Mesh.from_polygons`, :meth:`Mesh.from_flat`,
/// :func:`topomesh.load` or a primitive such as :func:`topomesh.cube`.
/// Self-loops, multi-edges, two-gons and point-spheres are legal. Open
/// meshes are accepted and kept open: each boundary loop is stored as a hole
/// face, never exported (see :meth:`boundary_loops`, :attr:`is_closed`).
#[pyclass(name = "Mesh", module = "topomesh", frozen)]
pub struct PyMesh {
    pub inner: Mesh,
    /// Creases and attributes (`super::data`).
    pub data: super::data::MeshData,
    cache: Cache,
}

/// Exports and queries computed on first use: the mesh never changes, so the
/// arrays handed out are read-only views of these buffers (or of the
/// positions), with the `Mesh` object as their base.
#[derive(Default)]
struct Cache {
    polygons: OnceLock<(Vec<i64>, Vec<i64>)>,
    twins: OnceLock<Vec<i64>>,
    genus: OnceLock<i64>,
    n_components: OnceLock<usize>,
}

/// A read-only NumPy view of `data`, kept alive by `owner`.
fn view_1d<'py>(owner: &Bound<'py, PyMesh>, data: &[i64]) -> PyResult<Bound<'py, PyArray1<i64>>> {
    // SAFETY: `data` is a buffer of the frozen `owner` (never mutated nor
    // moved while it lives), and `owner` becomes the array's base.
    let a = unsafe { PyArray1::borrow_from_array(&ArrayView1::from(data), owner.clone().into_any()) };
    a.getattr("flags")?.setattr("writeable", false)?;
    Ok(a)
}

impl PyMesh {
    pub fn wrap(inner: Mesh) -> Self {
        PyMesh { inner, data: Default::default(), cache: Cache::default() }
    }

    pub fn with_data(inner: Mesh, data: super::data::MeshData) -> Self {
        PyMesh { inner, data, cache: Cache::default() }
    }

    /// `(face_sizes, face_indices)` as int64, computed once.
    fn polygons(&self, py: Python<'_>) -> &(Vec<i64>, Vec<i64>) {
        self.cache.polygons.get_or_init(|| {
            // written as int64 in parallel, then viewed (never copied) by the getters
            super::detach(py, || self.inner.polygons_i64())
        })
    }

    /// `triangles()` through the full triangulation (faces other than plain triangles).
    fn triangles_general<'py>(&self, py: Python<'py>, return_faces: bool) -> PyResult<Bound<'py, PyAny>> {
        let (t, f) = super::run_interruptible(py, || {
            let t = self.inner.triangles();
            crate::cancel::check().map(|()| t)
        })?;
        let tris = u32_rows(py, &t).into_any();
        if return_faces {
            Ok((tris, i64_array(py, f.iter().map(|&x| x as i64))).into_pyobject(py)?.into_any())
        } else {
            Ok(tris)
        }
    }

    fn twins(&self, py: Python<'_>) -> &Vec<i64> {
        self.cache.twins.get_or_init(|| super::detach(py, || self.inner.corner_twins()))
    }

    fn face_id(&self, f: i64) -> PyResult<FaceId> {
        if f < 0 || f as usize >= self.inner.n_faces() {
            return Err(arg_err(format!("face {f} out of range (mesh has {} faces)", self.inner.n_faces())));
        }
        Ok(FaceId(f as u32))
    }

    fn corner(&self, face: i64, position: i64) -> PyResult<Corner> {
        let f = self.face_id(face)?;
        if position < 0 {
            return Err(arg_err(format!("corner position {position} of face {face} is negative")));
        }
        self.inner.corner(f, position as usize).map_err(err)
    }

    /// Calls `module.func(self, *args)`: interop and file code lives in Python.
    fn delegate<'py>(slf: &Bound<'py, Self>, module: &str, func: &str, args: &[Bound<'py, PyAny>]) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let f = py.import(module)?.getattr(func)?;
        let mut all = vec![slf.clone().into_any()];
        all.extend(args.iter().cloned());
        f.call1(pyo3::types::PyTuple::new(py, all)?)
    }
}

fn build_twins(py: Python<'_>, pos: Vec<DVec3>, sizes: &[i64], idx: &[i64], twins: &[i64]) -> PyResult<PyMesh> {
    let m = super::run_interruptible(py, || Mesh::from_corner_twins_i64(pos, sizes, idx, twins))?;
    Ok(PyMesh::wrap(m))
}

fn vertex_point(obj: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    super::convert::point3(obj, "create_vertex", "point")
}

/// Flat face indices as the caller gave them: int64, or an int32 array's
/// values read in place (a PLY file's, many libraries' face arrays).
enum FlatIndices<'a> {
    I64(&'a [i64]),
    I32(&'a [i32]),
}

/// The values of `obj` when it is a C-contiguous int32 array of `ndim`
/// dimensions, borrowed (read as they are, no int64 copy).
fn int32_array<'py>(obj: &Bound<'py, PyAny>, ndim: usize) -> Option<numpy::PyReadonlyArrayDyn<'py, i32>> {
    let a = obj.cast::<numpy::PyArrayDyn<i32>>().ok()?;
    (a.ndim() == ndim && a.is_c_contiguous()).then(|| numpy::PyArrayMethods::readonly(a))
}

fn build(py: Python<'_>, pos: Vec<DVec3>, sizes: &[i64], idx: FlatIndices<'_>, close_boundaries: bool, allow_multi_edges: bool) -> PyResult<PyMesh> {
    let opts = BuildOptions { close_boundaries, allow_multi_edges };
    let corners = match idx {
        FlatIndices::I64(i) => i.len(),
        FlatIndices::I32(i) => i.len(),
    };
    let c = crate::budget::Counts::plain(pos.len() as u64, corners as u64 / 2, sizes.len() as u64);
    let m = super::run_interruptible(py, || {
        crate::budget::check("from_polygons", &format!("a mesh of {} faces", sizes.len()), crate::budget::build_bytes(&c))?;
        match idx {
            FlatIndices::I64(i) => Mesh::from_polygons(pos, sizes, i, opts),
            FlatIndices::I32(i) => Mesh::from_polygons_i32(pos, sizes, i, opts),
        }
        .map_err(|e| match e {
            // an even number of sides on one vertex pair is how a mesh with
            // multi-edges is written (OBJ, OFF, polygon arrays): say how to read it back
            crate::MeshError::NonManifoldEdge { ref faces, .. } if !allow_multi_edges && faces.len() % 2 == 0 => crate::MeshError::InvalidArgument(format!(
                "{e} (if these are several edges between the same two vertices, as a mesh with multi-edges is written, pass allow_multi_edges=True)"
            )),
            e => e,
        })
    })?;
    super::repair::warn_inside_out(py, &m)?;
    Ok(PyMesh::wrap(m))
}

#[pymethods]
impl PyMesh {
    /// Build a mesh from vertices and polygon faces.
    ///
    /// Parameters
    /// ----------
    /// vertices : array_like, shape (V, 3)
    ///     Real coordinates (converted to float64).
    /// faces : sequence of sequences of int, or int array of shape (F, k)
    ///     Each face lists its vertex indices counter-clockwise seen from
    ///     outside. Faces may have any size; a size-1 face whose vertex is in
    ///     no other face is a point-sphere.
    /// close_boundaries : bool or None, default None
    ///     Legacy spelling of ``boundaries``: ``True`` is the default
    ///     behaviour (keep boundary loops), ``False`` refuses open meshes
    ///     (``boundaries="refuse"``).
    /// allow_multi_edges : bool, default False
    ///     Accept more than two face sides on one vertex pair, pairing them in
    ///     order of appearance.
    /// boundaries : {"keep", "refuse"}, default "keep"
    ///     ``"keep"``: an open mesh is accepted and stays open; each boundary
    ///     loop is stored as one hole face (topology only: never exported,
    ///     not counted by :attr:`euler_characteristic`; see
    ///     :meth:`boundary_loops`). ``"refuse"``: a boundary edge raises
    ///     :class:`MeshError` naming it.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Naming the face or vertex: index out of range, empty face, edge used
    ///     by more than two faces, inconsistent orientation, non-manifold
    ///     vertex (e.g. two boundary loops touching at a vertex), non-finite
    ///     coordinate, unreferenced vertex, wrong dtype or shape; a boundary
    ///     edge when boundaries are refused; an unknown ``boundaries`` value or
    ///     ``close_boundaries=True`` with ``boundaries="refuse"``.
    #[staticmethod]
    #[pyo3(signature = (vertices, faces, close_boundaries = None, allow_multi_edges = false, boundaries = "keep"))]
    fn from_polygons(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        close_boundaries: Option<bool>,
        allow_multi_edges: bool,
        boundaries: &str,
    ) -> PyResult<PyMesh> {
        let keep = super::boundary::keep_boundaries("from_polygons", close_boundaries, boundaries)?;
        let pos = positions(py, vertices)?;
        // an (F, k) int32 array (k > 0) is read in place
        if let Some(a) = int32_array(faces, 2) {
            let (nf, k) = (a.shape()[0], a.shape()[1]);
            if k > 0 {
                return build(py, pos, &vec![k as i64; nf], FlatIndices::I32(a.as_slice()?), keep, allow_multi_edges);
            }
        }
        let (sizes, idx) = self::faces(py, faces)?;
        build(py, pos, &sizes, FlatIndices::I64(idx.as_slice()), keep, allow_multi_edges)
    }

    /// Build a mesh from vertices, ``face_sizes`` (F,) and flat ``face_indices``,
    /// the layout of the :attr:`face_sizes` / :attr:`face_indices` exports.
    ///
    /// Without ``twins``: same checks and options as :meth:`from_polygons`
    /// (face sides are paired by vertex pair, which is ambiguous where several
    /// sides join the same two vertices). With ``twins`` (the
    /// :attr:`corner_twins` export, int (N,)), the mesh is rebuilt exactly:
    /// the same corners are joined by edges and hole faces are re-created from
    /// the ``-1`` sides, so ``Mesh.from_flat(m.vertices, m.face_sizes,
    /// m.face_indices, twins=m.corner_twins) == m`` for every mesh;
    /// ``allow_multi_edges`` is then not needed and ignored, and an open mesh
    /// (``-1`` twins) is refused only when boundaries are.
    ///
    /// Open meshes are accepted by default and stay open
    /// (``boundaries="keep"``); ``boundaries="refuse"`` or the legacy
    /// ``close_boundaries=False`` refuse them, as in :meth:`from_polygons`.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     As :meth:`from_polygons`; with ``twins`` also naming the corner and
    ///     face of a twin out of range, asymmetric, or not running between the
    ///     same two vertices in the opposite direction.
    #[staticmethod]
    #[pyo3(signature = (vertices, face_sizes, face_indices, close_boundaries = None, allow_multi_edges = false, twins = None, boundaries = "keep"))]
    #[allow(clippy::too_many_arguments)]
    fn from_flat(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        face_sizes: &Bound<'_, PyAny>,
        face_indices: &Bound<'_, PyAny>,
        close_boundaries: Option<bool>,
        allow_multi_edges: bool,
        twins: Option<&Bound<'_, PyAny>>,
        boundaries: &str,
    ) -> PyResult<PyMesh> {
        let keep = super::boundary::keep_boundaries("from_flat", close_boundaries, boundaries)?;
        let pos = positions(py, vertices)?;
        let sizes = indices_1d(py, face_sizes, "face_sizes")?;
        match twins {
            Some(t) if !t.is_none() => {
                // int32 indices and twins (a PLY file's) are read as they are
                if let (Ok(i), Ok(w)) = (face_indices.cast::<PyArray1<i32>>(), t.cast::<PyArray1<i32>>()) {
                    let (i, w) = (numpy::PyArrayMethods::readonly(i), numpy::PyArrayMethods::readonly(w));
                    if let (Ok(i), Ok(w)) = (i.as_slice(), w.as_slice()) {
                        let s = sizes.as_slice();
                        let m = super::run_interruptible(py, || Mesh::from_corner_twins_i32(pos, s, i, w))?;
                        if !keep {
                            super::boundary::refuse_open("from_flat", &m)?;
                        }
                        return Ok(PyMesh::wrap(m));
                    }
                }
                let idx = indices_1d(py, face_indices, "face_indices")?;
                let t = indices_1d(py, t, "twins")?;
                let m = build_twins(py, pos, sizes.as_slice(), idx.as_slice(), t.as_slice())?;
                if !keep {
                    super::boundary::refuse_open("from_flat", &m.inner)?;
                }
                Ok(m)
            }
            _ => match int32_array(face_indices, 1) {
                // int32 indices (a foreign PLY file's) are read as they are
                Some(i) => build(py, pos, sizes.as_slice(), FlatIndices::I32(i.as_slice()?), keep, allow_multi_edges),
                None => build(py, pos, sizes.as_slice(), FlatIndices::I64(indices_1d(py, face_indices, "face_indices")?.as_slice()), keep, allow_multi_edges),
            },
        }
    }

    /// Vertex coordinates, float64 array of shape (V, 3): a read-only view of
    /// the mesh's own buffer (no copy; ``np.array(m.vertices)`` for a
    /// writable copy).
    #[getter]
    fn vertices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let p = slf.get().inner.positions();
        // SAFETY: DVec3 is repr(C) of three f64 (24 bytes, no padding), so
        // the positions are a contiguous (V, 3) f64 buffer; it belongs to the
        // frozen mesh, which becomes the array's base.
        let a = unsafe {
            let view = ArrayView2::from_shape_ptr((p.len(), 3), p.as_ptr() as *const f64);
            PyArray2::borrow_from_array(&view, slf.clone().into_any())
        };
        a.getattr("flags")?.setattr("writeable", false)?;
        Ok(a)
    }

    /// Number of corners of each exported face, int64 (F,), read-only (computed
    /// once, then a view). Hole faces are left out.
    #[getter]
    fn face_sizes<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        view_1d(slf, &slf.get().polygons(slf.py()).0)
    }

    /// Vertex indices of all exported faces, concatenated, int64, read-only.
    /// Self-loops show as a vertex repeated in a row. With :attr:`face_sizes`
    /// and :attr:`corner_twins` this describes the mesh exactly.
    #[getter]
    fn face_indices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        view_1d(slf, &slf.get().polygons(slf.py()).1)
    }

    /// The twin of every exported corner, int64 aligned with
    /// :attr:`face_indices`, read-only: the corner on the other side of the
    /// edge that starts at this corner, -1 when that side belongs to a hole
    /// face (a boundary side), -2 for a point-sphere's lone corner. Pass it as
    /// ``twins`` to :meth:`from_flat` to rebuild the mesh exactly; hole faces
    /// are re-created one per boundary loop, after the given faces, in order of
    /// the loop's lowest boundary corner, starting at that corner's twin.
    #[getter]
    fn corner_twins<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        view_1d(slf, slf.get().twins(slf.py()))
    }

    /// Whether OBJ/OFF (a polygon list without twins) reproduce this mesh:
    /// :meth:`from_polygons` of the exports (with ``allow_multi_edges=True``,
    /// and ``close_boundaries=True`` if it has holes) gives it back.
    fn _polygons_are_lossless(&self, py: Python<'_>) -> bool {
        super::detach(py, || self.inner.polygons_are_lossless())
    }

    /// ``pickle`` support: rebuilt exactly from the lossless flat arrays,
    /// with creases and attributes.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let py = slf.py();
        let f = py.import("topomesh.io")?.getattr("_from_state")?;
        let args = (
            Self::vertices(slf)?.call_method0("copy")?,
            Self::face_sizes(slf)?.call_method0("copy")?,
            Self::face_indices(slf)?.call_method0("copy")?,
            Self::corner_twins(slf)?.call_method0("copy")?,
            slf.get()._data_state(py)?,
        );
        Ok((f, args.into_pyobject(py)?.into_any()))
    }

    /// Faces in pyvista/VTK layout ``[n, i0, ..., n, ...]``, int64.
    #[getter]
    fn padded_faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let p = super::detach(py, || self.inner.to_padded_faces());
        i64_array(py, p.iter().map(|&s| s as i64))
    }

    /// The two end vertices of every edge, int64 (E, 2).
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let m = &self.inner;
        let rows: Vec<[u32; 2]> = m.edges().map(|e| [m.vertex(e.halfedge()).0, m.head(e.halfedge()).0]).collect();
        u32_rows(py, &rows)
    }

    /// Number of vertices, point-spheres included.
    #[getter]
    fn n_vertices(&self) -> usize {
        self.inner.n_vertices()
    }
    /// Number of edges (each is two half-edges; self-loops and multi-edges count once per edge).
    #[getter]
    fn n_edges(&self) -> usize {
        self.inner.n_edges()
    }
    /// Number of faces, hole faces included (see :attr:`n_holes`): an open
    /// mesh has ``n_faces - n_holes`` real faces (those of :attr:`face_sizes`).
    #[getter]
    fn n_faces(&self) -> usize {
        self.inner.n_faces()
    }
    /// Hole faces: one per boundary loop of an open mesh (the same as
    /// :attr:`n_boundary_loops`).
    #[getter]
    fn n_holes(&self) -> usize {
        self.inner.n_holes()
    }
    /// χ = V − E + F of the surface as it is: hole faces (boundary loops) are
    /// not counted, so χ = 2c − 2g − b (c components, g :attr:`genus`, b
    /// :attr:`n_boundary_loops`); on a closed mesh the usual 2c − 2g.
    #[getter]
    fn euler_characteristic(&self) -> i64 {
        self.inner.euler_characteristic()
    }
    /// Total genus: the sum of the genera of the components (computed once).
    /// An open mesh has the genus of its surface with every boundary loop
    /// capped by a disk.
    #[getter]
    fn genus(&self, py: Python<'_>) -> i64 {
        *self.cache.genus.get_or_init(|| super::detach(py, || self.inner.genus()))
    }
    /// Genus of each connected component, as a list.
    #[getter]
    fn component_genera(&self) -> Vec<i64> {
        self.inner.component_genera()
    }
    /// Number of connected components (computed once).
    #[getter]
    fn n_components(&self, py: Python<'_>) -> usize {
        *self.cache.n_components.get_or_init(|| super::detach(py, || self.inner.n_components()))
    }
    /// Edges whose two ends are the same vertex.
    #[getter]
    fn n_self_loops(&self) -> usize {
        self.inner.n_self_loops()
    }
    /// ``{face size: count}``, holes included.
    #[getter]
    fn face_size_histogram(&self) -> std::collections::BTreeMap<usize, usize> {
        self.inner.face_size_histogram()
    }
    /// ``{valence: count}``; a self-loop adds 2 to its vertex's valence.
    #[getter]
    fn valence_histogram(&self) -> std::collections::BTreeMap<usize, usize> {
        self.inner.valence_histogram()
    }
    /// Mean of each face's corner positions, float64 (F, 3), holes included.
    #[getter]
    fn face_centroids<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let c = super::detach(py, || self.inner.face_centroids());
        vec3_array(py, &c)
    }
    /// Unit face normals by Newell's method, float64 (F, 3); zero rows for
    /// degenerate faces.
    #[getter]
    fn face_normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let c = super::detach(py, || self.inner.face_normals());
        vec3_array(py, &c)
    }
    /// Area-weighted unit vertex normals, float64 (V, 3).
    #[getter]
    fn vertex_normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let c = super::detach(py, || self.inner.vertex_normals());
        vec3_array(py, &c)
    }
    /// Signed enclosed volume; positive when faces are oriented outward.
    #[getter]
    fn volume(&self) -> f64 {
        self.inner.signed_volume()
    }

    /// Triangles for rendering and validation, int64 (T, 3).
    ///
    /// The triangles of :meth:`triangulate`: indices ``>= n_vertices`` refer
    /// to the points it adds (``triangulate()[0][n_vertices:]``), so pair
    /// these triangles with ``triangulate()``'s vertices, not with
    /// :attr:`vertices`, unless ``triangles().max() < n_vertices``. With
    /// ``return_faces=True`` also returns the source face of every triangle.
    #[pyo3(signature = (return_faces = false))]
    fn triangles<'py>(&self, py: Python<'py>, return_faces: bool) -> PyResult<Bound<'py, PyAny>> {
        // all-triangle meshes: the faces themselves, straight into one buffer (issue 19)
        // (checked while written: one walk, the multi-edge search beside it)
        let nf = self.inner.n_faces();
        if self.inner.may_be_plain_triangles() {
            // SAFETY: every entry is written before the array is returned; when
            // the faces turn out not to be the triangles, the array is dropped.
            let arr = unsafe { PyArray2::<i64>::new(py, [nf, 3], false) };
            let plain = {
                use numpy::PyArrayMethods;
                let mut rw = arr.readwrite();
                let out = rw.as_slice_mut().map_err(|e| arg_err(e.to_string()))?;
                super::detach(py, || self.inner.write_triangle_faces_if_plain(out))
            };
            if !plain {
                return self.triangles_general(py, return_faces);
            }
            let tris = arr.into_any();
            return if return_faces {
                Ok((tris, i64_array(py, 0..nf as i64)).into_pyobject(py)?.into_any())
            } else {
                Ok(tris)
            };
        }
        self.triangles_general(py, return_faces)
    }

    /// A closed triangle mesh of this mesh: ``(vertices, triangles, faces)``.
    ///
    /// ``vertices`` float64 (V + S, 3) are :attr:`vertices` followed by S
    /// added points; ``triangles`` int64 (T, 3) index them,
    /// counter-clockwise seen from outside; ``faces`` int64 (T,) is the source
    /// face of each triangle (triangles are grouped by face, in face order).
    ///
    /// Each face is triangulated in the plane of its Newell normal (fanned
    /// if convex, strictly convex faces of more than 32 corners by ears of
    /// every other corner, repeatedly; ear-clipped otherwise) so that no diagonal is an edge of
    /// the mesh or another face's diagonal: on a mesh without self-loops,
    /// one- or two-gons or vertices repeated in a face, every triangle edge
    /// has exactly two triangles. Points are added where that needs them:
    /// the middle of every extra edge between the same two vertices
    /// (multi-edges), then, in face order, one point inside each face with no
    /// fitting triangulation by diagonals (the corners' mean, when the face
    /// is star-shaped from it; otherwise one point beside the middle of each
    /// colliding diagonal). Self-loop repeats are dropped and faces left with
    /// fewer than three corners give no triangle (the triangle mesh pinches
    /// there); holes are left out.
    fn triangulate<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>, Bound<'py, PyArray1<i64>>)> {
        let t = super::run_interruptible(py, || {
            let t = self.inner.triangulate();
            crate::cancel::check().map(|()| t)
        })?;
        let mut v = self.inner.positions().to_vec();
        v.extend_from_slice(&t.points);
        Ok((vec3_array(py, &v), u32_rows(py, &t.tris), i64_array(py, t.tri_face.iter().map(|&x| x as i64))))
    }

    /// Check every structural invariant; raise :class:`MeshError` naming the
    /// first one broken. A mesh made by topomesh always passes.
    fn validate(&self, py: Python<'_>) -> PyResult<()> {
        super::detach(py, || self.inner.validate()).map_err(err)
    }

    // ------------------------------------------------ fundamental operators

    /// CreateVertex(p) (dissertation ch. II.5): a new mesh with an added
    /// point-sphere at ``p``. Returns ``(mesh, vertex, face)``.
    /// V+1, F+1, components+1, genus unchanged.
    fn create_vertex(&self, #[pyo3(from_py_with = vertex_point)] point: [f64; 3]) -> PyResult<(PyMesh, usize, usize)> {
        super::data::warn_dropped(&self.data, "create_vertex")?;
        let mut m = self.inner.clone();
        let (v, f) = m.create_vertex(DVec3::from_array(point)).map_err(err)?;
        Ok((PyMesh::wrap(m), v.idx(), f.idx()))
    }

    /// DeleteVertex(v): a new mesh without the point-sphere ``v``. The last
    /// vertex takes index ``v`` and the last face the point-sphere's face
    /// index. Raises :class:`MeshError` if ``v`` has edges.
    fn delete_vertex(&self, #[pyo3(from_py_with = super::sat_i64)] vertex: i64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "delete_vertex")?;
        if vertex < 0 || vertex as usize >= self.inner.n_vertices() {
            return Err(arg_err(format!("vertex {vertex} out of range (mesh has {} vertices)", self.inner.n_vertices())));
        }
        let mut m = self.inner.clone();
        m.delete_vertex(VertexId(vertex as u32)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// InsertEdge(c1, c2): a new mesh with an edge between corner
    /// ``position1`` of ``face1`` and corner ``position2`` of ``face2``
    /// (positions as in :attr:`face_indices`). Returns ``(mesh, edge)``.
    ///
    /// Same face: it splits (F+1, genus unchanged). Two faces of one
    /// component: they merge (F−1, genus+1). Two components: they join
    /// (F−1, components−1).
    fn insert_edge(&self, #[pyo3(from_py_with = super::sat_i64)] face1: i64, #[pyo3(from_py_with = super::sat_i64)] position1: i64, #[pyo3(from_py_with = super::sat_i64)] face2: i64, #[pyo3(from_py_with = super::sat_i64)] position2: i64) -> PyResult<(PyMesh, usize)> {
        super::data::warn_dropped(&self.data, "insert_edge")?;
        let c1 = self.corner(face1, position1)?;
        let c2 = self.corner(face2, position2)?;
        let mut m = self.inner.clone();
        let e = m.insert_edge(c1, c2).map_err(err)?;
        Ok((PyMesh::wrap(m), e.idx()))
    }

    /// DeleteEdge(e): a new mesh without edge ``e`` (inverse of
    /// :meth:`insert_edge`). Different faces on its sides merge (F−1); the
    /// same face on both sides separates (F+1, genus−1 or components+1).
    fn delete_edge(&self, #[pyo3(from_py_with = super::sat_i64)] edge: i64) -> PyResult<PyMesh> {
        super::data::warn_dropped(&self.data, "delete_edge")?;
        if edge < 0 || edge as usize >= self.inner.n_edges() {
            return Err(arg_err(format!("edge {edge} out of range (mesh has {} edges)", self.inner.n_edges())));
        }
        let mut m = self.inner.clone();
        m.delete_edge(EdgeId(edge as u32)).map_err(err)?;
        Ok(PyMesh::wrap(m))
    }

    /// A new mesh with the same connectivity and new vertex positions (V, 3).
    fn with_vertices(&self, py: Python<'_>, vertices: &Bound<'_, PyAny>) -> PyResult<PyMesh> {
        let pos = positions(py, vertices)?;
        if pos.len() != self.inner.n_vertices() {
            return Err(arg_err(format!("with_vertices: got {} vertices, mesh has {}", pos.len(), self.inner.n_vertices())));
        }
        if let Some(v) = pos.iter().position(|p| !p.is_finite()) {
            return Err(err(crate::MeshError::NonFinite { vertex: v }));
        }
        let mut m = self.inner.clone();
        m.positions_mut().copy_from_slice(&pos);
        Ok(PyMesh::with_data(m, self.data.clone_ref(py)))
    }

    // -------------------------------------------- interop (pure Python side)

    /// A ``trimesh.Trimesh`` of :meth:`triangles` (``process=False``); an
    /// open mesh stays open (``is_watertight`` False, the same boundary edges).
    fn to_trimesh<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Self::delegate(slf, "topomesh._interop", "to_trimesh", &[])
    }
    /// A ``pyvista.PolyData`` with the polygon faces (no triangulation; hole
    /// faces left out, so an open mesh stays open).
    fn to_pyvista<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Self::delegate(slf, "topomesh._interop", "to_pyvista", &[])
    }
    /// A ``manifold3d.Manifold`` of :meth:`triangles`; raises
    /// :class:`MeshError` for an open mesh (manifold3d holds closed solids).
    fn to_manifold<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Self::delegate(slf, "topomesh._interop", "to_manifold", &[])
    }
    /// Write to ``path``, atomically; the format comes from the extension:
    /// ``.npz`` and ``.ply`` keep every mesh exactly, ``.obj`` and ``.off``
    /// only meshes their polygon list gives back (else :class:`MeshError`
    /// naming the lossless formats), ``.stl`` (binary, float32) and
    /// ``.3mf`` (through trimesh) the triangles of :meth:`triangulate`, for
    /// printers. See :func:`topomesh.io.save`.
    fn save<'py>(slf: &Bound<'py, Self>, path: &Bound<'py, PyAny>) -> PyResult<()> {
        Self::delegate(slf, "topomesh.io", "save", &[path.clone()])?;
        Ok(())
    }

    /// Write OBJ or OFF text (``format`` "obj" or "off") to ``path``; used by
    /// :func:`topomesh.io.save`.
    fn _write_text(&self, py: Python<'_>, path: std::path::PathBuf, format: &str) -> PyResult<()> {
        let fmt = match format {
            "obj" => crate::io::TextFormat::Obj,
            "off" => crate::io::TextFormat::Off,
            _ => return Err(arg_err(format!("unknown text format {format:?}"))),
        };
        super::detach(py, || {
            let f = std::fs::File::create(&path)
                .map_err(|e| crate::MeshError::Io(format!("{}: {e}", path.display())))?;
            crate::io::write_text(&self.inner, fmt, f)
        })
        .map_err(err)
    }

    fn __repr__(&self) -> String {
        let m = &self.inner;
        let open = if m.is_closed() { String::new() } else { format!(", boundary_loops={}", m.n_boundary_loops()) };
        format!(
            "Mesh(V={}, E={}, F={}, genus={}, components={}{open})",
            m.n_vertices(),
            m.n_edges(),
            m.n_faces(),
            m.genus(),
            m.n_components()
        )
    }

    /// Equal when the lossless exports are: same vertices (exactly), same
    /// faces with the same corner order, the same corners joined by edges
    /// (:attr:`corner_twins`), and as many edges and hole faces (the twins'
    /// -1 sides determine the hole faces). Edge ids are not compared.
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> bool {
        let Ok(o) = other.cast::<PyMesh>() else { return false };
        let o = o.get();
        let (a, b) = (&self.inner, &o.inner);
        a.positions() == b.positions()
            && a.n_edges() == b.n_edges()
            && a.n_holes() == b.n_holes()
            && self.polygons(py) == o.polygons(py)
            && self.twins(py) == o.twins(py)
    }

    fn __copy__(slf: Py<Self>) -> Py<Self> {
        slf
    }
    fn __deepcopy__(slf: Py<Self>, _memo: &Bound<'_, PyAny>) -> Py<Self> {
        slf
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMesh>()?;
    super::primitives::register(m)
}
