//! Printability: wall thickness by ray casting (`geometry::thickness`) and
//! the check `Mesh.printable`, whose report is built in Python
//! (`topomesh.printing`) from `_print_check`.

use super::convert::{i64_array, u32_rows, vec3_array};
use super::mesh::PyMesh;
use super::run_interruptible;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;

#[pymethods]
impl PyMesh {
    /// Wall thickness per face, float64 (F,), indexed like
    /// :attr:`face_centroids` (hole faces included).
    ///
    /// From the centroid of every triangle of :meth:`triangulate` a ray is
    /// cast along the inward normal; the wall there is the distance to the
    /// first other triangle it hits (hits closer than 1e-9 of the
    /// triangle's longest edge are contacts and are skipped). A face gets
    /// the smallest value of its triangles. ``inf`` where every ray leaves
    /// the surface (an open or inside-out part); NaN for hole faces and faces
    /// without a triangle of positive area. A bounding volume hierarchy
    /// answers the rays: O(T log T), parallel, with the GIL released.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     The memory budget is too small for the triangulation and the
    ///     hierarchy.
    fn wall_thickness<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let w = run_interruptible(py, || self.inner.wall_thickness())?;
        Ok(w.into_pyarray(py))
    }

    /// Check the mesh for 3D printing with walls of at least
    /// ``min_thickness`` (in the mesh's units).
    ///
    /// Parameters
    /// ----------
    /// min_thickness : float
    ///     The thinnest wall the printer makes; finite and > 0.
    ///
    /// Returns
    /// -------
    /// topomesh.printing.PrintReport
    ///     ``ok``; ``self_intersections`` (face pairs whose triangles cross,
    ///     the exact check of :meth:`self_intersections`) and their count of
    ///     triangle pairs; ``thin_faces`` (faces whose :meth:`wall_thickness`
    ///     is below ``min_thickness``), ``min_thickness_found`` and the
    ///     thinnest face; ``open_boundaries`` and ``watertight``. Printing
    ///     the report gives a readable summary. See
    ///     :func:`topomesh.printing.printable`.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``min_thickness`` not a finite number > 0.
    fn printable<'py>(slf: &Bound<'py, Self>, min_thickness: f64) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let f = py.import("topomesh.printing")?.getattr("printable")?;
        f.call1((slf.clone(), min_thickness))
    }

    /// The measurements of :func:`topomesh.printing.printable`, from one
    /// triangulation: ``(face thickness (F,) float64, crossing triangle
    /// pairs (K, 2) int64, source face of every triangle (T,) int64,
    /// (unpaired triangle sides, pinched vertices))``.
    fn _print_check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (w, pairs, tri_face, defects) = run_interruptible(py, || {
            let t = self.inner.triangle_wall_thickness()?;
            let w = crate::geometry::thickness::per_face(self.inner.n_faces(), &t.thickness, &t.tri_face);
            crate::cancel::check()?;
            let pairs = crate::geometry::crossing::crossing_pairs(&t.points, &t.tris, None, true);
            let d = crate::geometry::triangle_defects(&t.tris);
            Ok((w, pairs, t.tri_face, (d.unpaired_sides, d.pinched_vertices)))
        })?;
        let rows: Vec<[u32; 2]> = pairs.iter().map(|&(i, j)| [i, j]).collect();
        let out = (
            w.into_pyarray(py),
            u32_rows(py, &rows),
            i64_array(py, tri_face.iter().map(|&f| f as i64)),
            defects,
        );
        Ok(out.into_pyobject(py)?.into_any())
    }

    /// The triangles STL and 3MF get (:func:`topomesh.io.save`):
    /// ``(vertices (V', 3) float64, triangles (T, 3) int64, (unpaired
    /// sides, pinched vertices))``, the vertices and added points of :meth:`triangulate` that
    /// a triangle uses, renumbered in order.
    fn _print_triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (p, tris, defects) = run_interruptible(py, || {
            let (mut tris, p) = crate::geometry::triangles_with_points(&self.inner);
            // keep the used points in their order (point-spheres and one-gons have no triangle)
            let mut new = vec![u32::MAX; p.len()];
            for t in &tris {
                for &v in t {
                    new[v as usize] = 0;
                }
            }
            let mut kept = Vec::with_capacity(p.len());
            for (v, n) in new.iter_mut().enumerate() {
                if *n == 0 {
                    *n = kept.len() as u32;
                    kept.push(p[v]);
                }
            }
            for t in tris.iter_mut() {
                *t = t.map(|v| new[v as usize]);
            }
            let d = crate::geometry::triangle_defects(&tris);
            Ok((kept, tris, (d.unpaired_sides, d.pinched_vertices)))
        })?;
        Ok((vec3_array(py, &p), u32_rows(py, &tris), defects).into_pyobject(py)?.into_any())
    }
}
