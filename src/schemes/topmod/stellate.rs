//! Stellation: TopMod's *Stellate* (`subdivideAllFaces(obj, false)`, the
//! centroid fan), *Double Stellate* (`starSubdivide`) and *Stellate with
//! edge removal* (`stellateSubdivide`), read from TopMod's source
//! (`include/dlflaux/DLFLSubdiv.cc`, `DLFLExtrude.cc: stellateFace`), the
//! only description of these schemes.
//!
//! * [`stellate`] — every n-gon becomes the n triangles
//!   `[tail(h), head(h), c]` around a new vertex c at its centroid moved by
//!   `offset` along the face's unit (Newell) normal (TopMod's `stellateFace`).
//!   V' = V + F, E' = 3E, F' = 2E, all triangles.
//! * [`double_stellate`] — `starSubdivide(offset)`: stellate, stellate every
//!   triangle again, then move the first round's centres by `offset` along
//!   their face's unit normal. V' = V + F + 2E, E' = 9E, F' = 6E, all triangles.
//! * [`stellate_edge_removal`] — `stellateSubdivide`: stellate, then delete
//!   every old edge: the two triangles beside edge a→b (in faces f, g) merge
//!   into the quad `[b, c_f, a, c_g]`. V' = V + F, E' = 2E, F' = E, all quads
//!   (Conway's *join* topology).
//! * [`double_stellate_misc`] — TopMod's second double stellation, *Double
//!   Stellate (Misc.)* (`twostellateSubdivide(obj, height, curve)`,
//!   DLFLSubdiv.cc, the callback `subStellate2`): stellate with the centres
//!   moved by `height`, stellate every triangle with its centre moved by
//!   `curve`, then delete every edge of the first stellation. That is
//!   [`stellate_edge_removal`]`(`[`stellate`]`(m, height), curve)`, written so:
//!   V' = V + F + 2E, E' = 6E, F' = 3E, all quads (each triangle side of the
//!   first stellation becomes the quad of its ends and its two triangles'
//!   centres).
//!
//! Vertex layout: the input's vertices first (same positions), then the
//! centres in face order (then, for [`double_stellate`], the second round's
//! centres in the first round's face order). A self-loop, one-gon or
//! two-gon is fanned like any face (a one-gon's triangle is `[v, v, c]`).

use crate::schemes::keyed::{In, Out};
use crate::error::Result;
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;

/// Centroid fan of every face, centres moved by `offset` along the face
/// normal. See the module docs.
pub fn stellate(m: &Mesh, offset: f64) -> Result<Mesh> {
    with_point_spheres("stellate", m, |m| stellate_step(m, offset))
}

fn stellate_step(m: &Mesh, offset: f64) -> Result<Mesh> {
    // Conway's kis of every face, with TopMod's apex
    let i = In::new(m)?;
    let c = i.centroids();
    let n = if offset != 0.0 { i.normals() } else { Vec::new() };
    crate::schemes::conway::kis::fan("stellate", &i, |_| true, |f| if offset != 0.0 { c[f] + offset * n[f] } else { c[f] })
}

/// TopMod's double stellation (`starSubdivide`). See the module docs.
pub fn double_stellate(m: &Mesh, offset: f64) -> Result<Mesh> {
    let once = stellate(m, 0.0)?;
    let mut twice = stellate(&once, 0.0)?;
    if offset != 0.0 {
        // the first round's centres follow the input's vertices (point-spheres excluded)
        let real: Vec<usize> = (0..m.n_faces()).filter(|&f| m.face_halfedge(crate::FaceId(f as u32)).is_some()).collect();
        let nv = m.n_vertices() - (m.n_faces() - real.len());
        for (k, &f) in real.iter().enumerate() {
            let n = m.face_unit_normal(crate::FaceId(f as u32));
            twice.pos[nv + k] += offset * n;
        }
    }
    Ok(twice)
}

/// Stellation followed by the deletion of every old edge. See the module docs.
pub fn stellate_edge_removal(m: &Mesh, offset: f64) -> Result<Mesh> {
    with_point_spheres("stellate_edge_removal", m, |m| edge_removal_step(m, offset))
}

fn edge_removal_step(m: &Mesh, offset: f64) -> Result<Mesh> {
    let i = In::new(m)?;
    let v = i.nv as u32;
    let mut pos = i.positions(i.nf);
    let n = if offset != 0.0 { i.normals() } else { Vec::new() };
    for (f, c) in i.centroids().into_iter().enumerate() {
        pos.push(if offset != 0.0 { c + offset * n[f] } else { c });
    }
    // keys: the spoke of every corner (h)
    let mut o = Out::new(pos, i.nh, i.ne, 2 * i.nh).of(&i);
    o.keeps_vertices(i.nv);
    // the centre of face f is born from f (its quads straddle two faces)
    o.vertex_origins(|| (0..i.nv as u32).map(|v| crate::schemes::face_parents::VERT | v).chain(0..i.nf as u32).collect());
    for e in 0..i.ne {
        let (h, t) = (2 * e, 2 * e + 1);
        // the quad of edge e straddles both its faces: the first side's
        o.from_face(i.face[h] as usize);
        o.c(i.vert[t], i.next[h]);
        o.c(v + i.face[h], h as u32);
        o.c(i.vert[h], i.next[t]);
        o.c(v + i.face[t], t as u32);
        o.end();
    }
    o.finish("stellate_edge_removal")
}

/// TopMod's *Double Stellate (Misc.)*, `twostellateSubdivide(height,
/// curve)`: the join of the stellation. See the module docs.
pub fn double_stellate_misc(m: &Mesh, height: f64, curve: f64) -> Result<Mesh> {
    stellate_edge_removal(&stellate(m, height)?, curve)
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    #[test]
    fn stellate_counts() {
        check("stellate", |m| stellate(m, 0.0), |_, (v, e, f)| (v + f, 3 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(3, 2 * e)]));
        check("stellate offset", |m| stellate(m, 0.3), |_, (v, e, f)| (v + f, 3 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(3, 2 * e)]));
    }

    #[test]
    fn double_stellate_counts() {
        check("double_stellate", |m| double_stellate(m, 0.2), |_, (v, e, f)| (v + f + 2 * e, 9 * e, 6 * e), |_, (_, e, _)| BTreeMap::from([(3, 6 * e)]));
    }

    #[test]
    fn edge_removal_counts() {
        check("stellate_edge_removal", |m| stellate_edge_removal(m, 0.0), |_, (v, e, f)| (v + f, 2 * e, e), |_, (_, e, _)| BTreeMap::from([(4, e)]));
        // the cube gives the rhombic dodecahedron
        let r = stellate_edge_removal(&crate::primitives::cube(), 0.0).unwrap();
        assert_eq!(hist_of(&r), BTreeMap::from([(4, 12)]));
        assert_eq!(r.valence_histogram().get(&3), Some(&8));
        assert_eq!(r.valence_histogram().get(&4), Some(&6));
    }

    #[test]
    fn double_stellate_misc_counts() {
        check("double_stellate_misc", |m| double_stellate_misc(m, 0.2, -0.1), |_, (v, e, f)| (v + f + 2 * e, 6 * e, 3 * e), |_, (_, e, _)| BTreeMap::from([(4, 3 * e)]));
        // the join of the stellated cube: its 24 triangles' centres are 3-valent,
        // the cube's corners keep valence 6 and the face centres 4
        let r = double_stellate_misc(&crate::primitives::cube(), 0.0, 0.0).unwrap();
        let h = r.valence_histogram();
        assert_eq!((h.get(&3), h.get(&4), h.get(&6)), (Some(&24), Some(&6), Some(&8)));
    }

    #[test]
    fn offset_moves_the_centres_out() {
        let c = crate::primitives::cube();
        let a = stellate(&c, 0.0).unwrap();
        let b = stellate(&c, 0.5).unwrap();
        assert!(b.signed_volume() > a.signed_volume() + 1e-9);
        let d0 = double_stellate(&c, 0.0).unwrap();
        let d1 = double_stellate(&c, 0.5).unwrap();
        assert!(d1.signed_volume() > d0.signed_volume() + 1e-9);
    }
}
