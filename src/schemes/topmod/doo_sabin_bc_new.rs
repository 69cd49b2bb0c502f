//! TopMod's *Doo Sabin BC New* remeshing (`dooSabinSubdivideBCNew(obj, sf,
//! length)`, `include/dlflaux/DLFLSubdiv.cc`, the callback
//! `subdivideDooSabinBCNew`; TopMod's source is the only description):
//! every edge halved (`subdivideAllEdges`), a Doo-Sabin extrusion of length
//! 0 of every face (`extrudeFaceDS(fp, 0, 1, 0, sf)`: the Doo-Sabin mask of
//! the halved face, scaled by `scale` about its centroid), deletion of the
//! halved edges, then at every midpoint m the two new ring points beside it
//! joined by an edge and m's two edges deleted; finally every old vertex
//! moved to `length · v + (1 − length) · (mean of its ring points)`.
//!
//! Built here in one pass. With T(h) and M(h) the ring points of face f at
//! the tail of its corner h and at that side's midpoint (f's ring is
//! `T(h₀) M(h₀) T(h₁) M(h₁) …`), an edge with half-edges h (v → w, face f)
//! and t (w → v, face g) gives the two pentagons
//!
//! ```text
//! [v, T(next t), M(t), M(h), T(h)]   and   [w, T(next h), M(h), M(t), T(t)]
//! ```
//!
//! sharing the new edge M(h)–M(t); every face keeps its ring as a 2n-gon.
//! Counts: V' = V + 4E, E' = 7E, F' = F + 2E; face sizes: a 2n-gon per
//! n-gon and 2E pentagons; every old vertex keeps its valence. Vertex
//! layout: the input's vertices, then T(h), M(h) at 2h, 2h + 1.
//!
//! `scale` in (0, 2] and `length` in [0, 1] (TopMod's UI; defaults 1).

use crate::schemes::keyed::{In, Out};
use super::corner_cutting::cut_face;
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

/// TopMod's Doo-Sabin BC New. See the module docs.
pub fn doo_sabin_bc_new(m: &Mesh, scale: f64, length: f64) -> Result<Mesh> {
    if !(scale.is_finite() && scale > 0.0 && scale <= 2.0) {
        return Err(MeshError::InvalidArgument(format!("doo_sabin_bc_new: scale = {} must be in (0, 2]", crate::error::num(scale))));
    }
    if !(length.is_finite() && (0.0..=1.0).contains(&length)) {
        return Err(MeshError::InvalidArgument(format!("doo_sabin_bc_new: length = {} must be in [0, 1]", crate::error::num(length))));
    }
    with_point_spheres("doo_sabin_bc_new", m, |m| step(m, scale, length))
}

fn step(m: &Mesh, scale: f64, length: f64) -> Result<Mesh> {
    let i = In::new(m)?;
    let (nv, ne, nh) = (i.nv as u32, i.ne as u32, i.nh as u32);
    let mut pos = i.positions(2 * i.nh);
    pos.resize(i.nv + 2 * i.nh, DVec3::ZERO);
    // the rings: Doo-Sabin's mask over the halved face, scaled about its centroid
    let (mut x, mut ring) = (Vec::new(), Vec::new());
    for f in 0..i.nf {
        let hs = i.fl.corners(f);
        x.clear();
        for &h in hs {
            x.push(i.p(h as usize));
            x.push((i.p(h as usize) + i.q(h as usize)) * 0.5);
        }
        ring.clear();
        cut_face(&x, 0.25 + 5.0 / (4.0 * x.len() as f64), &mut ring);
        let c = ring.iter().sum::<DVec3>() / ring.len() as f64;
        for (j, &h) in hs.iter().enumerate() {
            pos[(nv + 2 * h) as usize] = c + scale * (ring[2 * j] - c);
            pos[(nv + 2 * h + 1) as usize] = c + scale * (ring[2 * j + 1] - c);
        }
    }
    if length != 1.0 {
        let mut sum = crate::mesh::zeroed_points(i.nv);
        let mut cnt = vec![0u32; i.nv];
        for h in 0..i.nh {
            let v = i.vert[h] as usize;
            sum[v] += pos[i.nv + 2 * h];
            cnt[v] += 1;
        }
        for v in 0..i.nv {
            pos[v] = length * pos[v] + (1.0 - length) * sum[v] / cnt[v] as f64;
        }
    }
    let (t, mid) = (|h: u32| nv + 2 * h, |h: u32| nv + 2 * h + 1);
    // keys: T(h)→M(h) is h, M(h)→T(next h) is H + h, the vertical v–T(h) is
    // 2H + h, the cross edge of edge e is 3H + e
    let (r1, r2, vk, x_) = (|h: u32| h, |h: u32| nh + h, |h: u32| 2 * nh + h, |e: u32| 3 * nh + e);
    let mut o = Out::new(pos, 3 * i.nh + i.ne, i.nf + 2 * i.ne, 4 * i.nh + 10 * i.ne).of(&i);
    o.keeps_vertices(i.nv);
    for f in 0..i.nf {
        o.from_face(f);
        for &h in i.fl.corners(f) {
            o.c(t(h), r1(h));
            o.c(mid(h), r2(h));
        }
        o.end();
    }
    for e in 0..ne {
        // the pentagon at the tail of a: [tail a, T(next b), M(b), M(a), T(a)]
        for (a, b) in [(2 * e, 2 * e + 1), (2 * e + 1, 2 * e)] {
            // it straddles edge e at a's tail: a's face
            o.from_face(i.face[a as usize] as usize);
            let nb = i.next[b as usize];
            o.c(i.vert[a as usize], vk(nb));
            o.c(t(nb), r2(b));
            o.c(mid(b), x_(e));
            o.c(mid(a), r1(a));
            o.c(t(a), vk(a));
            o.end();
        }
    }
    o.finish("doo_sabin_bc_new")
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    #[test]
    fn counts_and_sizes() {
        for (s, l) in [(1.0, 1.0), (0.7, 0.3)] {
            check("doo_sabin_bc_new", |m| doo_sabin_bc_new(m, s, l), |_, (v, e, f)| (v + 4 * e, 7 * e, f + 2 * e), |m, (_, e, _)| {
                let mut h = BTreeMap::new();
                for (n, c) in hist_of(m) {
                    *h.entry(2 * n).or_insert(0) += c;
                }
                *h.entry(5).or_insert(0) += 2 * e;
                h
            });
        }
    }

    #[test]
    fn old_vertices_keep_valence_and_move_with_length() {
        let c = crate::primitives::cube();
        let r = doo_sabin_bc_new(&c, 1.0, 1.0).unwrap();
        for v in 0..c.n_vertices() {
            let id = crate::VertexId(v as u32);
            assert_eq!(r.valence(id), c.valence(id));
            assert_eq!(r.position(id), c.position(id));
        }
        // length 0: each old vertex at the mean of its ring points, inside the cube
        let r0 = doo_sabin_bc_new(&c, 1.0, 0.0).unwrap();
        assert!(r0.positions()[..8].iter().all(|p| p.abs().max_element() < 1.0 - 1e-6));
        assert!(doo_sabin_bc_new(&c, 0.0, 1.0).unwrap_err().to_string().contains("scale"));
        assert!(doo_sabin_bc_new(&c, 1.0, 1.5).unwrap_err().to_string().contains("length"));
    }
}
