//! Step 3 (VII.3 step 3, VII.4–VII.5): the inner surface's points. Merged
//! offset corners, two miter vertices per non-convex edge on the line
//! where its faces' offset planes meet, the clip of offset corners at
//! concave corners, and the weld of near points around each vertex; with
//! the face-cycle helpers that split a welded cycle into polygons.

use super::inset::{corner_sides, inside_corner};
use super::offset::Plan;
use super::{EdgeKind, MITER_REACH, WELD_TOL};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::{DMat3, DVec3};

/// A face's own offset corner (not merged) moves onto a miter vertex at the
/// same original vertex that lies on the face's offset plane, inside the
/// face's inset corner: the offset face is clipped by the offset of the
/// concave corner instead of reaching into it (module docs, step 3).
fn clip_to_miter_vertices(m: &Mesh, pl: &Plan, ip: &mut [DVec3]) {
    let pos = m.positions();
    let ng = pl.group_pos.len();
    let mut gsize = vec![0u32; ng];
    for h in m.halfedges() {
        gsize[pl.group[h.idx()] as usize] += 1;
    }
    let mut ends: Vec<usize> = Vec::new();
    for v in m.vertices() {
        ends.clear();
        ends.extend(m.vertex_halfedges(v).filter(|h| pl.kind[h.edge().idx()] == EdgeKind::Miter).map(|h| ng + 2 * h.edge().idx() + (h.0 & 1) as usize));
        // per-face corners stay on their right prisms (module docs)
        if ends.is_empty() || pl.per_face {
            continue;
        }
        let pv = pos[v.idx()];
        for h in m.vertex_halfedges(v) {
            let g = pl.group[h.idx()] as usize;
            let f = m.face(h).idx();
            let (n, d, dd) = (pl.face_n[f], pl.face_d[f], pl.face_depth[f]);
            let (w1, w2, convex) = corner_sides(m, n, h);
            if gsize[g] != 1 || !convex {
                continue;
            }
            let on_plane = |x: DVec3| (n.dot(x) - (n.dot(pv) - dd)).abs() <= 1e-7 * dd;
            if let Some(&i) = ends.iter().find(|&&i| on_plane(ip[i]) && inside_corner(ip[i], pv, (w1, w2), d * (1.0 - 1e-7))) {
                ip[g] = ip[i];
            }
        }
    }
}

/// The inner surface's points: merged offset corners (`group`), then two
/// miter points per edge (`G + 2e + end`, end 0 at the tail of `2e`), welded
/// where they coincide around one original vertex.
pub(super) struct Inner {
    pub(super) pos: Vec<DVec3>,
    /// Representative of every inner point after welding.
    pub(super) rep: Vec<u32>,
}

pub(super) fn inner_points(m: &Mesh, pl: &Plan, refined: bool, full: &[bool]) -> Result<Inner> {
    let pos = m.positions();
    let ng = pl.group_pos.len();
    let ne = m.n_edges();
    let mut ip = pl.group_pos.clone();
    ip.resize(ng + 2 * ne, DVec3::NAN);
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        if pl.kind[e.idx()] != EdgeKind::Miter {
            continue;
        }
        let h = e.halfedge();
        let th = h.twin();
        let (f1, f2) = (m.face(h).idx(), m.face(th).idx());
        let (n1, n2) = (pl.face_n[f1], pl.face_n[f2]);
        let u = (pos[m.head(h).idx()] - pos[m.vertex(h).idx()]).normalize();
        // end 0 at tail(h): corners h (f1) and next(th) (f2); end 1: next(h) and th
        for (end, (c1, c2)) in [(h, m.next(th)), (m.next(h), th)].into_iter().enumerate() {
            let pv = pos[m.vertex(c1).idx()];
            // exactly on L_e, the line where the two offset planes meet, so
            // the two miter quads stay planar (VII.5.4, Fig. 61): start at
            // the point of L_e in the plane through the vertex normal to the
            // edge, then slide along L_e towards the offset planes of the
            // other faces around the vertex (least squares), or to the
            // middle of the two offset corners when none of them fixes it
            let x0 = DMat3::from_cols(n1, n2, u).transpose().inverse() * DVec3::new(n1.dot(pv) - pl.face_depth[f1], n2.dot(pv) - pl.face_depth[f2], u.dot(pv));
            if !x0.is_finite() {
                return Err(MeshError::InvalidArgument(format!("menger: edge {} folds back on itself (φ = 360°)", e.0)));
            }
            let (mut num, mut den) = (0.0, 0.0);
            let mut dmin = f64::INFINITY;
            for hh in m.vertex_halfedges(m.vertex(c1)) {
                let f = m.face(hh).idx();
                dmin = dmin.min(pl.face_depth[f]);
                if f == f1 || f == f2 {
                    continue;
                }
                let n = pl.face_n[f];
                num += (n.dot(x0) - (n.dot(pv) - pl.face_depth[f])) * n.dot(u);
                den += n.dot(u) * n.dot(u);
            }
            let (r1, r2) = (pl.group_pos[pl.group[c1.idx()] as usize], pl.group_pos[pl.group[c2.idx()] as usize]);
            // per-face corners (module docs, "Per-face corners"): always the
            // middle, so the miter quads run along the edge like a strip and
            // leave the vertex's neighbourhood to its vertex face (slid
            // towards the other planes, the miter point comes back to the
            // vertex as the depth shrinks: octahedron 2, 168 → 0 pairs)
            let s = if den > 1e-6 && !pl.per_face { -num / den } else { (0.5 * (r1 + r2) - x0).dot(u) };
            // kept within MITER_REACH·D of the vertex (near-parallel planes)
            let dmax = if refined { MITER_REACH } else { 2.0 } * dmin;
            let r0 = (x0 - pv).length();
            ip[ng + 2 * e.idx() + end] = if pl.per_face {
                // per-face corners: the middle along the edge is kept (the
                // offset corners bound it), and only the distance from the
                // edge is bounded, by the two faces' own depths (a reach
                // bound by the thinnest face around the vertex pulled a 312°
                // edge's miter point back to the vertex: tetrahedron 3)
                let reach = if refined { MITER_REACH } else { 2.0 } * pl.face_depth[f1].min(pl.face_depth[f2]);
                let x = if r0 > reach { pv + (x0 - pv) * (reach / r0) } else { x0 };
                x + u * s
            } else if r0 > dmax {
                // nearly parallel offset planes (φ just above 180°) meet far
                // away: pulled back towards the vertex, off the planes
                pv + (x0 - pv) * (dmax / r0)
            } else {
                let smax = (dmax * dmax - r0 * r0).sqrt();
                x0 + u * s.clamp(-smax, smax)
            };
        }
    }
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        if pl.kind[e.idx()] != EdgeKind::Miter {
            continue;
        }
        let h = e.halfedge();
        for (end, c1) in [h, m.next(h)].into_iter().enumerate() {
            if full[m.vertex(c1).idx()] {
                ip[ng + 2 * e.idx() + end] = pl.group_pos[pl.group[c1.idx()] as usize];
            }
        }
    }
    clip_to_miter_vertices(m, pl, &mut ip);
    // weld inner points around each original vertex: neighbours along the
    // vertex face's cycle when closer than WELD_TOL·D (an edge of the inner
    // surface collapses), any two when they coincide
    let mut parent: Vec<u32> = (0..ip.len() as u32).collect();
    let mut cyc: Vec<u32> = Vec::new();
    for v in m.vertices() {
        crate::cancel::poll(v.0 as usize)?;
        let Some(h0) = m.vertex_halfedge(v) else { continue };
        cyc.clear();
        let mut dmin = f64::INFINITY;
        let mut h = h0;
        loop {
            cyc.push(pl.group[h.idx()]);
            dmin = dmin.min(pl.face_depth[m.face(h).idx()]);
            if pl.kind[h.edge().idx()] == EdgeKind::Miter {
                cyc.push((ng + 2 * h.edge().idx() + (h.0 & 1) as usize) as u32);
            }
            h = m.next(h.twin());
            if h == h0 {
                break;
            }
        }
        // near points (closer than WELD_TOL·D) are welded when that keeps
        // the vertex face one polygon or removes it entirely (it then splits
        // into pieces of two sides, whose sides are glued); a split that
        // leaves a polygon touching another piece at one point would pinch
        // the surface, so then only coincident points are welded
        let k = cyc.len();
        let close = |tol: f64, i: usize, j: usize| cyc[i] != cyc[j] && ip[cyc[i] as usize].distance(ip[cyc[j] as usize]) <= tol;
        let mut local: Vec<u32> = (0..k as u32).collect();
        for i in 0..k {
            for j in i + 1..k {
                if close(WELD_TOL * dmin, i, j) {
                    crate::union_find::union(&mut local, i as u32, j as u32);
                }
            }
        }
        let welded: Vec<u32> = (0..k).map(|i| cyc[crate::union_find::root(&mut local, i as u32) as usize]).collect();
        let pieces = split_cycle(&welded);
        let mut pairs: Vec<(u32, u32)> = pieces.iter().filter(|p| p.len() == 2).map(|p| (p[0].min(p[1]), p[0].max(p[1]))).collect();
        pairs.sort_unstable();
        pairs.dedup();
        let ok = refined && !pl.per_face && (pieces.len() == 1 || (pieces.iter().all(|p| p.len() == 2) && pairs.len() == pieces.len()));
        let tol = if ok { WELD_TOL * dmin } else { 1e-7 * dmin };
        for i in 0..k {
            for j in i + 1..k {
                if close(tol, i, j) {
                    crate::union_find::union(&mut parent, cyc[i], cyc[j]);
                }
            }
        }
    }
    let rep: Vec<u32> = (0..ip.len() as u32).map(|i| crate::union_find::root(&mut parent, i)).collect();
    Ok(Inner { pos: ip, rep })
}

/// A face cycle after welding: consecutive repeats removed, then split
/// wherever it passes a vertex twice (the pieces touch only there).
pub(super) fn split_cycle(poly: &[u32]) -> Vec<Vec<u32>> {
    let d = dedup_cycle(poly);
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            if d[i] == d[j] {
                let mut out = split_cycle(&d[i..j]);
                let rest: Vec<u32> = d[j..].iter().chain(&d[..i]).copied().collect();
                out.extend(split_cycle(&rest));
                return out;
            }
        }
    }
    vec![d]
}

/// The cycle with consecutive repeated vertices (cyclically) removed.
fn dedup_cycle(poly: &[u32]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::with_capacity(poly.len());
    for &x in poly {
        if out.last() != Some(&x) {
            out.push(x);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}
