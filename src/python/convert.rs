//! NumPy <-> core conversions with input checks that name the problem.

use super::arg_err;
use glam::DVec3;
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn};
use pyo3::prelude::*;

/// `numpy.asarray(obj)` with a named error instead of numpy's own.
fn as_ndarray<'py>(py: Python<'py>, obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    np.call_method1("asarray", (obj,))
        .map_err(|e| arg_err(format!("{what}: cannot be read as an array ({e})")))
}

fn dtype_kind(a: &Bound<'_, PyAny>) -> PyResult<String> {
    a.getattr("dtype")?.getattr("kind")?.extract()
}

/// A `(V, 3)` array of finite numbers → positions. Integer and float32
/// input is accepted (converted); anything else is a `MeshError`.
pub(crate) fn positions(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    let a = as_ndarray(py, obj, "vertices")?;
    let kind = dtype_kind(&a)?;
    if !matches!(kind.as_str(), "f" | "i" | "u") {
        return Err(arg_err(format!(
            "vertices: dtype {} is not a real number type (expected float64, shape (V, 3))",
            a.getattr("dtype")?.str()?
        )));
    }
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    if shape.len() != 2 || shape[1] != 3 {
        return Err(arg_err(format!("vertices: shape {shape:?} is not (V, 3)")));
    }
    let a = py.import("numpy")?.call_method1("ascontiguousarray", (a, "float64"))?;
    let arr = a.cast::<PyArray2<f64>>()?.readonly();
    let s = arr.as_slice()?;
    let nv = s.len() / 3;
    if nv < PAR_POSITIONS {
        return Ok(s.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect());
    }
    // large: copied on the pool without the GIL, into pages mapped first
    super::detach(py, || crate::cancel::par_collect(nv, |v| DVec3::new(s[3 * v], s[3 * v + 1], s[3 * v + 2]))).map_err(super::err)
}

/// Vertices from which [`positions`] copies in parallel.
const PAR_POSITIONS: usize = 1 << 16;

/// Integers read from Python: borrowed from a contiguous `int64` NumPy
/// array when the input is one (no copy), owned otherwise.
pub(crate) enum Ints<'py> {
    Owned(Vec<i64>),
    Array(PyReadonlyArrayDyn<'py, i64>),
}

impl Ints<'_> {
    pub fn as_slice(&self) -> &[i64] {
        match self {
            Ints::Owned(v) => v,
            Ints::Array(a) => a.as_slice().expect("ascontiguousarray gives a contiguous array"),
        }
    }
}

/// A 1-D array of integers → `i64`s (no silent float truncation).
pub(crate) fn indices_1d<'py>(py: Python<'py>, obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Ints<'py>> {
    let a = as_ndarray(py, obj, what)?;
    let kind = dtype_kind(&a)?;
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    if shape.len() != 1 {
        return Err(arg_err(format!("{what}: shape {shape:?} is not one-dimensional")));
    }
    if shape[0] > 0 && !matches!(kind.as_str(), "i" | "u") {
        return Err(arg_err(format!("{what}: dtype {} is not an integer type", a.getattr("dtype")?.str()?)));
    }
    let a = py.import("numpy")?.call_method1("ascontiguousarray", (a, "int64"))?;
    Ok(Ints::Array(a.cast_into::<PyArrayDyn<i64>>()?.readonly()))
}

/// Faces given as a 2-D integer array `(F, k)` or as any sequence of index
/// sequences (ragged allowed) → `(sizes, flat indices)`.
pub(crate) fn faces<'py>(py: Python<'py>, obj: &Bound<'py, PyAny>) -> PyResult<(Vec<i64>, Ints<'py>)> {
    // fast path: a rectangular integer ndarray
    if let Ok(kind) = dtype_kind(obj) {
        let shape: Vec<usize> = obj.getattr("shape")?.extract()?;
        if shape.len() == 2 {
            if !matches!(kind.as_str(), "i" | "u") && shape[0] * shape[1] > 0 {
                return Err(arg_err(format!("faces: dtype {} is not an integer type", obj.getattr("dtype")?.str()?)));
            }
            let a = py.import("numpy")?.call_method1("ascontiguousarray", (obj, "int64"))?;
            let arr = a.cast_into::<PyArrayDyn<i64>>()?.readonly();
            if shape[1] == 0 && shape[0] > 0 {
                return Err(crate::python::err(crate::MeshError::EmptyFace { face: 0 }));
            }
            return Ok((vec![shape[1] as i64; shape[0]], Ints::Array(arr)));
        }
        if shape.len() != 1 || kind != "O" {
            return Err(arg_err(format!("faces: array of shape {shape:?} is neither (F, k) nor a sequence of faces")));
        }
    }
    let seq = obj
        .try_iter()
        .map_err(|_| arg_err("faces: expected a sequence of index sequences or an (F, k) integer array"))?;
    let mut sizes = Vec::new();
    let mut flat = Vec::new();
    for (f, face) in seq.enumerate() {
        let face = face?;
        let idx = indices_1d(py, &face, &format!("face {f}"))
            .map_err(|e| arg_err(format!("{}", e.value(py))))?;
        let idx = idx.as_slice();
        if idx.is_empty() {
            return Err(crate::python::err(crate::MeshError::EmptyFace { face: f }));
        }
        sizes.push(idx.len() as i64);
        flat.extend_from_slice(idx);
    }
    Ok((sizes, Ints::Owned(flat)))
}

pub(crate) fn vec3_array<'py>(py: Python<'py>, v: &[DVec3]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|p| p.to_array()).collect();
    Array2::from_shape_vec((v.len(), 3), flat).expect("shape").into_pyarray(py)
}

pub(crate) fn i64_array<'py>(py: Python<'py>, v: impl IntoIterator<Item = i64>) -> Bound<'py, PyArray1<i64>> {
    Array1::from_iter(v).into_pyarray(py)
}

pub(crate) fn u32_rows<'py, const K: usize>(py: Python<'py>, v: &[[u32; K]]) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = v.iter().flat_map(|r| r.iter().map(|&x| x as i64)).collect();
    Array2::from_shape_vec((v.len(), K), flat).expect("shape").into_pyarray(py)
}

/// A point given as three real numbers (any sequence or array of length
/// 3) for parameter `name` of `call`: anything else is a `MeshError` that
/// names them and shows what was given, instead of pyo3's conversion error.
pub(crate) fn point3(obj: &Bound<'_, PyAny>, call: &str, name: &str) -> PyResult<[f64; 3]> {
    let bad = || {
        let got = obj.repr().map_or_else(|_| "?".into(), |r| r.to_string());
        arg_err(format!("{call}: {name} must be three real numbers, got {got}"))
    };
    let v: Vec<f64> = obj.extract().map_err(|_| bad())?;
    <[f64; 3]>::try_from(v).map_err(|_| bad())
}
