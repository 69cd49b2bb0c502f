//! Schemes with their data: levels of `crate::schemes::level` run one after
//! another, carrying crease sharpness and attributes to the output and, on
//! request, returning the correspondence (origins and the subdivision
//! matrix `S`, composed over the levels).
//!
//! Vertex attributes are interpolated per level with that level's stencils
//! (`A ← S_k A`), never through the composed matrix, so they cost one
//! sparse product per level and column. Face attributes are gathered
//! through the composed face origins once at the end.

use super::mesh::PyMesh;
use crate::mesh::Mesh;
use crate::schemes::creases::{ring, Creases, SubdivOptions};
use crate::schemes::corner_linear::Primal;
use crate::schemes::face_varying::{FaceVarying, Interpolation};
use crate::schemes::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use crate::schemes::stencil::Stencils;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What a scheme binding passes on.
pub(crate) struct Spec {
    /// The scheme's name in messages and the progress bar.
    pub name: &'static str,
    /// Its count formulas, for the memory budget.
    pub predict: crate::budget::Predictor,
    pub options: SubdivOptions,
    /// The scheme reads and carries crease sharpness (Catmull-Clark, Loop).
    pub uses_creases: bool,
    /// How corner (face-varying) attributes are interpolated; None: the
    /// scheme has no face-varying rules and carries them with the generic
    /// corner transfer (`crate::schemes::corner_transfer`).
    pub face_varying: Option<Interpolation>,
    /// The level with vertex data interpolated by the scheme's direct
    /// masks (no stencils built), when it has one.
    pub with_data: Option<DataLevel>,
    /// Corner data read straight off the level's output numbering
    /// (`crate::schemes::corner_direct`) where the scheme has such a path
    /// and it applies; the generic corner transfer otherwise.
    pub corner_direct: Option<CornerLevel>,
    /// Positions are linear in the input's: the level's stencils are the
    /// subdivision matrix. When false (Menger) they are only the attribute
    /// transfer, and the correspondence says so.
    pub linear: bool,
    /// The level on an input nobody else holds (the previous level of a
    /// multi-level call), where the scheme frees part of it early (issue
    /// 19); plain calls only, the output equal to `level`'s.
    pub owned: Option<OwnedLevel>,
    /// Corner data at points born in large faces written by the scheme
    /// after the generic transfer, whose level then skips their dense rows.
    pub large_corners: Option<LargeCorners>,
}

/// A scheme's corner data at points born in large faces (open Doo-Sabin's
/// `open_large_corners`): where `applies` holds for the level's input, the
/// level is asked for `Request::skip_large_face_rows` and `fill` (input,
/// output, input rows, output rows, k) writes those corners after the
/// generic transfer.
pub(crate) struct LargeCorners {
    pub applies: fn(&Mesh) -> bool,
    pub fill: Box<dyn Fn(&Mesh, &Mesh, &[f64], &mut [f64], usize) -> crate::Result<()> + Send + Sync>,
}

/// A level that takes its input by value.
pub(crate) type OwnedLevel = Box<dyn Fn(Mesh, &Request) -> crate::Result<Level> + Send + Sync>;

impl Spec {
    /// Catmull-Clark or Loop: creases, face-varying data and direct data
    /// masks, with the keywords parsed (a `MeshError` names a bad one).
    pub fn with_rules(
        name: &'static str,
        predict: crate::budget::Predictor,
        boundary: &str,
        crease_method: &str,
        corner_interpolation: &str,
        with_data: impl Fn(&Mesh, &Request, &[(Vec<f64>, usize)]) -> crate::Result<(Level, Vec<Vec<f64>>)> + Send + Sync + 'static,
    ) -> PyResult<Spec> {
        Ok(Spec {
            name,
            predict,
            options: options(name, boundary, crease_method)?,
            uses_creases: true,
            face_varying: Some(self::corner_interpolation(name, corner_interpolation)?),
            with_data: Some(Box::new(with_data)),
            corner_direct: None,
            linear: true,
            owned: None,
            large_corners: None,
        })
    }

    /// A scheme without crease, face-varying or direct-data rules.
    pub fn plain(name: &'static str, predict: crate::budget::Predictor) -> Spec {
        Spec { name, predict, options: SubdivOptions::default(), uses_creases: false, face_varying: None, with_data: None, corner_direct: None, linear: true, owned: None, large_corners: None }
    }

    /// The scheme's own masks interpolate vertex data (no stencils built
    /// where they apply).
    pub fn with_direct(self, with_data: impl Fn(&Mesh, &Request, &[(Vec<f64>, usize)]) -> crate::Result<(Level, Vec<Vec<f64>>)> + Send + Sync + 'static) -> Spec {
        Spec { with_data: Some(Box::new(with_data)), ..self }
    }

    /// Corner data goes through `corners` (input, output, rows, k) where it
    /// applies (it returns `None` where not, and the generic transfer runs).
    pub fn with_corners(self, corners: impl Fn(&Mesh, &Mesh, &[f64], usize) -> crate::Result<Option<Vec<f64>>> + Send + Sync + 'static) -> Spec {
        Spec { corner_direct: Some(Box::new(corners)), ..self }
    }

    /// Corner data at points born in large faces come from `fill` after
    /// the generic transfer (`LargeCorners`).
    pub fn with_large_corners(
        self,
        applies: fn(&Mesh) -> bool,
        fill: impl Fn(&Mesh, &Mesh, &[f64], &mut [f64], usize) -> crate::Result<()> + Send + Sync + 'static,
    ) -> Spec {
        Spec { large_corners: Some(LargeCorners { applies, fill: Box::new(fill) }), ..self }
    }

    /// Levels after the first take their input by value (`owned`).
    pub fn with_owned(self, owned: impl Fn(Mesh, &Request) -> crate::Result<Level> + Send + Sync + 'static) -> Spec {
        Spec { owned: Some(Box::new(owned)), ..self }
    }

    /// A scheme whose positions are not linear in the input's: its levels'
    /// stencils carry attributes but are no subdivision matrix.
    pub fn nonlinear(name: &'static str, predict: crate::budget::Predictor) -> Spec {
        Spec { linear: false, ..Spec::plain(name, predict) }
    }
}

/// A level function that also interpolates vertex data.
pub(crate) type DataLevel = Box<dyn Fn(&Mesh, &Request, &[(Vec<f64>, usize)]) -> crate::Result<(Level, Vec<Vec<f64>>)> + Send + Sync>;

/// Corner rows of a level's output from its input's (input, output, rows,
/// k), or `None` where the scheme's direct path does not apply.
pub(crate) type CornerLevel = Box<dyn Fn(&Mesh, &Mesh, &[f64], usize) -> crate::Result<Option<Vec<f64>>> + Send + Sync>;

/// Corner data of a scheme with face-varying rules.
enum Corner {
    /// Exported corner rows under `FVAR_LINEAR_ALL`, read off each level's
    /// numbering ([`crate::schemes::corner_linear`]).
    Linear(Vec<f64>, usize),
    /// On its face-varying mesh (every other choice, or a level the linear
    /// path does not describe).
    Mesh(FaceVarying),
}

struct State<'a> {
    options: SubdivOptions,
    want_matrix: bool,
    want_origins: bool,
    creases: Option<Creases>,
    attrs: Vec<(Vec<f64>, usize)>,
    corners: Vec<Corner>,
    /// Per-corner rows of the schemes without face-varying rules.
    corner_rows: Vec<(Vec<f64>, usize)>,
    /// The scheme's direct corner path declined a level (a layout it does
    /// not read, such as Sierpinski's self-loops): the later levels, which
    /// keep that feature, ask for the transfer's stencils up front.
    corner_direct_declined: bool,
    matrix: Option<Stencils>,
    origins: Option<Origins>,
    name: &'a str,
    /// Index of the next level within this call.
    level: usize,
}

/// Runs `level` `iterations` times on `slf` with its data; returns a `Mesh`,
/// or `(Mesh, Correspondence)` when `correspondence` is true.
pub(crate) fn run<'py>(
    py: Python<'py>,
    slf: &PyMesh,
    iterations: i128,
    progress: bool,
    spec: Spec,
    correspondence: bool,
    level: impl Fn(&Mesh, &Request) -> crate::Result<Level> + Sync,
) -> PyResult<Bound<'py, PyAny>> {
    let input = &slf.inner;
    let options = spec.options;
    if !correspondence && slf.data.is_empty() {
        let (out, _) = super::iterate_with(py, input, iterations, progress, spec.name, spec.predict, 0usize, |src, k| {
            *k += 1;
            let req = Request { options, level: *k - 1, ..Default::default() };
            match (src, spec.owned.as_ref()) {
                (super::Src::Level(m), Some(owned)) => owned(m, &req),
                (src, _) => level(&src, &req),
            }
            .map(|l| l.mesh)
        })?;
        return Ok(Bound::new(py, PyMesh::wrap(out.unwrap_or_else(|| input.clone())))?.into_any());
    }
    // vertex attributes as flat float64 rows
    let mut attrs = Vec::with_capacity(slf.data.vertex.len());
    let mut shapes = Vec::with_capacity(slf.data.vertex.len());
    for (_, a) in &slf.data.vertex {
        let a = a.bind(py).cast::<PyArrayDyn<f64>>()?.readonly();
        let shape = a.shape().to_vec();
        let k = if shape.len() == 2 { shape[1] } else { 1 };
        attrs.push((a.as_slice()?.to_vec(), k));
        shapes.push(shape.len());
    }
    // corner attributes: value ids by exact equality of rows, then their face-varying meshes
    let mut corners = Vec::with_capacity(slf.data.corner.len());
    let mut corner_shapes = Vec::with_capacity(slf.data.corner.len());
    let mut corner_rows: Vec<(Vec<f64>, usize)> = Vec::new();
    if !slf.data.corner.is_empty() {
        for (_, a) in &slf.data.corner {
            let a = a.bind(py).cast::<PyArrayDyn<f64>>()?.readonly();
            let shape = a.shape().to_vec();
            let k = if shape.len() == 2 { shape[1] } else { 1 };
            if spec.face_varying.is_none() {
                // no face-varying rules: the generic corner transfer (schemes::corner_transfer)
                corner_rows.push((a.as_slice()?.to_vec(), k));
                corner_shapes.push(shape.len());
                continue;
            }
            if spec.face_varying == Some(Interpolation::All) {
                corners.push(Corner::Linear(a.as_slice()?.to_vec(), k));
            } else {
                let (ids, table) = dedupe(a.as_slice()?, k);
                let cr = if spec.uses_creases { slf.data.creases.as_ref() } else { None };
                corners.push(Corner::Mesh(super::detach(py, || FaceVarying::new(input, &ids, &table, k, cr)).map_err(super::err)?));
            }
            corner_shapes.push(shape.len());
        }
    }
    let need_origins = correspondence || !slf.data.face.is_empty();
    let state = State {
        options,
        want_matrix: correspondence,
        want_origins: need_origins,
        creases: if spec.uses_creases { slf.data.creases.clone() } else { None },
        attrs,
        corners,
        corner_rows,
        corner_direct_declined: false,
        matrix: None,
        origins: None,
        name: spec.name,
        level: 0,
    };
    let (out, st) = super::iterate_with(py, input, iterations, progress, spec.name, spec.predict, state, |src, st| {
        let m: &Mesh = &src;
        let direct = spec.with_data.as_ref().filter(|_| !st.attrs.is_empty());
        // corner rows: the scheme's direct path where it applies (no stencils or
        // origins needed), else the generic transfer
        let corners_direct = spec.corner_direct.as_ref().filter(|_| !st.corner_direct_declined && crate::schemes::corner_direct::applies(m));
        let transfer = !st.corner_rows.is_empty() && corners_direct.is_none();
        // the stencils only carry corner data (no matrix, no vertex data,
        // which may read the stencils even through a direct path): the
        // scheme writes the corners of large faces itself, and the level
        // skips their dense rows
        let large = spec.large_corners.as_ref().filter(|l| transfer && !st.want_matrix && st.attrs.is_empty() && (l.applies)(m));
        let req = Request {
            stencils: st.want_matrix || (!st.attrs.is_empty() && direct.is_none()) || transfer,
            origins: st.want_origins || transfer,
            creases: st.creases.as_ref(),
            options: st.options,
            level: st.level,
            skip_large_face_rows: large.is_some(),
        };
        st.level += 1;
        if req.stencils && large.is_none() {
            crate::budget::check_stencils(spec.name, m)?;
        }
        let lv = match direct {
            Some(f) => {
                let (lv, data) = f(m, &req, &st.attrs)?;
                for ((a, _), d) in st.attrs.iter_mut().zip(data) {
                    *a = d;
                }
                lv
            }
            None => level(m, &req)?,
        };
        if req.stencils && lv.stencils.is_none() {
            return Err(crate::MeshError::Precondition(format!(
                "{}: its level has no stencils, so it has no subdivision matrix and cannot interpolate vertex attributes",
                st.name
            )));
        }
        if let Some(s) = &lv.stencils {
            if direct.is_none() {
                for (a, k) in &mut st.attrs {
                    *a = s.apply(a, *k)?;
                }
            }
            if st.want_matrix {
                st.matrix = Some(match &st.matrix {
                    None => s.clone(),
                    Some(prev) => s.compose(prev)?,
                });
            }
        }
        if !st.corners.is_empty() {
            let interp = spec.face_varying.unwrap_or_default();
            let geometry_creases = st.creases.clone();
            let primal = if spec.name == "loop" { Primal::Triangles } else { Primal::Quads };
            for c in &mut st.corners {
                let fv = match c {
                    Corner::Linear(rows, k) => match crate::schemes::corner_linear::level(m, &lv.mesh, primal, rows, *k)? {
                        Some(next) => {
                            *rows = next;
                            continue;
                        }
                        // not the layout the linear path reads: the data's own mesh from here on
                        None => {
                            let (ids, table) = dedupe(rows, *k);
                            FaceVarying::new(m, &ids, &table, *k, None)?
                        }
                    },
                    Corner::Mesh(fv) => std::mem::replace(fv, FaceVarying { mesh: Mesh::new(), values: vec![], k: 0, creases: None }),
                };
                *c = Corner::Mesh(fv.with_creases(m, geometry_creases.as_ref(), st.options)?.with_plus_corners(m, interp)?.level(&level, interp, st.options)?);
            }
        }
        let mut rest: Vec<usize> = Vec::new(); // corner arrays the direct path did not take
        match corners_direct {
            Some(f) => {
                for (i, (rows, k)) in st.corner_rows.iter_mut().enumerate() {
                    match f(m, &lv.mesh, rows, *k)? {
                        Some(next) => *rows = next,
                        None => {
                            st.corner_direct_declined = true;
                            rest.push(i);
                        }
                    }
                }
            }
            None if transfer => rest.extend(0..st.corner_rows.len()),
            None => {}
        }
        if !rest.is_empty() {
            // the same level again, with what the transfer reads, when the first did not keep it
            let full;
            let lvt = if lv.stencils.is_some() && lv.origins.is_some() {
                &lv
            } else {
                if large.is_none() {
                    crate::budget::check_stencils(spec.name, m)?;
                }
                full = level(m, &Request { stencils: true, origins: true, ..req })?;
                &full
            };
            let (Some(s), Some(o)) = (&lvt.stencils, &lvt.origins) else {
                return Err(crate::MeshError::Precondition(format!("{}: its level has no stencils or origins, so it cannot carry corner attributes", st.name)));
            };
            let mut arrays: Vec<(Vec<f64>, usize)> = rest.iter().map(|&i| std::mem::take(&mut st.corner_rows[i])).collect();
            let inputs: Vec<Vec<f64>> = if large.is_some() { arrays.iter().map(|(a, _)| a.clone()).collect() } else { Vec::new() };
            crate::schemes::corner_transfer::transfer(m, &lvt.mesh, s, o, &mut arrays)?;
            if let Some(l) = large {
                for ((a, k), input) in arrays.iter_mut().zip(&inputs) {
                    (l.fill)(m, &lvt.mesh, input, a, *k)?;
                }
            }
            for (&i, a) in rest.iter().zip(arrays) {
                st.corner_rows[i] = a;
            }
        }
        if let (Some(o), true) = (lv.origins, st.want_origins) {
            st.origins = Some(match &st.origins {
                None => o,
                Some(prev) => o.compose(prev),
            });
        }
        st.creases = if spec.uses_creases { lv.creases } else { None };
        Ok(lv.mesh)
    })?;
    let zero_levels = out.is_none();
    let out = out.unwrap_or_else(|| input.clone());
    let origins = if need_origins { Some(st.origins.unwrap_or_else(|| identity_origins(input))) } else { None };
    let (face_kinds, face_origins, face_parents) = match &origins {
        Some(o) => exported_face_origins(input, &out, o),
        None => (vec![], vec![], vec![]),
    };
    // the output's data
    let mut data = super::data::MeshData { creases: if zero_levels && spec.uses_creases { slf.data.creases.clone() } else { st.creases }, ..Default::default() };
    for (((name, _), (a, k)), nd) in slf.data.vertex.iter().zip(st.attrs).zip(shapes) {
        let arr = PyArray1::from_vec(py, a);
        let arr = if nd == 2 { arr.reshape([out.n_vertices(), k])?.into_any() } else { arr.into_any() };
        arr.getattr("flags")?.setattr("writeable", false)?;
        data.vertex.push((name.clone(), arr.unbind()));
    }
    for (((name, _), (v, k)), &nd) in slf.data.corner.iter().zip(st.corner_rows).zip(&corner_shapes) {
        let n = v.len() / k.max(1);
        let arr = PyArray1::from_vec(py, v);
        let arr = if nd == 2 { arr.reshape([n, k])?.into_any() } else { arr.into_any() };
        arr.getattr("flags")?.setattr("writeable", false)?;
        data.corner.push((name.clone(), arr.unbind()));
    }
    for (((name, _), c), nd) in slf.data.corner.iter().zip(st.corners).zip(corner_shapes) {
        let (v, k) = match c {
            Corner::Linear(v, k) => (v, k),
            Corner::Mesh(fv) => {
                let rows = super::detach(py, || fv.corner_rows()).map_err(super::err)?;
                let k = fv.k;
                let mut v = Vec::with_capacity(rows.len() * k);
                for r in rows {
                    v.extend_from_slice(&fv.values[r as usize * k..(r as usize + 1) * k]);
                }
                (v, k)
            }
        };
        let n = v.len() / k.max(1);
        let arr = PyArray1::from_vec(py, v);
        let arr = if nd == 2 { arr.reshape([n, k])?.into_any() } else { arr.into_any() };
        arr.getattr("flags")?.setattr("writeable", false)?;
        data.corner.push((name.clone(), arr.unbind()));
    }
    if !slf.data.face.is_empty() {
        let idx = PyArray1::from_vec(py, face_parents.clone());
        for (name, a) in &slf.data.face {
            let arr = a.bind(py).call_method1("take", (&idx, 0))?;
            arr.getattr("flags")?.setattr("writeable", false)?;
            data.face.push((name.clone(), arr.unbind()));
        }
    }
    let mesh = Bound::new(py, PyMesh::with_data(out, data))?;
    if !correspondence {
        return Ok(mesh.into_any());
    }
    let out = &mesh.get().inner;
    let o = origins.expect("requested");
    let (vertex_kinds, vertex_origins) = exported_vertex_origins(input, &o);
    let matrix = st.matrix.unwrap_or_else(|| Stencils::identity(input.n_vertices()));
    let kw = PyDict::new(py);
    kw.set_item("face_parents", PyArray1::from_vec(py, face_parents))?;
    kw.set_item("face_kinds", PyArray1::from_vec(py, face_kinds))?;
    kw.set_item("face_origins", PyArray1::from_vec(py, face_origins))?;
    kw.set_item("vertex_kinds", PyArray1::from_vec(py, vertex_kinds))?;
    kw.set_item("vertex_origins", PyArray1::from_vec(py, vertex_origins))?;
    kw.set_item("indptr", PyArray1::from_vec(py, matrix.off.iter().map(|&x| x as i64).collect()))?;
    kw.set_item("indices", PyArray1::from_vec(py, matrix.col.iter().map(|&x| x as i64).collect()))?;
    kw.set_item("weights", PyArray1::from_vec(py, matrix.w))?;
    kw.set_item("shape", (out.n_vertices(), input.n_vertices()))?;
    kw.set_item("linear", spec.linear)?;
    kw.set_item("scheme", spec.name)?;
    let c = py.import("topomesh.correspondence")?.getattr("Correspondence")?.call((), Some(&kw))?;
    Ok(pyo3::types::PyTuple::new(py, [mesh.into_any(), c])?.into_any())
}

/// Value ids of rows of `k` numbers by exact equality (bit patterns, with
/// -0.0 equal to 0.0), and the table of distinct rows in first-seen order
/// (OBJ's `vt` table, `io::obj::distinct_rows`).
fn dedupe(a: &[f64], k: usize) -> (Vec<u32>, Vec<f64>) {
    let (first, ids) = crate::io::obj::distinct_rows(a, k);
    let k = k.max(1);
    (ids, first.iter().flat_map(|&c| a[c * k..(c + 1) * k].iter().copied()).collect())
}

/// Zero levels: every element is its own origin.
fn identity_origins(m: &Mesh) -> Origins {
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    Origins {
        vertex_kind: vec![VERTEX; nv],
        vertex: (0..nv as u32).collect(),
        edge_kind: vec![EDGE; ne],
        edge: (0..ne as u32).collect(),
        face_kind: vec![FACE; nf],
        face: (0..nf as u32).collect(),
    }
}

/// Exported index of every internal face (-1 for holes).
fn face_export(m: &Mesh) -> Vec<i64> {
    let mut k = 0i64;
    m.f_hole
        .iter()
        .map(|&h| {
            if h {
                -1
            } else {
                k += 1;
                k - 1
            }
        })
        .collect()
}

/// Per exported output face: origin kind, origin index (exported ids) and
/// the parent face: the origin face, or for a face born from an edge or a
/// vertex the first real face of that edge (its first side) or around that
/// vertex (from its first outgoing half-edge).
fn exported_face_origins(input: &Mesh, out: &Mesh, o: &Origins) -> (Vec<i8>, Vec<i64>, Vec<i64>) {
    let fe = face_export(input);
    let (_, _, face) = input.halfedge_columns();
    let real = |h: u32| -> Option<i64> { (!input.f_hole[face[h as usize] as usize]).then(|| fe[face[h as usize] as usize]) };
    let n = out.n_faces() - out.n_holes();
    let (mut kinds, mut idx, mut parents) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    for f in 0..out.n_faces() {
        if out.f_hole[f] {
            continue;
        }
        let (k, i) = (o.face_kind[f], o.face[f]);
        kinds.push(k as i8);
        let parent = match k {
            FACE => fe[i as usize],
            EDGE => real(2 * i).or_else(|| real(2 * i + 1)).unwrap_or(-1),
            _ => {
                let v = input.v_out[i as usize];
                if v & crate::mesh::POINT != 0 {
                    fe[(v & !crate::mesh::POINT) as usize]
                } else {
                    ring(input, v).find_map(real).unwrap_or(-1)
                }
            }
        };
        idx.push(if k == FACE { fe[i as usize] } else { i as i64 });
        parents.push(parent);
    }
    (kinds, idx, parents)
}

fn exported_vertex_origins(input: &Mesh, o: &Origins) -> (Vec<i8>, Vec<i64>) {
    let fe = face_export(input);
    o.vertex_kind
        .iter()
        .zip(&o.vertex)
        .map(|(&k, &i)| (k as i8, if k == FACE { fe[i as usize] } else { i as i64 }))
        .unzip()
}


/// Parses the ``boundary`` and ``crease_method`` keywords.
pub(crate) fn corner_interpolation(call: &str, s: &str) -> PyResult<Interpolation> {
    Ok(match s {
        "all" => Interpolation::All,
        "boundaries" => Interpolation::Boundaries,
        "corners_only" => Interpolation::CornersOnly,
        "corners_plus1" => Interpolation::CornersPlus1,
        "corners_plus2" => Interpolation::CornersPlus2,
        "smooth" => Interpolation::Smooth,
        _ => return Err(super::arg_err(format!("{call}: corner_interpolation = {s:?}; expected \"all\" (linear, OpenSubdiv's default), \"boundaries\", \"corners_only\", \"corners_plus1\", \"corners_plus2\" or \"smooth\""))),
    })
}

pub(crate) fn options(call: &str, boundary: &str, crease_method: &str) -> PyResult<SubdivOptions> {
    use crate::schemes::creases::{Boundary, CreaseMethod};
    let boundary = match boundary {
        "edge_and_corner" => Boundary::EdgeAndCorner,
        "edge_only" => Boundary::EdgeOnly,
        _ => return Err(super::arg_err(format!("{call}: boundary = {boundary:?}; expected \"edge_and_corner\" (OpenSubdiv's default) or \"edge_only\""))),
    };
    let crease_method = match crease_method {
        "uniform" => CreaseMethod::Uniform,
        "chaikin" => CreaseMethod::Chaikin,
        _ => return Err(super::arg_err(format!("{call}: crease_method = {crease_method:?}; expected \"uniform\" or \"chaikin\""))),
    };
    Ok(SubdivOptions { boundary, crease_method })
}
