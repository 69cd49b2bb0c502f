//! Linear vertex insertion (TopMod's *Linear Vertex Insertion*,
//! `subdivideAllFaces(obj, true)`), subdivision of selected faces
//! (`subdivideFaces(obj, faces, usequads)`) and edge splitting
//! (`subdivideAllEdges(obj, k)`), read from TopMod's source
//! (`include/dlflaux/DLFLSubdiv.cc`, `subdivideFace`, `subdivideFaces`).
//!
//! * [`linear_vertex_insertion`] — every edge split at its midpoint, every
//!   face's centroid joined to its edges' midpoints: corner h of an n-gon
//!   becomes the quad `[tail(h), m(h), c, m(prev h)]` (Catmull-Clark's
//!   connectivity with linear positions). V' = V + E + F, E' = 4E, F' = 2E
//!   quads.
//! * [`subdivide_faces`] — the same on the selected faces only (`quads`), or
//!   their centroid fan (`!quads`, TopMod's `usequads = false`). With k
//!   selected faces of Σn corners and s edges having a selected side:
//!   quads: V' = V + s + k, E' = E + s + Σn, F' = F − k + Σn; an unselected
//!   face gains one corner per split edge. Fan: V' = V + k, E' = E + Σn,
//!   F' = F − k + Σn.
//! * [`split_edges`] — every edge cut into `parts` equal segments: V' = V +
//!   (parts − 1)E, E' = parts·E, F' = F, an n-gon becomes a (parts·n)-gon.
//!
//! Vertex layout: the input's vertices, then the edge points (edge order,
//! from the tail of the edge's first half-edge), then the centres (face order).

use crate::schemes::keyed::{In, Out};
use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE};
use crate::schemes::hosts::with_point_spheres;

/// Linear vertex insertion on every face. See the module docs.
pub fn linear_vertex_insertion(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("linear_vertex_insertion", m, |m| {
        let all: Vec<usize> = (0..m.n_faces()).collect();
        faces_step("linear_vertex_insertion", m, &all, true)
    })
}

/// Subdivides the faces `faces` (indices into `m`'s faces, repeats allowed)
/// into quads (`quads`) or centroid-fan triangles. See the module docs.
/// Point-sphere and hole faces cannot be selected.
pub fn subdivide_faces(m: &Mesh, faces: &[usize], quads: bool) -> Result<Mesh> {
    let sel = selection("subdivide_faces", m, faces)?;
    with_point_spheres("subdivide_faces", m, |m| faces_step("subdivide_faces", m, &sel, quads))
}

/// Checks a face selection (in range, no point-sphere, no hole) and
/// renumbers it to the faces left once point-spheres are set aside
/// ([`with_point_spheres`]).
pub(crate) fn selection(name: &str, m: &Mesh, faces: &[usize]) -> Result<Vec<usize>> {
    crate::schemes::hosts::refuse_holes(name, m)?;
    for &f in faces {
        if f >= m.n_faces() {
            return Err(MeshError::InvalidArgument(format!("{name}: face {f} out of range (the mesh has {} faces)", m.n_faces())));
        }
        if m.face_halfedge(crate::FaceId(f as u32)).is_none() {
            return Err(MeshError::InvalidArgument(format!("{name}: face {f} is a point-sphere (it has no edge)")));
        }
    }
    let mut fmap = vec![NONE; m.n_faces()];
    let mut k = 0u32;
    for f in 0..m.n_faces() {
        if m.face_halfedge(crate::FaceId(f as u32)).is_some() {
            fmap[f] = k;
            k += 1;
        }
    }
    Ok(faces.iter().map(|&f| fmap[f] as usize).collect())
}

fn faces_step(name: &str, m: &Mesh, faces: &[usize], quads: bool) -> Result<Mesh> {
    let i = In::new(m)?;
    let (nh, ne) = (i.nh, i.ne);
    let mut selected = vec![false; i.nf];
    let mut order = Vec::with_capacity(faces.len());
    for &f in faces {
        if !selected[f] {
            selected[f] = true;
            order.push(f);
        }
    }
    // edge points: edges with a selected side, when splitting
    let mut epoint = vec![NONE; ne];
    let mut pos = i.positions(0);
    if quads {
        for e in 0..ne {
            if selected[i.face[2 * e] as usize] || selected[i.face[2 * e + 1] as usize] {
                epoint[e] = pos.len() as u32;
                pos.push((i.p(2 * e) + i.q(2 * e)) * 0.5);
            }
        }
    }
    let cent = i.centroids();
    let mut centre = vec![NONE; i.nf];
    for &f in &order {
        centre[f] = pos.len() as u32;
        pos.push(cent[f]);
    }
    // keys: [0, H) the edges (2e for an unsplit edge, h for the segment at
    // tail(h) of a split one), [H, 2H) the spoke of corner h
    let key_of = |h: usize| if epoint[h >> 1] == NONE { (h & !1) as u32 } else { h as u32 };
    let mut o = Out::new(pos, 2 * nh, i.nf + nh, 4 * nh).of(&i);
    o.keeps_vertices(i.nv);
    for f in 0..i.nf {
        o.from_face(f);
        let hs = i.fl.corners(f);
        if !selected[f] {
            for &h in hs {
                let h = h as usize;
                o.c(i.vert[h], key_of(h));
                if epoint[h >> 1] != NONE {
                    o.c(epoint[h >> 1], (h ^ 1) as u32);
                }
            }
            o.end();
        } else if quads {
            for &h in hs {
                let (h, p) = (h as usize, i.prev[h as usize] as usize);
                o.c(i.vert[h], h as u32);
                o.c(epoint[h >> 1], (nh + h) as u32);
                o.c(centre[f], (nh + p) as u32);
                o.c(epoint[p >> 1], (p ^ 1) as u32);
                o.end();
            }
        } else {
            for &h in hs {
                let h = h as usize;
                o.c(i.vert[h], key_of(h));
                o.c(i.vert[h ^ 1], nh as u32 + i.next[h]);
                o.c(centre[f], (nh + h) as u32);
                o.end();
            }
        }
    }
    o.finish(name)
}

/// Every edge cut into `parts` (>= 1) equal segments. See the module docs.
pub fn split_edges(m: &Mesh, parts: usize) -> Result<Mesh> {
    if parts == 0 {
        return Err(MeshError::InvalidArgument("split_edges: parts = 0 must be >= 1".into()));
    }
    with_point_spheres("split_edges", m, |m| {
        let i = In::new(m)?;
        let (v, k) = (i.nv, parts);
        crate::schemes::hosts::check_output_size("split_edges", k.saturating_mul(i.nh), v.saturating_add((k - 1).saturating_mul(i.ne)))?;
        let mut pos = i.positions((k - 1) * i.ne);
        for e in 0..i.ne {
            let (a, b) = (i.p(2 * e), i.q(2 * e));
            for j in 1..k {
                pos.push(a.lerp(b, j as f64 / k as f64));
            }
        }
        // point j (0..=k) of edge e, from tail(2e); key of segment s: e·k + s
        let pt = |h: usize, j: usize| -> u32 {
            if j == 0 {
                i.vert[h & !1]
            } else if j == k {
                i.vert[h | 1]
            } else {
                (v + (h >> 1) * (k - 1) + j - 1) as u32
            }
        };
        let mut o = Out::new(pos, k * i.ne, i.nf, k * i.nh).of(&i);
        o.keeps_vertices(i.nv);
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                let h = h as usize;
                let e = h >> 1;
                for s in 0..k {
                    if h & 1 == 0 {
                        o.c(pt(h, s), (e * k + s) as u32);
                    } else {
                        o.c(pt(h, k - s), (e * k + k - 1 - s) as u32);
                    }
                }
            }
            o.end();
        }
        o.finish("split_edges")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    #[test]
    fn linear_counts() {
        check("linear_vertex_insertion", linear_vertex_insertion, |_, (v, e, f)| (v + e + f, 4 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(4, 2 * e)]));
    }

    #[test]
    fn split_counts() {
        for k in 1..4 {
            check("split_edges", |m| split_edges(m, k), |_, (v, e, f)| (v + (k - 1) * e, k * e, f), |m, _| {
                hist_of(m).into_iter().map(|(n, c)| (k * n, c)).collect()
            });
        }
    }

    #[test]
    fn selected_faces() {
        let c = crate::primitives::cube();
        // faces 0 and 1 share an edge? count the split edges directly
        for sel in [vec![0usize], vec![0, 1], vec![0, 1, 2, 3, 4, 5], vec![2, 2]] {
            let mut s = std::collections::BTreeSet::new();
            for &f in &sel {
                for h in c.face_halfedges(crate::FaceId(f as u32)) {
                    s.insert(h.edge().0);
                }
            }
            let uniq: std::collections::BTreeSet<usize> = sel.iter().copied().collect();
            let (k, n) = (uniq.len(), 4 * uniq.len());
            let q = subdivide_faces(&c, &sel, true).unwrap();
            q.validate().unwrap();
            assert_eq!((q.n_vertices(), q.n_edges(), q.n_faces()), (8 + s.len() + k, 12 + s.len() + n, 6 - k + n), "{sel:?}");
            let t = subdivide_faces(&c, &sel, false).unwrap();
            t.validate().unwrap();
            assert_eq!((t.n_vertices(), t.n_edges(), t.n_faces()), (8 + k, 12 + n, 6 - k + n), "{sel:?}");
        }
        let all = subdivide_faces(&c, &[0, 1, 2, 3, 4, 5], true).unwrap();
        assert_eq!(all.to_polygons(), linear_vertex_insertion(&c).unwrap().to_polygons());
        assert!(subdivide_faces(&c, &[6], true).is_err());
    }
}
