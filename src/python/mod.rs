//! PyO3 bindings: the `topomesh._core` extension module. Thin: argument
//! conversion, GIL release around heavy work, error mapping. Each topic has
//! its own file; scheme files add methods to `Mesh` with their own
//! `#[pymethods] impl PyMesh` block (pyo3's `multiple-pymethods`).

use pyo3::prelude::*;

mod alloc;
mod display;
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

pyo3::create_exception!(
    topomesh,
    GeometryWarning,
    pyo3::exceptions::PyUserWarning,
    "A result that is a valid manifold but geometrically flawed (for example self-intersecting); the message says where and how much."
);

/// Maps a core error to the Python `topomesh.MeshError` (a `ValueError`).
pub(crate) fn err(e: crate::MeshError) -> PyErr {
    MeshError::new_err(e.to_string())
}

pub(crate) fn arg_err(msg: impl Into<String>) -> PyErr {
    MeshError::new_err(msg.into())
}

/// Runs one level of a scheme `iterations` times with the GIL released, one
/// tqdm update per level when `progress` is true. `iterations < 0` is a
/// `MeshError` naming the scheme; 0 returns an equal mesh.
pub(crate) fn iterate(
    py: Python<'_>,
    mesh: &crate::Mesh,
    iterations: i64,
    progress: bool,
    name: &str,
    step: impl Fn(&crate::Mesh) -> crate::Result<crate::Mesh> + Sync,
) -> PyResult<mesh::PyMesh> {
    if iterations < 0 {
        return Err(arg_err(format!("{name}: iterations = {iterations} must be >= 0")));
    }
    let bar = if progress {
        let kw = pyo3::types::PyDict::new(py);
        kw.set_item("total", iterations)?;
        kw.set_item("desc", name)?;
        Some(py.import("tqdm")?.getattr("tqdm")?.call((), Some(&kw))?)
    } else {
        None
    };
    let mut cur: Option<crate::Mesh> = None;
    for _ in 0..iterations {
        let src = cur.as_ref().unwrap_or(mesh);
        cur = Some(py.detach(|| step(src)).map_err(err)?);
        if let Some(b) = &bar {
            b.call_method1("update", (1,))?;
        }
    }
    if let Some(b) = &bar {
        b.call_method0("close")?;
    }
    Ok(mesh::PyMesh::wrap(cur.unwrap_or_else(|| mesh.clone())))
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MeshError", m.py().get_type::<MeshError>())?;
    m.add("GeometryWarning", m.py().get_type::<GeometryWarning>())?;
    mesh::register(m)?;
    ops::register(m)?;
    ifs::register(m)?;
    fractal::register(m)?;
    Ok(())
}
