//! File readers of the core exposed to `topomesh.io` (private helpers).

use super::convert::{i64_array, vec3_array};
use super::mesh::PyMesh;
use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Reads an OBJ file with the core reader (GIL released). Returns
/// ``(vertices (V, 3) float64, face_sizes (F,) int64, face_indices int64,
/// n_polylines, n_points, extras)``; indices are 0-based in the file's ``v``
/// order. ``extras`` holds what the file has of: ``"texcoords"`` ((T, k)
/// float64, k the most components a ``vt`` had) with ``"corner_texcoords"``
/// (per corner, -1 where none), ``"normals"`` (N, 3) with
/// ``"corner_normals"``, ``"face_groups"`` (per face, int64) with
/// ``"group_names"`` (list of str), ``"face_materials"`` with
/// ``"material_names"``.
#[pyfunction]
fn _read_obj<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let d = super::run_interruptible(py, || crate::io::read_obj(&path))?;
    let extras = PyDict::new(py);
    if !d.corner_texcoords.is_empty() {
        let k = d.texcoord_dim.max(1);
        let rows: Vec<Vec<f64>> = d.texcoords.iter().map(|r| r[..k].to_vec()).collect();
        let table = if rows.is_empty() { numpy::PyArray2::<f64>::zeros(py, [0, k], false) } else { PyArray2::from_vec2(py, &rows)? };
        extras.set_item("texcoords", table)?;
        extras.set_item("corner_texcoords", i64_array(py, d.corner_texcoords))?;
    }
    if !d.corner_normals.is_empty() {
        extras.set_item("normals", vec3_array(py, &d.normals))?;
        extras.set_item("corner_normals", i64_array(py, d.corner_normals))?;
    }
    if !d.face_groups.is_empty() {
        extras.set_item("face_groups", i64_array(py, d.face_groups.iter().map(|&g| g as i64)))?;
        extras.set_item("group_names", d.group_names)?;
    }
    if !d.face_materials.is_empty() {
        extras.set_item("face_materials", i64_array(py, d.face_materials.iter().map(|&g| g as i64)))?;
        extras.set_item("material_names", d.material_names)?;
    }
    let out = (
        vec3_array(py, &d.positions),
        i64_array(py, d.sizes),
        i64_array(py, d.indices),
        d.n_polylines,
        d.n_points,
        extras,
    );
    Ok(out.into_pyobject(py)?.into_any())
}

/// Writes ``mesh`` as OBJ to ``path`` with the core writer (GIL released):
/// ``texcoords`` (C, k) and ``normals`` (C, 3) float64 per exported corner
/// become deduplicated ``vt``/``vn`` tables and ``f v/vt/vn`` corners;
/// ``groups`` / ``materials`` are ``(ids per face, names)`` written as ``g``
/// / ``usemtl`` lines where they change.
#[pyfunction]
#[pyo3(signature = (mesh, path, texcoords = None, normals = None, groups = None, materials = None))]
fn _write_obj(
    py: Python<'_>,
    mesh: PyRef<'_, PyMesh>,
    path: std::path::PathBuf,
    texcoords: Option<PyReadonlyArray2<'_, f64>>,
    normals: Option<PyReadonlyArray2<'_, f64>>,
    groups: Option<(PyReadonlyArray1<'_, i64>, Vec<String>)>,
    materials: Option<(PyReadonlyArray1<'_, i64>, Vec<String>)>,
) -> PyResult<()> {
    let tk = texcoords.as_ref().map(|t| t.as_array().ncols());
    let t = texcoords.as_ref().map(|t| t.as_slice()).transpose()?;
    let n = normals.as_ref().map(|n| n.as_slice()).transpose()?;
    let g = groups.as_ref().map(|(i, names)| i.as_slice().map(|i| (i, names.as_slice()))).transpose()?;
    let mt = materials.as_ref().map(|(i, names)| i.as_slice().map(|i| (i, names.as_slice()))).transpose()?;
    let attrs = crate::io::ObjAttributes { texcoords: t.zip(tk), normals: n, groups: g, materials: mt };
    let m = &mesh.inner;
    super::detach(py, || {
        let f = std::fs::File::create(&path).map_err(|e| crate::MeshError::Io(format!("{}: {e}", path.display())))?;
        crate::io::write_obj(m, &attrs, f)
    })
    .map_err(super::err)
}

/// The whole file at ``path`` as uint8 (GIL released): a buffer whose pages
/// are mapped before the read (``crate::io::read_file``); a MeshError naming
/// the path when it cannot be read or would exceed the memory budget.
#[pyfunction]
fn _read_bytes<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Bound<'py, numpy::PyArray1<u8>>> {
    use numpy::IntoPyArray;
    Ok(super::run_interruptible(py, || crate::io::read_file(&path))?.into_pyarray(py))
}

/// The columns of ``n`` records of ``record`` bytes from byte ``start`` of
/// ``data`` (GIL released): per ``(offset, width)`` field, its bytes of every
/// record, contiguous (uint8), for a uniform PLY element.
#[pyfunction]
fn _ply_gather<'py>(
    py: Python<'py>,
    data: numpy::PyReadonlyArray1<'py, u8>,
    start: usize,
    n: usize,
    record: usize,
    fields: Vec<(usize, usize)>,
) -> PyResult<Vec<Bound<'py, numpy::PyArray1<u8>>>> {
    use numpy::IntoPyArray;
    let data = data.as_slice()?;
    let cols = super::run_interruptible(py, || crate::io::ply::gather(data, start, n, record, &fields))?;
    Ok(cols.into_iter().map(|c| c.into_pyarray(py)).collect())
}

/// :func:`_ply_gather` of the records of the file at ``path`` (GIL
/// released), read through two reused buffers instead of whole
/// (``crate::io::ply::gather_file``); a MeshError naming the path when it
/// cannot be read, or when the records run past its end.
#[pyfunction]
fn _ply_gather_file<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    start: u64,
    n: usize,
    record: usize,
    fields: Vec<(usize, usize)>,
) -> PyResult<Vec<Bound<'py, numpy::PyArray1<u8>>>> {
    use numpy::IntoPyArray;
    let cols = super::run_interruptible(py, || crate::io::ply::gather_file(&path, start, n, record, &fields))?;
    Ok(cols.into_iter().map(|c| c.into_pyarray(py)).collect())
}

/// Splits the ``n`` binary little-endian records of a PLY element starting at
/// byte ``start`` of ``data`` (uint8, as :func:`_read_bytes` gives it; GIL
/// released). ``props`` gives, per property,
/// ``(count bytes or 0 for a scalar, count signed, value bytes)``. Returns
/// ``(values, counts, end)``: per property its raw value bytes (uint8) and,
/// for lists, each record's count (int64; ``None`` for scalars), and the
/// byte offset after the last record.
#[pyfunction]
fn _ply_split_records<'py>(
    py: Python<'py>,
    data: numpy::PyReadonlyArray1<'py, u8>,
    start: usize,
    n: usize,
    props: Vec<(u8, bool, u8)>,
    element: &str,
) -> PyResult<Bound<'py, PyAny>> {
    use numpy::IntoPyArray;
    let props: Vec<crate::io::ply::Property> = props
        .into_iter()
        .map(|(c, s, v)| crate::io::ply::Property { count: (c > 0).then_some((c, s)), value_size: v })
        .collect();
    let data = data.as_slice()?;
    let cols = super::detach(py, || crate::io::ply::split_records(data, start, n, &props, element)).map_err(super::err)?;
    let values: Vec<Bound<'py, PyAny>> = cols.values.into_iter().map(|v| v.into_pyarray(py).into_any()).collect();
    let counts: Vec<Option<Bound<'py, PyAny>>> = props
        .iter()
        .zip(cols.counts)
        .map(|(p, c)| p.count.map(|_| c.into_pyarray(py).into_any()))
        .collect();
    Ok((values, counts, cols.end).into_pyobject(py)?.into_any())
}

/// Appends to the file at ``path`` the binary little-endian PLY face
/// records of faces with ``sizes`` corners, the inverse of
/// :func:`_ply_split_records` (GIL released; ``crate::io::ply::write_records``:
/// chunk by chunk, the next chunk laid out while this one is written).
/// ``fields`` gives, per property in record order, ``(count bytes (1 or 4)
/// or 0 for a scalar, values per corner, value bytes, source bytes per
/// value (the value bytes, or 8 for int64 narrowed to int32), the column's
/// raw little-endian bytes (uint8))``. A MeshError when the layout is wrong
/// or the file cannot be written.
#[pyfunction]
fn _ply_write_records(
    py: Python<'_>,
    path: std::path::PathBuf,
    sizes: PyReadonlyArray1<'_, i64>,
    fields: Vec<(u8, u32, u8, u8, PyReadonlyArray1<'_, u8>)>,
) -> PyResult<()> {
    let sizes = sizes.as_slice()?;
    let cols = fields
        .iter()
        .map(|(c, per, vs, ss, d)| Ok(crate::io::ply::Field { count: *c, per: *per, value_size: *vs, source_size: *ss, data: d.as_slice()? }))
        .collect::<PyResult<Vec<_>>>()?;
    super::run_interruptible(py, || {
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| crate::MeshError::Io(format!("{}: {e}", path.display())))?;
        crate::io::ply::write_records(&mut f, sizes, &cols, 0)
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_read_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(_ply_gather, m)?)?;
    m.add_function(wrap_pyfunction!(_ply_gather_file, m)?)?;
    m.add_function(wrap_pyfunction!(_ply_split_records, m)?)?;
    m.add_function(wrap_pyfunction!(_ply_write_records, m)?)?;
    m.add_function(wrap_pyfunction!(_read_obj, m)?)?;
    m.add_function(wrap_pyfunction!(_write_obj, m)?)?;
    Ok(())
}
