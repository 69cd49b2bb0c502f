//! Bindings of `crate::ifs` (subdivision schemes as attractors). The class is
//! `topomesh._core.IFS`; constructors are `ifs_*` functions, re-exported
//! without the prefix by `topomesh.ifs`.

use super::{arg_err, err, run_interruptible};
use crate::ifs::{fractals, rules, Ifs, Mat};
use numpy::ndarray::{Array1, Array2, ArrayD, IxDyn};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

/// A `levels` argument: 0 to the IFS limit ([`crate::ifs::render::MAX_LEVELS`]).
fn levels_in(call: &str, levels: i128) -> PyResult<usize> {
    super::usize_in(call, "levels", levels, 0, crate::ifs::render::MAX_LEVELS)
}

/// A real array of any shape → (shape, flat data), with a named error.
fn real_array(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<usize>, Vec<f64>)> {
    let np = py.import("numpy")?;
    let a = np
        .call_method1("asarray", (obj,))
        .map_err(|e| arg_err(format!("{what}: cannot be read as an array ({e})")))?;
    let kind: String = a.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "f" | "i" | "u" | "b") {
        return Err(arg_err(format!("{what}: dtype {} is not a real number type", a.getattr("dtype")?.str()?)));
    }
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    let a = np.call_method1("ascontiguousarray", (a, "float64"))?;
    let a = a.cast::<PyArrayDyn<f64>>()?.readonly();
    Ok((shape, a.as_slice()?.to_vec()))
}

/// An `(n, k)` real array → rows.
fn rows(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<f64>>> {
    let (shape, data) = real_array(py, obj, what)?;
    match shape.as_slice() {
        [n, k] if *k > 0 => Ok((0..*n).map(|i| data[i * k..(i + 1) * k].to_vec()).collect()),
        [k] if *k > 0 => Ok(vec![data]),
        _ => Err(arg_err(format!("{what}: shape {shape:?} is not (n, k)"))),
    }
}

/// A `(k, r, c)` real array → matrices.
fn stack(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Mat>> {
    let (shape, data) = real_array(py, obj, what)?;
    let [k, r, c] = shape.as_slice() else {
        return Err(arg_err(format!("{what}: shape {shape:?} is not (k, rows, cols)")));
    };
    Ok((0..*k).map(|i| Mat { rows: *r, cols: *c, data: data[i * r * c..(i + 1) * r * c].to_vec() }).collect())
}

fn mat_array<'py>(py: Python<'py>, m: &Mat) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_vec((m.rows, m.cols), m.data.clone()).expect("shape").into_pyarray(py)
}

/// Drawn points (`c·D` per point, `count` points grouped as `lead`) →
/// `(*lead, D)` for one component, `(c, *lead, D)` for several.
fn points_array<'py>(py: Python<'py>, ifs: &Ifs, flat: Vec<f64>, lead: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    let c = ifs.components().len();
    let d = ifs.ambient_dim();
    let count: usize = lead.iter().product();
    let mut shape = lead.to_vec();
    shape.push(d);
    if c == 1 {
        return ArrayD::from_shape_vec(IxDyn(&shape), flat).expect("shape").into_pyarray(py);
    }
    let mut out = Vec::with_capacity(flat.len());
    for comp in 0..c {
        for p in 0..count {
            out.extend_from_slice(&flat[p * c * d + comp * d..p * c * d + (comp + 1) * d]);
        }
    }
    shape.insert(0, c);
    ArrayD::from_shape_vec(IxDyn(&shape), out).expect("shape").into_pyarray(py)
}

/// An iterated function system of affine maps in lifted homogeneous
/// coordinates, built from a subdivision scheme and its control points
/// (Schaefer, Levin, Goldman, *Subdivision Schemes and Attractors*, eq. 2:
/// ``f_i(X) = X P^-1 S_i P``) or from plain affine maps.
///
/// Build one with the constructors of :mod:`topomesh.ifs`
/// (:func:`~topomesh.ifs.cubic_bspline`, :func:`~topomesh.ifs.koch`, …).
/// Point outputs have shape ``(..., D)``; an IFS that is a union of ``c``
/// attractors (:meth:`union`) puts a leading axis of length ``c`` in front.
#[pyclass(name = "IFS", module = "topomesh.ifs", frozen)]
pub struct PyIfs {
    pub inner: Ifs,
}

fn wrap(r: crate::Result<Ifs>) -> PyResult<PyIfs> {
    r.map(|inner| PyIfs { inner }).map_err(err)
}

#[pymethods]
impl PyIfs {
    fn __repr__(&self) -> String {
        format!(
            "IFS({:?}, maps={}, dim={}, ambient_dim={}, components={})",
            self.inner.name(),
            self.inner.n_maps(),
            self.inner.dim(),
            self.inner.ambient_dim(),
            self.inner.components().len()
        )
    }

    /// Name of the scheme or fractal.
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }

    /// Number of maps.
    #[getter]
    fn n_maps(&self) -> usize {
        self.inner.n_maps()
    }

    /// Lifted dimension ``n`` (size of the matrices).
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// Dimension ``D`` of the drawn points.
    #[getter]
    fn ambient_dim(&self) -> usize {
        self.inner.ambient_dim()
    }

    /// Number of attractors drawn (1, or 2 for a union).
    #[getter]
    fn n_components(&self) -> usize {
        self.inner.components().len()
    }

    /// The lifted maps ``M_i = P^-1 S_i P`` as ``(k, n, n)`` float64 (row vectors: ``x -> x M_i``).
    #[getter]
    fn maps<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let n = self.inner.dim();
        let data: Vec<f64> = self.inner.maps().iter().flat_map(|m| m.data.clone()).collect();
        ArrayD::from_shape_vec(IxDyn(&[self.inner.n_maps(), n, n]), data).expect("shape").into_pyarray(py)
    }

    /// The subdivision blocks ``S_i`` as ``(k, n, n)`` float64, or None.
    #[getter]
    fn blocks<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArrayDyn<f64>>> {
        let b = self.inner.blocks()?;
        let n = b[0].rows;
        let data: Vec<f64> = b.iter().flat_map(|m| m.data.clone()).collect();
        Some(ArrayD::from_shape_vec(IxDyn(&[b.len(), n, n]), data).expect("shape").into_pyarray(py))
    }

    /// The lifted control-point matrix ``P`` (section 2), ``(n, n)``, or None.
    #[getter]
    fn lifted_control_points<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.inner.control().map(|p| mat_array(py, p))
    }

    /// The control points, ``(n, D)`` float64 (``(c, n, D)`` for a union), or None.
    #[getter]
    fn control_points<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArrayDyn<f64>>>> {
        let Some(p) = self.inner.control() else { return Ok(None) };
        let rows: Vec<Vec<f64>> = (0..p.rows).map(|r| p.row(r).to_vec()).collect();
        let y = self.inner.start_points(&rows).map_err(err)?;
        Ok(Some(points_array(py, &self.inner, self.inner.draw(&y), &[p.rows])))
    }

    /// Spectral radius of each map's linear part, ``(k,)`` float64 (all < 1).
    #[getter]
    fn contraction<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        Array1::from_vec(self.inner.contraction().to_vec()).into_pyarray(py)
    }

    /// The fixed point of map ``i`` (a point of the attractor), drawn coordinates.
    fn fixed_point<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = super::big_int)] i: i128) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let i = super::usize_in("fixed_point", "i", i, 0, self.inner.n_maps().saturating_sub(1))?;
        let x = self.inner.fixed_point(i);
        let y = self.inner.start_points(&[x]).map_err(err)?;
        Ok(points_array(py, &self.inner, self.inner.draw(&y), &[]))
    }

    /// Deterministic iteration ``X_{k+1} = F(X_k)`` from a compact start set.
    ///
    /// Parameters
    /// ----------
    /// start : array_like, shape (m, k) or (k,)
    ///     Start points given by their first ``k <= dim`` lifted coordinates
    ///     (a point, the ends of a segment, the corners of a triangle, …);
    ///     missing coordinates are 0 and homogeneous ones are set to 1.
    /// levels : int
    ///     Number of rounds.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (n_maps**levels, m, D)
    ///     Image ``w`` of the start set; words in lexicographic order with
    ///     the outermost map first, so curves come out in order.
    fn iterate<'py>(&self, py: Python<'py>, start: &Bound<'py, PyAny>, #[pyo3(from_py_with = super::big_int)] levels: i128) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let levels = levels_in("iterate", levels)?;
        let s = rows(py, start, "start")?;
        let m = s.len();
        let out = run_interruptible(py, || self.inner.iterate(&s, levels))?;
        let words = out.len() / (m * self.inner.components().len() * self.inner.ambient_dim());
        Ok(points_array(py, &self.inner, out, &[words, m]))
    }

    /// Subdivision through the IFS: ``F^levels(P)``, every block ``S_w P``.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (n_maps**levels, n, D)
    ///     The refined control polygons (nets), one per word, in order.
    fn subdivide<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = super::big_int)] levels: i128) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let levels = levels_in("subdivide", levels)?;
        let out = run_interruptible(py, || self.inner.subdivide(levels))?;
        let n = self.inner.dim();
        let words = out.len() / (n * self.inner.components().len() * self.inner.ambient_dim());
        Ok(points_array(py, &self.inner, out, &[words, n]))
    }

    /// The chaos game: random map words applied to a point of the attractor.
    ///
    /// Parameters
    /// ----------
    /// n_points : int
    /// seed : int, default 0
    ///     Seed of the generator (xoshiro256++); equal seeds give equal output.
    /// probabilities : array_like, shape (n_maps,), optional
    ///     Map probabilities (normalized); uniform by default.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (n_points, D)
    #[pyo3(signature = (n_points, seed = 0, probabilities = None))]
    fn chaos_game<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = super::big_int)] n_points: i128,
        #[pyo3(from_py_with = super::big_int)] seed: i128,
        probabilities: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let n_points = super::usize_in("chaos_game", "n_points", n_points, 0, crate::ifs::render::MAX_OUTPUT)?;
        if !(0..=u64::MAX as i128).contains(&seed) {
            return Err(arg_err(format!("chaos_game: seed = {seed} is out of range; it must be an integer in [0, 2**64 - 1]")));
        }
        let seed = seed as u64;
        let out = run_interruptible(py, || self.inner.chaos_game(n_points, seed, probabilities.as_deref()))?;
        Ok(points_array(py, &self.inner, out, &[n_points]))
    }

    /// An ordered polyline on a curve attractor: ``n_maps**levels + 1``
    /// vertices, all on the curve, in parameter order.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray, shape (n_maps**levels + 1, D)
    fn polyline<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = super::big_int)] levels: i128) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let levels = levels_in("polyline", levels)?;
        let out = run_interruptible(py, || self.inner.polyline(levels))?;
        let count = out.len() / (self.inner.components().len() * self.inner.ambient_dim());
        Ok(points_array(py, &self.inner, out, &[count]))
    }

    /// A triangle mesh of a surface patch (or of the gasket) at ``levels``:
    /// images of the base triangulation of the parameter domain, vertices
    /// merged, all on the attractor.
    ///
    /// Returns
    /// -------
    /// vertices : numpy.ndarray, shape (V, D), float64
    /// triangles : numpy.ndarray, shape (T, 3), int64
    fn mesh<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = super::big_int)] levels: i128) -> PyResult<(Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArray2<i64>>)> {
        let levels = levels_in("mesh", levels)?;
        let (v, t) = run_interruptible(py, || self.inner.mesh(levels))?;
        let count = v.len() / self.inner.ambient_dim();
        Ok((points_array(py, &self.inner, v, &[count]), super::convert::u32_rows(py, &t)))
    }

    /// The IFS made of the maps in ``keep`` (its attractor is a subset; Fig. 9).
    fn subset(&self, keep: Vec<usize>) -> PyResult<PyIfs> {
        wrap(self.inner.subset(&keep))
    }

    /// The IFS whose attractor is the union of both (section 2.2): block-diagonal maps.
    fn union(&self, other: &PyIfs) -> PyResult<PyIfs> {
        wrap(self.inner.union(&other.inner))
    }
}

/// IFS from subdivision blocks ``(k, n, n)`` (rows summing to 1) and ``n``
/// control points ``(n, D)`` (eq. 2). Raises MeshError when the points are not
/// an affine basis or a map is not contractive.
#[pyfunction]
#[pyo3(signature = (blocks, control_points, name = "custom"))]
fn ifs_from_subdivision(py: Python<'_>, blocks: &Bound<'_, PyAny>, control_points: &Bound<'_, PyAny>, name: &str) -> PyResult<PyIfs> {
    let b = stack(py, blocks, "blocks")?;
    let p = rows(py, control_points, "control_points")?;
    wrap(Ifs::from_subdivision(b, &p, name))
}

fn affine_maps(py: Python<'_>, matrices: &Bound<'_, PyAny>, translations: &Bound<'_, PyAny>) -> PyResult<Vec<fractals::Affine>> {
    let a = stack(py, matrices, "matrices")?;
    let t = rows(py, translations, "translations")?;
    if a.len() != t.len() {
        return Err(arg_err("matrices and translations: different numbers of maps"));
    }
    Ok(a.iter().zip(t).map(|(m, t)| ((0..m.rows).map(|r| m.row(r).to_vec()).collect(), t)).collect())
}

/// The classical IFS of affine maps ``x -> A_i x + t_i``: matrices ``(k, D, D)``,
/// translations ``(k, D)``.
#[pyfunction]
#[pyo3(signature = (matrices, translations, name = "affine"))]
fn ifs_from_affine(py: Python<'_>, matrices: &Bound<'_, PyAny>, translations: &Bound<'_, PyAny>, name: &str) -> PyResult<PyIfs> {
    let maps = affine_maps(py, matrices, translations)?;
    wrap(Ifs::from_affine(&maps, name))
}

/// Eq. 5: subdivision rules for affine maps at reference control points
/// (barycentric w.r.t. nearby control points), drawn with ``control_points``.
#[pyfunction]
#[pyo3(signature = (matrices, translations, reference, control_points = None, name = "fractal"))]
fn ifs_from_affine_with_control(
    py: Python<'_>,
    matrices: &Bound<'_, PyAny>,
    translations: &Bound<'_, PyAny>,
    reference: &Bound<'_, PyAny>,
    control_points: Option<&Bound<'_, PyAny>>,
    name: &str,
) -> PyResult<PyIfs> {
    let maps = affine_maps(py, matrices, translations)?;
    let r = rows(py, reference, "reference")?;
    let p = match control_points {
        Some(c) => rows(py, c, "control_points")?,
        None => r.clone(),
    };
    wrap(fractals::affine_with_control(&maps, &r, &p, name))
}

fn curve_rules(arity: usize, stencils: Vec<Vec<(i64, f64)>>) -> rules::CurveRules {
    rules::CurveRules { arity, rules: stencils }
}

/// Curve IFS of a uniform scheme given by its rules: ``stencils[r]`` lists
/// ``(offset, weight)`` with ``p[m*i + r] = sum w * p[i + offset]``.
#[pyfunction]
#[pyo3(signature = (control_points, stencils, arity = 2, name = "curve"))]
fn ifs_curve(
    py: Python<'_>,
    control_points: &Bound<'_, PyAny>,
    stencils: Vec<Vec<(i64, f64)>>,
    #[pyo3(from_py_with = super::big_int)] arity: i128,
    name: &str,
) -> PyResult<PyIfs> {
    let arity = super::usize_in("curve", "arity", arity, 2, 64)?;
    let p = rows(py, control_points, "control_points")?;
    wrap(rules::curve_ifs(&curve_rules(arity, stencils), &p, name))
}

/// Plain subdivision of an open control polygon with the same rules.
#[pyfunction]
#[pyo3(signature = (control_points, stencils, levels, arity = 2))]
fn ifs_curve_subdivide<'py>(
    py: Python<'py>,
    control_points: &Bound<'py, PyAny>,
    stencils: Vec<Vec<(i64, f64)>>,
    #[pyo3(from_py_with = super::big_int)] levels: i128,
    #[pyo3(from_py_with = super::big_int)] arity: i128,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let levels = levels_in("subdivide_curve", levels)?;
    let arity = super::usize_in("subdivide_curve", "arity", arity, 2, 64)?;
    let p = rows(py, control_points, "control_points")?;
    let d = p[0].len();
    let rules = curve_rules(arity, stencils);
    let out = run_interruptible(py, || rules.subdivide(&p, levels))?;
    Ok(Array2::from_shape_vec((out.len(), d), out.concat()).expect("shape").into_pyarray(py))
}

/// The stencils of a named curve scheme: ``"cubic_bspline"``, ``"four_point"``, ``"chaikin"``.
#[pyfunction]
fn ifs_curve_stencils(scheme: &str) -> PyResult<Vec<Vec<(i64, f64)>>> {
    Ok(match scheme {
        "cubic_bspline" => rules::CurveRules::cubic_bspline(),
        "four_point" => rules::CurveRules::four_point(),
        "chaikin" => rules::CurveRules::chaikin(),
        _ => return Err(arg_err(format!("unknown curve scheme {scheme:?}"))),
    }
    .rules)
}

/// B-spline IFS by blossoming: degree, knots (without the two outer dummy
/// knots, ``len(knots) + 1 - degree`` control points) and the pieces
/// ``[(a, b), ...]`` the domain is split into.
#[pyfunction]
#[pyo3(signature = (control_points, degree, knots, pieces, name = "bspline"))]
fn ifs_bspline(py: Python<'_>, control_points: &Bound<'_, PyAny>, #[pyo3(from_py_with = super::big_int)] degree: i128, knots: Vec<f64>, pieces: Vec<(f64, f64)>, name: &str) -> PyResult<PyIfs> {
    let degree = super::usize_in("bspline", "degree", degree, 0, 64)?;
    let p = rows(py, control_points, "control_points")?;
    wrap(rules::bspline_ifs(degree, &knots, &pieces, &p, name))
}

/// Bézier curve of degree ``n - 1`` (de Casteljau halves).
#[pyfunction]
fn ifs_bezier(py: Python<'_>, control_points: &Bound<'_, PyAny>) -> PyResult<PyIfs> {
    let p = rows(py, control_points, "control_points")?;
    wrap(rules::bezier_ifs(&p))
}

/// Surface patch IFS: ``"bicubic"`` (16 points, 4x4 grid, 4 maps), ``"loop"``
/// (19 points on ``hex_lattice(2)``, 6 maps), ``"sqrt3"`` (61 points on
/// ``hex_lattice(4)``, 19 maps).
#[pyfunction]
fn ifs_surface(py: Python<'_>, control_points: &Bound<'_, PyAny>, scheme: &str) -> PyResult<PyIfs> {
    let p = rows(py, control_points, "control_points")?;
    let r = match scheme {
        "bicubic" => rules::bicubic_ifs(&p),
        "loop" => rules::loop_hexagon_ifs(&p),
        "sqrt3" => rules::sqrt3_hexagon_ifs(&p),
        _ => return Err(arg_err(format!("unknown surface scheme {scheme:?} (expected 'bicubic', 'loop' or 'sqrt3')"))),
    };
    wrap(r)
}

/// Plain subdivision of a surface control net with the same rules: returns
/// the refined points ``(N, D)`` and their lattice triangles ``(T, 3)``.
#[pyfunction]
fn ifs_surface_subdivide<'py>(py: Python<'py>, control_points: &Bound<'py, PyAny>, scheme: &str, #[pyo3(from_py_with = super::big_int)] levels: i128) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>)> {
    let levels = levels_in("subdivide_surface", levels)?;
    let p = rows(py, control_points, "control_points")?;
    let (r, sites) = rules::surface_control_sites(scheme, p.len()).map_err(err)?;
    let (s, pos) = run_interruptible(py, || rules::lattice_subdivide(&r, &sites, &p, levels))?;
    let d = p[0].len();
    let tris = rules::lattice_triangles(&s);
    Ok((Array2::from_shape_vec((pos.len(), d), pos.concat()).expect("shape").into_pyarray(py), super::convert::u32_rows(py, &tris)))
}

/// Cartesian positions ``(1 + 3r(r+1), 2)`` of the triangular-lattice points of
/// hex radius ``r``, in the order the hexagonal patches expect.
#[pyfunction]
fn ifs_hex_lattice<'py>(py: Python<'py>, #[pyo3(from_py_with = super::big_int)] radius: i128) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let radius = super::int_in("hex_lattice", "radius", radius, 0, 64)?;
    let pts = rules::hex_lattice(radius);
    let flat: Vec<f64> = pts.iter().flat_map(|p| rules::hex_to_xy([p[0] as f64, p[1] as f64])).collect();
    Ok(Array2::from_shape_vec((pts.len(), 2), flat).expect("shape").into_pyarray(py))
}

/// Koch curve with five control points (section 4.1); rules derived at the
/// reference points :func:`ifs_koch_reference`.
#[pyfunction]
fn ifs_koch(py: Python<'_>, control_points: &Bound<'_, PyAny>) -> PyResult<PyIfs> {
    let p = rows(py, control_points, "control_points")?;
    wrap(fractals::koch_ifs(&p))
}

/// Sierpinski gasket with six control points (section 4.2), Lagrange edge rules.
#[pyfunction]
fn ifs_gasket(py: Python<'_>, control_points: &Bound<'_, PyAny>) -> PyResult<PyIfs> {
    let p = rows(py, control_points, "control_points")?;
    wrap(fractals::gasket_ifs(&p))
}

/// The five reference Koch control points ``(5, 2)``.
#[pyfunction]
fn ifs_koch_reference<'py>(py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
    let r = fractals::koch_reference();
    Array2::from_shape_vec((5, 2), r.concat()).expect("shape").into_pyarray(py)
}

/// The six reference gasket control points ``(6, 2)``: corners at even indices.
#[pyfunction]
fn ifs_gasket_reference<'py>(py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
    let r = fractals::gasket_reference();
    Array2::from_shape_vec((6, 2), r.concat()).expect("shape").into_pyarray(py)
}

/// The classical Koch IFS (four similarities of the unit segment).
#[pyfunction]
fn ifs_koch_standard() -> PyResult<PyIfs> {
    wrap(Ifs::from_affine(&fractals::koch_maps(), "koch (standard)"))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyIfs>()?;
    m.add_function(wrap_pyfunction!(ifs_from_subdivision, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_from_affine, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_from_affine_with_control, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_curve, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_curve_subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_curve_stencils, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_bspline, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_bezier, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_surface, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_surface_subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_hex_lattice, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_koch, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_gasket, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_koch_reference, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_gasket_reference, m)?)?;
    m.add_function(wrap_pyfunction!(ifs_koch_standard, m)?)?;
    Ok(())
}
