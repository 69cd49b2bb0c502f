//! Honeycomb's and vertex truncation's output written straight into the
//! mesh columns ([`crate::mesh::Columns`], issue 19 item 1), in closed form,
//! instead of listing corners and twins for [`Mesh::from_corner_twins`].
//!
//! Both schemes keep every old face as one *front* face (old face order)
//! and add one face per vertex after them (old vertex order); point-sphere
//! faces and their vertices are carried through, hole marks are copied.
//! The result is what `from_corner_twins` built from the old corner lists
//! (kept test-only in `twin_reference.rs`), bit for bit:
//! `from_corner_twins` numbers edges by their first corner (the one whose
//! twin comes later in corner order), that corner gets `2e` with `e` the
//! number of first corners before it, its twin `2e + 1`; each vertex's
//! `v_out` is its first corner. Front corners come before every vertex-face
//! corner, which fixes most of the numbering by position alone:
//!
//! * **Honeycomb** (front corner of h, then two corners per rotation slot
//!   `g`: `v'_g`, `v'_{prev g}`). Front corners are all first: id `2·cidx(h)`.
//!   The even slot corner's twin is a front corner: id `2·cidx(prev g) + 1`.
//!   The odd slot corners pair with each other (one inserted edge per old
//!   edge); the lower slot is first, ranked by one parallel pass over the
//!   vertices and a prefix.
//! * **Vertex truncation**, cuts apart (two front corners per old corner:
//!   `p_h`, `p_twin h`; one slot corner `p_g`): the second front corner is
//!   always first, the first one when its twin `p_twin h` of face(twin h)
//!   comes later, i.e. when `cidx(twin h) > cidx(h)`; ranked per face and a
//!   prefix. Slot corners are never first: id of the front twin + 1.
//! * **Merged cuts** (`ratio = 1/2`: one front corner `m_e(h)`, one slot
//!   corner): front `2·cidx(h)`, slot `2·cidx(prev g) + 1`.

use super::hosts::{FaceLayout, SyncPtr, MIN_LEN};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, POINT};
use glam::DVec3;
use rayon::prelude::*;

/// The two output face families' numbering shared by both schemes.
struct Frame {
    nf: usize,
    /// Per old vertex: the output face of its vertex face, or for a
    /// point-sphere vertex its output vertex.
    vface: Vec<u32>,
    /// Point-sphere faces and their output vertices: `(old face, new vertex)`.
    points: Vec<(u32, u32)>,
}

impl Frame {
    /// Numbers the vertex faces and the point-sphere vertices (in vertex
    /// order, after the scheme's own `n_before`), and returns the latter's
    /// positions, to be appended after the scheme's.
    fn numbered(m: &Mesh, n_before: usize) -> (Frame, Vec<DVec3>) {
        let mut pos = Vec::new();
        let (nv, nf) = (m.n_vertices(), m.n_faces());
        let any_point = m.v_out.par_iter().with_min_len(1 << 14).any(|&o| o & POINT != 0);
        let mut points = Vec::new();
        let vface = if !any_point {
            (0..nv as u32).into_par_iter().with_min_len(1 << 14).map(|v| nf as u32 + v).collect()
        } else {
            let mut k = nf as u32;
            m.v_out
                .iter()
                .enumerate()
                .map(|(v, &o)| {
                    if o & POINT != 0 {
                        let id = (n_before + pos.len()) as u32;
                        pos.push(m.pos[v]);
                        points.push((o & !POINT, id));
                        id
                    } else {
                        k += 1;
                        k - 1
                    }
                })
                .collect()
        };
        (Frame { nf, vface, points }, pos)
    }

    /// Number of output faces.
    fn n_faces(&self, m: &Mesh) -> usize {
        self.nf + m.n_vertices() - self.points.len()
    }

    /// Point-sphere links and hole marks, then the checked mesh.
    fn finish(&self, m: &Mesh, mut c: Columns) -> Result<Mesh> {
        for &(f, v) in &self.points {
            c.f_start[f as usize] = POINT | v;
            c.v_out[v as usize] = POINT | f;
        }
        c.f_hole[..self.nf].copy_from_slice(&m.f_hole);
        Mesh::from_columns(c)
    }
}

/// Raw pointers to the half-edge and face columns of `c`, for the parallel
/// fills whose writes are disjoint by construction.
#[derive(Clone, Copy)]
pub(crate) struct Out {
    next: SyncPtr<u32>,
    prev: SyncPtr<u32>,
    vert: SyncPtr<u32>,
    face: SyncPtr<u32>,
    f_start: SyncPtr<u32>,
}

impl Out {
    pub(crate) fn of(c: &mut Columns) -> Out {
        Out {
            next: SyncPtr(c.he_next.as_mut_ptr()),
            prev: SyncPtr(c.he_prev.as_mut_ptr()),
            vert: SyncPtr(c.he_vert.as_mut_ptr()),
            face: SyncPtr(c.he_face.as_mut_ptr()),
            f_start: SyncPtr(c.f_start.as_mut_ptr()),
        }
    }
    /// Writes the half-edge `id` of output face `f`, with vertex `v`, followed by `nx`.
    ///
    /// # Safety
    /// `id`, `nx` and `f` are in range, and no other thread writes half-edge
    /// `id`, the `prev` of `nx`, or (through [`Out::start`]) face `f`.
    #[inline]
    pub(crate) unsafe fn link(self, id: u32, v: u32, f: u32, nx: u32) {
        unsafe {
            *self.next.get().add(id as usize) = nx;
            *self.prev.get().add(nx as usize) = id;
            *self.vert.get().add(id as usize) = v;
            *self.face.get().add(id as usize) = f;
        }
    }
    /// # Safety
    /// As [`Out::link`], for `f_start[f]`.
    #[inline]
    pub(crate) unsafe fn start(self, f: u32, id: u32) {
        unsafe { *self.f_start.get().add(f as usize) = id };
    }
}

/// Honeycomb's connectivity (one new vertex per old half-edge, new vertex
/// `h` for half-edge `h`, then the point-spheres'); see the module docs.
/// The positions are left to the caller ([`Pending::finish`]).
pub(crate) fn honeycomb_columns(m: &Mesh, fl: &FaceLayout) -> Result<Pending> {
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let cidx = &fl.cidx;
    let (frame, points) = Frame::numbered(m, nh);
    // the odd slot corner of g pairs with that of next(twin(prev g)); the lower slot is first
    let partner = |g: u32| next[(prev[g as usize] ^ 1) as usize];
    let rot = |g: u32| prev[g as usize] ^ 1;
    let mut rank = vec![0u32; nh];
    let rp = SyncPtr(rank.as_mut_ptr());
    let cnt: Vec<u32> = (0..nv)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            let s = m.v_out[v];
            if s & POINT != 0 || crate::cancel::requested() {
                return 0; // cancelled: the check after the loop reports it
            }
            // rotation position from v_out, needed only when the partner is
            // at the same vertex (a self-loop's two ends)
            let at = |x: u32| {
                let (mut y, mut k) = (s, 0u32);
                while y != x {
                    y = rot(y);
                    k += 1;
                }
                k
            };
            let (mut g, mut r) = (s, 0u32);
            loop {
                let p = partner(g);
                let (vp, vg) = (vert[p as usize], vert[g as usize]);
                // slots are laid out vertex after vertex, in rotation order
                let first = if vp != vg { vp > vg } else { at(p) > at(g) };
                // SAFETY: every half-edge leaves one vertex, whose task alone writes it.
                unsafe { *rp.get().add(g as usize) = r << 1 | first as u32 };
                r += first as u32;
                g = rot(g);
                if g == s {
                    return r;
                }
            }
        })
        .collect();
    crate::cancel::check()?;
    let mut ebase = Vec::with_capacity(nv);
    let mut acc = nh as u32; // the front corners' edges come first
    for c in cnt {
        ebase.push(acc);
        acc += c;
    }
    if acc as usize * 2 != 3 * nh {
        return Err(MeshError::Invariant(format!("honeycomb: {} inserted edges for {} old edges", acc as usize - nh, nh / 2)));
    }
    let odd_first = |g: u32| 2 * (ebase[vert[g as usize] as usize] + (rank[g as usize] >> 1));
    let odd = |g: u32| if rank[g as usize] & 1 != 0 { odd_first(g) } else { odd_first(partner(g)) + 1 };
    let even = |g: u32| 2 * cidx[prev[g as usize] as usize] + 1;
    let mut cols = Columns::for_points_unfilled(nh + points.len(), 3 * nh, frame.n_faces(m));
    let out = Out::of(&mut cols);
    // front faces: new vertex h at corner h, ids 2·cidx
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        let hs = fl.corners(f);
        if hs.is_empty() || crate::cancel::requested() {
            return;
        }
        let b = 2 * fl.off[f];
        // SAFETY: the ids 2·cidx of face f's corners and face f are written by this task only.
        unsafe {
            out.start(f as u32, b);
            for (k, &h) in hs.iter().enumerate() {
                let nx = if k + 1 == hs.len() { b } else { b + 2 * (k as u32 + 1) };
                out.link(b + 2 * k as u32, h, f as u32, nx);
            }
        }
    });
    // vertex faces: per rotation slot g, v'_g then v'_{prev g}
    (0..nv).into_par_iter().with_min_len(MIN_LEN).for_each(|v| {
        let s = m.v_out[v];
        if s & POINT != 0 || crate::cancel::requested() {
            return;
        }
        let of = frame.vface[v];
        let mut g = s;
        // SAFETY: the even and odd ids of v's slots (a bijection onto the
        // odd front twins and the inserted edges' half-edges) and face `of`
        // are written by this task only.
        unsafe {
            let e0 = even(s);
            out.start(of, e0);
            let mut e = e0;
            loop {
                let (o, gn) = (odd(g), rot(g));
                let en = if gn == s { e0 } else { even(gn) };
                out.link(e, g, of, o);
                out.link(o, prev[g as usize], of, en);
                (e, g) = (en, gn);
                if g == s {
                    break;
                }
            }
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled: the front ids and the vertex faces' slots are a
    // bijection onto the 3H half-edges (the count checked above)
    unsafe { cols.assume_filled(3 * nh) };
    // new vertex h first shows up at its front corner
    cols.v_out[..nh].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(h, o)| *o = 2 * cidx[h]);
    Ok(Pending { cols, frame, points })
}

/// A scheme's columns before its positions (issue 19: the connectivity's
/// scratch is gone, and an input given up can lose what the positions do
/// not read, before they are allocated).
pub(crate) struct Pending {
    cols: Columns,
    frame: Frame,
    /// The point-sphere vertices' positions, after the scheme's own.
    points: Vec<DVec3>,
}

impl Pending {
    /// The mesh around the scheme's own new points `pos`; `m` is the input,
    /// of which only the hole flags are read here.
    pub(crate) fn finish(self, m: &Mesh, mut pos: Vec<DVec3>) -> Result<Mesh> {
        let Pending { mut cols, frame, points } = self;
        pos.extend(points);
        cols.pos = pos;
        frame.finish(m, cols)
    }
}

/// Vertex truncation's connectivity around its cut points (one per old
/// half-edge, or per old edge when `merge`d, then the point-spheres'); see
/// the module docs. The positions are left to the caller ([`Pending::finish`]).
pub(crate) fn truncation_columns(m: &Mesh, fl: &FaceLayout, merge: bool) -> Result<Pending> {
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let prev = &m.he_prev;
    let cidx = &fl.cidx;
    let n_cut = if merge { nh / 2 } else { nh };
    let (frame, points) = Frame::numbered(m, n_cut);
    let rot = |g: u32| prev[g as usize] ^ 1;
    let n_front = if merge { nh } else { 2 * nh };
    // per old corner (FaceLayout index): rank << 1 | first(p_h); face edge bases
    let mut rank = if merge { Vec::new() } else { vec![0u32; nh] };
    let mut ebase = Vec::new();
    if !merge {
        let rp = SyncPtr(rank.as_mut_ptr());
        let cnt: Vec<u32> = (0..nf)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|f| {
                if crate::cancel::requested() {
                    return 0;
                }
                let mut r = 0u32;
                for &h in fl.corners(f) {
                    let c = cidx[h as usize];
                    let first = cidx[(h ^ 1) as usize] > c;
                    // SAFETY: corner c belongs to face f, whose task alone writes it.
                    unsafe { *rp.get().add(c as usize) = r << 1 | first as u32 };
                    r += 1 + first as u32;
                }
                r
            })
            .collect();
        crate::cancel::check()?;
        ebase.reserve_exact(nf);
        let mut acc = 0u32;
        for c in cnt {
            ebase.push(acc);
            acc += c;
        }
        if 2 * acc as usize != 3 * nh {
            return Err(MeshError::Invariant(format!("vertex_truncation: {acc} edges for {} old edges", nh / 2)));
        }
    }
    let face = &m.he_face;
    // ids of p_h (slot 0) and p_twin(h) (slot 1) in h's front face
    let first0 = |h: u32| {
        let c = cidx[h as usize];
        2 * (ebase[face[h as usize] as usize] + (rank[c as usize] >> 1))
    };
    let id1 = |h: u32| {
        let r = rank[cidx[h as usize] as usize];
        2 * (ebase[face[h as usize] as usize] + (r >> 1) + (r & 1))
    };
    let id0 = |h: u32| if rank[cidx[h as usize] as usize] & 1 != 0 { first0(h) } else { first0(h ^ 1) + 1 };
    let n_out = if merge { nh / 2 } else { nh };
    let mut cols = Columns::for_points_unfilled(n_cut + points.len(), n_front + nh, frame.n_faces(m));
    let out = Out::of(&mut cols);
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        let hs = fl.corners(f);
        if hs.is_empty() || crate::cancel::requested() {
            return;
        }
        // SAFETY: face f's front corners and face f are written by this task only.
        unsafe {
            if merge {
                let b = 2 * fl.off[f];
                out.start(f as u32, b);
                for (k, &h) in hs.iter().enumerate() {
                    let nx = if k + 1 == hs.len() { b } else { b + 2 * (k as u32 + 1) };
                    out.link(b + 2 * k as u32, h >> 1, f as u32, nx);
                }
            } else {
                // each id computed once: p_h's id carries over to the next corner
                let a0 = id0(hs[0]);
                out.start(f as u32, a0);
                let mut a = a0;
                for (k, &h) in hs.iter().enumerate() {
                    let an = if k + 1 == hs.len() { a0 } else { id0(hs[k + 1]) };
                    let b = id1(h);
                    out.link(a, h, f as u32, b);
                    out.link(b, h ^ 1, f as u32, an);
                    a = an;
                }
            }
        }
    });
    // vertex faces: one corner per rotation slot, the twin of a front corner
    let slot = |g: u32| if merge { 2 * cidx[prev[g as usize] as usize] + 1 } else { id1(prev[g as usize]) + 1 };
    (0..nv).into_par_iter().with_min_len(MIN_LEN).for_each(|v| {
        let s = m.v_out[v];
        if s & POINT != 0 || crate::cancel::requested() {
            return;
        }
        let of = frame.vface[v];
        let mut g = s;
        // SAFETY: the slot ids of v (twins of distinct front corners) and
        // face `of` are written by this task only.
        unsafe {
            let s0 = slot(s);
            out.start(of, s0);
            let mut cur = s0;
            loop {
                let gn = rot(g);
                let nx = if gn == s { s0 } else { slot(gn) };
                out.link(cur, if merge { g >> 1 } else { g }, of, nx);
                (cur, g) = (nx, gn);
                if g == s {
                    break;
                }
            }
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled: the front corners and the vertex faces' slots
    // (twins of distinct front corners) are every half-edge
    unsafe { cols.assume_filled(n_front + nh) };
    // a cut point first shows up in the front face that comes first
    cols.v_out[..n_out].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(x, o)| {
        *o = if merge {
            2 * cidx[2 * x].min(cidx[2 * x + 1])
        } else if cidx[x] < cidx[x ^ 1] {
            id0(x as u32)
        } else {
            id1(x as u32 ^ 1)
        };
    });
    Ok(Pending { cols, frame, points })
}

#[cfg(test)]
mod tests {
    use super::super::twin_reference as old;
    use super::super::hosts::test_meshes as tm;
    use super::*;
    use crate::schemes::{honeycomb, vertex_truncation};

    /// The corpus (point-spheres, self-loops, one- and two-gons, repeated
    /// vertices), the open meshes, and meshes whose stored corners are not
    /// their first (after InsertEdge), over two levels: the same mesh as the
    /// corner-and-twin build, for honeycomb and both truncation modes.
    #[test]
    fn columns_equal_the_twin_build() {
        let mut meshes = tm::corpus();
        meshes.extend(tm::open_meshes());
        meshes.push(("handle_cube", tm::handle_cube()));
        meshes.push(("one_two_gon", tm::one_gon_two_gon_cube()));
        meshes.push(("star_prism", tm::star_prism()));
        for (name, m0) in &meshes {
            let mut ms = vec![m0.clone()];
            for _ in 0..2 {
                let m = ms.last().unwrap().clone();
                let pos: Vec<DVec3> = (0..m.n_halfedges()).map(|i| DVec3::new(i as f64, 0.5, -(i as f64))).collect();
                let new = honeycomb::honeycomb(&m, 0.5, None).unwrap();
                let want = old::honeycomb(&m, new.positions()[..m.n_halfedges()].to_vec()).unwrap();
                new.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(new == want, "honeycomb {name}");
                let fl = FaceLayout::new(&m).unwrap();
                for merge in [false, true] {
                    let p = if merge { pos[..m.n_edges()].to_vec() } else { pos.clone() };
                    let a = truncation_columns(&m, &fl, merge).unwrap().finish(&m, p.clone()).unwrap();
                    let b = old::vertex_truncation(&m, p, merge).unwrap();
                    a.validate().unwrap_or_else(|e| panic!("{name} merge {merge}: {e}"));
                    assert!(a == b, "vertex_truncation {name} merge {merge}");
                }
                let mode = vertex_truncation::Truncation::Polyhedral { ratio: 0.5 };
                ms.push(vertex_truncation::vertex_truncation(&new, mode).unwrap());
            }
        }
    }
}
