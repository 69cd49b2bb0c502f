//! Pentagonalization (TopMod's *Pentagonalization*, `pentagonalSubdivide(obj,
//! offset)`) and pentagon preserving remeshing (`pentagonalSubdivide2(obj,
//! scale_factor)`), read from TopMod's source
//! (`include/dlflaux/DLFLSubdiv.cc`), the only description of both.
//!
//! * [`pentagonalize`] — every edge trisected; in each face the centroid c
//!   is joined to the trisection point nearest the tail of each side, so
//!   corner h gives the pentagon `[p(h), p(twin h), head(h), p(next h), c]`
//!   (p(h) is the point at 1/3 of h from its tail). Each p(h) then moves by
//!   `offset` towards the centroid of its face (TopMod moves all but the
//!   last of each face, an artefact of its loop; here all move).
//!   V' = V + 2E + F, E' = 5E, F' = 2E pentagons. Vertex layout: old
//!   vertices, p(h) at V + h, centroids at V + 2E + f.
//! * [`pentagon_preserving`] — every edge split at its midpoint; each face
//!   of n ≥ 3 sides gets the n-gon of its midpoints scaled by `scale` about
//!   their centroid (TopMod's `scale`), joined to them by n pentagons
//!   `[m(h), head(h), m(next h), i(next h), i(h)]`; one- and two-gons only
//!   get their midpoints (TopMod skips them). With H₃ the corners of faces
//!   with n ≥ 3: V' = V + E + H₃, E' = 2E + 2H₃, F' = F + H₃; histogram:
//!   n-gons (n ≥ 3) kept, H₃ pentagons, a k-gon with k ≤ 2 becomes a 2k-gon.
//!   Vertex layout: old vertices, midpoints (edge order), inner points.

use crate::schemes::keyed::{In, Out};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

/// TopMod's pentagonalization with `offset` in [0, 1] (default 0). See the
/// module docs.
pub fn pentagonalize(m: &Mesh, offset: f64) -> Result<Mesh> {
    if !(offset.is_finite() && (0.0..=1.0).contains(&offset)) {
        return Err(MeshError::InvalidArgument(format!("pentagonalize: offset = {} must be in [0, 1]", crate::error::num(offset))));
    }
    with_point_spheres("pentagonalize", m, |m| {
        let i = In::new(m)?;
        let (v, nh, ne) = (i.nv, i.nh, i.ne);
        let cent = i.centroids();
        let mut pos = i.positions(nh + i.nf);
        for h in 0..nh {
            let p = i.p(h).lerp(i.q(h), 1.0 / 3.0);
            pos.push(p.lerp(cent[i.face[h] as usize], offset));
        }
        pos.extend_from_slice(&cent);
        let pt = |h: usize| (v + h) as u32;
        // keys: [0, H) the segment at tail(h), [H, H + E) the middle segment
        // of edge e, [H + E, 2H + E) the spoke of corner h
        let (mid, spoke) = (nh as u32, (nh + ne) as u32);
        let mut o = Out::new(pos, 2 * nh + ne, nh, 5 * nh).of(&i);
        o.keeps_vertices(v);
        for f in 0..i.nf {
            o.from_face(f);
            let c = (v + nh + f) as u32;
            for &h in i.fl.corners(f) {
                let (h, nx) = (h as usize, i.next[h as usize]);
                o.c(pt(h), mid + (h >> 1) as u32);
                o.c(pt(h ^ 1), (h ^ 1) as u32);
                o.c(i.vert[h ^ 1], nx);
                o.c(pt(nx as usize), spoke + nx);
                o.c(c, spoke + h as u32);
                o.end();
            }
        }
        o.finish("pentagonalize")
    })
}

/// TopMod's pentagon preserving remeshing with `scale` in [0, 1] (default
/// 0.75). See the module docs.
pub fn pentagon_preserving(m: &Mesh, scale: f64) -> Result<Mesh> {
    if !(scale.is_finite() && (0.0..=1.0).contains(&scale)) {
        return Err(MeshError::InvalidArgument(format!("pentagon_preserving: scale = {} must be in [0, 1]", crate::error::num(scale))));
    }
    with_point_spheres("pentagon_preserving", m, |m| {
        let i = In::new(m)?;
        let (v, nh) = (i.nv, i.nh);
        let (pos, inner) = preserving_positions(&i, scale);
        let mid = |h: usize| (v + (h >> 1)) as u32;
        // keys: [0, H) the half of edge(h) at tail(h), [H, 2H) the inner side
        // of corner h, [2H, 3H) the spoke m(h)–i(h)
        let (n1, n2) = (nh as u32, 2 * nh as u32);
        let mut o = Out::new(pos, 3 * nh, i.nf + nh, 7 * nh).of(&i);
        o.keeps_vertices(v);
        for f in 0..i.nf {
            o.from_face(f);
            let hs = i.fl.corners(f);
            if hs.len() < 3 {
                for &h in hs {
                    o.c(i.vert[h as usize], h);
                    o.c(mid(h as usize), h ^ 1);
                }
                o.end();
                continue;
            }
            for &h in hs {
                o.c(inner[h as usize], n1 + h);
            }
            o.end();
            for &h in hs {
                let (h, nx) = (h as usize, i.next[h as usize]);
                o.c(mid(h), (h ^ 1) as u32);
                o.c(i.vert[h ^ 1], nx);
                o.c(mid(nx as usize), n2 + nx);
                o.c(inner[nx as usize], n1 + h as u32);
                o.c(inner[h], n2 + h as u32);
                o.end();
            }
        }
        o.finish("pentagon_preserving")
    })
}

/// Pentagon preserving's vertices (old ones, edge midpoints at V + e, then
/// the inner points of the faces of 3 or more corners, in face order) and
/// the inner point of each corner; shared with [`super::pentagonal_dual`].
pub(crate) fn preserving_positions(i: &In<'_>, scale: f64) -> (Vec<DVec3>, Vec<u32>) {
    let (v, nh, ne) = (i.nv, i.nh, i.ne);
    let mut pos = i.positions(ne + nh);
    for e in 0..ne {
        pos.push((i.p(2 * e) + i.q(2 * e)) * 0.5);
    }
    let mut inner = vec![0u32; nh];
    for f in 0..i.nf {
        let hs = i.fl.corners(f);
        if hs.len() < 3 {
            continue;
        }
        let c: DVec3 = hs.iter().map(|&h| pos[v + (h as usize >> 1)]).sum::<DVec3>() / hs.len() as f64;
        for &h in hs {
            inner[h as usize] = pos.len() as u32;
            let q = pos[v + (h as usize >> 1)];
            pos.push(c + scale * (q - c));
        }
    }
    (pos, inner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    #[test]
    fn pentagonalize_counts() {
        for off in [0.0, 0.3] {
            check("pentagonalize", |m| pentagonalize(m, off), |_, (v, e, f)| (v + 2 * e + f, 5 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(5, 2 * e)]));
        }
        // TopMod's pentagonalization of the cube: 24 pentagons, 38 vertices
        let r = pentagonalize(&crate::primitives::cube(), 0.0).unwrap();
        assert_eq!((r.n_vertices(), r.n_faces()), (38, 24));
    }

    #[test]
    fn pentagon_preserving_counts() {
        let h3 = |m: &Mesh| m.faces().map(|f| m.face_degree(f)).filter(|&n| n >= 3).sum::<usize>();
        check("pentagon_preserving", |m| pentagon_preserving(m, 0.75), |m, (v, e, f)| (v + e + h3(m), 2 * e + 2 * h3(m), f + h3(m)), |m, _| {
            let mut h = BTreeMap::new();
            for (n, c) in hist_of(m) {
                *h.entry(if n >= 3 { n } else { 2 * n }).or_insert(0) += c;
            }
            *h.entry(5).or_insert(0) += h3(m);
            h
        });
        // the dodecahedron keeps its 12 pentagons and gains 60
        let r = pentagon_preserving(&crate::primitives::dodecahedron(), 0.75).unwrap();
        assert_eq!(r.face_size_histogram(), BTreeMap::from([(5, 72)]));
    }
}
