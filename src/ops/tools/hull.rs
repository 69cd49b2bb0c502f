//! Convex hull of a point set (TopMod's conical tools `createConvexHull`
//! and `createDualConvexHull`, `include/dlflaux/DLFLSculpting.cc`, built on
//! its own `DLFLConvexHull`; here a quickhull over exact orientation
//! predicates, `robust::orient3d` (Shewchuk), so no floating-point
//! tolerance decides which side of a plane a point lies on).
//!
//! The hull is triangulated while it grows. A point sees a face only when
//! it lies strictly beyond its plane (exact sign): a point outside the hull
//! is strictly beyond some face, so no extreme point is missed, and no new
//! triangle is degenerate (its apex is strictly beyond a face at every
//! horizon side). Counting a point in a face's plane but outside it as
//! seeing it, as this file first did, re-fanned a whole coplanar cap per
//! point (a cylinder's 32,000 rim points took 175 s, now 1 s) and kept
//! points that are not extreme or failed on integer lattices (5 of 300
//! degenerate test sets against Qhull). At the end, neighbouring triangles
//! in one plane (exactly, or within 1e-9 of the extent seen from both
//! triangles: the rounding of coordinates like the dodecahedron's) merge
//! into one polygon, a needle (a point added within rounding of a side)
//! joins its nearest neighbour, and vertices left in the middle of a
//! straight hull edge (valence 2) go: the result is a closed convex
//! polyhedron with one face per supporting plane and only extreme points
//! as vertices.

use crate::error::{MeshError, Result};
use crate::mesh::{BuildOptions, Mesh};
use crate::union_find::{root, union};
use glam::DVec3;
use robust::Coord3D;

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D { x: p.x, y: p.y, z: p.z }
}

/// > 0 when `d` lies on the side of triangle (a, b, c) from which it turns
/// counter-clockwise (the outside of an outward hull face); exact sign.
fn side(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    -robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

struct Tri {
    v: [u32; 3],
    /// Neighbour across side j (v[j] → v[j+1]).
    nb: [u32; 3],
    alive: bool,
    outside: Vec<u32>,
}

struct Hull<'a> {
    p: &'a [DVec3],
    tris: Vec<Tri>,
}

impl Hull<'_> {
    fn sees(&self, t: usize, q: u32) -> bool {
        let [a, b, c] = self.tris[t].v.map(|i| self.p[i as usize]);
        side(a, b, c, self.p[q as usize]) > 0.0
    }
    fn height(&self, t: usize, q: u32) -> f64 {
        let [a, b, c] = self.tris[t].v.map(|i| self.p[i as usize]);
        let n = (b - a).cross(c - a);
        n.dot(self.p[q as usize] - a) / n.length().max(f64::MIN_POSITIVE)
    }
    fn add(&mut self, v: [u32; 3]) -> u32 {
        self.tris.push(Tri { v, nb: [u32::MAX; 3], alive: true, outside: Vec::new() });
        self.tris.len() as u32 - 1
    }
}

/// The convex hull of `points` as a mesh of convex polygons, outward, and
/// for each of its vertices the index of the input point it is (the
/// lowest index among exact duplicates).
///
/// Errors: fewer than four distinct points, non-finite coordinates, or all
/// points in one plane (the hull has no volume).
pub fn convex_hull(points: &[DVec3]) -> Result<(Mesh, Vec<usize>)> {
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFinite { vertex: i });
    }
    // coordinates past 2^±200: the predicates' products overflow or
    // underflow, so the hull is found on the points divided by a power of
    // two (exact: the same decisions as at unit size) and the output takes
    // the given points back
    let Some(s) = crate::geometry::extreme_scale(points) else { return hull_of(points) };
    let q: Vec<DVec3> = points.iter().map(|p| *p / s).collect();
    let (mut m, source) = hull_of(&q)?;
    for (p, &i) in m.positions_mut().iter_mut().zip(&source) {
        *p = points[i];
    }
    Ok((m, source))
}

fn hull_of(points: &[DVec3]) -> Result<(Mesh, Vec<usize>)> {
    // exact duplicates out
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    let key = |i: u32| points[i as usize].to_array().map(f64::to_bits);
    order.sort_unstable_by_key(|&i| (key(i), i));
    order.dedup_by_key(|i| key(*i));
    order.sort_unstable();
    let p: Vec<DVec3> = order.iter().map(|&i| points[i as usize]).collect();
    let n = p.len();
    if n < 4 {
        return Err(MeshError::InvalidArgument(format!("convex_hull: {n} distinct points; a hull with volume needs at least 4")));
    }
    // initial tetrahedron from extreme points, each choice checked exactly
    let i0 = (0..n).min_by(|&a, &b| p[a].to_array().partial_cmp(&p[b].to_array()).unwrap()).unwrap();
    let i1 = (0..n).max_by(|&a, &b| (p[a] - p[i0]).length_squared().total_cmp(&(p[b] - p[i0]).length_squared())).unwrap();
    let area = |k: usize| (p[i1] - p[i0]).cross(p[k] - p[i0]).length_squared();
    let i2 = (0..n).max_by(|&a, &b| area(a).total_cmp(&area(b))).unwrap();
    let collinear = |k: usize| {
        let pr = |q: DVec3, ax: usize| match ax {
            0 => robust::Coord { x: q.y, y: q.z },
            1 => robust::Coord { x: q.z, y: q.x },
            _ => robust::Coord { x: q.x, y: q.y },
        };
        (0..3).all(|ax| robust::orient2d(pr(p[i0], ax), pr(p[i1], ax), pr(p[k], ax)) == 0.0)
    };
    let i2 = if collinear(i2) { (0..n).find(|&k| !collinear(k)) } else { Some(i2) };
    let Some(i2) = i2 else {
        return Err(MeshError::Precondition("convex_hull: all points lie on one line; the hull has no volume".into()));
    };
    let vol = |k: usize| side(p[i0], p[i1], p[i2], p[k]);
    let i3 = (0..n).max_by(|&a, &b| vol(a).abs().total_cmp(&vol(b).abs())).unwrap();
    if vol(i3) == 0.0 {
        return Err(MeshError::Precondition("convex_hull: all points lie in one plane; the hull has no volume".into()));
    }
    let (i1, i2) = if vol(i3) > 0.0 { (i2, i1) } else { (i1, i2) }; // i3 behind (i0, i1, i2)
    let mut h = Hull { p: &p, tris: Vec::new() };
    let (a, b, c, d) = (i0 as u32, i1 as u32, i2 as u32, i3 as u32);
    let t0 = h.add([a, b, c]);
    let t1 = h.add([a, d, b]);
    let t2 = h.add([b, d, c]);
    let t3 = h.add([c, d, a]);
    h.tris[t0 as usize].nb = [t1, t2, t3];
    h.tris[t1 as usize].nb = [t3, t2, t0];
    h.tris[t2 as usize].nb = [t1, t3, t0];
    h.tris[t3 as usize].nb = [t2, t1, t0];
    for q in 0..n as u32 {
        if [a, b, c, d].contains(&q) {
            continue;
        }
        if let Some(t) = (0..4).find(|&t| h.sees(t, q)) {
            h.tris[t].outside.push(q);
        }
    }
    let mut stack: Vec<u32> = (0..4).filter(|&t| !h.tris[t as usize].outside.is_empty()).collect();
    let mut start_of = vec![u32::MAX; n];
    let mut visible_mark: Vec<bool> = Vec::new();
    while let Some(t) = stack.pop() {
        let t = t as usize;
        if !h.tris[t].alive || h.tris[t].outside.is_empty() {
            continue;
        }
        crate::cancel::check()?;
        let q = *h.tris[t].outside.iter().max_by(|&&x, &&y| h.height(t, x).total_cmp(&h.height(t, y))).unwrap();
        // visible region by BFS from t
        visible_mark.resize(h.tris.len(), false);
        let mut visible = vec![t as u32];
        visible_mark[t] = true;
        let mut k = 0;
        while k < visible.len() {
            let f = visible[k] as usize;
            k += 1;
            for j in 0..3 {
                let g = h.tris[f].nb[j] as usize;
                if !visible_mark[g] && h.sees(g, q) {
                    visible_mark[g] = true;
                    visible.push(g as u32);
                }
            }
        }
        // horizon: sides of visible triangles against invisible ones
        let mut horizon = Vec::new();
        for &f in &visible {
            for j in 0..3 {
                let g = h.tris[f as usize].nb[j];
                if !visible_mark[g as usize] {
                    let v = h.tris[f as usize].v;
                    horizon.push((v[j], v[(j + 1) % 3], g));
                }
            }
        }
        let mut new = Vec::with_capacity(horizon.len());
        for &(u, w, g) in &horizon {
            let nt = h.add([u, w, q]);
            h.tris[nt as usize].nb[0] = g;
            let gj = (0..3).find(|&j| h.tris[g as usize].v[j] == w && h.tris[g as usize].v[(j + 1) % 3] == u).unwrap();
            h.tris[g as usize].nb[gj] = nt;
            if start_of[u as usize] != u32::MAX {
                return Err(MeshError::Invariant("convex_hull: a degenerate configuration split the visible region".into()));
            }
            start_of[u as usize] = nt;
            new.push(nt);
        }
        for &nt in &new {
            let [u, w, _] = h.tris[nt as usize].v;
            let next = start_of[w as usize];
            h.tris[nt as usize].nb[1] = next;
            h.tris[next as usize].nb[2] = nt;
            let _ = u;
        }
        for &(u, _, _) in &horizon {
            start_of[u as usize] = u32::MAX;
        }
        // orphaned points go to the first new triangle that sees them
        let mut orphans = Vec::new();
        for &f in &visible {
            h.tris[f as usize].alive = false;
            orphans.append(&mut h.tris[f as usize].outside);
        }
        visible_mark.resize(h.tris.len(), false);
        for &f in &visible {
            visible_mark[f as usize] = false;
        }
        for o in orphans {
            if o == q {
                continue;
            }
            if let Some(&nt) = new.iter().find(|&&nt| h.sees(nt as usize, o)) {
                h.tris[nt as usize].outside.push(o);
            }
        }
        stack.extend(new.iter().copied().filter(|&nt| !h.tris[nt as usize].outside.is_empty()));
    }
    // merge coplanar neighbours into polygons
    let alive: Vec<usize> = (0..h.tris.len()).filter(|&t| h.tris[t].alive).collect();
    let mut slot = vec![u32::MAX; h.tris.len()];
    for (k, &t) in alive.iter().enumerate() {
        slot[t] = k as u32;
    }
    let extent = p.iter().fold((p[0], p[0]), |(lo, hi), q| (lo.min(*q), hi.max(*q)));
    let tol = 1e-9 * (extent.1 - extent.0).length();
    let mut uf: Vec<u32> = (0..alive.len() as u32).collect();
    let corners = |t: usize| h.tris[t].v.map(|i| p[i as usize]);
    // distance of `q` from the plane of triangle `t` (rounded normal)
    let dist = |t: usize, q: DVec3| {
        let [a, b, c] = corners(t);
        (b - a).cross(c - a).normalize_or_zero().dot(q - a).abs()
    };
    // the corner of `g` not on `t` (they share a side)
    let far = |t: usize, g: usize| h.tris[g].v.iter().copied().find(|&x| !h.tris[t].v.contains(&x)).unwrap();
    // a needle (a point added within rounding of a side, such as an edge's
    // midpoint): its own plane is rounding noise
    let needle = |t: usize| {
        let [a, b, c] = corners(t);
        let l2 = (b - a).length_squared().max((c - b).length_squared()).max((a - c).length_squared());
        (b - a).cross(c - a).length() <= 1e-4 * l2
    };
    // needles joined to a neighbour in exactly one plane
    let mut exact = vec![false; h.tris.len()];
    for &t in &alive {
        let [a, b, c] = corners(t);
        for j in 0..3 {
            let g = h.tris[t].nb[j] as usize;
            if g > t && side(a, b, c, p[far(t, g) as usize]) == 0.0 {
                union(&mut uf, slot[t], slot[g]);
                (exact[t], exact[g]) = (true, true);
            }
        }
    }
    for &t in &alive {
        if needle(t) {
            continue;
        }
        for j in 0..3 {
            let g = h.tris[t].nb[j] as usize;
            // (pairs already joined, the exactly coplanar ones among them, are done)
            if g > t && !needle(g) && root(&mut uf, slot[t]) != root(&mut uf, slot[g]) {
                // within the rounding of coordinates such as the
                // dodecahedron's (golden-ratio) pentagons, seen from both
                // triangles: a sliver (a point added just outside a face's
                // side) lies within the tolerance of its steep neighbour's
                // plane while that neighbour's far corner is far from the
                // sliver's, and a one-sided test glued such neighbours into
                // pinched polygons that do not close
                if dist(t, p[far(t, g) as usize]).max(dist(g, p[far(g, t) as usize])) <= tol {
                    union(&mut uf, slot[t], slot[g]);
                }
            }
        }
    }
    // a needle in no exact plane with a neighbour joins the one neighbour
    // whose plane its far corner lies nearest (within the tolerance), so it
    // neither stays a face of its own (a two-gon once its middle corner
    // goes) nor bridges two faces
    for &t in &alive {
        if !needle(t) || exact[t] {
            continue;
        }
        let best = (0..3)
            .map(|j| h.tris[t].nb[j] as usize)
            .filter(|&g| !needle(g))
            .map(|g| (dist(g, p[far(g, t) as usize]), g))
            .min_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((_, g)) = best.filter(|b| b.0 <= tol) {
            union(&mut uf, slot[t], slot[g]);
        }
    }
    // boundary sides per group, chained by their tail vertex
    let mut group_sides: rustc_hash::FxHashMap<(usize, u32), u32> = Default::default();
    let mut groups: Vec<usize> = Vec::new();
    for &t in &alive {
        let r = root(&mut uf, slot[t]) as usize;
        for j in 0..3 {
            let g = h.tris[t].nb[j] as usize;
            if root(&mut uf, slot[g]) as usize != r {
                let v = h.tris[t].v;
                group_sides.insert((r, v[j]), v[(j + 1) % 3]);
            }
        }
        groups.push(r);
    }
    groups.sort_unstable();
    groups.dedup();
    // near-degenerate points (clusters far apart, a sliver): the merging
    // tolerance can fold the whole hull into two or three polygons, which
    // bound no volume
    if groups.len() < 4 {
        return Err(MeshError::Precondition(format!(
            "convex_hull: merging coplanar triangles (within {tol:e}, 1e-9 of the points' extent) leaves {} polygons, \
             too few to bound a volume: the points are nearly coplanar, or form clusters far smaller than their spread, \
             beyond the hull's precision",
            groups.len()
        )));
    }
    let mut first_side: rustc_hash::FxHashMap<usize, u32> = Default::default();
    for (&(r, u), _) in &group_sides {
        first_side.entry(r).and_modify(|x| *x = (*x).min(u)).or_insert(u);
    }
    let mut used = vec![u32::MAX; n];
    let mut pos = Vec::new();
    let mut source = Vec::new();
    let mut sizes = Vec::new();
    let mut idx = Vec::new();
    for r in groups {
        let Some(&s) = first_side.get(&r) else {
            return Err(MeshError::Precondition("convex_hull: a merged face has no sides (the points are too nearly coplanar for the hull's precision)".into()));
        };
        let mut u = s;
        let mut size = 0i64;
        loop {
            if used[u as usize] == u32::MAX {
                used[u as usize] = pos.len() as u32;
                pos.push(p[u as usize]);
                source.push(order[u as usize] as usize);
            }
            idx.push(used[u as usize] as i64);
            size += 1;
            // a merged face whose sides do not chain (coplanar merging gone
            // inconsistent at extreme coordinates) is an error, not a panic
            u = *group_sides
                .get(&(r, u))
                .ok_or_else(|| MeshError::InvalidArgument("convex_hull: a merged face does not close (points too far apart or nearly coplanar for the hull's precision)".into()))?;
            if u == s {
                break;
            }
            if size > n as i64 {
                return Err(MeshError::Invariant("convex_hull: a merged face does not close".into()));
            }
        }
        sizes.push(size);
    }
    let m = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default())?;
    // vertices in the middle of straight hull edges
    let keep: Vec<bool> = m.vertices().map(|v| m.valence(v) != 2).collect();
    if keep.iter().all(|&k| k) {
        return Ok((m, source));
    }
    let (m2, _) = m.remove_valence2_vertices()?;
    let source2 = source.iter().zip(&keep).filter(|(_, &k)| k).map(|(&s, _)| s).collect();
    Ok((m2, source2))
}

/// TopMod's dual convex hull (`createDualConvexHull`): the solid bounded by
/// the plane through every hull vertex normal to its averaged face normal.
/// TopMod peels these planes off the points' bounding box (widened by
/// 0.001); here the box is left out, so every face is one such plane (the
/// box would only cut corners that stick out of it). Computed exactly as
/// the polar of a hull: plane n·x = d about the vertex centroid c maps to
/// the point n / (d − n·c), and each face of those points' hull to a vertex.
pub fn dual_convex_hull(points: &[DVec3]) -> Result<Mesh> {
    let (hull, _) = convex_hull(points)?;
    let nv = hull.n_vertices();
    let c = hull.positions().iter().sum::<DVec3>() / nv as f64;
    let normals = hull.vertex_normals();
    let mut dual_pts = Vec::with_capacity(nv);
    for v in hull.vertices() {
        let nrm = normals[v.idx()];
        let d = nrm.dot(hull.position(v) - c);
        if !(d > 0.0) {
            return Err(MeshError::Precondition(format!("dual_convex_hull: the plane at hull vertex {} does not face away from the centroid", v.0)));
        }
        dual_pts.push(nrm / d);
    }
    let (q, _) = convex_hull(&dual_pts)?;
    // one vertex per face of q: the point whose polar is the face's plane
    let mut pos = Vec::with_capacity(q.n_faces());
    for f in q.faces() {
        let fp: Vec<DVec3> = q.face_vertices(f).map(|v| q.position(v)).collect();
        let nrm = q.face_newell(f).normalize();
        let h = nrm.dot(fp[0]);
        pos.push(c + nrm / h);
    }
    // one face per vertex of q: its faces around it
    let mut sizes = Vec::with_capacity(q.n_vertices());
    let mut idx = Vec::new();
    for v in q.vertices() {
        let start = q.vertex_halfedge(v).expect("hull vertex");
        let mut hh = start;
        let mut k = 0;
        loop {
            idx.push(q.face(hh).0 as i64);
            k += 1;
            hh = q.rotate(hh);
            if hh == start {
                break;
            }
        }
        sizes.push(k);
    }
    let m = Mesh::from_polygons(pos.clone(), &sizes, &idx, BuildOptions::default())?;
    if m.signed_volume() >= 0.0 {
        return Ok(m);
    }
    // the rotation ran the other way round: reverse every face
    let mut off = 0usize;
    for &s in &sizes {
        idx[off..off + s as usize].reverse();
        off += s as usize;
    }
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default())
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use super::*;
    use crate::primitives;

    #[test]
    fn hull_of_platonic_solids_is_the_solid() {
        for m in [primitives::cube(), primitives::dodecahedron(), primitives::icosahedron(), primitives::octahedron(), primitives::tetrahedron()] {
            let (h, src) = convex_hull(m.positions()).unwrap();
            assert_eq!(counts(&h), counts(&m));
            assert_eq!(h.face_size_histogram(), m.face_size_histogram());
            assert!(h.signed_volume() > 0.0);
            assert_eq!(src.len(), m.n_vertices());
        }
    }

    #[test]
    fn grid_points_merge_into_six_squares() {
        let m = grid_cube(4);
        let mut pts = m.positions().to_vec();
        pts.push(DVec3::ZERO); // an interior point
        pts.push(pts[3]); // a duplicate
        let (h, _) = convex_hull(&pts).unwrap();
        assert_eq!(counts(&h), (8, 12, 6, 1, 0));
        let d = dual_convex_hull(&pts).unwrap();
        assert_eq!(counts(&d), (6, 12, 8, 1, 0));
        assert!(convex_hull(&pts[..3]).is_err());
        let flat: Vec<DVec3> = (0..10).map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0)).collect();
        assert!(convex_hull(&flat).unwrap_err().to_string().contains("one plane"));
    }

    /// Points on two circles (a cylinder's rims, a prism's caps): every
    /// point lies in a cap's plane, outside the cap built so far. Counting
    /// such points as seeing the whole cap re-fanned it per point (32,000
    /// points took 175 s); strict visibility adds one triangle per point.
    /// The hull is the prism: one quad per side, the two caps.
    #[test]
    fn cylinder_caps_are_two_faces() {
        for k in [5usize, 64, 3000] {
            let pts: Vec<DVec3> = (0..2 * k)
                .map(|i| {
                    let t = std::f64::consts::TAU * (i % k) as f64 / k as f64;
                    DVec3::new(t.cos(), t.sin(), (i / k) as f64)
                })
                .collect();
            let (h, _) = convex_hull(&pts).unwrap();
            h.validate().unwrap();
            let hist: Vec<(usize, usize)> = h.face_size_histogram().into_iter().map(|(a, b)| (a as usize, b as usize)).collect();
            assert_eq!(counts(&h).3, 1, "{k}");
            assert_eq!(hist, vec![(4, k), (k, 2)], "{k}");
        }
    }

    /// The hull's outputs are Qhull's on degenerate sets where a face used
    /// to be re-fanned: an integer lattice and points on three planes
    /// (faces counted by Qhull, coplanar facets merged, in the commit that
    /// made visibility strict): before it, extra faces and vertices that are
    /// not extreme, or a "degenerate configuration" error.
    #[test]
    fn lattice_points_give_only_extreme_vertices() {
        let mut s: u64 = 99;
        let mut r = |k: i64| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s % (2 * k as u64 + 1)) as i64 - k
        };
        for _ in 0..200 {
            let pts: Vec<DVec3> = (0..60).map(|_| DVec3::new(r(3) as f64, r(3) as f64, r(3) as f64)).collect();
            let Ok((h, src)) = convex_hull(&pts) else { continue };
            h.validate().unwrap();
            // every vertex extreme: not in the convex hull of the others,
            // i.e. some face plane through it has all other points strictly
            // inside or on it, and its faces meet at a corner (not a
            // straight edge or a flat spot)
            for f in h.faces() {
                let v: Vec<DVec3> = h.face_vertices(f).map(|v| h.position(v)).collect();
                assert!(v.len() >= 3);
                for q in &pts {
                    assert!(side(v[0], v[1], v[2], *q) <= 0.0, "a point outside a face");
                }
                // no three consecutive corners collinear (a vertex in the middle of a side)
                for i in 0..v.len() {
                    let (a, b, c) = (v[i], v[(i + 1) % v.len()], v[(i + 2) % v.len()]);
                    assert!((b - a).cross(c - b).length() > 0.0, "a straight corner");
                }
            }
            // neighbouring faces are not coplanar (merged into one)
            for e in 0..h.n_edges() {
                let (f, g) = (h.face(crate::HalfedgeId::new(2 * e)), h.face(crate::HalfedgeId::new(2 * e + 1)));
                let fv: Vec<DVec3> = h.face_vertices(f).map(|v| h.position(v)).collect();
                let coplanar = h.face_vertices(g).all(|v| side(fv[0], fv[1], fv[2], h.position(v)) == 0.0);
                assert!(!coplanar, "two coplanar faces left unmerged");
            }
            assert_eq!(src.len(), h.n_vertices());
        }
    }

    #[test]
    fn random_points() {
        let mut s: u64 = 12345;
        let mut r = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for n in [5, 20, 200, 2000] {
            let pts: Vec<DVec3> = (0..n).map(|_| DVec3::new(r(), r(), r())).collect();
            let (h, src) = convex_hull(&pts).unwrap();
            let (_, _, _, c, g) = counts(&h);
            assert_eq!((c, g), (1, 0));
            // every point inside or on every face plane
            for f in h.faces() {
                let v: Vec<DVec3> = h.face_vertices(f).map(|v| h.position(v)).collect();
                for q in &pts {
                    assert!(side(v[0], v[1], v[2], *q) <= 1e-12);
                }
            }
            for (k, &i) in src.iter().enumerate() {
                assert_eq!(pts[i], h.position(crate::VertexId::new(k)));
            }
        }
    }
}
