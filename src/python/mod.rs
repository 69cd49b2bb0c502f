//! PyO3 bindings: the `topomesh._core` extension module. Thin: argument
//! conversion, GIL release around heavy work, error mapping. Each topic has
//! its own file; scheme files add methods to `Mesh` with their own
//! `#[pymethods] impl PyMesh` block (pyo3's `multiple-pymethods`).

use pyo3::prelude::*;

mod alloc;
pub(crate) mod convert;
pub(crate) mod ifs;
pub(crate) mod fractal;
pub(crate) mod mesh;
mod refine;
mod ops;
mod smooth;

pyo3::create_exception!(
    topomesh,
    MeshError,
    pyo3::exceptions::PyValueError,
    "Invalid mesh input or a broken operator precondition; the message names the face, vertex or edge."
);

/// Maps a core error to the Python `topomesh.MeshError` (a `ValueError`).
pub(crate) fn err(e: crate::MeshError) -> PyErr {
    MeshError::new_err(e.to_string())
}

pub(crate) fn arg_err(msg: impl Into<String>) -> PyErr {
    MeshError::new_err(msg.into())
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MeshError", m.py().get_type::<MeshError>())?;
    mesh::register(m)?;
    ops::register(m)?;
    ifs::register(m)?;
    fractal::register(m)?;
    Ok(())
}
