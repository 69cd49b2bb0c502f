//! Column modelling (TopMod's *Column Modeling*, `makeWireframeWithColumns`
//! → `createWireframeWithSegments(obj, thickness, numSides)`,
//! `include/dlflaux/DLFLCrust.cc`; TopMod's source is the only
//! description): every edge becomes a column, a prism of `segments` sides
//! and radius `thickness`, and every vertex a joint closing the columns that
//! meet there. UI defaults thickness 0.25, segments 4 (range [4, 100]; 3 is
//! accepted here too).
//!
//! TopMod places, for each edge at each end v, a ring of `segments` points
//! on a circle of radius `thickness` about the edge, perpendicular to it at
//! distance L_v from v, takes the convex hull of all rings at v as the joint,
//! deletes the hull edges that do not bound a ring by a parity rule, and
//! joins the two rings of every edge with `connectFaces`. A hull can miss a
//! ring (a ring hidden by the others, a non-convex fan of edges): TopMod then
//! prints "something not matched" and leaves a broken joint. Here the joint
//! is combinatorial instead, built in one pass with the same rings:
//!
//! * Ring of the outgoing half-edge h at v (axis a = direction of h, up u =
//!   the mean normal of the edge's two faces made perpendicular to a, left
//!   l = u × a): point j at `v + L_v a + t (cos φ_j u + sin φ_j l)`, φ_j =
//!   2πj/n. Both rings of an edge share u, so every column is a right prism
//!   of n quads.
//! * L_v (TopMod's formula, over consecutive edges around v instead of all
//!   pairs): max of `t / tan(θ/2) + |cos θ| t + 0.001 t` over the angles θ
//!   between an edge and the next one around v; 0 at a valence-1 vertex
//!   (its ring is capped by an n-gon there).
//! * Joint of a vertex of valence k ≥ 2: between each edge h and the next
//!   one g around v (the corner of one face), a strip of m = ⌊n/2⌋ quads
//!   joins the left arc of h's ring (points 0 … m, top to bottom) to the
//!   right arc of g's ring (points n … n − m); a top cap through the k top
//!   points and a bottom cap through the k bottom points (2k bottom points
//!   for odd n) close it. A cap of two corners is left out, its two strip
//!   edges being one edge (a valence-2 vertex is a bent column).
//!
//! Counts (V₁, V₂, V₃ the vertices of valence 1, 2, ≥ 3; n = `segments`,
//! m = ⌊n/2⌋, ε = 1 for even n, 0 for odd):
//!
//! ```text
//! V' = 2nE
//! E' = 3nE + (m + 1)(2E − V₁) − (1 + ε) V₂
//! F' = nE + m (2E − V₁) + 2 V₃ + (1 − ε) V₂ + V₁
//! ```
//!
//! Face sizes: nE + m(2E − V₁) + (1 − ε)V₂ quads, per valence-k ≥ 3 vertex
//! a k-gon and a k-gon (even n) or 2k-gon (odd n), an n-gon per valence-1
//! vertex. χ' = 2V − 2E, so each component of genus g gives genus
//! E − V + 1 (the cycle rank of its edge graph), as `wireframe`.
//!
//! Refused with a `MeshError`: a self-loop or zero-length edge (no axis), a
//! point-sphere (no edge), and an edge too short for its two rings (L at
//! both ends reaching past each other; two edges along the same line, as the
//! sides of a flat two-gon, give an infinite L). Open meshes are accepted:
//! hole faces take no part in the up vectors.

use crate::error::{MeshError, Result};
use crate::mesh::{HalfedgeId, Mesh};
use crate::schemes::keyed::Out;
use glam::DVec3;

impl Mesh {
    /// **Column modelling** (module docs): a prism of `segments` sides and
    /// radius `thickness` along every edge, joined at every vertex.
    ///
    /// Errors: `thickness` not finite and positive, `segments` outside
    /// [3, 100], a self-loop, zero-length or too short edge, a point-sphere.
    pub fn wireframe_columns(&self, thickness: f64, segments: usize) -> Result<Mesh> {
        let t = thickness;
        if !(t.is_finite() && t > 0.0) {
            return Err(MeshError::InvalidArgument(format!("wireframe_columns: thickness = {t} must be finite and positive")));
        }
        if !(3..=100).contains(&segments) {
            return Err(MeshError::InvalidArgument(format!("wireframe_columns: segments = {segments} must be in [3, 100]")));
        }
        // meshes at 1e±300 are modelled at unit size, the radius with them
        crate::geometry::scale_free(self, |m, s| m.columns_unscaled(thickness / s, segments))
    }

    fn columns_unscaled(&self, thickness: f64, segments: usize) -> Result<Mesh> {
        let t = thickness;
        if let Some(f) = self.faces().find(|&f| self.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("wireframe_columns: face {} is a point-sphere (a vertex without edges has no column)", f.0)));
        }
        let (n, nh, ne) = (segments, self.n_halfedges(), self.n_edges());
        let m = n / 2;
        let even = n % 2 == 0;
        let dir = |h: HalfedgeId| self.position(self.head(h)) - self.position(self.vertex(h));
        // axes and the shared up vector of every edge
        let mut up = crate::mesh::zeroed_points(ne);
        for e in self.edges() {
            let h = e.halfedge();
            let d = dir(h);
            if self.vertex(h) == self.head(h) || d.length() == 0.0 {
                return Err(MeshError::Precondition(format!(
                    "wireframe_columns: edge {} is a {} (a column needs an axis)",
                    e.0,
                    if self.vertex(h) == self.head(h) { "self-loop" } else { "zero-length edge" }
                )));
            }
            let a = d.normalize();
            let mut nrm = DVec3::ZERO;
            for s in [h, h.twin()] {
                if !self.is_hole(self.face(s)) {
                    nrm += self.face_unit_normal(self.face(s));
                }
            }
            let u = (nrm - nrm.dot(a) * a).normalize_or_zero();
            up[e.idx()] = if u == DVec3::ZERO { a.any_orthonormal_vector() } else { u };
        }
        // ring distance of every vertex (TopMod's formula over consecutive edges)
        let mut dist = vec![0.0f64; self.n_vertices()];
        for h in self.halfedges() {
            let g = self.rotate(h);
            if g == h {
                continue;
            }
            let c = dir(h).normalize().dot(dir(g).normalize()).clamp(-1.0, 1.0);
            let theta = c.acos();
            let l = t / (theta / 2.0).tan() + c.abs() * t + 0.001 * t;
            let v = self.vertex(h).idx();
            dist[v] = dist[v].max(if l.is_finite() { l } else { f64::INFINITY });
        }
        for e in self.edges() {
            let h = e.halfedge();
            let (a, b) = (dist[self.vertex(h).idx()], dist[self.head(h).idx()]);
            let len = dir(h).length();
            if !(a + b < len) {
                return Err(MeshError::Precondition(format!(
                    "wireframe_columns: edge {} (length {len}) is too short for its rings ({a} and {b} from its ends at thickness {t}; an edge along another one has no room at all); use a smaller thickness",
                    e.0
                )));
            }
        }
        // ring points: n per outgoing half-edge, at n·h + j
        let step = std::f64::consts::TAU / n as f64;
        let mut pos = Vec::with_capacity(n * nh);
        for h in self.halfedges() {
            let e = h.edge().idx();
            let a = dir(h).normalize();
            let u = up[e];
            let l = u.cross(a);
            let c = self.position(self.vertex(h)) + dist[self.vertex(h).idx()] * a;
            for j in 0..n {
                let (s, co) = (step * j as f64).sin_cos();
                pos.push(c + t * (co * u + s * l));
            }
        }
        let (n32, m32) = (n as u32, m as u32);
        let r = |h: HalfedgeId, j: u32| n32 * h.0 + j % n32;
        // keys: column edge (e, j) joins R(2e, j) and R(2e+1, n − j); ring side
        // (h, j) runs R(h, j) → R(h, j+1); rung (h, k) joins R(h, k) and R(rot h, n − k)
        let col = |e: u32, j: u32| n32 * e + j % n32;
        let side = |h: HalfedgeId, j: u32| n32 * ne as u32 + n32 * h.0 + j % n32;
        let rung0 = |h: HalfedgeId, k: u32| n32 * (ne + nh) as u32 + (m32 + 1) * h.0 + k;
        // at a valence-2 vertex the two-corner caps are left out: the second
        // strip uses the first one's top (and, for even n, bottom) rung
        let rung = |h: HalfedgeId, k: u32| {
            let g = self.rotate(h);
            if g != h && self.rotate(g) == h && h.0 > g.0 && (k == 0 || (even && k == m32)) {
                rung0(g, k)
            } else {
                rung0(h, k)
            }
        };
        let n_keys = n * (ne + nh) + (m + 1) * nh;
        let mut o = Out::new(pos, n_keys, 2 * n * ne, 8 * n * ne);
        // columns
        for e in self.edges() {
            let (h, tw) = (e.halfedge(), e.halfedge().twin());
            let e = e.0;
            for j in 0..n32 {
                o.c(r(h, j), col(e, j));
                o.c(r(tw, n32 - j), side(tw, n32 - j - 1));
                o.c(r(tw, n32 - j - 1), col(e, j + 1));
                o.c(r(h, j + 1), side(h, j));
                o.end();
            }
        }
        // joints
        for v in self.vertices() {
            crate::cancel::poll(v.idx())?;
            let h0 = self.vertex_halfedge(v).expect("no point-spheres");
            if self.rotate(h0) == h0 {
                for j in 0..n32 {
                    o.c(r(h0, j), side(h0, j));
                }
                o.end();
                continue;
            }
            let mut k = 0;
            let mut h = h0;
            loop {
                let g = self.rotate(h);
                for q in 0..m32 {
                    o.c(r(h, q), side(h, q));
                    o.c(r(h, q + 1), rung(h, q + 1));
                    o.c(r(g, n32 - q - 1), side(g, n32 - q - 1));
                    o.c(r(g, n32 - q), rung(h, q));
                    o.end();
                }
                k += 1;
                h = g;
                if h == h0 {
                    break;
                }
            }
            if k > 2 {
                loop {
                    o.c(r(h, 0), rung(h, 0));
                    h = self.rotate(h);
                    if h == h0 {
                        break;
                    }
                }
                o.end();
            }
            if k > 2 || !even {
                // reverse rotation: pred(h) = next(twin h)
                loop {
                    let p = self.next(h.twin());
                    if even {
                        o.c(r(h, m32), rung(p, m32));
                    } else {
                        o.c(r(h, m32), side(h, m32));
                        o.c(r(h, m32 + 1), rung(p, m32));
                    }
                    h = p;
                    if h == h0 {
                        break;
                    }
                }
                o.end();
            }
        }
        o.finish("wireframe_columns")
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::primitives;
    use std::collections::BTreeMap;

    /// The module docs' counts and face sizes.
    fn want(m: &crate::Mesh, n: usize) -> ((i64, i64, i64), BTreeMap<usize, usize>) {
        let (e, mm) = (m.n_edges() as i64, (n / 2) as i64);
        let even = (n % 2 == 0) as i64;
        let (mut v1, mut v2, mut v3) = (0, 0, 0);
        let mut hist = BTreeMap::new();
        for v in m.vertices() {
            match m.valence(v) {
                1 => {
                    v1 += 1;
                    *hist.entry(n).or_insert(0) += 1;
                }
                2 => v2 += 1,
                k => {
                    v3 += 1;
                    *hist.entry(k).or_insert(0) += 1;
                    *hist.entry(if even == 1 { k } else { 2 * k }).or_insert(0) += 1;
                }
            }
        }
        let quads = n as i64 * e + mm * (2 * e - v1) + (1 - even) * v2;
        *hist.entry(4).or_insert(0) += quads as usize;
        let n = n as i64;
        ((2 * n * e, 3 * n * e + (mm + 1) * (2 * e - v1) - (1 + even) * v2, n * e + mm * (2 * e - v1) + 2 * v3 + (1 - even) * v2 + v1), hist)
    }

    #[test]
    fn counts_genus_and_sizes() {
        // valence 2 (a cube with split edges), valence 1 (a dangling edge), non-convex faces, genus 1
        let split = primitives::cube().subdivide_all_edges(1).unwrap();
        let mut dangling = primitives::cube();
        let h = dangling.face_halfedge(crate::FaceId(0)).unwrap();
        let (p, _) = dangling.create_vertex(glam::DVec3::new(-0.5, -0.3, -0.4)).unwrap();
        dangling.insert_edge(crate::Corner::Halfedge(h), crate::Corner::Point(p)).unwrap();
        use crate::schemes::hosts::test_meshes::{handle_cube, star_prism};
        for m in [primitives::cube(), primitives::tetrahedron(), primitives::dodecahedron(), primitives::torus(6, 4, 1.0, 0.4).unwrap(), primitives::genus_surface(3).unwrap(), split, dangling, grid_cube(2), star_prism(), handle_cube()] {
            let (v, e, _, comps, _) = counts(&m);
            for n in [3, 4, 5, 8] {
                let r = m.wireframe_columns(0.05, n).unwrap_or_else(|err| panic!("n={n}: {err}"));
                r.validate().unwrap();
                let ((wv, we, wf), hist) = want(&m, n);
                assert_eq!((counts(&r).0, counts(&r).1, counts(&r).2), (wv, we, wf), "n={n}");
                assert_eq!(counts(&r).3, comps);
                assert_eq!(counts(&r).4, e - v + comps, "genus, n={n}");
                assert_eq!(r.face_size_histogram(), hist, "n={n}");
                assert!(r.positions().iter().all(|p| p.is_finite()));
            }
        }
    }

    #[test]
    fn refusals() {
        let c = primitives::cube();
        assert!(c.wireframe_columns(0.0, 4).unwrap_err().to_string().contains("thickness"));
        assert!(c.wireframe_columns(0.1, 2).unwrap_err().to_string().contains("segments"));
        assert!(c.wireframe_columns(0.1, 101).unwrap_err().to_string().contains("segments"));
        assert!(c.wireframe_columns(1.5, 4).unwrap_err().to_string().contains("too short"));
        assert!(loop_sphere().wireframe_columns(0.1, 4).unwrap_err().to_string().contains("self-loop"));
        assert!(digon_sphere().wireframe_columns(0.1, 4).unwrap_err().to_string().contains("too short"));
    }
}
