//! The simplest subdivision scheme (J. Peters & U. Reif, "The simplest
//! subdivision scheme for smoothing polyhedra", ACM TOG 16(4), 1997), one
//! level: mid-edge subdivision.
//!
//! What is implemented, exactly: every new vertex is the midpoint of an old
//! edge (a self-loop's midpoint is its vertex); every new vertex is joined to
//! the midpoints of the four edges that follow and precede its edge in the two
//! faces beside it. Each old n-gon becomes the n-gon of its edge midpoints
//! (F-face) and each old valence-k vertex the k-gon of the midpoints around
//! it (V-face), which cuts every vertex off at the edge midpoints ("connect
//! every edge midpoint to its four neighbouring edge midpoints", the paper's
//! abstract). On a regular quad mesh two steps are one binary refinement of
//! the four-direction (Zwart–Powell) box spline. The paper's improved weights for the
//! extraordinary (non-4-sided) faces are *not* applied: every new point is a
//! plain midpoint, so one step is exactly the rectification (medial
//! polyhedron) of the input.
//!
//! Counts (H = 2E): V' = E, E' = H = 2E, F' = F + V; every new vertex is
//! 4-valent. Output vertex e is the midpoint of edge e; faces are
//! `[F-faces | V-faces]`.
//!
//! Stencils and correspondence ([`simplest_level`]): the scheme is linear,
//! a row is `½ a + ½ b`. Origins: the midpoint of e → (EDGE, e); the F-face
//! of f → (FACE, f), the V-face of v → (VERTEX, v); every output edge lies
//! inside one input face (it cuts a corner of it) → (FACE, that face).
//! Open meshes: the paper has no boundary rule, and the plain mid-edge rule
//! at a boundary would replace the boundary polygon by its midpoint polygon
//! at every level (the hole keeps its n sides and shrinks towards a point).
//! topomesh keeps the boundary polyline instead, the convention of Blender's
//! *keep boundaries* it also uses for [`super::dual`] (the mid-edge step is a
//! rectification, dual-like): a boundary vertex stays, as a corner of its
//! V-face, and boundary edges are split at their midpoints. With E_b
//! boundary edges, V_b boundary vertices and h holes: V' = E + V_b,
//! E' = 2E + E_b, F' = F + V (the holes stay holes, each of n sides now
//! 2n). The boundary is interpolated as a polyline (a crease), the interior
//! is smoothed as on closed meshes.

use super::hosts::{check_output_size, refuse_holes, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use super::hosts::SyncPtr;
use crate::mesh::{Columns, Mesh};
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// One level of mid-edge ("simplest") subdivision. See the module docs.
pub fn simplest(m: &Mesh) -> Result<Mesh> {
    refuse_holes("simplest", m)?;
    with_point_spheres("simplest", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    build(Cow::Borrowed(m))
}

/// [`step`] on a level's input that nobody else holds (the previous level
/// of a multi-level call, issue 19): each part of the input goes once the
/// output no longer needs it. The output is [`step`]'s, bit for bit.
fn step_owned(m: Mesh) -> Result<Mesh> {
    build(Cow::Owned(m))
}

/// Connectivity straight into the columns (issue 19), numbered exactly as
/// `from_corner_twins` numbered the corners `[F-corners | V-slots]` it was
/// given (the `output_hashes` test holds it to that). Every F-corner c
/// (half-edge h at rank c in the faces' cycles, side m(h) → m(next h))
/// precedes its twin, a V-slot, so it is the first corner of edge c: it gets
/// half-edge 2c and its twin 2c + 1, the side m(x) → m(prev x) of the
/// V-face of vert[x] with x = next h (inside face[h], cutting its corner at
/// vert[x]). Walking on: the F-face goes to next h; the V-face rotates x to
/// prev[x] ^ 1 = h ^ 1, whose slot side starts the edge of prev(h ^ 1). So
/// each pair (2c, 2c + 1) is a lookup, written from its half-edge h.
///
/// A borrowed input gets its four half-edge columns in one pass and the
/// positions after the ranks are freed. An input given up (`Cow::Owned`)
/// loses its vertex starts, face starts and hole flags before any half-edge
/// column exists, and then each of its columns as soon as the output
/// columns still to come no longer read it (see the body).
fn build(mut src: Cow<'_, Mesh>) -> Result<Mesh> {
    let m: &Mesh = &src;
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (cidx, off) = FaceLayout::ranks(m)?;
    // a face starts at its first corner: F-face f at corner off[f], V-face v
    // at the slot of v_out[v]
    let prev = &m.he_prev;
    let f_start = crate::cancel::par_collect(nf + nv, |i| if i < nf { 2 * off[i] } else { 2 * cidx[prev[m.v_out[i - nf] as usize] as usize] + 1 })?;
    drop(off);
    // midpoint e is first seen at the lower of its two F-corners (every
    // F-corner comes before every V-slot)
    let v_out: Vec<u32> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| 2 * cidx[2 * e].min(cidx[2 * e + 1])).collect();
    if let Cow::Owned(m) = &mut src {
        (m.v_out, m.f_start, m.f_hole) = (Vec::new(), Vec::new(), Vec::new());
    }
    let nfu = nf as u32;
    let mut cols = Columns { pos: Vec::new(), v_out, he_next: Vec::new(), he_prev: Vec::new(), he_vert: Vec::new(), he_face: Vec::new(), f_start, f_hole: vec![false; nf + nv] };
    // the pair (2c, 2c + 1) of F-corner c = cidx[h] in each column, written
    // from h (x = next h); prev's second entry: the slot before x's in its
    // rotation is next(x ^ 1)'s, whose side starts the edge of x ^ 1
    let ci = |k: u32| 2 * cidx[k as usize];
    let next_pair = |prev: &[u32], h: usize, x: usize| (ci(x as u32), ci(prev[h ^ 1]) + 1);
    let prev_pair = |prev: &[u32], h: usize, x: usize| (ci(prev[h]), ci((x ^ 1) as u32) + 1);
    let vert_pair = |h: usize, x: usize| ((h >> 1) as u32, (x >> 1) as u32);
    let face_pair = |face: &[u32], vert: &[u32], h: usize, x: usize| (face[h], nfu + vert[x]);
    if matches!(src, Cow::Borrowed(_)) {
        // nothing to free: one pass writes the four columns
        let m: &Mesh = &src;
        let (next, prev, vert, face) = (&m.he_next, &m.he_prev, &m.he_vert, &m.he_face);
        let c4 = scatter(&cidx, |h| {
            let x = next[h] as usize;
            [next_pair(prev, h, x), prev_pair(prev, h, x), vert_pair(h, x), face_pair(face, vert, h, x)]
        })?;
        let [n, p, v, f] = c4;
        (cols.he_next, cols.he_prev, cols.he_vert, cols.he_face) = (n, p, v, f);
        drop(cidx);
        cols.pos = midpoints(m)?;
        return Mesh::from_columns(cols);
    }
    // An input given up (the previous level of a multi-level call): each
    // output column comes after the input columns only it needed have gone:
    // positions first (then the input's positions go), faces (then its
    // faces and vertices), next and prev (then its connectivity), the
    // vertex column last, from the ranks and the output's own next. Peak at
    // a level: 105 B per output face instead of the one pass's 125, on
    // triangle and quad inputs (`examples/peak_levels.rs`).
    cols.pos = midpoints(&src)?;
    let Cow::Owned(mut m) = src else { unreachable!() };
    m.pos = Vec::new();
    {
        let (next, vert, face) = (&m.he_next, &m.he_vert, &m.he_face);
        let c1 = scatter(&cidx, |h| [face_pair(face, vert, h, next[h] as usize)])?;
        let [f] = c1;
        cols.he_face = f;
    }
    (m.he_face, m.he_vert) = (Vec::new(), Vec::new());
    {
        let (next, prev) = (&m.he_next, &m.he_prev);
        let c2 = scatter(&cidx, |h| {
            let x = next[h] as usize;
            [next_pair(prev, h, x), prev_pair(prev, h, x)]
        })?;
        let [n, p] = c2;
        (cols.he_next, cols.he_prev) = (n, p);
    }
    drop(m);
    // vert[2c] = h / 2 (vert_pair's first) through the ranks; then
    // vert[2c + 1] = x / 2 is the entry of x's F-corner, the output's next of 2c
    let mut vcol: Vec<u32> = Vec::with_capacity(2 * nh);
    {
        let pv = SyncPtr(vcol.as_mut_ptr());
        cidx.par_iter().with_min_len(MIN_LEN).enumerate().for_each(|(h, &c)| {
            if crate::cancel::requested() {
                return;
            }
            // SAFETY: the ranks are a bijection onto 0..H; one task per slot
            unsafe { *pv.get().add(2 * c as usize) = (h >> 1) as u32 };
        });
        drop(cidx);
        // every even slot is written unless cancelled (then no odd slot is read)
        crate::cancel::check()?;
        let on = &cols.he_next;
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|c| {
            if crate::cancel::requested() {
                return;
            }
            // SAFETY: reads even slots (2 · a rank, all written above), writes odd ones, one task each
            unsafe { *pv.get().add(2 * c + 1) = *pv.get().add(on[2 * c] as usize) };
        });
        crate::cancel::check()?;
    }
    // SAFETY: both passes ran in full (not cancelled): every slot is written
    unsafe { vcol.set_len(2 * nh) };
    cols.he_vert = vcol;
    Mesh::from_columns(cols)
}

/// K columns of 2H entries with `pair(h)[k]` at `2c` and `2c + 1` of
/// column k, c = `cidx[h]`, for every half-edge h, written in parallel
/// into memory never zeroed first (`calloc` on reused heap memory clears
/// it with a `memset` that faults the pages in before the writes: about a
/// sixth of a warm torus level-2 call under `perf`).
fn scatter<const K: usize>(cidx: &[u32], pair: impl Fn(usize) -> [(u32, u32); K] + Sync) -> Result<[Vec<u32>; K]> {
    let n = 2 * cidx.len();
    let mut cols: [Vec<u32>; K] = std::array::from_fn(|_| Vec::with_capacity(n));
    let ptrs: [SyncPtr<u32>; K] = std::array::from_fn(|k| SyncPtr(cols[k].as_mut_ptr()));
    let ptrs = &ptrs;
    (0..cidx.len()).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let i = 2 * cidx[h] as usize;
        for (p, (a, b)) in ptrs.iter().zip(pair(h)) {
            // SAFETY: the ranks are a bijection onto 0..H (a walk of every
            // face cycle), so each pair (2c, 2c + 1) is written by one task,
            // inside the capacity
            unsafe {
                *p.get().add(i) = a;
                *p.get().add(i + 1) = b;
            }
        }
    });
    crate::cancel::check()?;
    for c in &mut cols {
        // SAFETY: not cancelled, so every task ran and every slot is written
        unsafe { c.set_len(n) };
    }
    Ok(cols)
}

/// Output vertex e: the midpoint of edge e (reads the positions and the
/// vertex column only).
fn midpoints(m: &Mesh) -> Result<Vec<DVec3>> {
    let (p, vert) = (&m.pos, &m.he_vert);
    let pos = (0..vert.len() / 2).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    Ok(pos)
}

/// [`simplest_level`] on an input the caller gives up (a previous level of
/// a multi-level call): a mesh without point-spheres, asked for no stencils
/// or origins, takes [`step_owned`] (closed) or [`open_build`] on the owned
/// input (open); anything else is [`simplest_level`]'s.
pub fn simplest_level_owned(m: Mesh, req: &Request) -> Result<Level> {
    crate::cancel::check()?;
    if req.stencils || req.origins || m.has_point_spheres() {
        return simplest_level(&m, req);
    }
    if m.n_holes() > 0 {
        return open_build(Cow::Owned(m), req);
    }
    Ok(Level { mesh: step_owned(m)?, stencils: None, origins: None, creases: None })
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`simplest`]. Open meshes keep their boundary polyline
/// (module docs).
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn simplest_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() > 0 {
            return open_level(m, req);
        }
        let mesh = step(m)?;
        let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            Some(Stencils::build(ne, nv, |e, row| {
                row.add(vert[2 * e], 0.5);
                row.add(vert[2 * e + 1], 0.5);
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let fl = FaceLayout::new(m)?;
            let vl = VertexLayout::new(m)?;
            let mut o = Origins::with_capacity(ne, mesh.n_edges(), nf + nv);
            o.vertex_kind = vec![EDGE; ne];
            o.vertex.extend(0..ne as u32);
            o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(VERTEX).take(nv)));
            o.face.extend((0..nf as u32).chain(0..nv as u32));
            // F-face corner c is half-edge fh[c]; V-face slot s is the outgoing half-edge whose slot it is
            let nh = m.n_halfedges();
            let mut slot_he = vec![0u32; nh];
            for h in 0..nh {
                slot_he[vl.vidx[h] as usize] = h as u32;
            }
            edge_origins_by_corner(&mesh, &mut o, |c| {
                let f = if c < nh { face[fl.fh[c] as usize] } else { face[slot_he[c - nh] as usize] };
                (FACE, f)
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}

/// [`simplest_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays): on a closed mesh without point-spheres each edge's
/// midpoint row (no stencils built), else through the stencils.
pub fn simplest_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    super::level::level_with_data(m, req, data, simplest_level, |a, k| {
        let vert = &m.he_vert;
        let mut out = vec![0.0; m.n_edges() * k];
        out.par_chunks_mut(k.max(1)).with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
            let (u, w) = (vert[2 * e] as usize, vert[2 * e + 1] as usize);
            for ((o, x), y) in o.iter_mut().zip(&a[u * k..(u + 1) * k]).zip(&a[w * k..(w + 1) * k]) {
                *o = (x + y) * 0.5;
            }
        });
        crate::cancel::check()?;
        Ok(out)
    })
}

/// One level on a mesh with hole faces (no point-spheres): boundary
/// vertices kept, boundary edges split (module docs). Faces are
/// `[F-faces of real faces | V-faces | holes]`.
///
/// The columns are written directly (issue 19), numbered as
/// `from_corner_twins_with_holes` numbered the corners it was given
/// (`reference::open_level_via_twins`, held to it by a test and by
/// `output_hashes`): corners `[F-corners | V-face corners | hole corners]`,
/// each edge numbered by its first corner. Every F-corner (side m(h) →
/// m(next h) of real h) comes before its twin, the V-side m(next h) →
/// m(h): F-corner c is edge c. In the V-face corners the only firsts are
/// the two sides around a kept boundary vertex w = vert[x] of a hole
/// half-edge x, m(x) → w and w → m(prev x) (their twins are hole corners),
/// so with r(x) the rank of x among the hole half-edges in rotation order
/// they are edges N + 2r(x) and N + 2r(x) + 1 (N = number of F-corners);
/// every hole corner is a second.
/// The rows of an open level's points: the edge midpoints, then the kept
/// boundary vertices `bverts`.
fn open_point_row<'a>(m: &'a Mesh, bverts: &'a [u32]) -> impl Fn(usize, &mut super::stencil::Row) + Sync + 'a {
    // (the vertex column's length: an owned input's `he_next` may be gone)
    let (ne, vert) = (m.he_vert.len() / 2, &m.he_vert);
    move |i, row| {
        if i < ne {
            row.add(vert[2 * i], 0.5);
            row.add(vert[2 * i + 1], 0.5);
        } else {
            row.add(bverts[i - ne], 1.0);
        }
    }
}

fn open_level(m: &Mesh, req: &Request) -> Result<Level> {
    open_build(Cow::Borrowed(m), req)
}

/// A rank in `cidx` that is a hole half-edge's rank in rotation order, not
/// an F-corner.
const HOLE: u32 = 1 << 31;

/// [`open_level`]'s build; an input given up (`Cow::Owned`, a previous
/// level of a multi-level call, issue 19) loses its vertex and face columns
/// before the output's half-edge columns exist, and its connectivity before
/// the positions do. The numbering's one table is `cidx`: the F-corner of
/// every real half-edge, the rank of every hole half-edge (tagged `HOLE`),
/// which also answers "is h a hole side" once the face columns are gone.
fn open_build(mut src: Cow<'_, Mesh>, req: &Request) -> Result<Level> {
    use crate::mesh::NONE;
    let (nv, ne, nf, nh) = (src.n_vertices(), src.n_edges(), src.n_faces(), src.n_halfedges());
    // the vertex and face columns, taken out of an owned input to be freed
    // before the output's half-edge columns exist
    let (v_out_in, f_start_in, f_hole_in): (Cow<[u32]>, Cow<[u32]>, Cow<[bool]>) = match &mut src {
        Cow::Owned(m) => (Cow::Owned(std::mem::take(&mut m.v_out)), Cow::Owned(std::mem::take(&mut m.f_start)), Cow::Owned(std::mem::take(&mut m.f_hole))),
        Cow::Borrowed(m) => (Cow::Borrowed(&m.v_out[..]), Cow::Borrowed(&m.f_start[..]), Cow::Borrowed(&m.f_hole[..])),
    };
    let m: &Mesh = &src;
    check_output_size("simplest", 2 * nh + nh, ne + nv)?;
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    // boundary vertices, in order of their first hole half-edge, after the edge midpoints
    let mut bidx = vec![NONE; nv];
    let mut bverts = Vec::new();
    for h in 0..nh {
        let v = vert[h] as usize;
        if f_hole_in[face[h] as usize] && bidx[v] == NONE {
            bidx[v] = bverts.len() as u32;
            bverts.push(v as u32);
        }
    }
    // F-corners: the real faces' corners in face order, each cycle from its first
    let mut cidx = vec![0u32; nh];
    let mut n_fc = 0u32;
    let mut holes = Vec::new(); // the hole faces, in order
    for f in 0..nf {
        crate::cancel::poll(f)?;
        if f_hole_in[f] {
            holes.push(f as u32);
            continue;
        }
        let s = f_start_in[f];
        let mut h = s;
        loop {
            cidx[h as usize] = n_fc;
            n_fc += 1;
            h = next[h as usize];
            if h == s {
                break;
            }
        }
    }
    // rank of every hole half-edge in rotation order; a kept vertex leaves
    // from the side w → m(prev x) at its first hole half-edge x
    let mut kept_out = vec![0u32; bverts.len()];
    let mut nb = 0u32;
    for v in 0..nv {
        crate::cancel::poll(v)?;
        if bidx[v] != NONE {
            kept_out[bidx[v] as usize] = 2 * (n_fc + 2 * nb + 1);
        }
        for x in super::creases::ring(m, v_out_in[v]) {
            if f_hole_in[face[x as usize] as usize] {
                cidx[x as usize] = HOLE | nb;
                nb += 1;
            }
        }
    }
    let (n_real, n_holes) = ((nf - holes.len()) as u32, holes.len() as u32);
    let hole = |h: usize| cidx[h] & HOLE != 0;
    let fc = |h: usize| cidx[h];
    let rank = |h: usize| cidx[h] & !HOLE;
    // output face of an input face: real faces keep their order, holes go last
    let fid = |f: u32| {
        let k = holes.partition_point(|&x| x < f) as u32;
        if holes.get(k as usize) == Some(&f) { n_real + nv as u32 + k } else { f - k }
    };
    let n_out_h = 2 * (n_fc as usize + 2 * nb as usize);
    // the edge of m(x) → w (the one of w → m(prev x) is the next)
    let ev = |x: usize| n_fc + 2 * rank(x);
    // half-edge of: the F-side of real h; the V-side leaving m(x) (its twin
    // is the F-side of prev x, or for a hole x the hole side w → m(x)); the
    // V-side leaving w; the hole sides w → m(k) and m(k) → w'
    let he_f = |h: usize| 2 * fc(h);
    let he_slot = |x: usize| if hole(x) { 2 * ev(x) } else { 2 * fc(prev[x] as usize) + 1 };
    let he_a1 = |k: usize| 2 * (ev(next[k] as usize) + 1) + 1;
    let vface = |x: usize| n_real + vert[x];
    let he_vx = |x: usize| 2 * (ev(x) + 1);
    let he_a = |k: usize| 2 * ev(k) + 1;
    let n_out_v = ne + bverts.len();
    let bv = |w: u32| (ne as u32) + bidx[w as usize];
    let n_out_f = (n_real + n_holes) as usize + nv;
    // faces start at their first corner: the cycle from f_start, the ring from v_out
    let mut f_start = vec![0u32; n_out_f];
    let mut f_hole = vec![false; n_out_f];
    for f in 0..nf {
        let s = f_start_in[f] as usize;
        let o = fid(f as u32) as usize;
        f_start[o] = if f_hole_in[f] { he_a(s) } else { he_f(s) };
        f_hole[o] = f_hole_in[f];
    }
    for v in 0..nv {
        f_start[(n_real as usize) + v] = he_slot(v_out_in[v] as usize);
    }
    // each vertex leaves from its first corner: a midpoint from its lower
    // F-corner (F-corners come first), or, with holes on both sides, from
    // its V-side of lower rank; a kept vertex as found above
    let mut v_out = Vec::with_capacity(n_out_v);
    v_out.par_extend((0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        let (a, b) = (2 * e, 2 * e + 1);
        match (hole(a), hole(b)) {
            (false, false) => 2 * fc(a).min(fc(b)),
            (false, true) => 2 * fc(a),
            (true, false) => 2 * fc(b),
            (true, true) => 2 * (n_fc + 2 * rank(a).min(rank(b))),
        }
    }));
    v_out.extend_from_slice(&kept_out);
    drop(kept_out);
    // origins first: they read the numbering's tables (never on an owned input)
    let origins = if req.origins {
        let mut o = Origins::with_capacity(n_out_v, n_out_h / 2, n_out_f);
        o.vertex_kind = std::iter::repeat(EDGE).take(ne).chain(std::iter::repeat(VERTEX).take(bverts.len())).collect();
        o.vertex = (0..ne as u32).chain(bverts.iter().copied()).collect();
        let real: Vec<u32> = (0..nf as u32).filter(|&f| !f_hole_in[f as usize]).collect();
        o.face_kind = std::iter::repeat(FACE).take(real.len()).chain(std::iter::repeat(VERTEX).take(nv)).chain(std::iter::repeat(FACE).take(holes.len())).collect();
        o.face = real.iter().copied().chain(0..nv as u32).chain(holes.iter().copied()).collect();
        // a real side cuts a corner of its face; the two sides at a kept
        // vertex are halves of the boundary edges they run along
        o.edge_kind = vec![0; n_out_h / 2];
        o.edge = vec![0; n_out_h / 2];
        for h in 0..nh {
            if !hole(h) {
                let e = fc(h) as usize;
                (o.edge_kind[e], o.edge[e]) = (FACE, face[h]);
            } else {
                let e = ev(h) as usize;
                (o.edge_kind[e], o.edge[e]) = (EDGE, (h >> 1) as u32);
                (o.edge_kind[e + 1], o.edge[e + 1]) = (EDGE, prev[h] >> 1);
            }
        }
        Some(o)
    } else {
        None
    };
    drop((v_out_in, f_start_in, f_hole_in));
    // the positions come last, once the numbering's tables are freed
    // (issue 19: peak memory)
    let mut cols = Columns { pos: Vec::new(), v_out, he_next: vec![0; n_out_h], he_prev: vec![0; n_out_h], he_vert: vec![0; n_out_h], he_face: vec![0; n_out_h], f_start, f_hole };
    {
        let cp = |c: &mut Vec<u32>| super::hosts::SyncPtr(c.as_mut_ptr());
        let (pn, pp, pv, pf) = (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face));
        let put = |i: u32, n: u32, v: u32, f: u32| {
            // SAFETY: every output half-edge is written once below (the ids
            // above are a bijection onto 0..n_out_h), and is the next of one
            unsafe {
                *pn.get().add(i as usize) = n;
                *pp.get().add(n as usize) = i;
                *pv.get().add(i as usize) = v;
                *pf.get().add(i as usize) = f;
            }
        };
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let mid = (h >> 1) as u32;
            let rot = (prev[h] ^ 1) as usize;
            let f = fid(face[h]);
            if !hole(h) {
                // F-face side m(h) → m(next h); V-face side m(h) → m(prev h)
                put(he_f(h), he_f(next[h] as usize), mid, f);
                put(he_slot(h), he_slot(rot), mid, vface(h));
            } else {
                // V-face of w: m(h) → w → m(prev h); the hole: w → m(h) → (next corner)
                let w = bv(vert[h]);
                put(he_slot(h), he_vx(h), mid, vface(h));
                put(he_vx(h), he_slot(rot), w, vface(h));
                put(he_a(h), he_a1(h), w, f);
                put(he_a1(h), he_a(next[h] as usize), mid, f);
            }
        });
    }
    crate::cancel::check()?;
    drop((cidx, bidx, holes));
    if let Cow::Owned(m) = &mut src {
        // the positions read the vertex positions and the vertex column only
        (m.he_next, m.he_prev, m.he_face) = (Vec::new(), Vec::new(), Vec::new());
    }
    let m: &Mesh = &src;
    // the rows are stored only when asked for (issue 19: peak memory)
    let st;
    (cols.pos, st) = Stencils::points_and_rows(n_out_v, nv, &m.pos, req.stencils, open_point_row(m, &bverts))?;
    drop(src);
    let mesh = Mesh::from_columns(cols)?;
    Ok(Level { mesh, stencils: st, origins, creases: None })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn owned_level_equals_the_borrowed_one() {
        // closed inputs (consumed), open and point-sphere ones (the borrowed
        // path); positions compared bit for bit
        let mut cases: Vec<(String, Mesh)> = corpus().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
        cases.extend(open_meshes().into_iter().map(|(n, m)| (n.to_string(), m)));
        cases.push(("torus".into(), crate::primitives::torus(12, 8, 3.0, 1.0).unwrap()));
        for (name, m) in cases {
            let req = Request::plain();
            let a = simplest_level(&m, &req).unwrap().mesh;
            let b = simplest_level_owned(m.clone(), &req).unwrap().mesh;
            assert_eq!(a, b, "{name}");
            assert_eq!(a.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>(),
                b.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>(), "{name}");
            // and on the first level's output, the input a multi-level call gives up
            let c = simplest_level(&a, &req).unwrap().mesh;
            assert_eq!(c, simplest_level_owned(a, &req).unwrap().mesh, "{name} level 2");
        }
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(simplest, |_, (v, e, f)| (e, 2 * e, f + v), |name, _, r| {
            assert!(r.vertices().filter(|&x| r.point_sphere_face(x).is_none()).all(|x| r.valence(x) == 4), "{name} 4-valent");
        });
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        level_matches_plain_on_corpus(simplest, simplest_level, |name, m, lv| {
            let o = lv.origins.as_ref().unwrap();
            let fl = FaceLayout::new(m).unwrap();
            assert!(origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices()).iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()).iter().all(|&c| c == 1), "{name}");
            // each face is the origin of its n corner-cutting edges
            let fe = origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces());
            for f in 0..m.n_faces() {
                assert_eq!(fe[f], fl.degree(f), "{name} face {f}");
            }
        });
    }

    #[test]
    fn open_meshes_keep_their_boundary_polyline() {
        for (name, m) in open_meshes() {
            let (v, e, f) = counts(&m);
            let nb = (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count();
            let vb = (0..v).filter(|&x| crate::schemes::creases::ring(&m, m.v_out[x]).any(|h| m.f_hole[m.he_face[h as usize] as usize])).count();
            let lv = simplest_level(&m, &full_request()).unwrap();
            check_level(name, &m, &lv);
            let r = &lv.mesh;
            assert_eq!(counts(r), (e + vb, 2 * e + nb, f + v), "{name}");
            assert_eq!((open_euler(r), r.n_holes()), (open_euler(&m), m.n_holes()), "{name}");
            let rb = (0..r.n_halfedges()).filter(|&h| r.f_hole[r.he_face[h] as usize]).count();
            assert_eq!(rb, 2 * nb, "{name}: boundary edges split");
            // every boundary point of the output lies on the input's boundary polyline
            for h in 0..r.n_halfedges() {
                if r.f_hole[r.he_face[h] as usize] {
                    let p = r.pos[r.he_vert[h] as usize];
                    let on = (0..m.n_halfedges()).filter(|&k| m.f_hole[m.he_face[k] as usize]).any(|k| {
                        let (a, b) = (m.pos[m.he_vert[k] as usize], m.pos[m.he_vert[k ^ 1] as usize]);
                        (p - a).length() < 1e-12 || (p - b).length() < 1e-12 || (p - (a + b) * 0.5).length() < 1e-12
                    });
                    assert!(on, "{name}: boundary point {p} off the input boundary");
                }
            }
            // a second level works on the output (open input again)
            let two = simplest_level(r, &full_request()).unwrap();
            check_level(name, r, &two);
        }
    }

    #[test]
    fn cube_gives_cuboctahedron() {
        let r = simplest(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert_eq!(r.face_size_histogram().get(&4), Some(&6));
    }
}

/// The builders the direct column fills replaced, kept as references.
#[cfg(test)]
#[path = "simplest_reference.rs"]
mod reference;
