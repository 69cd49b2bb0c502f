//! [`super::primal_columns`] for the two uniform inputs (issue 19): all
//! triangles without face points (midpoint and Loop on triangle meshes),
//! and all quads with a face point per face in face order (Catmull-Clark
//! from its second level on, and midpoint on quad meshes). The same
//! columns, bit for bit, with the general build's per-face records
//! replaced by arithmetic.
//!
//! Every face has `N` corners (`N` = 3 or 4), so a corner index `c` (the
//! face layout's `cidx`) is `N f + k` and gives the face and the local index
//! in one load. Face `f`'s block is output corners `4N f ..`, one sub-block
//! of `S` corners per corner `k` in the general build's layout:
//! * triangles (`S = 3`): `[a(h), s(h), b(h)]`, then the middle triangle
//!   `m₀ m₁ m₂`; `s(h_k)` is the first corner of its edge (its twin
//!   `m_{k−1}` comes later in the block), `m` never is;
//! * quads (`S = 4`): `[a(h), s₁(h), s₂(h), b(h)]` around the face point;
//!   `s₁(h_k)` is twin of `s₂(h_{k+1})`, so `s₁` is first except at `k = 3`
//!   and `s₂` only at `k = 0`.
//!
//! `a(h)` and `b(h)` (slot `N − 1`) are first by the position of their
//! twins `b(next(twin h))`, `a(twin(prev h))` in the twin's block, which
//! compares blocks first. The numbering rules (ids `2e`/`2e + 1`, ranks,
//! vertices' first corners) are those of `primal_columns.rs`.

use super::hosts::{FaceLayout, SyncPtr, MIN_LEN};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use rayon::prelude::*;

/// Which uniform input [`applies`] found.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Uniform {
    /// Every face a triangle, no face points.
    Triangles,
    /// Every face a quad, face `f`'s point numbered `f`.
    Quads,
}

/// The uniform input this is, if any: no holes, every face of one degree
/// with the face points that degree needs.
pub(crate) fn applies(m: &Mesh, fl: &FaceLayout, face_point: &[u32]) -> Option<Uniform> {
    let nf = m.n_faces();
    if fl.off.len() != nf + 1 || nf == 0 {
        return None;
    }
    let degrees = |n: u32| fl.off[nf] as usize == n as usize * nf && fl.off.par_windows(2).with_min_len(MIN_LEN).all(|w| w[1] - w[0] == n);
    if face_point.par_iter().with_min_len(MIN_LEN).all(|&x| x == NONE) && degrees(3) {
        Some(Uniform::Triangles)
    } else if face_point.par_iter().with_min_len(MIN_LEN).enumerate().all(|(f, &x)| x == f as u32) && degrees(4) {
        Some(Uniform::Quads)
    } else {
        None
    }
}

/// The connectivity columns (positions empty) for `n_points` output
/// vertices, and the side map when asked for, of an input [`applies`]
/// found `kind`. Same as `primal_columns::fill` on this input.
pub(crate) fn fill(m: &Mesh, cidx: &[u32], kind: Uniform, n_points: usize, want_sides: bool) -> Result<(Columns, Vec<u32>)> {
    match kind {
        Uniform::Triangles => fill_n::<3>(m, cidx, n_points, want_sides),
        Uniform::Quads => fill_n::<4>(m, cidx, n_points, want_sides),
    }
}

struct Ranks<'a, const N: u32> {
    cidx: &'a [u32],
    /// Per corner: `rank << 4 | mask` (rank: first corners of the face's
    /// block before this sub-block; mask bit `s`: slot `s` is first).
    rm: Vec<u32>,
    /// Per face: first corners before its block.
    ebase: Vec<u32>,
}

impl<const N: u32> Ranks<'_, N> {
    /// Slot of `b`.
    const B: u32 = N - 1;

    /// Position of slot `slot` of corner `c`'s sub-block in the output
    /// corner order.
    #[inline]
    fn pos(c: u32, slot: u32) -> u32 {
        4 * N * (c / N) + N * (c % N) + slot
    }
    /// The corner after `c` in its face.
    #[inline]
    fn next_c(c: u32) -> u32 {
        if c % N == N - 1 {
            c + 1 - N
        } else {
            c + 1
        }
    }
    /// Id of slot `slot` of corner `c` when it is first.
    #[inline]
    fn first_id(&self, c: u32, slot: u32) -> u32 {
        let rm = self.rm[c as usize];
        2 * (self.ebase[(c / N) as usize] + (rm >> 4) + (rm & 15 & ((1 << slot) - 1)).count_ones())
    }
    /// Id of `a` of corner `c` (half-edge `h`).
    #[inline]
    fn id_a(&self, c: u32, h: u32) -> u32 {
        if self.rm[c as usize] & 1 != 0 {
            self.first_id(c, 0)
        } else {
            // twin: b(next(twin h))
            self.first_id(Self::next_c(self.cidx[(h ^ 1) as usize]), Self::B) + 1
        }
    }
    /// Id of `b` of corner `c`, whose half-edge's previous is `p`.
    #[inline]
    fn id_b(&self, c: u32, p: u32) -> u32 {
        if self.rm[c as usize] >> Self::B & 1 != 0 {
            self.first_id(c, Self::B)
        } else {
            // twin: a(twin p)
            self.first_id(self.cidx[(p ^ 1) as usize], 0) + 1
        }
    }
}

fn fill_n<const N: u32>(m: &Mesh, cidx: &[u32], n_points: usize, want_sides: bool) -> Result<(Columns, Vec<u32>)> {
    let (next, vert, _) = m.halfedge_columns();
    let (nv, ne, nf) = (m.n_vertices() as u32, m.n_edges() as u32, m.n_faces());
    let want_points = m.n_vertices() + m.n_edges() + if N == 4 { nf } else { 0 };
    if n_points != want_points {
        return Err(MeshError::Invariant(format!("uniform host: {n_points} points, {want_points} expected")));
    }
    let n = N as usize;
    // the face's half-edges from its first corner
    let corners = |f: usize| {
        let mut hs = [0u32; 4];
        hs[0] = m.f_start[f];
        for k in 1..n {
            hs[k] = next[hs[k - 1] as usize];
        }
        hs
    };
    type R<'a, const N: u32> = Ranks<'a, N>;
    let mut rk = R::<N> { cidx, rm: vec![0; n * nf], ebase: Vec::with_capacity(nf) };
    // pass 1: which corners are first, per face
    let cnt: Vec<u32> = {
        let rmp = SyncPtr(rk.rm.as_mut_ptr());
        (0..nf)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|f| {
                if crate::cancel::requested() {
                    return 0;
                }
                let hs = corners(f);
                let mut r = 0u32;
                for k in 0..N {
                    let (h, p) = (hs[k as usize], hs[((k + N - 1) % N) as usize]);
                    let c = N * f as u32 + k;
                    let a = R::<N>::pos(R::<N>::next_c(cidx[(h ^ 1) as usize]), R::<N>::B) > R::<N>::pos(c, 0);
                    let b = R::<N>::pos(cidx[(p ^ 1) as usize], 0) > R::<N>::pos(c, R::<N>::B);
                    let inner = if N == 3 { 2 } else { ((k < 3) as u32) << 1 | ((k == 0) as u32) << 2 };
                    let mask = a as u32 | inner | (b as u32) << R::<N>::B;
                    // SAFETY: corner c belongs to face f only.
                    unsafe { *rmp.get().add(c as usize) = r << 4 | mask };
                    r += mask.count_ones();
                }
                r
            })
            .collect()
    };
    crate::cancel::check()?;
    let mut acc = 0u32;
    for (f, c) in cnt.into_iter().enumerate() {
        crate::cancel::poll(f)?;
        rk.ebase.push(acc);
        acc += c;
    }
    let nh = 2 * acc as usize;
    if nh != 4 * n * nf {
        return Err(MeshError::Invariant(format!("uniform host: {} corners but {nh} half-edges", 4 * n * nf)));
    }
    let mut cols = Columns::for_points_unfilled(n_points, nh, 4 * nf);
    let mut sides = if want_sides { vec![NONE; acc as usize] } else { Vec::new() };
    let rk = &rk;
    let (pn, pp, pv, pf, ps, po, psd) = (
        SyncPtr(cols.he_next.as_mut_ptr()),
        SyncPtr(cols.he_prev.as_mut_ptr()),
        SyncPtr(cols.he_vert.as_mut_ptr()),
        SyncPtr(cols.he_face.as_mut_ptr()),
        SyncPtr(cols.f_start.as_mut_ptr()),
        SyncPtr(cols.v_out.as_mut_ptr()),
        SyncPtr(sides.as_mut_ptr()),
    );
    // pass 2: the columns, per face
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        if crate::cancel::requested() {
            return;
        }
        let hs = corners(f);
        let c0 = N * f as u32;
        let fo = 4 * f as u32;
        // SAFETY: the ids are a bijection from output corners onto
        // half-edges, and the output faces 4f.. and face point f belong to
        // face f alone, so no two writes hit the same entry.
        unsafe {
            let cycle = |ids: &[u32], vs: &[u32], of: u32| {
                let l = ids.len();
                for j in 0..l {
                    let (id, idn) = (ids[j], ids[if j + 1 == l { 0 } else { j + 1 }]);
                    *pn.get().add(id as usize) = idn;
                    *pp.get().add(idn as usize) = id;
                    *pv.get().add(id as usize) = vs[j];
                    *pf.get().add(id as usize) = of;
                }
                *ps.get().add(of as usize) = ids[0];
            };
            let outer = |k: usize, a: u32, b: u32| {
                if want_sides {
                    if a & 1 == 0 {
                        *psd.get().add((a >> 1) as usize) = hs[k];
                    }
                    if b & 1 == 0 {
                        *psd.get().add((b >> 1) as usize) = hs[(k + n - 1) % n] ^ 1;
                    }
                }
            };
            if N == 3 {
                let s = [rk.first_id(c0, 1), rk.first_id(c0 + 1, 1), rk.first_id(c0 + 2, 1)];
                for k in 0..3 {
                    let (h, p) = (hs[k], hs[(k + 2) % 3]);
                    let c = c0 + k as u32;
                    let (a, b) = (rk.id_a(c, h), rk.id_b(c, p));
                    cycle(&[a, s[k], b], &[vert[h as usize], nv + (h >> 1), nv + (p >> 1)], fo + k as u32);
                    outer(k, a, b);
                }
                // the middle triangle: m_k is the twin of s_{k+1}
                cycle(&[s[1] + 1, s[2] + 1, s[0] + 1], &[nv + (hs[0] >> 1), nv + (hs[1] >> 1), nv + (hs[2] >> 1)], fo + 3);
            } else {
                let s1 = [rk.first_id(c0, 1), rk.first_id(c0 + 1, 1), rk.first_id(c0 + 2, 1)];
                let s2_0 = rk.first_id(c0, 2);
                // s₁ of corner 3 is the twin of s₂ of corner 0, s₂ of corner k the twin of s₁ of k − 1
                let i1 = [s1[0], s1[1], s1[2], s2_0 + 1];
                let i2 = [s2_0, s1[0] + 1, s1[1] + 1, s1[2] + 1];
                let fpv = nv + ne + f as u32;
                for k in 0..4 {
                    let (h, p) = (hs[k], hs[(k + 3) % 4]);
                    let c = c0 + k as u32;
                    let (a, b) = (rk.id_a(c, h), rk.id_b(c, p));
                    cycle(&[a, i1[k], i2[k], b], &[vert[h as usize], nv + (h >> 1), fpv, nv + (p >> 1)], fo + k as u32);
                    outer(k, a, b);
                }
                *po.get().add(fpv as usize) = s2_0;
            }
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled, so every face's block ran, and the ids are a
    // bijection onto the half-edges: every entry is written
    unsafe { cols.assume_filled(nh) };
    // vertex points: the a corner of the outgoing half-edge first in face order
    cols.v_out[..nv as usize].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        if crate::cancel::requested() {
            return;
        }
        let best = super::primal_columns::first_outgoing(m, cidx, v);
        *o = rk.id_a(cidx[best as usize], best);
    });
    // edge points: the lowest of the two sides' candidates, slot 1 of a
    // corner k < N − 1 or, for k = N − 1, b of the face's corner 0 (whose
    // half-edge is next h, so its previous is h)
    cols.v_out[nv as usize..(nv + ne) as usize].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
        if crate::cancel::requested() {
            return;
        }
        let cand = |h: u32| {
            let c = cidx[h as usize];
            if c % N < N - 1 {
                (R::<N>::pos(c, 1), c, true, h)
            } else {
                (R::<N>::pos(c + 1 - N, R::<N>::B), c + 1 - N, false, h)
            }
        };
        let (x, y) = (cand(2 * e as u32), cand(2 * e as u32 + 1));
        let (_, c, inner, h) = if x.0 < y.0 { x } else { y };
        *o = if inner { rk.first_id(c, 1) } else { rk.id_b(c, h) };
    });
    crate::cancel::check()?;
    Ok((cols, sides))
}

#[cfg(test)]
mod tests {
    use super::super::hosts::test_meshes as tm;
    use super::*;
    use glam::DVec3;

    /// The same mesh and side map as the twin build, on every closed
    /// all-triangle and all-quad mesh of the corpus, also after InsertEdge
    /// (faces and vertices whose stored corner is not their first) and
    /// after a level (the numbering a second level sees).
    #[test]
    fn equals_the_twin_build() {
        let mut meshes: Vec<(String, Mesh)> = Vec::new();
        for (name, m) in tm::corpus() {
            let sizes = tm::face_sizes(&m);
            if m.n_holes() == 0 && !m.v_out.iter().any(|&o| o & crate::mesh::POINT != 0) && (sizes.iter().all(|&s| s == 3) || sizes.iter().all(|&s| s == 4)) {
                meshes.push((name.to_string(), m));
            }
        }
        let ico = crate::primitives::icosahedron();
        meshes.push(("loop icosahedron".into(), crate::schemes::loop_subdivision::loop_subdivision(&ico).unwrap()));
        let torus = crate::primitives::torus(7, 5, 3.0, 1.0).unwrap();
        meshes.push(("triangulated torus".into(), crate::schemes::hosts::fan_triangulate(&torus).unwrap().expect("quads get fans")));
        meshes.push(("catmull-clark tetrahedron".into(), crate::schemes::catmull_clark::catmull_clark(&crate::primitives::tetrahedron()).unwrap()));
        meshes.push(("torus".into(), torus));
        let kinds: Vec<Uniform> = meshes.iter().map(|(_, m)| if tm::face_sizes(m)[0] == 3 { Uniform::Triangles } else { Uniform::Quads }).collect();
        assert!(kinds.iter().filter(|&&k| k == Uniform::Triangles).count() >= 3 && kinds.iter().filter(|&&k| k == Uniform::Quads).count() >= 3, "{kinds:?}");
        for ((name, m), kind) in meshes.iter().zip(kinds) {
            let fl = FaceLayout::new(m).unwrap();
            let nf = m.n_faces();
            let fp: Vec<u32> = if kind == Uniform::Triangles { vec![NONE; nf] } else { (0..nf as u32).collect() };
            assert_eq!(applies(m, &fl, &fp), Some(kind), "{name}");
            let n_points = m.n_vertices() + m.n_edges() + if kind == Uniform::Quads { nf } else { 0 };
            let pos: Vec<DVec3> = (0..n_points).map(|i| DVec3::splat(i as f64)).collect();
            for sides in [false, true] {
                let (mut cols, sa) = fill(m, &fl.cidx, kind, n_points, sides).unwrap();
                cols.pos = pos.clone();
                let a = Mesh::from_columns(cols).unwrap();
                a.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                let (b, sb) = super::super::hosts::primal_host_twins(m, &fl, &fp, pos.clone(), sides).unwrap();
                assert_eq!(a, b, "{name}");
                assert_eq!(sides.then_some(sa), sb, "{name}");
            }
            // a face point missing, or out of order: not uniform
            if kind == Uniform::Quads && nf > 1 {
                let mut swapped = fp.clone();
                swapped.swap(0, 1);
                assert_eq!(applies(m, &fl, &swapped), None, "{name}");
            }
        }
    }
}
