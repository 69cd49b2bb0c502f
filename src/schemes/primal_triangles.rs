//! [`super::primal_columns`] for an all-triangle input without face points
//! or holes (midpoint and Loop on triangle meshes, the common case; issue
//! 19, midpoint against libigl's `upsample`): the same columns, bit for bit,
//! with the per-face records replaced by arithmetic.
//!
//! Every face has three corners, so a corner index `c` (the face layout's
//! `cidx`) is `3f + k` and gives the face and the local index in one load;
//! face `f`'s block is output corners `12f..12f + 12` (sub-blocks
//! `[a(h), s(h), b(h)]` per corner `k`, then the middle triangle's
//! `m₀ m₁ m₂`) and output faces `4f..4f + 4`. In that block: `s(h_k)` is
//! always the first corner of its edge (its twin `m_{k−1}` comes later in
//! the block), `m` never is, and `a(h)`, `b(h)` are first by the position of
//! their twins `b(next(twin h))`, `a(twin(prev h))` in the twin's block,
//! which compares blocks first. The numbering rules (ids `2e`/`2e + 1`, ranks,
//! vertices' first corners) are those of `primal_columns.rs`.

use super::hosts::{FaceLayout, SyncPtr, MIN_LEN};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use rayon::prelude::*;

/// Position of slot `slot` of corner `c`'s sub-block in the output corner order.
#[inline]
fn pos(c: u32, slot: u32) -> u32 {
    12 * (c / 3) + 3 * (c % 3) + slot
}

/// The corner after `c` in its face.
#[inline]
fn next_c(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

struct Ranks<'a> {
    cidx: &'a [u32],
    /// Per corner: `rank << 3 | mask` (rank: first corners of the face's
    /// block before this sub-block; mask bit `s`: slot `s` is first).
    rm: Vec<u32>,
    /// Per face: first corners before its block.
    ebase: Vec<u32>,
}

impl Ranks<'_> {
    /// Id of slot `slot` of corner `c` when it is first.
    #[inline]
    fn first_id(&self, c: u32, slot: u32) -> u32 {
        let rm = self.rm[c as usize];
        2 * (self.ebase[(c / 3) as usize] + (rm >> 3) + (rm & ((1 << slot) - 1)).count_ones())
    }
    /// Id of `a` of corner `c` (half-edge `h`).
    #[inline]
    fn id_a(&self, c: u32, h: u32) -> u32 {
        if self.rm[c as usize] & 1 != 0 {
            self.first_id(c, 0)
        } else {
            // twin: b(next(twin h)), slot 2 of the corner after twin h's
            self.first_id(next_c(self.cidx[(h ^ 1) as usize]), 2) + 1
        }
    }
    /// Id of `b` of corner `c`, whose half-edge's previous is `p`.
    #[inline]
    fn id_b(&self, c: u32, p: u32) -> u32 {
        if self.rm[c as usize] & 4 != 0 {
            self.first_id(c, 2)
        } else {
            // twin: a(twin p), slot 0
            self.first_id(self.cidx[(p ^ 1) as usize], 0) + 1
        }
    }
}

/// Whether [`primal_triangles`] builds this input: no face points, no
/// holes, every face a triangle.
pub(crate) fn applies(m: &Mesh, fl: &FaceLayout, face_point: &[u32]) -> bool {
    let nf = m.n_faces();
    fl.off.len() == nf + 1
        && fl.off[nf] as usize == 3 * nf
        && face_point.par_iter().with_min_len(MIN_LEN).all(|&x| x == NONE)
        && fl.off.par_windows(2).with_min_len(MIN_LEN).all(|w| w[1] - w[0] == 3)
}

/// The connectivity columns (positions empty) for `n_points` output
/// vertices, and the side map when asked for; the input must pass
/// [`applies`]. Same as `primal_columns::fill` on this input.
pub(crate) fn fill(m: &Mesh, cidx: &[u32], n_points: usize, want_sides: bool) -> Result<(Columns, Vec<u32>)> {
    let (next, vert, _) = m.halfedge_columns();
    let (nv, nf) = (m.n_vertices() as u32, m.n_faces());
    if n_points != m.n_vertices() + m.n_edges() {
        return Err(MeshError::Invariant(format!("triangle host: {n_points} points for {} vertices and {} edges", nv, m.n_edges())));
    }
    let tri = |f: usize| {
        let h0 = m.f_start[f];
        let h1 = next[h0 as usize];
        [h0, h1, next[h1 as usize]]
    };
    let mut rk = Ranks { cidx, rm: vec![0; 3 * nf], ebase: Vec::with_capacity(nf) };
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
                let hs = tri(f);
                let mut r = 0u32;
                for k in 0..3u32 {
                    let (h, p) = (hs[k as usize], hs[((k + 2) % 3) as usize]);
                    let c = 3 * f as u32 + k;
                    let a = pos(next_c(cidx[(h ^ 1) as usize]), 2) > pos(c, 0);
                    let b = pos(cidx[(p ^ 1) as usize], 0) > pos(c, 2);
                    let mask = a as u32 | 2 | (b as u32) << 2;
                    // SAFETY: corner c belongs to face f only.
                    unsafe { *rmp.get().add(c as usize) = r << 3 | mask };
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
    if nh != 12 * nf {
        return Err(MeshError::Invariant(format!("triangle host: {} corners but {nh} half-edges", 12 * nf)));
    }
    let mut cols = Columns::for_points_unfilled(n_points, nh, 4 * nf);
    let mut sides = if want_sides { vec![NONE; acc as usize] } else { Vec::new() };
    let rk = &rk;
    let (pn, pp, pv, pf, ps, psd) = (
        SyncPtr(cols.he_next.as_mut_ptr()),
        SyncPtr(cols.he_prev.as_mut_ptr()),
        SyncPtr(cols.he_vert.as_mut_ptr()),
        SyncPtr(cols.he_face.as_mut_ptr()),
        SyncPtr(cols.f_start.as_mut_ptr()),
        SyncPtr(sides.as_mut_ptr()),
    );
    // pass 2: the columns, per face
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        if crate::cancel::requested() {
            return;
        }
        let hs = tri(f);
        let c0 = 3 * f as u32;
        let fo = 4 * f as u32;
        let s = [rk.first_id(c0, 1), rk.first_id(c0 + 1, 1), rk.first_id(c0 + 2, 1)];
        // SAFETY: the ids are a bijection from output corners onto
        // half-edges, and the output faces 4f.. belong to face f alone, so
        // no two writes hit the same entry.
        unsafe {
            let cycle = |ids: [u32; 3], vs: [u32; 3], of: u32| {
                for j in 0..3 {
                    let (id, idn) = (ids[j], ids[(j + 1) % 3]);
                    *pn.get().add(id as usize) = idn;
                    *pp.get().add(idn as usize) = id;
                    *pv.get().add(id as usize) = vs[j];
                    *pf.get().add(id as usize) = of;
                }
                *ps.get().add(of as usize) = ids[0];
            };
            for k in 0..3usize {
                let (h, p) = (hs[k], hs[(k + 2) % 3]);
                let c = c0 + k as u32;
                let (a, b) = (rk.id_a(c, h), rk.id_b(c, p));
                cycle([a, s[k], b], [vert[h as usize], nv + (h >> 1), nv + (p >> 1)], fo + k as u32);
                if want_sides {
                    if a & 1 == 0 {
                        *psd.get().add((a >> 1) as usize) = h;
                    }
                    if b & 1 == 0 {
                        *psd.get().add((b >> 1) as usize) = p ^ 1;
                    }
                }
            }
            // the middle triangle: m_k is the twin of s_{k+1}
            cycle([s[1] + 1, s[2] + 1, s[0] + 1], [nv + (hs[0] >> 1), nv + (hs[1] >> 1), nv + (hs[2] >> 1)], fo + 3);
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled, so every face's block ran, and the ids are a
    // bijection onto the half-edges: every entry is written
    unsafe { cols.assume_filled(nh) };
    let prev = &m.he_prev;
    // vertex points: the a corner of the outgoing half-edge first in face order
    cols.v_out[..nv as usize].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        if crate::cancel::requested() {
            return;
        }
        let s = m.v_out[v];
        let (mut h, mut best) = (s, s);
        loop {
            if cidx[h as usize] < cidx[best as usize] {
                best = h;
            }
            h = prev[h as usize] ^ 1;
            if h == s {
                break;
            }
        }
        *o = rk.id_a(cidx[best as usize], best);
    });
    // edge points: the lowest of the two sides' candidates, s(h) of a
    // corner k < 2 or, for k = 2, b of the face's corner 0 (b(next h))
    cols.v_out[nv as usize..].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
        if crate::cancel::requested() {
            return;
        }
        let cand = |h: u32| {
            let c = cidx[h as usize];
            if c % 3 < 2 {
                (pos(c, 1), c, true, h)
            } else {
                (pos(c - 2, 2), c - 2, false, next[h as usize])
            }
        };
        let (x, y) = (cand(2 * e as u32), cand(2 * e as u32 + 1));
        let (_, c, inner, h) = if x.0 < y.0 { x } else { y };
        *o = if inner { rk.first_id(c, 1) } else { rk.id_b(c, prev[h as usize]) };
    });
    crate::cancel::check()?;
    Ok((cols, sides))
}

#[cfg(test)]
mod tests {
    use super::super::hosts::test_meshes as tm;
    use super::*;
    use glam::DVec3;

    /// The same mesh and side map as the general build, on every
    /// all-triangle closed mesh of the corpus, also after InsertEdge
    /// (faces and vertices whose stored corner is not their first) and
    /// after a Loop level (the numbering a second level sees).
    #[test]
    fn equals_the_general_build() {
        let mut meshes: Vec<(String, Mesh)> = Vec::new();
        for (name, m) in tm::corpus() {
            if m.n_holes() == 0 && !m.v_out.iter().any(|&o| o & crate::mesh::POINT != 0) && tm::face_sizes(&m).iter().all(|&s| s == 3) {
                meshes.push((name.to_string(), m));
            }
        }
        let ico = crate::primitives::icosahedron();
        meshes.push(("loop icosahedron".into(), crate::schemes::loop_subdivision::loop_subdivision(&ico).unwrap()));
        let tt = crate::schemes::hosts::fan_triangulate(&crate::primitives::torus(7, 5, 3.0, 1.0).unwrap()).unwrap().expect("quads get fans");
        meshes.push(("triangulated torus".into(), tt));
        assert!(meshes.len() >= 4, "{}", meshes.len());
        for (name, m) in &meshes {
            let fl = FaceLayout::new(m).unwrap();
            let fp = vec![NONE; m.n_faces()];
            assert!(applies(m, &fl, &fp), "{name}");
            let n_points = m.n_vertices() + m.n_edges();
            let pos: Vec<DVec3> = (0..n_points).map(|i| DVec3::splat(i as f64)).collect();
            for sides in [false, true] {
                let (mut cols, sa) = fill(m, &fl.cidx, n_points, sides).unwrap();
                cols.pos = pos.clone();
                let a = Mesh::from_columns(cols).unwrap();
                a.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                let (b, sb) = super::super::hosts::primal_host_twins(m, &fl, &fp, pos.clone(), sides).unwrap();
                assert_eq!(a, b, "{name}");
                assert_eq!(sides.then_some(sa), sb, "{name}");
            }
        }
    }
}
