//! TopMod's object tools: planarize all faces, spherize, remove valence-2
//! vertices, clean up two-gons, split valence-2 vertices, subdivide all
//! edges. TopMod's source is the only description of these
//! (TopModLab/TopMod, `include/dlflaux/DLFLCast.cc`: `planarize`,
//! `spheralize`; `include/dlflcore/DLFLCore.cc`: `cleanupWingedVertices`,
//! `cleanup2gons`, `splitValence2Vertices`, `subdivideAllEdges`); where this
//! file departs from it, the function's docs say so.
//!
//! The topology-changing tools rebuild the mesh in one pass over its
//! corners (`Mesh::from_corner_twins`), so they are linear in the mesh size
//! whatever the number of elements they change.

use crate::error::{MeshError, Result};
use crate::mesh::{EdgeId, FaceStart, HalfedgeId, Mesh, VertexId};
use glam::{DMat3, DVec3};

/// What [`Mesh::planarize`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct Planarized {
    /// Iterations run (fewer than asked when the residual reached `tol`).
    pub iterations: usize,
    /// The residual before the first iteration.
    pub initial_residual: f64,
    /// The residual after the last one: the largest distance of a vertex to
    /// its face's least-squares plane, over all real faces.
    pub residual: f64,
}

/// Eigenvector of the smallest eigenvalue of a symmetric 3×3 matrix
/// (cyclic Jacobi rotations; 3×3 converges in a handful of sweeps).
fn smallest_eigenvector(m: DMat3) -> DVec3 {
    let mut a = m.to_cols_array_2d();
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off <= 1e-300 {
            break;
        }
        for (p, q) in [(0usize, 1usize), (0, 2), (1, 2)] {
            if a[p][q].abs() <= 1e-300 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let i = (0..3).min_by(|&i, &j| a[i][i].total_cmp(&a[j][j])).unwrap();
    DVec3::new(v[0][i], v[1][i], v[2][i])
}

impl Mesh {
    /// The least-squares plane of each face, as (centroid, unit normal);
    /// `None` for hole and point-sphere faces.
    fn best_fit_planes(&self) -> Vec<Option<(DVec3, DVec3)>> {
        self.faces()
            .map(|f| {
                if self.is_hole(f) || self.face_halfedge(f).is_none() {
                    return None;
                }
                let pts: Vec<DVec3> = self.face_vertices(f).map(|v| self.position(v)).collect();
                let c = pts.iter().sum::<DVec3>() / pts.len() as f64;
                let mut cov = DMat3::ZERO;
                for p in &pts {
                    let d = *p - c;
                    cov += DMat3::from_cols(d * d.x, d * d.y, d * d.z);
                }
                let n = smallest_eigenvector(cov);
                // orient as the face (the eigenvector's sign is arbitrary)
                let n = if n.dot(self.face_newell(f)) < 0.0 { -n } else { n };
                Some((c, n.normalize_or_zero()))
            })
            .collect()
    }

    /// The largest distance of a vertex to the least-squares plane of one
    /// of its (real) faces; 0 for a mesh of triangles.
    pub fn planarity_residual(&self) -> f64 {
        let planes = self.best_fit_planes();
        let mut r: f64 = 0.0;
        for h in self.halfedges() {
            if let Some((c, n)) = planes[self.face(h).idx()] {
                r = r.max(n.dot(self.position(self.vertex(h)) - c).abs());
            }
        }
        r
    }

    /// **Planarize all faces** (TopMod's `planarize`, DLFLCast.cc), made
    /// iterative: each iteration fits every face's least-squares plane, then
    /// moves every vertex to the mean of its projections onto the planes of
    /// its faces. Stops after `iterations` or once the residual
    /// ([`Mesh::planarity_residual`]) is at most `tol`. Topology is unchanged.
    ///
    /// TopMod projects each vertex 100 times with a decreasing step onto the
    /// planes of its faces (Newell normal, centroid), once, and reports nothing.
    pub fn planarize(&mut self, iterations: usize, tol: f64) -> Result<Planarized> {
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(MeshError::InvalidArgument(format!("planarize: tol = {} must be finite and >= 0", crate::error::num(tol))));
        }
        let initial_residual = self.planarity_residual();
        let mut residual = initial_residual;
        let mut done = 0;
        while done < iterations && residual > tol {
            crate::cancel::check()?;
            let planes = self.best_fit_planes();
            let mut sum = crate::mesh::zeroed_points(self.n_vertices());
            let mut cnt = vec![0u32; self.n_vertices()];
            for h in self.halfedges() {
                if let Some((c, n)) = planes[self.face(h).idx()] {
                    let v = self.vertex(h).idx();
                    let p = self.pos[v];
                    sum[v] += p - n * n.dot(p - c);
                    cnt[v] += 1;
                }
            }
            for v in 0..self.n_vertices() {
                if cnt[v] > 0 {
                    self.pos[v] = sum[v] / cnt[v] as f64;
                }
            }
            done += 1;
            residual = self.planarity_residual();
        }
        Ok(Planarized { iterations: done, initial_residual, residual })
    }

    /// **Spherize** (TopMod's `spheralize`, DLFLCast.cc): every vertex moved
    /// along the ray from `center` to the sphere of `radius` about it.
    /// Defaults: the vertex centroid and the mean distance to it (so the
    /// model keeps its place and size; TopMod puts the result on the unit
    /// sphere about the origin, which `center` = centroid and `radius` = 1
    /// followed by a translation gives). Topology is unchanged.
    ///
    /// Errors: a non-positive or non-finite radius; a vertex at the centre.
    pub fn spherize(&mut self, center: Option<DVec3>, radius: Option<f64>) -> Result<()> {
        let nv = self.n_vertices();
        if nv == 0 {
            return Ok(());
        }
        if crate::geometry::extreme_scale(&self.pos).is_some() {
            // coordinates at 1e±300: lengths and the mean overflow or
            // underflow; spherized at unit size (exact powers of two)
            if let Some(c) = center.filter(|c| !c.is_finite()) {
                return Err(MeshError::InvalidArgument(format!("spherize: center = {c} must be finite")));
            }
            if let Some(r) = radius.filter(|r| !(r.is_finite() && *r > 0.0)) {
                return Err(MeshError::InvalidArgument(format!("spherize: radius = {} must be finite and positive", crate::error::num(r))));
            }
            let out = crate::geometry::scale_free(self, |m, s| {
                let mut m = m.clone();
                m.spherize(center.map(|c| c / s), radius.map(|r| r / s))?;
                Ok(m)
            })?;
            self.pos = out.pos;
            return Ok(());
        }
        let c = center.unwrap_or_else(|| self.pos.iter().sum::<DVec3>() / nv as f64);
        if !c.is_finite() {
            return Err(MeshError::InvalidArgument("spherize: center must be finite".into()));
        }
        let r = radius.unwrap_or_else(|| self.pos.iter().map(|p| (*p - c).length()).sum::<f64>() / nv as f64);
        if !(r.is_finite() && r > 0.0) {
            return Err(MeshError::InvalidArgument(format!("spherize: radius = {} must be finite and positive", crate::error::num(r))));
        }
        if let Some(v) = self.pos.iter().position(|p| (*p - c).length() <= 1e-12 * r) {
            return Err(MeshError::Precondition(format!("spherize: vertex {v} lies at the centre; it has no direction")));
        }
        for p in self.pos.iter_mut() {
            *p = c + (*p - c).normalize() * r;
        }
        Ok(())
    }

    /// Face order of corners for a rebuild: per face its corners from the
    /// first, as half-edges (`None` for a point-sphere face, with its vertex).
    fn corner_layout(&self) -> (Vec<u32>, Vec<std::result::Result<HalfedgeId, VertexId>>) {
        let mut sizes = Vec::with_capacity(self.n_faces());
        let mut corners = Vec::with_capacity(self.n_halfedges() + 1);
        for f in self.faces() {
            match self.face_start(f) {
                FaceStart::Point(v) => {
                    sizes.push(1);
                    corners.push(Err(v));
                }
                FaceStart::Halfedge(_) => {
                    let before = corners.len();
                    corners.extend(self.face_halfedges(f).map(Ok));
                    sizes.push((corners.len() - before) as u32);
                }
            }
        }
        (sizes, corners)
    }

    /// The one-pass rebuild of the removal tools: the faces `keep_face`
    /// keeps, each with the corners `keep_corner` keeps (point-sphere faces
    /// whole), vertices renumbered by `vmap`, and each kept corner's twin the
    /// kept corner `twin_of` walks to; hole flags carried over.
    fn rebuild(
        &self,
        pos: Vec<DVec3>,
        keep_face: impl Fn(crate::FaceId) -> bool,
        keep_corner: impl Fn(HalfedgeId) -> bool,
        vmap: impl Fn(VertexId) -> u32,
        twin_of: impl Fn(HalfedgeId) -> HalfedgeId,
    ) -> Result<Mesh> {
        let (sizes0, layout) = self.corner_layout();
        let mut new_c = vec![u32::MAX; self.n_halfedges()];
        let (mut sizes, mut verts, mut holes) = (Vec::new(), Vec::new(), Vec::new());
        let mut i = 0;
        for (f, &d) in self.faces().zip(&sizes0) {
            let d = d as usize;
            if keep_face(f) {
                let start = verts.len();
                for c in &layout[i..i + d] {
                    match *c {
                        Err(v) => verts.push(vmap(v)),
                        Ok(h) if keep_corner(h) => {
                            new_c[h.idx()] = verts.len() as u32;
                            verts.push(vmap(self.vertex(h)));
                        }
                        Ok(_) => {}
                    }
                }
                sizes.push((verts.len() - start) as u32);
                holes.push(self.is_hole(f));
            }
            i += d;
        }
        let mut twin = vec![u32::MAX; verts.len()];
        for h in self.halfedges() {
            let c = new_c[h.idx()];
            if c != u32::MAX {
                twin[c as usize] = new_c[twin_of(h).idx()];
            }
        }
        let mut m = Mesh::from_corner_twins(pos, &sizes, &verts, &twin)?;
        m.f_hole = holes;
        Ok(m)
    }

    /// **Remove valence-2 vertices** (TopMod's `cleanupWingedVertices`): each
    /// vertex with exactly two edges goes, its two edges becoming one.
    /// Returns the new mesh and the number removed.
    ///
    /// Contract per removed vertex: V−1, E−1, F, genus and components
    /// unchanged; each face beside it loses a corner. Vertices on a
    /// self-loop and those whose removal would empty a face are kept (the
    /// two-gon sphere stays, as in TopMod). Removed in index order, a chain
    /// of them at once; survivors keep their order.
    pub fn remove_valence2_vertices(&self) -> Result<(Mesh, usize)> {
        let nv = self.n_vertices();
        let mut removed = vec![false; nv];
        let mut kept_in_face: Vec<usize> = self.faces().map(|f| self.face_degree(f)).collect();
        let mut count = 0;
        for v in self.vertices() {
            let Some(h1) = self.vertex_halfedge(v) else { continue };
            let h2 = self.rotate(h1);
            if self.rotate(h2) != h1 || h2 == h1 || h2 == h1.twin() {
                continue; // valence ≠ 2, or a self-loop
            }
            let (fa, fb) = (self.face(h1).idx(), self.face(h2).idx());
            let need = if fa == fb { 3 } else { 2 };
            if kept_in_face[fa] < need || kept_in_face[fb] < need {
                continue;
            }
            kept_in_face[fa] -= 1;
            kept_in_face[fb] -= 1;
            removed[v.idx()] = true;
            count += 1;
        }
        if count == 0 {
            return Ok((self.clone(), 0));
        }
        let mut new_v = vec![u32::MAX; nv];
        let mut pos = Vec::with_capacity(nv - count);
        for v in 0..nv {
            if !removed[v] {
                new_v[v] = pos.len() as u32;
                pos.push(self.pos[v]);
            }
        }
        let m = self.rebuild(
            pos,
            |_| true,
            |h| !removed[self.vertex(h).idx()],
            |v| new_v[v.idx()],
            // the kept corner at the head of this side's new span, in the other face
            |h| {
                let mut t = h.twin();
                while removed[self.vertex(t).idx()] {
                    t = self.prev(t);
                }
                t
            },
        )?;
        Ok((m, count))
    }

    /// **Clean up two-gons** (TopMod's `cleanup2gons`): every two-gon face
    /// goes, its two sides becoming one edge. Returns the new mesh and the
    /// number removed.
    ///
    /// Contract per removed two-gon: V, E−1, F−1, genus and components
    /// unchanged. A stack of two-gons between the same two vertices goes at
    /// once; a component made only of two-gons keeps two of them (the
    /// two-gon sphere), and a two-gon whose sides are one edge (a sphere of
    /// one edge and one face) is kept. Hole faces are never removed.
    pub fn cleanup_two_gons(&self) -> Result<(Mesh, usize)> {
        let nf = self.n_faces();
        let mut removed = vec![false; nf];
        for f in self.faces() {
            if self.is_hole(f) || self.face_degree(f) != 2 {
                continue;
            }
            let Some(h) = self.face_halfedge(f) else { continue };
            if self.next(h).twin() != h {
                removed[f.idx()] = true;
            }
        }
        // a closed ring of two-gons keeps two neighbours
        let mut seen = vec![false; nf];
        for f in self.faces() {
            if !removed[f.idx()] || seen[f.idx()] {
                continue;
            }
            let a = self.face_halfedge(f).unwrap();
            let mut h = a;
            let mut ring = false;
            loop {
                seen[self.face(h).idx()] = true;
                let t = h.twin();
                let g = self.face(t);
                if !removed[g.idx()] {
                    break;
                }
                if g == f {
                    ring = true;
                    break;
                }
                h = self.next(t);
            }
            if ring {
                removed[f.idx()] = false;
                removed[self.face(a.twin()).idx()] = false;
            } else {
                let mut h = self.next(a);
                loop {
                    let g = self.face(h.twin());
                    if !removed[g.idx()] || seen[g.idx()] {
                        break;
                    }
                    seen[g.idx()] = true;
                    h = self.next(h.twin());
                }
            }
        }
        let count = removed.iter().filter(|&&r| r).count();
        if count == 0 {
            return Ok((self.clone(), 0));
        }
        let m = self.rebuild(
            self.pos.clone(),
            |f| !removed[f.idx()],
            |_| true,
            |v| v.0,
            |h| {
                let mut t = h.twin();
                while removed[self.face(t).idx()] {
                    t = self.next(t).twin();
                }
                t
            },
        )?;
        Ok((m, count))
    }

    /// **Split valence-2 vertices** (TopMod's `splitValence2Vertices`): each
    /// vertex with two edges (not a self-loop) becomes two, by SubdivideEdge
    /// on its second edge, the pair set apart along the difference of the
    /// two edge directions: by `offset` each, or, when `offset` is `None`,
    /// by a tenth of each edge's length (TopMod's negative offset).
    /// Returns the number split.
    ///
    /// Contract per split vertex: V+1, E+1, F, genus unchanged. Vertices
    /// made by the split are not split again.
    pub fn split_valence2_vertices(&mut self, offset: Option<f64>) -> Result<usize> {
        if let Some(o) = offset {
            if !(o.is_finite() && o > 0.0) {
                return Err(MeshError::InvalidArgument(format!("split_valence2_vertices: offset = {} must be finite and positive", crate::error::num(o))));
            }
        }
        let todo: Vec<VertexId> = self
            .vertices()
            .filter(|&v| {
                self.vertex_halfedge(v).is_some_and(|h1| {
                    let h2 = self.rotate(h1);
                    self.rotate(h2) == h1 && h2 != h1 && h2 != h1.twin()
                })
            })
            .collect();
        for &v in &todo {
            let h1 = self.vertex_halfedge(v).expect("valence 2");
            let h2 = self.rotate(h1);
            let o = self.position(v);
            let (a, b) = (self.position(self.head(h1)), self.position(self.head(h2)));
            let (l1, l2) = ((a - o).length(), (b - o).length());
            let (d1, d2) = ((a - o).normalize_or_zero(), (b - o).normalize_or_zero());
            let mut dir = (d1 - d2).normalize_or_zero();
            if dir == DVec3::ZERO {
                dir = if d1 == DVec3::ZERO { DVec3::X } else { d1.any_orthonormal_vector() };
            }
            let e2: EdgeId = h2.edge();
            let s = self.subdivide_edge(e2, 0.5)?; // both ends placed below
            let (o1, o2) = match offset {
                Some(x) => (x, x),
                None => (0.1 * l1, 0.1 * l2),
            };
            self.set_position(v, o + o1 * dir);
            self.set_position(s.vertex, o - o2 * dir);
        }
        Ok(todo.len())
    }

    /// **Subdivide all edges** (TopMod's `subdivideAllEdges`): `n` new
    /// vertices on every edge, evenly spaced, in one pass. n = 1 puts one at
    /// each midpoint.
    ///
    /// Contract: V + nE, E(n+1), F unchanged, each face of size k becomes
    /// one of size k(n+1); genus and components unchanged. New vertex j
    /// (0-based) of edge e is vertex V + e·n + j, counted from the tail of
    /// the edge's half-edge 2e.
    pub fn subdivide_all_edges(&self, n: usize) -> Result<Mesh> {
        let (nv, ne) = (self.n_vertices(), self.n_edges());
        let total = nv as u64 + (ne as u64) * n as u64;
        if n == 0 || total > (1u64 << 31) - 1 {
            return Err(MeshError::InvalidArgument(format!(
                "subdivide_all_edges: n = {n} must be >= 1 and give fewer than 2**31 vertices ({total})"
            )));
        }
        let mut pos = Vec::with_capacity(total as usize);
        pos.extend_from_slice(&self.pos);
        for e in self.edges() {
            let h = e.halfedge();
            let (a, b) = (self.position(self.vertex(h)), self.position(self.head(h)));
            for j in 1..=n {
                pos.push(a.lerp(b, j as f64 / (n + 1) as f64));
            }
        }
        let k = n + 1;
        let (sizes0, layout) = self.corner_layout();
        let mut base = vec![0u32; self.n_halfedges()];
        let mut verts = Vec::with_capacity(self.n_halfedges() * k + 1);
        let mut sizes = Vec::with_capacity(sizes0.len());
        let mut i = 0;
        for &s in &sizes0 {
            let mut size = 0u32;
            for c in &layout[i..i + s as usize] {
                match *c {
                    Err(v) => {
                        verts.push(v.0);
                        size += 1;
                    }
                    Ok(h) => {
                        base[h.idx()] = verts.len() as u32;
                        verts.push(self.vertex(h).0);
                        let first = (nv + h.edge().idx() * n) as u32;
                        for j in 0..n {
                            let jj = if h.0 & 1 == 0 { j } else { n - 1 - j };
                            verts.push(first + jj as u32);
                        }
                        size += k as u32;
                    }
                }
            }
            sizes.push(size);
            i += s as usize;
        }
        let mut twin = vec![u32::MAX; verts.len()];
        for h in self.halfedges() {
            let (b, t) = (base[h.idx()], base[h.twin().idx()]);
            for j in 0..k as u32 {
                twin[(b + j) as usize] = t + (k as u32 - 1 - j);
            }
        }
        let mut m = Mesh::from_corner_twins(pos, &sizes, &verts, &twin)?;
        m.f_hole = self.f_hole.clone();
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::mesh::Mesh;
    use crate::primitives;

    #[test]
    fn subdivide_all_edges_counts() {
        for m in [primitives::cube(), primitives::torus(5, 4, 1.0, 0.3).unwrap(), loop_sphere(), digon_sphere()] {
            let (v, e, f, c, g) = counts(&m);
            for n in 1..4 {
                let s = m.subdivide_all_edges(n).unwrap();
                let n = n as i64;
                assert_eq!(counts(&s), (v + n * e, e * (n + 1), f, c, g));
            }
        }
    }

    #[test]
    fn valence2_round_trip() {
        let m = primitives::dodecahedron();
        let s = m.subdivide_all_edges(2).unwrap();
        let (r, k) = s.remove_valence2_vertices().unwrap();
        assert_eq!(k, 2 * m.n_edges());
        assert_eq!(counts(&r), counts(&m));
        for (p, q) in r.positions().iter().zip(m.positions()) {
            assert!((*p - *q).length() < 1e-12);
        }
        // the two-gon sphere is left alone, the loop sphere too
        assert_eq!(digon_sphere().remove_valence2_vertices().unwrap().1, 1);
        assert_eq!(loop_sphere().remove_valence2_vertices().unwrap().1, 0);
    }

    #[test]
    fn split_valence2() {
        let mut m = primitives::cube().subdivide_all_edges(1).unwrap();
        let (v, e, f, c, g) = counts(&m);
        let k = m.split_valence2_vertices(None).unwrap() as i64;
        assert_eq!(k, 12);
        assert_eq!(counts(&m), (v + k, e + k, f, c, g));
    }

    #[test]
    fn two_gons_cleaned() {
        let m = digon_sphere();
        let (r, k) = m.cleanup_two_gons().unwrap();
        assert_eq!((k, counts(&r)), (0, counts(&m)));
        // a cube with a two-gon stack on one edge: connect the same corners twice
        let mut c = primitives::cube();
        let before = counts(&c);
        let h = c.face_halfedge(crate::FaceId(0)).unwrap();
        let (a, b) = (crate::Corner::Halfedge(h), crate::Corner::Halfedge(c.next(h)));
        c.insert_edge(a, b).unwrap();
        c.insert_edge(crate::Corner::Halfedge(h), crate::Corner::Halfedge(c.next(h))).unwrap();
        let two = c.face_size_histogram().get(&2).copied().unwrap_or(0);
        assert_eq!(two, 2);
        let (r, k) = c.cleanup_two_gons().unwrap();
        assert_eq!(k, 2);
        assert_eq!(counts(&r), before);
    }

    #[test]
    fn planarize_reduces_residual() {
        let mut m = grid_cube(3);
        let mut s: u64 = 99;
        for p in m.positions_mut() {
            for k in 0..3 {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                p[k] += ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.1;
            }
        }
        let before = counts(&m);
        let mut prev = m.planarity_residual();
        assert!(prev > 1e-3);
        for _ in 0..5 {
            let r = m.planarize(5, 0.0).unwrap();
            assert!(r.residual < prev, "{} !< {prev}", r.residual);
            prev = r.residual;
        }
        assert_eq!(counts(&m), before);
        let mut t = primitives::octahedron();
        assert_eq!(t.planarize(10, 1e-12).unwrap().iterations, 0);
        assert_eq!(Mesh::new().planarity_residual(), 0.0);
    }

    #[test]
    fn spherize_puts_vertices_on_sphere() {
        let mut m = grid_cube(2);
        m.spherize(None, Some(2.0)).unwrap();
        let c = m.positions().iter().sum::<glam::DVec3>() / m.n_vertices() as f64;
        assert!(m.positions().iter().all(|p| ((*p - c).length() - 2.0).abs() < 1e-9 || c.length() > 1e-9));
        assert!(m.spherize(Some(m.position(crate::VertexId(0))), None).is_err());
    }
}
