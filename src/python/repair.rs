//! Bindings of the repair path (`crate::repair`) and of the constructors
//! that apply it: `Mesh._repair` / `Mesh._repair_flat` (wrapped by
//! `topomesh.repair`), `Mesh.from_trimesh` / `Mesh.from_pyvista` (delegating
//! to `topomesh._interop`), and the inside-out warning of `from_polygons`.

use super::convert::{faces, i64_array, indices_1d, positions, vec3_array};
use numpy::{PyArray1, PyArray2};
use super::mesh::PyMesh;
use super::err;
use crate::repair::{inside_out_components, merge_vertices, repair_mesh, RepairReport};
use crate::Mesh;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Warns with `GeometryWarning` when closed components of `m` are inside out
/// (negative signed volume); called by `Mesh.from_polygons` / `from_flat`.
pub(crate) fn warn_inside_out(py: Python<'_>, m: &Mesh) -> PyResult<()> {
    let bad = super::detach(py, || inside_out_components(m));
    if bad.is_empty() {
        return Ok(());
    }
    let listed: Vec<String> = bad.iter().take(5).map(|(k, v)| format!("component {k} (volume {v:.6e})")).collect();
    let more = if bad.len() > 5 { format!(" and {} more", bad.len() - 5) } else { String::new() };
    let msg = format!(
        "{} closed component{} inside out (negative signed volume): {}{more}; pass it through topomesh.repair(...) to orient it outward",
        bad.len(),
        if bad.len() == 1 { " is" } else { "s are" },
        listed.join(", ")
    );
    super::warn_geometry(py, msg)
}

fn report_dict<'py>(py: Python<'py>, r: &RepairReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("tolerance", r.tolerance)?;
    d.set_item("vertices_merged", r.vertices_merged)?;
    d.set_item("degenerate_faces_dropped", r.degenerate_faces_dropped)?;
    d.set_item("duplicate_faces_dropped", r.duplicate_faces_dropped)?;
    d.set_item("non_manifold_edges_split", r.non_manifold_edges_split)?;
    d.set_item("faces_flipped", r.faces_flipped)?;
    d.set_item("components_flipped", r.components_flipped)?;
    d.set_item("non_orientable_edges_cut", r.non_orientable_edges_cut)?;
    d.set_item("pinched_vertices_split", r.pinched_vertices_split)?;
    d.set_item("unreferenced_vertices_removed", r.unreferenced_vertices_removed)?;
    d.set_item("boundary_loops", r.boundary_loops)?;
    Ok(d)
}

fn run<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    sizes: &[i64],
    idx: &[i64],
    tolerance: Option<f64>,
    close_boundaries: bool,
) -> PyResult<(PyMesh, Bound<'py, PyDict>)> {
    let pos = positions(py, vertices)?;
    let (m, r) = super::run_interruptible(py, || repair_mesh(&pos, sizes, idx, tolerance, close_boundaries))?;
    Ok((PyMesh::wrap(m), report_dict(py, &r)?))
}

#[pymethods]
impl PyMesh {
    /// The repair path on polygons (see :func:`topomesh.repair`): returns the
    /// mesh and the report's counts as a dict.
    #[staticmethod]
    #[pyo3(signature = (vertices, faces, tolerance = None, close_boundaries = None, boundaries = "keep"))]
    fn _repair<'py>(
        py: Python<'py>,
        vertices: &Bound<'py, PyAny>,
        faces: &Bound<'py, PyAny>,
        tolerance: Option<f64>,
        close_boundaries: Option<bool>,
        boundaries: &str,
    ) -> PyResult<(PyMesh, Bound<'py, PyDict>)> {
        let keep = super::boundary::keep_boundaries("repair", close_boundaries, boundaries)?;
        let (sizes, idx) = self::faces(py, faces)?;
        run(py, vertices, &sizes, idx.as_slice(), tolerance, keep)
    }

    /// :meth:`_repair` on ``face_sizes`` + flat ``face_indices``.
    #[staticmethod]
    #[pyo3(signature = (vertices, face_sizes, face_indices, tolerance = None, close_boundaries = None, boundaries = "keep"))]
    fn _repair_flat<'py>(
        py: Python<'py>,
        vertices: &Bound<'py, PyAny>,
        face_sizes: &Bound<'py, PyAny>,
        face_indices: &Bound<'py, PyAny>,
        tolerance: Option<f64>,
        close_boundaries: Option<bool>,
        boundaries: &str,
    ) -> PyResult<(PyMesh, Bound<'py, PyDict>)> {
        let close_boundaries = super::boundary::keep_boundaries("repair", close_boundaries, boundaries)?;
        let sizes = indices_1d(py, face_sizes, "face_sizes")?;
        let idx = indices_1d(py, face_indices, "face_indices")?;
        run(py, vertices, sizes.as_slice(), idx.as_slice(), tolerance, close_boundaries)
    }

    /// Merge vertices within ``tolerance`` (0: exactly equal only), the weld
    /// of :func:`topomesh.repair`: returns the distinct positions (V, 3), in
    /// order of first appearance, and the index of every input vertex (N,).
    #[staticmethod]
    #[pyo3(signature = (vertices, tolerance = 0.0))]
    fn _weld<'py>(
        py: Python<'py>,
        vertices: &Bound<'py, PyAny>,
        tolerance: f64,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<i64>>)> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(super::arg_err(format!("weld: tolerance = {} must be a finite number >= 0", crate::error::num(tolerance))));
        }
        let pos = positions(py, vertices)?;
        if let Some(v) = pos.iter().position(|p| !p.is_finite()) {
            return Err(err(crate::MeshError::NonFinite { vertex: v }));
        }
        let (uniq, cluster) = super::detach(py, || merge_vertices(&pos, tolerance));
        Ok((vec3_array(py, &uniq), i64_array(py, cluster.iter().map(|&c| c as i64))))
    }

    /// A mesh from a ``trimesh.Trimesh`` (its vertices and triangles).
    ///
    /// Parameters
    /// ----------
    /// tm : trimesh.Trimesh
    /// close_boundaries : bool or None, default None
    ///     Legacy spelling of ``boundaries`` (``True``: keep, ``False``: refuse).
    /// repair : bool, default False
    ///     Pass the triangles through :func:`topomesh.repair` first (merge,
    ///     drop degenerate and duplicate faces, orient, split pinches); call
    ///     :func:`topomesh.repair` yourself to get the report.
    /// tolerance : float, optional
    ///     Merge tolerance of the repair (default 1e-9 × bounding-box diagonal).
    /// boundaries : {"keep", "refuse"}, default "keep"
    ///     An open mesh (trimesh's ``is_watertight`` False) is kept open, its
    ///     boundary loops stored as hole faces; ``"refuse"`` raises
    ///     :class:`MeshError` at a boundary edge.
    #[staticmethod]
    #[pyo3(signature = (tm, close_boundaries = None, repair = false, tolerance = None, boundaries = "keep"))]
    fn from_trimesh<'py>(
        py: Python<'py>,
        tm: &Bound<'py, PyAny>,
        close_boundaries: Option<bool>,
        repair: bool,
        tolerance: Option<f64>,
        boundaries: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let keep = super::boundary::keep_boundaries("from_trimesh", close_boundaries, boundaries)?;
        delegate(py, "from_trimesh", tm, keep, repair, tolerance)
    }

    /// A mesh from a pyvista dataset: ``PolyData`` (polygon faces and
    /// triangle strips; vertex and line cells are left out) or any other
    /// dataset, e.g. an ``UnstructuredGrid``, through its ``extract_surface()``.
    /// Options as in :meth:`from_trimesh` (open surfaces are kept open by default).
    #[staticmethod]
    #[pyo3(signature = (data, close_boundaries = None, repair = false, tolerance = None, boundaries = "keep"))]
    fn from_pyvista<'py>(
        py: Python<'py>,
        data: &Bound<'py, PyAny>,
        close_boundaries: Option<bool>,
        repair: bool,
        tolerance: Option<f64>,
        boundaries: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let keep = super::boundary::keep_boundaries("from_pyvista", close_boundaries, boundaries)?;
        delegate(py, "from_pyvista", data, keep, repair, tolerance)
    }
}

fn delegate<'py>(
    py: Python<'py>,
    func: &str,
    obj: &Bound<'py, PyAny>,
    keep: bool,
    repair: bool,
    tolerance: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let kw = PyDict::new(py);
    kw.set_item("boundaries", if keep { "keep" } else { "refuse" })?;
    kw.set_item("repair", repair)?;
    kw.set_item("tolerance", tolerance)?;
    py.import("topomesh._interop")?.getattr(func)?.call((obj,), Some(&kw))
}
