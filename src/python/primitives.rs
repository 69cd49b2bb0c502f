//! The primitives: Platonic solids, the torus and the genus-g slab
//! (`crate::primitives`).

use super::mesh::PyMesh;
use crate::primitives;
use pyo3::prelude::*;

/// Regular tetrahedron at alternate corners of the cube [-1, 1]³.
#[pyfunction]
fn tetrahedron() -> PyMesh {
    // in topomesh's pool, never rayon's global one (`pool` module docs)
    PyMesh::wrap(super::pool::run(primitives::tetrahedron))
}
/// The cube [-1, 1]³ (8 vertices, 12 edges, 6 quads).
#[pyfunction]
fn cube() -> PyMesh {
    // in topomesh's pool, never rayon's global one (`pool` module docs)
    PyMesh::wrap(super::pool::run(primitives::cube))
}
/// Octahedron with vertices (±1, 0, 0), (0, ±1, 0), (0, 0, ±1).
#[pyfunction]
fn octahedron() -> PyMesh {
    // in topomesh's pool, never rayon's global one (`pool` module docs)
    PyMesh::wrap(super::pool::run(primitives::octahedron))
}
/// Dodecahedron with circumradius √3 (20 vertices, 12 pentagons).
#[pyfunction]
fn dodecahedron() -> PyMesh {
    // in topomesh's pool, never rayon's global one (`pool` module docs)
    PyMesh::wrap(super::pool::run(primitives::dodecahedron))
}
/// Icosahedron with vertices (0, ±1, ±φ) and cyclic permutations.
#[pyfunction]
fn icosahedron() -> PyMesh {
    // in topomesh's pool, never rayon's global one (`pool` module docs)
    PyMesh::wrap(super::pool::run(primitives::icosahedron))
}
/// Quad torus around the z axis: ``major`` segments around the axis, ``minor``
/// around the tube. V = major·minor, F = V, genus 1.
#[pyfunction]
#[pyo3(signature = (major = 24, minor = 12, major_radius = 1.0, minor_radius = 0.4))]
fn torus(
    py: Python<'_>,
    #[pyo3(from_py_with = super::big_int)] major: i128,
    #[pyo3(from_py_with = super::big_int)] minor: i128,
    major_radius: f64,
    minor_radius: f64,
) -> PyResult<PyMesh> {
    let major = super::usize_in("torus", "major", major, 3, crate::mesh::MAX_ELEMENTS)?;
    let minor = super::usize_in("torus", "minor", minor, 3, crate::mesh::MAX_ELEMENTS)?;
    super::finite_in("torus", "major_radius", major_radius, f64::MIN_POSITIVE, f64::MAX)?;
    super::finite_in("torus", "minor_radius", minor_radius, f64::MIN_POSITIVE, f64::MAX)?;
    super::run_interruptible(py, || primitives::torus(major, minor, major_radius, minor_radius)).map(PyMesh::wrap)
}
/// A closed genus-``g`` slab, tunnelled with InsertEdge (quads only).
///
/// Parameters
/// ----------
/// g : int
///     The genus, 0 to 10000.
#[pyfunction]
fn genus_surface(py: Python<'_>, #[pyo3(from_py_with = super::big_int)] g: i128) -> PyResult<PyMesh> {
    let g = super::usize_in("genus_surface", "g", g, 0, 10_000)?;
    super::run_interruptible(py, || primitives::genus_surface(g)).map(PyMesh::wrap)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tetrahedron, m)?)?;
    m.add_function(wrap_pyfunction!(cube, m)?)?;
    m.add_function(wrap_pyfunction!(octahedron, m)?)?;
    m.add_function(wrap_pyfunction!(dodecahedron, m)?)?;
    m.add_function(wrap_pyfunction!(icosahedron, m)?)?;
    m.add_function(wrap_pyfunction!(torus, m)?)?;
    m.add_function(wrap_pyfunction!(genus_surface, m)?)?;
    Ok(())
}
