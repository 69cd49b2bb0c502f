//! The open level of [`super::simplest`] (boundary vertices kept, boundary
//! edges split; module docs of `simplest`), written straight into the
//! columns.

use super::super::hosts::{check_output_size, MIN_LEN};
use super::super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Columns, Mesh};
use rayon::prelude::*;
use std::borrow::Cow;

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
pub(super) fn open_point_row<'a>(vert: &'a [u32], bverts: &'a [u32]) -> impl Fn(usize, &mut super::super::stencil::Row) + Sync + 'a {
    let ne = vert.len() / 2;
    move |i, row| {
        if i < ne {
            row.add(vert[2 * i], 0.5);
            row.add(vert[2 * i + 1], 0.5);
        } else {
            row.add(bverts[i - ne], 1.0);
        }
    }
}

pub(super) fn open_level(m: &Mesh, req: &Request) -> Result<Level> {
    open_build(Cow::Borrowed(m), req)
}

/// A rank in `cidx` that is a hole half-edge's rank in rotation order, not
/// an F-corner.
const HOLE: u32 = 1 << 31;

/// [`open_level`]'s build; an input given up (`Cow::Owned`, a previous
/// level of a multi-level call, issue 19) loses its vertex starts, face
/// starts and hole flags before the output's half-edge columns exist, then
/// its positions once the output's are made, its vertex and face columns
/// once the output's are written, and its next, prev and ranks last, so
/// that little of it is alive beside the output. The numbering's one table
/// is `cidx`: the F-corner of
/// every real half-edge, the rank of every hole half-edge (tagged `HOLE`),
/// which also answers "is h a hole side" once the face columns are gone.
pub(super) fn open_build(mut src: Cow<'_, Mesh>, req: &Request) -> Result<Level> {
    use crate::mesh::NONE;
    let (nv, ne, nf, nh) = (src.n_vertices(), src.n_edges(), src.n_faces(), src.n_halfedges());
    // the vertex and face columns, taken out of an owned input to be freed
    // before the output's half-edge columns exist
    let (v_out_in, f_start_in, f_hole_in): (Cow<[u32]>, Cow<[u32]>, Cow<[bool]>) = match &mut src {
        Cow::Owned(m) => (Cow::Owned(std::mem::take(&mut m.v_out)), Cow::Owned(std::mem::take(&mut m.f_start)), Cow::Owned(std::mem::take(&mut m.f_hole))),
        Cow::Borrowed(m) => (Cow::Borrowed(&m.v_out[..]), Cow::Borrowed(&m.f_start[..]), Cow::Borrowed(&m.f_hole[..])),
    };
    // and the half-edge columns, each freed after its last reader
    let (next_c, prev_c, vert_c, face_c): (Cow<[u32]>, Cow<[u32]>, Cow<[u32]>, Cow<[u32]>) = match &mut src {
        Cow::Owned(m) => {
            let t = |c: &mut Vec<u32>| Cow::Owned(std::mem::take(c));
            (t(&mut m.he_next), t(&mut m.he_prev), t(&mut m.he_vert), t(&mut m.he_face))
        }
        Cow::Borrowed(m) => (Cow::Borrowed(&m.he_next[..]), Cow::Borrowed(&m.he_prev[..]), Cow::Borrowed(&m.he_vert[..]), Cow::Borrowed(&m.he_face[..])),
    };
    check_output_size("simplest", 2 * nh + nh, ne + nv)?;
    let (next, prev, vert, face) = (&*next_c, &*prev_c, &*vert_c, &*face_c);
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
        for x in super::super::creases::ring_in(prev, v_out_in[v]) {
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
    // the sides written from input half-edge h: (id, id of its next) and
    // (vertex, face). Real h: its F-face side m(h) → m(next h) and its
    // V-face side m(h) → m(prev h); hole h: the V-face of w, m(h) → w →
    // m(prev h), and the hole's w → m(h) → (next corner)
    let ids = |h: usize| -> ([(u32, u32); 4], usize) {
        let rot = (prev[h] ^ 1) as usize;
        if !hole(h) {
            ([(he_f(h), he_f(next[h] as usize)), (he_slot(h), he_slot(rot)), (0, 0), (0, 0)], 2)
        } else {
            ([(he_slot(h), he_vx(h)), (he_vx(h), he_slot(rot)), (he_a(h), he_a1(h)), (he_a1(h), he_a(next[h] as usize))], 4)
        }
    };
    let vals = |h: usize| -> [(u32, u32); 4] {
        let (mid, f) = ((h >> 1) as u32, fid(face[h]));
        if !hole(h) {
            [(mid, f), (mid, vface(h)), (0, 0), (0, 0)]
        } else {
            let w = bv(vert[h]);
            [(mid, vface(h)), (w, vface(h)), (w, f), (mid, f)]
        }
    };
    let cp = |c: &mut Vec<u32>| super::super::hosts::SyncPtr(c.as_mut_ptr());
    let mut cols = Columns { pos: Vec::new(), v_out, he_next: Vec::new(), he_prev: Vec::new(), he_vert: Vec::new(), he_face: Vec::new(), f_start, f_hole };
    let st;
    // SAFETY (every write below): the ids above are a bijection onto
    // 0..n_out_h, each written once as some side's id and once as one
    // side's next, by the task of that side's input half-edge
    if let Cow::Borrowed(m) = &src {
        // nothing to free: one pass writes the four columns, the positions
        // come last, once the numbering's tables are freed
        (cols.he_next, cols.he_prev, cols.he_vert, cols.he_face) = (vec![0; n_out_h], vec![0; n_out_h], vec![0; n_out_h], vec![0; n_out_h]);
        let (pn, pp, pv, pf) = (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let ((is, k), vs) = (ids(h), vals(h));
            for ((i, n), (v, f)) in is.into_iter().zip(vs).take(k) {
                unsafe {
                    *pn.get().add(i as usize) = n;
                    *pp.get().add(n as usize) = i;
                    *pv.get().add(i as usize) = v;
                    *pf.get().add(i as usize) = f;
                }
            }
        });
        crate::cancel::check()?;
        drop((cidx, bidx, holes));
        (cols.pos, st) = Stencils::points_and_rows(n_out_v, nv, &m.pos, req.stencils, open_point_row(vert, &bverts))?;
    } else {
        // given up: positions first, then the vertex and face columns, then
        // next and prev, each input column freed after its last reader
        (cols.pos, st) = Stencils::points_and_rows(n_out_v, nv, &src.pos, req.stencils, open_point_row(vert, &bverts))?;
        if let Cow::Owned(m) = &mut src {
            m.pos = Vec::new();
        }
        (cols.he_vert, cols.he_face) = (vec![0; n_out_h], vec![0; n_out_h]);
        let (pv, pf) = (cp(&mut cols.he_vert), cp(&mut cols.he_face));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() {
                return;
            }
            let ((is, k), vs) = (ids(h), vals(h));
            for ((i, _), (v, f)) in is.into_iter().zip(vs).take(k) {
                unsafe {
                    *pv.get().add(i as usize) = v;
                    *pf.get().add(i as usize) = f;
                }
            }
        });
        crate::cancel::check()?;
        drop((vert_c, face_c, bidx, holes, bverts));
        (cols.he_next, cols.he_prev) = (vec![0; n_out_h], vec![0; n_out_h]);
        let (pn, pp) = (cp(&mut cols.he_next), cp(&mut cols.he_prev));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() {
                return;
            }
            let (is, k) = ids(h);
            for (i, n) in is.into_iter().take(k) {
                unsafe {
                    *pn.get().add(i as usize) = n;
                    *pp.get().add(n as usize) = i;
                }
            }
        });
        crate::cancel::check()?;        drop((next_c, prev_c, cidx));
    }
    drop(src);
    let mesh = Mesh::from_columns(cols)?;
    Ok(Level { mesh, stencils: st, origins, creases: None })
}
