//! File readers of the core exposed to `topomesh.io` (private helpers).

use super::convert::{i64_array, vec3_array};
use pyo3::prelude::*;

/// Reads an OBJ file with the core reader (GIL released). Returns
/// ``(vertices (V, 3) float64, face_sizes (F,) int64, face_indices int64,
/// n_polylines, n_points)``; indices are 0-based in the file's ``v`` order.
#[pyfunction]
fn _read_obj<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let d = super::run_interruptible(py, || crate::io::read_obj(&path))?;
    let out = (
        vec3_array(py, &d.positions),
        i64_array(py, d.sizes),
        i64_array(py, d.indices),
        d.n_polylines,
        d.n_points,
    );
    Ok(out.into_pyobject(py)?.into_any())
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_read_obj, m)?)?;
    Ok(())
}
