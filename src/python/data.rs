//! Data a `Mesh` carries beside its geometry: crease sharpness (per edge and
//! per vertex) and named vertex and face attributes. The schemes carry them
//! to their output (`super::levels`); the topological operators return
//! meshes without them.

use super::mesh::PyMesh;
use super::arg_err;
use crate::schemes::creases::{edges_sharper_than, Creases, INFINITE};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// Crease sharpness and attributes of a mesh.
#[derive(Default)]
pub struct MeshData {
    pub creases: Option<Creases>,
    /// `(name, array)`: float64 arrays of shape (V,) or (V, k), read-only.
    pub vertex: Vec<(String, Py<PyAny>)>,
    /// `(name, array)`: arrays of any dtype whose first axis runs over the
    /// exported faces, read-only.
    pub face: Vec<(String, Py<PyAny>)>,
    /// `(name, array)`: float64 arrays of shape (C,) or (C, k), one row per
    /// exported corner (aligned with `face_indices`), read-only.
    pub corner: Vec<(String, Py<PyAny>)>,
}

/// Warns (`GeometryWarning`) that operator `op` returns a mesh without the
/// input's creases and attributes: the local operators and the object
/// tools rebuild faces and edges and carry positions only (the Conway
/// operators and TopMod's remeshing schemes carry face attributes, see
/// [`inherited`]), and data must never vanish unannounced. The message
/// names what is dropped.
pub(crate) fn warn_dropped(data: &MeshData, op: &str) -> PyResult<()> {
    warn_dropping(data, op, false, false)
}

/// The output of a remeshing operator (Conway, TopMod) from `input`, with
/// the input's face attributes inherited through `parents` (per output
/// face, the input face it descends from:
/// `crate::schemes::face_parents`), after warning about the rest. Without
/// parents (a step of the chain does not record them) everything is
/// dropped with the warning, as before issue 15.
pub(crate) fn inherited(py: Python<'_>, data: &MeshData, op: &str, input: &crate::Mesh, out: crate::Mesh, parents: Option<Vec<u32>>) -> PyResult<PyMesh> {
    finite_output(op, input, &out)?;
    if data.is_empty() {
        return Ok(PyMesh::wrap(out));
    }
    // these operators refuse holes, so internal face ids are the exported ones
    let usable = |p: &Vec<u32>| p.len() == out.n_faces() && input.n_holes() == 0 && out.n_holes() == 0;
    let Some(p) = parents.filter(|p| !data.face.is_empty() && usable(p)) else {
        warn_dropped(data, op)?;
        return Ok(PyMesh::wrap(out));
    };
    warn_dropping(data, op, false, true)?;
    let idx = numpy::PyArray1::from_vec(py, p.into_iter().map(i64::from).collect::<Vec<i64>>());
    let mut d = MeshData::default();
    for (name, a) in &data.face {
        let arr = a.bind(py).call_method1("take", (&idx, 0))?;
        arr.getattr("flags")?.setattr("writeable", false)?;
        d.face.push((name.clone(), arr.unbind()));
    }
    Ok(PyMesh::with_data(out, d))
}

/// A `MeshError` naming `op` when its output has a non-finite position
/// (an operator's arithmetic overflowing f64 on coordinates near its
/// limit), instead of handing over a mesh that fails validation. Checked
/// when the input has a coordinate past 2^100 or a nonzero one below
/// 2^-100, the only inputs where products of lengths leave f64.
pub(crate) fn finite_output(op: &str, input: &crate::Mesh, out: &crate::Mesh) -> PyResult<()> {
    use rayon::prelude::*;
    // overflow and underflow need coordinates far from 1: only then is the
    // output scanned (a pass over its positions is ~4 % of a fast operator)
    // in this process's pool, never rayon's global one (`pool` module docs)
    let (low, top) = super::pool::run(|| crate::geometry::coordinate_range(input.positions()));
    if top <= 2f64.powi(100) && low >= 2f64.powi(-100) {
        return Ok(());
    }
    let finite = |c: &[glam::DVec3]| c.iter().fold(true, |ok, p| ok & p.is_finite());
    if super::pool::run(|| out.positions().par_chunks(1 << 14).all(finite)) {
        return Ok(());
    }
    let v = out.positions().iter().position(|p| !p.is_finite()).unwrap_or(0);
    Err(super::err(crate::MeshError::Precondition(format!(
        "{op}: output vertex {v} has a non-finite position: the arithmetic overflows float64 on this mesh's coordinates \
         (largest magnitude {top:e}); scale the mesh down first"
    ))))
}

/// Runs `build` from `input`, recording face parents when `want` (the
/// input has face attributes to inherit), else plainly.
pub(crate) fn build_traced(want: bool, input: &crate::Mesh, build: impl FnOnce() -> crate::Result<crate::Mesh>) -> crate::Result<(crate::Mesh, Option<Vec<u32>>)> {
    if want {
        crate::schemes::face_parents::traced(input, build)
    } else {
        Ok((build()?, None))
    }
}

/// The names of what `data` holds beside what is kept (`vertex`, `face`:
/// those attributes survive), e.g. `creases, vertex attributes ["c"]`.
fn dropped_names(data: &MeshData, vertex: bool, face: bool) -> Vec<String> {
    let list = |what: &str, v: &[(String, Py<PyAny>)]| -> Option<String> {
        (!v.is_empty()).then(|| format!("{what} attributes [{}]", v.iter().map(|(n, _)| format!("{n:?}")).collect::<Vec<_>>().join(", ")))
    };
    let mut out = Vec::new();
    if data.creases.is_some() {
        out.push("creases".to_string());
    }
    out.extend(if vertex { None } else { list("vertex", &data.vertex) });
    out.extend(if face { None } else { list("face", &data.face) });
    out.extend(list("corner", &data.corner));
    out
}

/// [`warn_dropped`] for an operator that keeps the vertex and/or face
/// attributes (same vertices, or same faces in the same order): warns about
/// the rest only.
pub(crate) fn warn_dropping(data: &MeshData, op: &str, vertex: bool, face: bool) -> PyResult<()> {
    let names = dropped_names(data, vertex, face);
    if names.is_empty() {
        return Ok(());
    }
    Python::attach(|py| {
        let msg = format!(
            "{op}: the result does not carry the input's {} (this operator rebuilds the faces and edges and keeps positions only); \
             attach them again with with_creases / with_attributes, or call without_data() first to silence this",
            names.join(", ")
        );
        PyErr::warn(py, &py.get_type::<super::GeometryWarning>(), &std::ffi::CString::new(msg).expect("no NUL"), 1)
    })
}

/// The data an operator keeps: all of it when `all` (positions moved,
/// topology and numbering unchanged), else the vertex and face attributes
/// as flagged, after warning about the rest ([`warn_dropping`]).
pub(crate) fn kept(py: Python<'_>, data: &MeshData, op: &str, all: bool, vertex: bool, face: bool) -> PyResult<MeshData> {
    if all {
        return Ok(data.clone_ref(py));
    }
    warn_dropping(data, op, vertex, face)?;
    let c = |v: &Vec<(String, Py<PyAny>)>| v.iter().map(|(n, a)| (n.clone(), a.clone_ref(py))).collect();
    Ok(MeshData { creases: None, vertex: if vertex { c(&data.vertex) } else { vec![] }, face: if face { c(&data.face) } else { vec![] }, corner: vec![] })
}

impl MeshData {
    pub fn is_empty(&self) -> bool {
        self.creases.is_none() && self.vertex.is_empty() && self.face.is_empty() && self.corner.is_empty()
    }
    pub fn clone_ref(&self, py: Python<'_>) -> MeshData {
        let c = |v: &Vec<(String, Py<PyAny>)>| v.iter().map(|(n, a)| (n.clone(), a.clone_ref(py))).collect();
        MeshData { creases: self.creases.clone(), vertex: c(&self.vertex), face: c(&self.face), corner: c(&self.corner) }
    }
}

/// A read-only copy of `a` as a NumPy array (of `dtype` if given).
fn frozen_copy<'py>(py: Python<'py>, a: &Bound<'py, PyAny>, dtype: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    let kw = PyDict::new(py);
    kw.set_item("copy", true)?;
    if let Some(d) = dtype {
        kw.set_item("dtype", d)?;
    }
    let c = np.call_method("array", (a,), Some(&kw))?;
    c.getattr("flags")?.setattr("writeable", false)?;
    Ok(c)
}

/// Sharpness values: finite and >= 0, or +inf (stored as OpenSubdiv's 10).
fn sharpness_value(call: &str, what: &str, s: f64) -> PyResult<f64> {
    if s.is_nan() || s < 0.0 {
        return Err(arg_err(format!("{call}: {what} has sharpness {}; sharpness must be >= 0 (inf or >= 10: infinitely sharp)", crate::error::num(s))));
    }
    Ok(if s >= INFINITE { INFINITE } else { s })
}

/// Reads per-element sharpness: an array of `n` numbers, or a mapping from
/// keys to numbers resolved by `key`.
fn read_sharpness(
    py: Python<'_>,
    call: &str,
    what: &str,
    obj: &Bound<'_, PyAny>,
    n: usize,
    key: impl Fn(&Bound<'_, PyAny>) -> PyResult<Vec<usize>>,
) -> PyResult<Vec<f64>> {
    let mut out = vec![0.0; n];
    if let Ok(d) = obj.cast::<PyDict>() {
        for (k, v) in d.iter() {
            let s: f64 = v.extract().map_err(|_| arg_err(format!("{call}: the sharpness of {what} {k} is not a number")))?;
            let s = sharpness_value(call, &format!("{what} {k}"), s)?;
            for i in key(&k)? {
                out[i] = s;
            }
        }
        return Ok(out);
    }
    let a = py.import("numpy")?.call_method1("asarray", (obj, "float64")).map_err(|e| arg_err(format!("{call}: {what} sharpness cannot be read as numbers ({e})")))?;
    let a = a.cast_into::<PyArray1<f64>>().map_err(|_| arg_err(format!("{call}: {what} sharpness must be a 1-D array of {n} numbers or a mapping")))?;
    if a.len() != n {
        return Err(arg_err(format!("{call}: {} {what} sharpness values for {n} {what}s", a.len())));
    }
    let ro = a.readonly();
    for (i, (&s, o)) in ro.as_array().iter().zip(out.iter_mut()).enumerate() {
        *o = sharpness_value(call, &format!("{what} {i}"), s)?;
    }
    Ok(out)
}

#[pymethods]
impl PyMesh {
    /// A copy with crease sharpness (DeRose, Kass & Truong 1998, as in
    /// OpenSubdiv), used by :meth:`catmull_clark` and :meth:`loop` and
    /// carried to their output.
    ///
    /// Parameters
    /// ----------
    /// edge_sharpness : array of shape (E,) or dict, optional
    ///     Per edge, aligned with :attr:`edges`; or a mapping from vertex
    ///     pairs ``(a, b)`` (either order; every edge between them) to
    ///     sharpness. 0 is smooth, ``inf`` (or anything >= 10) infinitely
    ///     sharp; a semi-sharp crease of sharpness s stays sharp for s
    ///     levels.
    /// vertex_sharpness : array of shape (V,) or dict, optional
    ///     Per vertex corner sharpness, or a mapping from vertex to it.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///     The same mesh and attributes with these creases (replacing any).
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A negative or NaN sharpness, a wrong length, or a pair that is no edge.
    #[pyo3(signature = (edge_sharpness = None, vertex_sharpness = None))]
    fn with_creases(&self, py: Python<'_>, edge_sharpness: Option<&Bound<'_, PyAny>>, vertex_sharpness: Option<&Bound<'_, PyAny>>) -> PyResult<PyMesh> {
        let m = &self.inner;
        let call = "with_creases";
        let edge = match edge_sharpness {
            None => vec![0.0; m.n_edges()],
            Some(o) => {
                let mut by_pair: std::collections::HashMap<(u32, u32), Vec<usize>> = std::collections::HashMap::new();
                if o.is_instance_of::<PyDict>() {
                    for e in 0..m.n_edges() {
                        let (a, b) = (m.he_vert[2 * e], m.he_vert[2 * e + 1]);
                        by_pair.entry((a.min(b), a.max(b))).or_default().push(e);
                    }
                }
                read_sharpness(py, call, "edge", o, m.n_edges(), |k| {
                    let (a, b): (i64, i64) = k.extract().map_err(|_| arg_err(format!("{call}: edge key {k} is not a vertex pair (a, b)")))?;
                    let key = (a.min(b), a.max(b));
                    if key.0 < 0 {
                        return Err(arg_err(format!("{call}: ({a}, {b}) is not an edge of the mesh")));
                    }
                    by_pair.get(&(key.0 as u32, key.1 as u32)).cloned().ok_or_else(|| arg_err(format!("{call}: ({a}, {b}) is not an edge of the mesh")))
                })?
            }
        };
        let vertex = match vertex_sharpness {
            None => vec![0.0; m.n_vertices()],
            Some(o) => read_sharpness(py, call, "vertex", o, m.n_vertices(), |k| {
                let v: i64 = k.extract().map_err(|_| arg_err(format!("{call}: vertex key {k} is not an integer")))?;
                if v < 0 || v as usize >= m.n_vertices() {
                    return Err(arg_err(format!("{call}: vertex {v} out of range (mesh has {} vertices)", m.n_vertices())));
                }
                Ok(vec![v as usize])
            })?,
        };
        let mut data = self.data.clone_ref(py);
        data.creases = Some(Creases { edge, vertex });
        Ok(PyMesh::with_data(m.clone(), data))
    }

    /// A copy whose edges with a dihedral angle above ``angle`` degrees
    /// (between the normals of their two faces) get crease ``sharpness``
    /// (kept where the edge is already sharper); boundary edges are sharp
    /// already. Other creases and attributes are kept.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``angle`` outside [0, 180] or a negative/NaN ``sharpness``.
    #[pyo3(signature = (angle = 30.0, sharpness = f64::INFINITY))]
    fn mark_creases(&self, py: Python<'_>, angle: f64, sharpness: f64) -> PyResult<PyMesh> {
        let angle = super::finite_in("mark_creases", "angle", angle, 0.0, 180.0)?;
        let s = sharpness_value("mark_creases", "the given edges", sharpness)?;
        let m = &self.inner;
        let edges = super::detach(py, || edges_sharper_than(m, angle.to_radians()));
        let mut data = self.data.clone_ref(py);
        let c = data.creases.get_or_insert_with(|| Creases { edge: vec![0.0; m.n_edges()], vertex: vec![0.0; m.n_vertices()] });
        for e in edges {
            let x = &mut c.edge[e as usize];
            *x = x.max(s);
        }
        Ok(PyMesh::with_data(m.clone(), data))
    }

    /// Crease sharpness per edge (aligned with :attr:`edges`), float64;
    /// ``inf`` for infinitely sharp, zeros without creases.
    #[getter]
    fn edge_sharpness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let n = self.inner.n_edges();
        let v: Vec<f64> = (0..n).map(|e| self.data.creases.as_ref().map_or(0.0, |c| c.edge(e))).map(shown).collect();
        PyArray1::from_vec(py, v)
    }

    /// Corner sharpness per vertex, float64 (``inf`` for infinite).
    #[getter]
    fn vertex_sharpness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let n = self.inner.n_vertices();
        let v: Vec<f64> = (0..n).map(|i| self.data.creases.as_ref().map_or(0.0, |c| c.vertex(i))).map(shown).collect();
        PyArray1::from_vec(py, v)
    }

    /// A copy with named attributes (added to, or replacing, those of the
    /// same name), carried through every scheme.
    ///
    /// Parameters
    /// ----------
    /// vertex : dict of str to array, optional
    ///     Arrays of shape (V,) or (V, k) of finite numbers (colours,
    ///     scalars, another pose's positions); the schemes interpolate them
    ///     with their own vertex weights (``S @ a``), so they come out as
    ///     float64.
    /// face : dict of str to array, optional
    ///     Arrays whose first axis has one entry per face (as
    ///     :attr:`face_sizes`), any dtype (material or group ids); every
    ///     child face inherits its parent's entry.
    /// corner : dict of str to array or (table, index), optional
    ///     Face-varying data such as UVs with seams: per corner (aligned
    ///     with :attr:`face_indices`) an array of shape (C,) or (C, k), or a
    ///     value table (n, k) with an index per corner (as OBJ's ``vt``).
    ///     An edge is a seam where its two sides' values differ.
    ///     :meth:`catmull_clark` and :meth:`loop` subdivide them with
    ///     OpenSubdiv's face-varying rules (``corner_interpolation``);
    ///     every other scheme carries them with its own vertex weights read
    ///     within one input face's values (never across a seam).
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A wrong length, a non-numeric or non-finite vertex attribute.
    #[pyo3(signature = (vertex = None, face = None, corner = None))]
    fn with_attributes(&self, py: Python<'_>, vertex: Option<&Bound<'_, PyDict>>, face: Option<&Bound<'_, PyDict>>, corner: Option<&Bound<'_, PyDict>>) -> PyResult<PyMesh> {
        let m = &self.inner;
        let mut data = self.data.clone_ref(py);
        let n_faces = m.n_faces() - m.n_holes();
        let np = py.import("numpy")?;
        if let Some(d) = vertex {
            for (k, a) in d.iter() {
                let name: String = k.extract().map_err(|_| arg_err(format!("with_attributes: vertex attribute name {k} is not a string")))?;
                let raw = np.call_method1("asarray", (&a,))?;
                let kind: String = raw.getattr("dtype")?.getattr("kind")?.extract()?;
                if !matches!(kind.as_str(), "f" | "i" | "u" | "b") {
                    return Err(arg_err(format!("with_attributes: vertex attribute {name:?} has dtype {} (numbers expected: vertex attributes are interpolated)", raw.getattr("dtype")?.str()?)));
                }
                let arr = frozen_copy(py, &raw, Some("float64"))?;
                let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
                if shape.is_empty() || shape.len() > 2 || shape[0] != m.n_vertices() {
                    return Err(arg_err(format!("with_attributes: vertex attribute {name:?} has shape {}, expected ({}, k) or ({},)", shape_str(&shape), m.n_vertices(), m.n_vertices())));
                }
                let finite: bool = np.call_method1("isfinite", (&arr,))?.call_method0("all")?.extract()?;
                if !finite {
                    let bad: usize = np.call_method1("argmin", (np.call_method1("isfinite", (&arr,))?.call_method1("reshape", (shape[0], -1i64))?.call_method1("all", (1,))?,))?.extract()?;
                    return Err(arg_err(format!("with_attributes: vertex attribute {name:?} is not finite at vertex {bad}")));
                }
                data.vertex.retain(|(n, _)| *n != name);
                data.vertex.push((name, arr.unbind()));
            }
        }
        if let Some(d) = face {
            for (k, a) in d.iter() {
                let name: String = k.extract().map_err(|_| arg_err(format!("with_attributes: face attribute name {k} is not a string")))?;
                let arr = frozen_copy(py, &a, None)?;
                let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
                if shape.is_empty() || shape[0] != n_faces {
                    return Err(arg_err(format!("with_attributes: face attribute {name:?} has shape {}, expected first axis {n_faces} (one per face)", shape_str(&shape))));
                }
                data.face.retain(|(n, _)| *n != name);
                data.face.push((name, arr.unbind()));
            }
        }
        if let Some(d) = corner {
            let n_corners: usize = m.faces().filter(|&f| !m.is_hole(f)).map(|f| m.face_degree(f)).sum();
            if m.has_point_spheres() {
                return Err(arg_err("with_attributes: corner attributes need a mesh without point-spheres (their lone corner has no neighbourhood)"));
            }
            for (k, a) in d.iter() {
                let name: String = k.extract().map_err(|_| arg_err(format!("with_attributes: corner attribute name {k} is not a string")))?;
                // (table, index) → per-corner rows
                let a = match a.cast::<PyTuple>() {
                    Ok(t) if t.len() == 2 => {
                        let table = np.call_method1("asarray", (t.get_item(0)?, "float64"))?;
                        let index = np.call_method1("asarray", (t.get_item(1)?,))?;
                        let ikind: String = index.getattr("dtype")?.getattr("kind")?.extract()?;
                        let n: usize = table.getattr("shape")?.get_item(0)?.extract()?;
                        if !matches!(ikind.as_str(), "i" | "u") {
                            return Err(arg_err(format!("with_attributes: corner attribute {name:?}: the index must be integers")));
                        }
                        let size: usize = index.getattr("size")?.extract()?;
                        if size > 0 {
                            let (lo, hi): (i64, i64) = (index.call_method0("min")?.extract()?, index.call_method0("max")?.extract()?);
                            if lo < 0 || hi as usize >= n {
                                return Err(arg_err(format!("with_attributes: corner attribute {name:?}: index values {lo}..{hi} outside the table's {n} rows")));
                            }
                        }
                        table.call_method1("take", (index, 0))?
                    }
                    _ => a,
                };
                let raw = np.call_method1("asarray", (&a,))?;
                let kind: String = raw.getattr("dtype")?.getattr("kind")?.extract()?;
                if !matches!(kind.as_str(), "f" | "i" | "u" | "b") {
                    return Err(arg_err(format!("with_attributes: corner attribute {name:?} has dtype {} (numbers expected)", raw.getattr("dtype")?.str()?)));
                }
                let arr = frozen_copy(py, &raw, Some("float64"))?;
                let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
                if shape.is_empty() || shape.len() > 2 || shape[0] != n_corners {
                    return Err(arg_err(format!("with_attributes: corner attribute {name:?} has shape {}, expected ({n_corners}, k) or ({n_corners},) (one row per corner, as face_indices)", shape_str(&shape))));
                }
                let finite: bool = np.call_method1("isfinite", (&arr,))?.call_method0("all")?.extract()?;
                if !finite {
                    return Err(arg_err(format!("with_attributes: corner attribute {name:?} is not finite")));
                }
                data.corner.retain(|(n, _)| *n != name);
                data.corner.push((name, arr.unbind()));
            }
        }
        Ok(PyMesh::with_data(m.clone(), data))
    }

    /// The corner (face-varying) attributes: a new dict of read-only
    /// float64 arrays, one row per corner (as :attr:`face_indices`).
    #[getter]
    fn corner_attributes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (n, a) in &self.data.corner {
            d.set_item(n, a.bind(py))?;
        }
        Ok(d)
    }

    /// The vertex attributes: a new dict of read-only float64 arrays.
    #[getter]
    fn vertex_attributes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (n, a) in &self.data.vertex {
            d.set_item(n, a.bind(py))?;
        }
        Ok(d)
    }

    /// The face attributes: a new dict of read-only arrays (one entry per face).
    #[getter]
    fn face_attributes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (n, a) in &self.data.face {
            d.set_item(n, a.bind(py))?;
        }
        Ok(d)
    }

    /// A copy without creases and attributes.
    fn without_data(&self) -> PyMesh {
        PyMesh::wrap(self.inner.clone())
    }

    /// Whether the mesh carries a crease table at all (it may still be all
    /// zeros): lets the writers skip building :meth:`_corner_sharpness`.
    fn _has_creases(&self) -> bool {
        self.data.creases.is_some()
    }

    /// Sharpness of the edge leaving every exported corner (aligned with
    /// :attr:`face_indices`).
    fn _corner_sharpness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let m = &self.inner;
        let mut v = Vec::with_capacity(m.n_halfedges());
        for f in m.faces() {
            if m.is_hole(f) {
                continue;
            }
            if m.face_halfedge(f).is_none() {
                v.push(0.0); // a point-sphere's lone corner
            }
            for h in m.face_halfedges(f) {
                v.push(shown(self.data.creases.as_ref().map_or(0.0, |c| c.edge(h.edge().idx()))));
            }
        }
        PyArray1::from_vec(py, v)
    }

    /// A copy with edge sharpness given per exported corner (as
    /// :meth:`_corner_sharpness`) and vertex sharpness; for unpickling.
    fn _with_corner_sharpness(&self, py: Python<'_>, corner: &Bound<'_, PyAny>, vertex: &Bound<'_, PyAny>) -> PyResult<PyMesh> {
        let m = &self.inner;
        let n_corners = m.faces().filter(|&f| !m.is_hole(f)).map(|f| m.face_degree(f)).sum();
        let cs = read_sharpness(py, "_with_corner_sharpness", "corner", corner, n_corners, |_| Ok(vec![]))?;
        let mut edge = vec![0.0; m.n_edges()];
        let mut c = 0;
        for f in m.faces() {
            if m.is_hole(f) {
                continue;
            }
            if m.face_halfedge(f).is_none() {
                c += 1;
            }
            for h in m.face_halfedges(f) {
                edge[h.edge().idx()] = cs[c];
                c += 1;
            }
        }
        let vs = read_sharpness(py, "_with_corner_sharpness", "vertex", vertex, m.n_vertices(), |_| Ok(vec![]))?;
        let mut data = self.data.clone_ref(py);
        data.creases = Some(Creases { edge, vertex: vs });
        Ok(PyMesh::with_data(m.clone(), data))
    }

    /// `(corner sharpness, vertex_sharpness, vertex attributes, face
    /// attributes)` for pickling, or None.
    pub(crate) fn _data_state<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyTuple>>> {
        if self.data.is_empty() {
            return Ok(None);
        }
        let creases = self.data.creases.is_some();
        // per exported corner: edge ids are renumbered by a rebuild, corners are not
        let es = if creases { Some(self._corner_sharpness(py)) } else { None };
        let vs = if creases { Some(self.vertex_sharpness(py)) } else { None };
        Ok(Some(PyTuple::new(
            py,
            [
                es.into_pyobject(py)?.into_any(),
                vs.into_pyobject(py)?.into_any(),
                self.vertex_attributes(py)?.into_any(),
                self.face_attributes(py)?.into_any(),
                self.corner_attributes(py)?.into_any(),
            ],
        )?))
    }
}

/// A NumPy-style shape: `(7, 3)`, `(5,)`.
fn shape_str(s: &[usize]) -> String {
    match s {
        [a] => format!("({a},)"),
        _ => format!("({})", s.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ")),
    }
}

/// Stored sharpness as users see it (10 = infinite).
fn shown(s: f64) -> f64 {
    if s >= INFINITE {
        f64::INFINITY
    } else {
        s
    }
}

