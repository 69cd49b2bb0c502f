//! Display in Jupyter and off-screen: `Mesh.plot`, `_repr_html_`,
//! `_repr_png_`. Rendering is pure Python (`topomesh.viz`, pyvista imported
//! lazily); these methods only forward to it.

use super::convert::i64_array;
use super::mesh::PyMesh;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

fn viz<'py>(slf: &Bound<'py, PyMesh>, func: &str, kwargs: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
    let py = slf.py();
    let f = py.import("topomesh.viz")?.getattr(func)?;
    f.call(PyTuple::new(py, [slf.clone().into_any()])?, kwargs)
}

#[pymethods]
impl PyMesh {
    /// Render with pyvista: shaded polygon faces, the polygon edges (not the
    /// triangulation's) and a title with V, E, F and genus.
    ///
    /// Parameters
    /// ----------
    /// color_by : None, {"face_size", "valence", "component"} or array_like
    ///     Colour faces by their number of corners, vertices by their
    ///     valence, faces by their connected component, or by any array of
    ///     one value per exported face (``len(face_sizes)``) or per vertex.
    /// edges : bool, default True
    ///     Draw the polygon edges.
    /// notebook : bool or None, default None
    ///     Use pyvista's Jupyter backend; None means "when running in a
    ///     Jupyter kernel". Where that backend cannot render (no trame, no
    ///     GPU, ``pyvista.set_jupyter_backend("static")``) a static PNG is shown.
    /// screenshot : str or path-like, optional
    ///     Also write the render to this PNG file (off-screen).
    /// off_screen : bool or None, default None
    ///     Render without a window; None means "when there is no display or a
    ///     screenshot is asked for".
    /// window_size : (int, int), default (640, 480)
    /// title : bool or str, default True
    ///     True writes the counts; a string is written above them.
    ///
    /// color : str, optional
    ///     Surface colour when ``color_by`` is None.
    /// view : (float, float, float), optional
    ///     Direction from the mesh to the camera (z up); the parallel camera
    ///     is fitted to the mesh seen from there.
    ///
    /// Returns
    /// -------
    /// IPython.display.Image or None
    ///     Outside Jupyter, off-screen: the PNG as an Image (its bytes when
    ///     IPython is missing). In Jupyter the image or live viewer is
    ///     displayed where the call is and None is returned; None too after
    ///     an interactive window closes.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Naming the option when an option or its value is not allowed.
    #[pyo3(signature = (**options))]
    fn plot<'py>(slf: &Bound<'py, Self>, options: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
        viz(slf, "plot", options)
    }

    /// A compact HTML summary for Jupyter: counts, χ, genus per component,
    /// boundaries, histograms, bounding box, and a small render when the mesh
    /// is small and pyvista renders off-screen. Never raises.
    fn _repr_html_<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        viz(slf, "repr_html", None)
    }

    /// A PNG thumbnail (bytes) where pyvista renders off-screen, else None.
    fn _repr_png_<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        viz(slf, "repr_png", None)
    }

    /// Connected-component label of every vertex, int64 (V,), numbered in
    /// order of first vertex (the order of :attr:`component_genera`).
    fn _vertex_components<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let (c, _) = super::detach(py, || self.inner.vertex_components());
        i64_array(py, c.iter().map(|&x| x as i64))
    }
}
