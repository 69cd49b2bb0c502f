//! One level of a scheme with what a pipeline asks of it beside the mesh:
//! the subdivision stencils (the matrix `S`), the correspondence of every
//! output element with the input element it was born from, and the crease
//! sharpness carried to the output.
//!
//! Origins use internal ids (hole faces included); the Python layer maps
//! them to exported indices. A scheme fills only what the [`Request`] asks
//! for, so a plain call costs nothing extra.

use super::creases::{Creases, SubdivOptions};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};

/// The kind of an input element an output element was born from.
pub const VERTEX: u8 = 0;
pub const EDGE: u8 = 1;
pub const FACE: u8 = 2;

/// `(kind, index)` of the input element every output vertex, edge and face
/// was born from: the lowest-dimensional input element whose refinement
/// contains it (a vertex point comes from its vertex, an edge point from
/// its edge, a face point or a face's inner edge from its face).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Origins {
    pub vertex_kind: Vec<u8>,
    pub vertex: Vec<u32>,
    pub edge_kind: Vec<u8>,
    pub edge: Vec<u32>,
    pub face_kind: Vec<u8>,
    pub face: Vec<u32>,
}

impl Origins {
    pub fn with_capacity(nv: usize, ne: usize, nf: usize) -> Origins {
        Origins {
            vertex_kind: Vec::with_capacity(nv),
            vertex: Vec::with_capacity(nv),
            edge_kind: Vec::with_capacity(ne),
            edge: Vec::with_capacity(ne),
            face_kind: Vec::with_capacity(nf),
            face: Vec::with_capacity(nf),
        }
    }

    /// Origins of `self` (a level made from `prev`'s output) expressed in
    /// `prev`'s input: each element's origin is replaced by the origin of
    /// the element it names.
    pub fn compose(&self, prev: &Origins) -> Origins {
        let look = |k: u8, i: u32| -> (u8, u32) {
            let i = i as usize;
            match k {
                VERTEX => (prev.vertex_kind[i], prev.vertex[i]),
                EDGE => (prev.edge_kind[i], prev.edge[i]),
                _ => (prev.face_kind[i], prev.face[i]),
            }
        };
        let map = |kinds: &[u8], idx: &[u32]| -> (Vec<u8>, Vec<u32>) { kinds.iter().zip(idx).map(|(&k, &i)| look(k, i)).unzip() };
        let (vertex_kind, vertex) = map(&self.vertex_kind, &self.vertex);
        let (edge_kind, edge) = map(&self.edge_kind, &self.edge);
        let (face_kind, face) = map(&self.face_kind, &self.face);
        Origins { vertex_kind, vertex, edge_kind, edge, face_kind, face }
    }

    /// Checks lengths against `out` and indices against `input` (tests and
    /// debug builds).
    pub fn check(&self, input: &Mesh, out: &Mesh) -> std::result::Result<(), String> {
        let ok = |kinds: &[u8], idx: &[u32], n: usize, what: &str| -> std::result::Result<(), String> {
            if kinds.len() != n || idx.len() != n {
                return Err(format!("{} {what} origins for {n} {what}s", kinds.len()));
            }
            for (j, (&k, &i)) in kinds.iter().zip(idx).enumerate() {
                let lim = match k {
                    VERTEX => input.n_vertices(),
                    EDGE => input.n_edges(),
                    FACE => input.n_faces(),
                    _ => return Err(format!("{what} {j}: kind {k}")),
                };
                if i as usize >= lim {
                    return Err(format!("{what} {j}: origin ({k}, {i}) out of range"));
                }
            }
            Ok(())
        };
        ok(&self.vertex_kind, &self.vertex, out.n_vertices(), "vertex")?;
        ok(&self.edge_kind, &self.edge, out.n_edges(), "edge")?;
        ok(&self.face_kind, &self.face, out.n_faces(), "face")
    }
}

/// What a caller wants from a level beside the mesh.
#[derive(Clone, Copy, Debug, Default)]
pub struct Request<'a> {
    pub stencils: bool,
    pub origins: bool,
    /// Crease sharpness of the input (Catmull-Clark and Loop).
    pub creases: Option<&'a Creases>,
    pub options: SubdivOptions,
    /// Index of this level within one call (0 for the first): √3's
    /// boundary rule refines the boundary on odd indices only.
    pub level: usize,
    /// The stencils are read only by the corner transfer, whose caller
    /// writes the corners at points born in large faces itself: a scheme
    /// may give those points a placeholder row (open Doo-Sabin's corner
    /// points in real faces of more than 64 corners, whose dense rows cost
    /// n² per n-gon). Positions are unaffected.
    pub skip_large_face_rows: bool,
}

impl Request<'_> {
    /// Nothing beyond the mesh.
    pub fn plain() -> Request<'static> {
        Request::default()
    }

    /// Whether `m` sees only the closed-surface rules: no hole, no nonzero
    /// sharpness (the schemes' direct masks apply).
    pub fn smooth_on(&self, m: &Mesh) -> bool {
        m.n_holes() == 0 && self.creases.map_or(true, |c| c.is_smooth())
    }
}

/// The shared tail of the primal levels (Catmull-Clark, Loop): positions
/// from `stencils` unless `smooth` (then the scheme's `direct` masks), the
/// host's connectivity, and the output's crease sharpness when asked for.
#[allow(clippy::too_many_arguments)]
pub(crate) fn primal_output(
    m: &Mesh,
    fl: super::hosts::FaceLayout,
    face_point: Vec<u32>,
    ls: &super::creases::LevelSharpness,
    req: &Request,
    stencils: Option<&Stencils>,
    smooth: bool,
    direct: impl FnOnce() -> Result<Vec<glam::DVec3>>,
) -> Result<(Mesh, Option<Creases>)> {
    // positions after the connectivity (issue 19: peak memory); one per
    // input vertex, input edge and face point
    let n_points = m.n_vertices() + m.n_edges() + face_point.iter().filter(|&&x| x != crate::mesh::NONE && x != super::hosts::HOLE).count();
    let pos = || match (stencils, smooth) {
        (Some(s), false) => s.apply_points(&m.pos),
        _ => direct(),
    };
    let (mesh, sides) = super::primal_columns::primal_columns_late(m, fl, face_point, n_points, req.creases.is_some(), pos)?;
    let creases = match (req.creases, &sides) {
        (Some(c), Some(sd)) => Some(ls.child_creases(m, Some(c), sd, mesh.n_vertices())),
        _ => None,
    };
    Ok((mesh, creases))
}

/// A level's output.
#[derive(Debug)]
pub struct Level {
    pub mesh: Mesh,
    pub stencils: Option<Stencils>,
    pub origins: Option<Origins>,
    pub creases: Option<Creases>,
}

impl Level {
    pub fn plain(mesh: Mesh) -> Level {
        Level { mesh, stencils: None, origins: None, creases: None }
    }
}

/// Edge origins from face and vertex origins, for the primal schemes whose
/// output edges either split an input edge (one end is that edge's point,
/// the other an input vertex's point) or lie inside an input face: an edge
/// between a vertex-born and an edge-born point is born from that edge, and
/// every other edge from the face of its first side's output face.
pub fn primal_edge_origins(out: &Mesh, o: &mut Origins) {
    let (_, vert, face) = out.halfedge_columns();
    let ne = out.n_edges();
    o.edge_kind.clear();
    o.edge.clear();
    o.edge_kind.reserve_exact(ne);
    o.edge.reserve_exact(ne);
    for e in 0..ne {
        let (a, b) = (vert[2 * e] as usize, vert[2 * e + 1] as usize);
        let (ka, kb) = (o.vertex_kind[a], o.vertex_kind[b]);
        if ka == EDGE && kb == VERTEX {
            o.edge_kind.push(EDGE);
            o.edge.push(o.vertex[a]);
        } else if ka == VERTEX && kb == EDGE {
            o.edge_kind.push(EDGE);
            o.edge.push(o.vertex[b]);
        } else {
            // inside a face: take a real (non-hole) side
            let f = if out.f_hole[face[2 * e] as usize] { face[2 * e + 1] } else { face[2 * e] } as usize;
            o.edge_kind.push(o.face_kind[f]);
            o.edge.push(o.face[f]);
        }
    }
}

/// Runs a level on `m` with its point-spheres set aside (as
/// [`super::hosts::with_point_spheres`], holes allowed: the scheme decides),
/// then appends them unchanged, with identity stencil rows and origins.
pub fn with_point_spheres_level(m: &Mesh, req: &Request, step: impl Fn(&Mesh, &Request) -> Result<Level>) -> Result<Level> {
    crate::cancel::check()?;
    let n_points = m.v_out.iter().filter(|&&o| o & POINT != 0).count();
    if n_points == 0 {
        return step(m, req);
    }
    let mut vmap = vec![NONE; m.n_vertices()];
    let mut vback = Vec::with_capacity(m.n_vertices() - n_points);
    let mut fmap = vec![NONE; m.n_faces()];
    let mut fback = Vec::with_capacity(m.n_faces());
    let mut points = Vec::with_capacity(n_points);
    let mut rest = Mesh::new();
    for (v, &o) in m.v_out.iter().enumerate() {
        if o & POINT != 0 {
            points.push(v);
        } else {
            vmap[v] = rest.pos.len() as u32;
            vback.push(v as u32);
            rest.pos.push(m.pos[v]);
            rest.v_out.push(o);
        }
    }
    for (f, &s) in m.f_start.iter().enumerate() {
        if s & POINT == 0 {
            fmap[f] = rest.f_start.len() as u32;
            fback.push(f as u32);
            rest.f_start.push(s);
            rest.f_hole.push(m.f_hole[f]);
        }
    }
    crate::cancel::check()?;
    rest.he_next = m.he_next.clone();
    rest.he_prev = m.he_prev.clone();
    rest.he_vert = m.he_vert.iter().map(|&v| vmap[v as usize]).collect();
    rest.he_face = m.he_face.iter().map(|&f| fmap[f as usize]).collect();
    let rest_creases = req.creases.map(|c| Creases { edge: c.edge.clone(), vertex: vback.iter().map(|&v| c.vertex[v as usize]).collect() });
    let sub = Request { creases: rest_creases.as_ref(), ..*req };
    crate::cancel::check()?;
    let mut lv = if rest.n_faces() == 0 {
        Level {
            mesh: Mesh::new(),
            stencils: req.stencils.then(|| Stencils { off: vec![0], col: vec![], w: vec![], n_cols: 0 }),
            origins: req.origins.then(Origins::default),
            creases: req.creases.map(|_| Creases::default()),
        }
    } else {
        step(&rest, &sub)?
    };
    let out = &mut lv.mesh;
    for &v in &points {
        let (ov, of) = (out.pos.len() as u32, out.f_start.len() as u32);
        out.pos.push(m.pos[v]);
        out.v_out.push(POINT | of);
        out.f_start.push(POINT | ov);
        out.f_hole.push(false);
    }
    if let Some(s) = &mut lv.stencils {
        for c in &mut s.col {
            *c = vback[*c as usize];
        }
        s.n_cols = m.n_vertices();
        for &v in &points {
            s.col.push(v as u32);
            s.w.push(1.0);
            s.off.push(s.col.len());
        }
    }
    if let Some(o) = &mut lv.origins {
        let back = |k: &[u8], i: &mut [u32]| {
            for (k, i) in k.iter().zip(i.iter_mut()) {
                match *k {
                    VERTEX => *i = vback[*i as usize],
                    FACE => *i = fback[*i as usize],
                    _ => {}
                }
            }
        };
        back(&o.vertex_kind, &mut o.vertex);
        back(&o.edge_kind, &mut o.edge);
        back(&o.face_kind, &mut o.face);
        for &v in &points {
            o.vertex_kind.push(VERTEX);
            o.vertex.push(v as u32);
            o.face_kind.push(FACE);
            o.face.push((m.v_out[v] & !POINT) as u32);
        }
    }
    if let Some(c) = &mut lv.creases {
        c.vertex.extend(points.iter().map(|_| 0.0));
    }
    Ok(lv)
}

/// The value of `cell`, made by `make` on first use (what the unstable
/// `OnceCell::get_or_try_init` does): the data levels build their face
/// layout or fan once for all the data columns.
pub(crate) fn once<T>(cell: &std::cell::OnceCell<T>, make: impl FnOnce() -> Result<T>) -> Result<&T> {
    if let Some(v) = cell.get() {
        return Ok(v);
    }
    let _ = cell.set(make()?);
    Ok(cell.get().expect("just set"))
}

/// [`level_with_data`] for a scheme whose connectivity does not depend on
/// the positions and whose positions are the stencils applied to them
/// (Catmull-Clark, Doo-Sabin, Loop after its centroid fan): where the
/// stencils would hold over 16 terms per corner (Σ n² over the real faces,
/// large faces) and the data would go through them (holes or creases, no
/// stencils asked for), the data go through the
/// positions-only level instead, three columns at a time as the positions
/// of a copy of the mesh. The stencils hold all n² terms of an n-gon's
/// rows (an open P8000 with one attribute took 1.9 s); the positions-only
/// rows take a large face's mean or sums once. Data with a non-finite
/// value, or that a level refuses as positions, take the stencils.
pub fn level_with_data_linear(
    m: &Mesh,
    req: &Request,
    data: &[(Vec<f64>, usize)],
    level: impl Fn(&Mesh, &Request) -> Result<Level>,
    direct: impl Fn(&[f64], usize) -> Result<Vec<f64>>,
) -> Result<(Level, Vec<Vec<f64>>)> {
    let smooth = masks_apply(m, req);
    // the stencils' terms grow as Σ n² over the real faces; past 16 terms
    // per corner a level per three columns costs less
    let large = || {
        let (mut sq, mut corners) = (0u64, 0u64);
        for f in (0..m.n_faces()).filter(|&f| !m.f_hole[f] && m.f_start[f] & POINT == 0) {
            let n = m.face_degree(crate::mesh::FaceId(f as u32)) as u64;
            sq += n * n;
            corners += n;
        }
        sq > 16 * corners
    };
    if data.is_empty() || smooth || req.stencils || !large() {
        return level_with_data(m, req, data, level, direct);
    }
    let lv = level(m, req)?;
    let plain = Request { origins: false, ..*req };
    let nv = m.n_vertices();
    let rows = lv.mesh.n_vertices();
    // three columns at a time as a copy's positions; None where a level
    // refuses them (positions must be finite: NaN or huge data)
    let through_positions = |a: &[f64], k: usize| -> Option<Vec<f64>> {
        let mut o = vec![0.0; rows * k];
        let mut copy = m.clone();
        for c in (0..k).step_by(3) {
            for v in 0..nv {
                let x = |j: usize| if c + j < k { a[v * k + c + j] } else { 0.0 };
                copy.pos[v] = glam::DVec3::new(x(0), x(1), x(2));
            }
            let p = level(&copy, &plain).ok()?.mesh.pos;
            for (r, q) in p.iter().enumerate() {
                for j in 0..(k - c).min(3) {
                    o[r * k + c + j] = q[j];
                }
            }
        }
        Some(o)
    };
    let mut stencils = None;
    let mut out = Vec::with_capacity(data.len());
    for (a, k) in data {
        let o = match a.iter().all(|x| x.is_finite()).then(|| through_positions(a, *k)).flatten() {
            Some(o) => o,
            None => {
                crate::cancel::check()?;
                if stencils.is_none() {
                    stencils = level(m, &Request { stencils: true, ..*req })?.stencils;
                }
                stencils.as_ref().expect("requested").apply(a, *k)?
            }
        };
        out.push(o);
    }
    Ok((lv, out))
}

/// Whether the scheme's direct masks interpolate data on `m`: a smooth
/// closed mesh without point-spheres ([`level_with_data`]).
fn masks_apply(m: &Mesh, req: &Request) -> bool {
    req.smooth_on(m) && !m.v_out.iter().any(|&o| o & POINT != 0)
}

/// A level that also interpolates vertex data (row-major `(rows, k)`
/// arrays): through `direct` (the scheme's masks applied to the data, no
/// stencils built) on a smooth closed mesh without point-spheres and when
/// no stencils are requested, else through the level's stencils.
pub fn level_with_data(
    m: &Mesh,
    req: &Request,
    data: &[(Vec<f64>, usize)],
    level: impl Fn(&Mesh, &Request) -> Result<Level>,
    direct: impl Fn(&[f64], usize) -> Result<Vec<f64>>,
) -> Result<(Level, Vec<Vec<f64>>)> {
    let smooth = masks_apply(m, req);
    if data.is_empty() || (smooth && !req.stencils) {
        let lv = level(m, req)?;
        let out = data.iter().map(|(a, k)| direct(a, *k)).collect::<Result<_>>()?;
        return Ok((lv, out));
    }
    let mut lv = level(m, &Request { stencils: true, ..*req })?;
    let st = lv.stencils.as_ref().expect("requested");
    let out = data.iter().map(|(a, k)| st.apply(a, *k)).collect::<Result<_>>()?;
    if !req.stencils {
        lv.stencils = None;
    }
    Ok((lv, out))
}
