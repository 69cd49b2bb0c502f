//! Dual 12.6.4 remeshing (TopMod's *Dual 12.6.4*, `dual1264Subdivide(obj,
//! sf)`), read from TopMod's source (`include/dlflaux/DLFLSubdiv.cc`), the
//! only description of it. TopMod's *12.6.4* is `dual ∘ dual_12_6_4 ∘ dual`
//! (`MainWindow::subdivide1264`), in `compose`.
//!
//! Each n-gon gets its own 2n-gon through the two trisection points of each
//! of its sides (`⅔ a + ⅓ b`, `⅓ a + ⅔ b` for side a→b), scaled by `scale`
//! about their centroid (TopMod's `scale`); the two copies of each edge's
//! segment are joined by a quad and each valence-k vertex is left with a
//! 2k-gon. V' = 4E, E' = 6E, F' = F + E + V; histogram: an n-gon gives a
//! 2n-gon, E quads, a valence-k vertex a 2k-gon; every vertex is 3-valent
//! (the 4.6.12 tiling from a 6-valent triangle mesh). Output vertices 2h
//! and 2h + 1 are the points of half-edge h. At `scale` = 1 the quads have
//! zero width (coincident points), as in TopMod.

use crate::schemes::keyed::{In, Out};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

/// TopMod's dual 12.6.4 with `scale` in (0, 1] (default 0.7). See the
/// module docs.
pub fn dual_12_6_4(m: &Mesh, scale: f64) -> Result<Mesh> {
    if !(scale.is_finite() && scale > 0.0 && scale <= 1.0) {
        return Err(MeshError::InvalidArgument(format!("dual_12_6_4: scale = {} must be in (0, 1]", crate::error::num(scale))));
    }
    with_point_spheres("dual_12_6_4", m, |m| {
        let i = In::new(m)?;
        let nh = i.nh as u32;
        let pos = positions(&i, scale);
        // keys: [0, H) the side along h, [H, 2H) the side cutting corner h,
        // [2H, 3H) the quad side at tail(h)
        let mut o = Out::new(pos, 3 * i.nh, i.nf + i.ne + i.nv, 6 * i.nh).of(&i);
        // points 2h, 2h + 1 lie in h's face
        o.vertex_origins(|| i.face.iter().flat_map(|&f| [f, f]).collect());
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                o.c(2 * h, h);
                o.c(2 * h + 1, nh + i.next[h as usize]);
            }
            o.end();
        }
        for e in 0..i.ne as u32 {
            let (h, t) = (2 * e, 2 * e + 1);
            // the quad of edge e straddles both its faces: the first side's
            o.from_face(i.face[h as usize] as usize);
            o.c(2 * h + 1, h);
            o.c(2 * h, 2 * nh + h);
            o.c(2 * t + 1, t);
            o.c(2 * t, 2 * nh + t);
            o.end();
        }
        for v in 0..i.nv {
            o.from_vertex(v);
            let k0 = m.v_out[v] as usize;
            let mut k = k0;
            loop {
                let p = i.prev[k];
                let r = i.rot(k);
                o.c(2 * k as u32, nh + k as u32);
                o.c(2 * p + 1, 2 * nh + r as u32);
                k = r;
                if k == k0 {
                    break;
                }
            }
            o.end();
        }
        o.finish("dual_12_6_4")
    })
}

/// Dual 12.6.4's vertices: points 2h, 2h + 1 of half-edge h; shared with
/// [`super::twelve_six_four_dual`].
pub(crate) fn positions(i: &In<'_>, scale: f64) -> Vec<DVec3> {
    let mut pos = crate::mesh::zeroed_points(2 * i.nh);
    for f in 0..i.nf {
        let hs = i.fl.corners(f);
        let mut c = DVec3::ZERO;
        for &h in hs {
            let (a, b) = (i.p(h as usize), i.q(h as usize));
            let (p1, p2) = (a.lerp(b, 1.0 / 3.0), a.lerp(b, 2.0 / 3.0));
            pos[2 * h as usize] = p1;
            pos[2 * h as usize + 1] = p2;
            c += p1 + p2;
        }
        c /= 2.0 * hs.len() as f64;
        for &h in hs {
            for p in &mut pos[2 * h as usize..2 * h as usize + 2] {
                *p = c + scale * (*p - c);
            }
        }
    }
    pos
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    #[test]
    fn counts() {
        check("dual_12_6_4", |m| dual_12_6_4(m, 0.7), |_, (v, e, f)| (4 * e, 6 * e, f + e + v), |m, (_, e, _)| {
            let mut h = BTreeMap::new();
            for (n, c) in hist_of(m) {
                *h.entry(2 * n).or_insert(0) += c;
            }
            *h.entry(4).or_insert(0) += e;
            for (k, c) in m.valence_histogram().into_iter().filter(|&(k, _)| k > 0) {
                *h.entry(2 * k).or_insert(0) += c;
            }
            h
        });
        let r = dual_12_6_4(&crate::primitives::cube(), 0.7).unwrap();
        assert!(r.valence_histogram().keys().all(|&k| k == 3));
        assert!(dual_12_6_4(&r, 0.0).is_err());
    }
}
