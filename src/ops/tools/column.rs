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
//!   pairs, with a margin of 0.25 t instead of 0.001 t): max of
//!   `t / tan(θ/2) + |cos θ| t + 0.25 t` over the angles θ between an edge
//!   and the next one around v; 0 at a valence-1 vertex (its ring is capped
//!   by an n-gon there). At `t / tan(θ/2)` the facing points of the two
//!   rings coincide: with TopMod's margin they are 0.0014 t apart at right
//!   angles and the two strip quads meeting there fold over each other, a
//!   crossing at every vertex of a quad mesh with n = 4 (measured over 14
//!   inputs and n = 3..8: 9,408 crossing pairs with 0.001 t, 1,130 with
//!   0.25 t; docs/tools.md).
//! * Joint of a vertex of valence k ≥ 2: between each edge h and the next
//!   one g around v (the corner of one face), a strip of m = ⌊n/2⌋ quads
//!   joins the left arc of h's ring (points 0 … m, top to bottom) to the
//!   right arc of g's ring (points n … n − m); a top cap through the k top
//!   points and a bottom cap through the k bottom points close it. For odd
//!   n the bottom points are 2k and the bottom cap is a fan of 2k triangles
//!   around their mean, not a 2k-gon: at a saddle (the inner ring of a
//!   torus) that polygon is far from planar, and a triangulation of it
//!   crossed the strips (`torus(24, 12)` at n = 3: 285 crossing pairs, 0
//!   with the fan; over 14 inputs at n = 3, thickness 0.05 and 0.2 of the
//!   shortest edge, 642 → 72). A cap of two corners is left out, its two
//!   strip edges being one edge (a valence-2 vertex is a bent column).
//!
//! Counts (V₁, V₂, V₃ the vertices of valence 1, 2, ≥ 3; n = `segments`,
//! m = ⌊n/2⌋, ε = 1 for even n, 0 for odd):
//!
//! ```text
//! V' = 2nE + (1 − ε) V₃
//! E' = 3nE + (m + 1)(2E − V₁) − (1 + ε) V₂ + 2 (1 − ε) S₃
//! F' = nE + m (2E − V₁) + (1 + ε) V₃ + (1 − ε)(V₂ + 2 S₃) + V₁
//! ```
//!
//! with S₃ = 2E − V₁ − 2V₂ the valences summed over the valence-≥3
//! vertices. Face sizes: nE + m(2E − V₁) + (1 − ε)V₂ quads, per valence-k
//! ≥ 3 vertex a k-gon and a k-gon (even n) or a k-gon and 2k triangles
//! (odd n), an n-gon per valence-1 vertex. χ' = 2V − 2E, so each component of genus g gives genus
//! E − V + 1 (the cycle rank of its edge graph), as `wireframe`.
//!
//! Joints that still cross (strongly curved vertices) are moved out by
//! [`Mesh::wireframe_columns_checked`] (`column_repair.rs`), which the Python
//! call runs unless `check_crossings=False`.
//!
//! Refused with a `MeshError`: a self-loop or zero-length edge (no axis), a
//! point-sphere (no edge), and an edge too short for its two rings (L at
//! both ends reaching past each other; two edges along the same line, as the
//! sides of a flat two-gon, give an infinite L). Open meshes are accepted:
//! hole faces take no part in the up vectors.

use crate::error::{MeshError, Result};
use crate::mesh::{HalfedgeId, Mesh};
use crate::mesh::Columns;
use crate::schemes::face_vertex_columns::Out;
use crate::schemes::hosts::{SyncPtr, VertexLayout, MIN_LEN};
use glam::DVec3;
use rayon::prelude::*;

/// The ring distance's margin, in thicknesses (module docs: TopMod's is
/// 0.001, which at right angles leaves the strips' middle rung 0.0014 t long).
const MARGIN: f64 = 0.25;

impl Mesh {
    /// **Column modelling** (module docs): a prism of `segments` sides and
    /// radius `thickness` along every edge, joined at every vertex.
    ///
    /// Errors: `thickness` not finite and positive, `segments` outside
    /// [3, 100], a self-loop, zero-length or too short edge, a point-sphere.
    pub fn wireframe_columns(&self, thickness: f64, segments: usize) -> Result<Mesh> {
        let t = thickness;
        if !(t.is_finite() && t > 0.0) {
            return Err(MeshError::InvalidArgument(format!("wireframe_columns: thickness = {} must be finite and positive", crate::error::num(t))));
        }
        if !(3..=100).contains(&segments) {
            return Err(MeshError::InvalidArgument(format!("wireframe_columns: segments = {segments} must be in [3, 100]")));
        }
        // meshes at 1e±300 are modelled at unit size, the radius with them
        crate::geometry::scale_free(self, |m, s| m.columns_unscaled(thickness / s, segments, None))
    }

    /// [`Mesh::wireframe_columns`] with the ring distance of vertex v
    /// multiplied by `grow[v]` (`column_repair`; arguments checked there).
    pub(super) fn columns_grown(&self, thickness: f64, segments: usize, grow: &[f64]) -> Result<Mesh> {
        crate::geometry::scale_free(self, |m, s| m.columns_unscaled(thickness / s, segments, Some(grow)))
    }

    fn columns_unscaled(&self, thickness: f64, segments: usize, grow: Option<&[f64]>) -> Result<Mesh> {
        let t = thickness;
        if let Some(f) = self.faces().find(|&f| self.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("wireframe_columns: face {} is a point-sphere (a vertex without edges has no column)", f.0)));
        }
        let (n, nh, ne) = (segments, self.n_halfedges(), self.n_edges());
        let dir = |h: HalfedgeId| self.position(self.head(h)) - self.position(self.vertex(h));
        // axes and the shared up vector of every edge (the first bad edge
        // is the one reported)
        let bad = (0..ne).into_par_iter().with_min_len(MIN_LEN).position_first(|e| {
            let h = HalfedgeId(2 * e as u32);
            self.vertex(h) == self.head(h) || dir(h).length() == 0.0
        });
        if let Some(e) = bad {
            let h = HalfedgeId(2 * e as u32);
            return Err(MeshError::Precondition(format!(
                "wireframe_columns: edge {e} is a {} (a column needs an axis)",
                if self.vertex(h) == self.head(h) { "self-loop" } else { "zero-length edge" }
            )));
        }
        // (each face's normal once, not once per side)
        let normals: Vec<DVec3> = (0..self.n_faces() as u32).into_par_iter().with_min_len(MIN_LEN).map(|f| {
            let f = crate::mesh::FaceId(f);
            if self.is_hole(f) { DVec3::ZERO } else { self.face_unit_normal(f) }
        }).collect();
        let up: Vec<DVec3> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
            let h = HalfedgeId(2 * e as u32);
            let a = dir(h).normalize();
            let mut nrm = DVec3::ZERO;
            for s in [h, h.twin()] {
                if !self.is_hole(self.face(s)) {
                    nrm += normals[self.face(s).idx()];
                }
            }
            let u = (nrm - nrm.dot(a) * a).normalize_or_zero();
            if u == DVec3::ZERO { a.any_orthonormal_vector() } else { u }
        }).collect();
        drop(normals);
        // ring distance of every vertex (TopMod's formula over consecutive edges)
        let ls: Vec<f64> = (0..nh as u32).into_par_iter().with_min_len(MIN_LEN).map(|h| {
            let h = HalfedgeId(h);
            let g = self.rotate(h);
            if g == h {
                return 0.0;
            }
            let c = dir(h).normalize().dot(dir(g).normalize()).clamp(-1.0, 1.0);
            let theta = c.acos();
            let l = t / (theta / 2.0).tan() + c.abs() * t + MARGIN * t;
            if l.is_finite() { l } else { f64::INFINITY }
        }).collect();
        let mut dist = vec![0.0f64; self.n_vertices()];
        for (h, &l) in ls.iter().enumerate() {
            let v = self.he_vert[h] as usize;
            dist[v] = dist[v].max(l);
        }
        drop(ls);
        if let Some(g) = grow {
            for (d, &k) in dist.iter_mut().zip(g) {
                *d *= k;
            }
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
        // ring points: n per outgoing half-edge, at n·h + j (the angles'
        // sines and cosines once, the same bits as per point)
        let step = std::f64::consts::TAU / n as f64;
        let trig: Vec<(f64, f64)> = (0..n).map(|j| (step * j as f64).sin_cos()).collect();
        let mut pos = crate::mesh::zeroed_points(n * nh);
        pos.par_chunks_mut(n).with_min_len(MIN_LEN / n).enumerate().for_each(|(h, ring)| {
            let h = HalfedgeId(h as u32);
            let a = dir(h).normalize();
            let u = up[h.edge().idx()];
            let l = u.cross(a);
            let c = self.position(self.vertex(h)) + dist[self.vertex(h).idx()] * a;
            for (p, &(s, co)) in ring.iter_mut().zip(&trig) {
                *p = c + t * (co * u + s * l);
            }
        });
        crate::cancel::check()?;
        if n % 2 == 1 {
            // the centre of every odd bottom cap (valence ≥ 3): the mean of
            // its 2k points, in the cap's order (module docs)
            let m = (n / 2) as u32;
            let centres: Vec<DVec3> = (0..self.n_vertices()).into_par_iter().with_min_len(MIN_LEN / n).filter_map(|v| {
                let h0 = self.v_out[v];
                let k = self.valence(crate::mesh::VertexId(v as u32));
                if k < 3 {
                    return None;
                }
                let (mut x, mut sum) = (h0, DVec3::ZERO);
                for _ in 0..k {
                    sum += pos[(n as u32 * x + m) as usize] + pos[(n as u32 * x + m + 1) as usize];
                    x = self.he_next[(x ^ 1) as usize];
                }
                Some(sum / (2 * k) as f64)
            }).collect();
            pos.extend(centres);
        }
        self.columns_direct(pos, n)
    }

    /// The connectivity written straight into the columns (issue 16: the
    /// keyed builder was three quarters of the tool's time), numbered
    /// exactly as the keyed builder numbered `tests::reference`'s faces
    /// (tested equal; the Python outputs' hashes are unchanged).
    ///
    /// Faces: the n quads of every edge's column (n·e + j), then every
    /// vertex's joint (its strips corner by corner, its top cap, its bottom
    /// cap). Edges are numbered by their first corner (half-edge 2k there,
    /// 2k + 1 on the twin). Column e's 3n edges come first, at 3n·e +
    /// [`col_local`] / [`side_local`]: its n long edges and the 2n ring
    /// sides, which the joints meet second. Then every vertex's rungs, in
    /// the joint order: m + 1 per corner (rung k of corner i at (m + 1) i +
    /// [`rung_local`]); at a valence-2 vertex the second corner's top rung
    /// (and bottom rung, even n) is the first corner's, so it adds m − ε.
    fn columns_direct(&self, pos: Vec<DVec3>, n: usize) -> Result<Mesh> {
        let (nv, ne) = (self.n_vertices(), self.n_edges());
        let (n32, m32) = (n as u32, (n / 2) as u32);
        let even = n % 2 == 0;
        let vl = VertexLayout::new(self)?;
        let (next, prev) = (&self.he_next, &self.he_prev);
        let rot = |k: u32| prev[k as usize] ^ 1;
        let unrot = |k: u32| next[(k ^ 1) as usize];
        // joint edges and faces before each vertex's
        // (and, for odd n, the centre of each valence-≥3 vertex's bottom fan)
        let (mut jb, mut fb, mut cb) = (vec![0u32; nv + 1], vec![0u32; nv + 1], vec![0u32; nv + 1]);
        for v in 0..nv {
            let k = vl.valence(v);
            let (edges, faces) = match k {
                1 => (0, 1),
                2 => (2 * (m32 + 1) - 1 - even as u32, 2 * m32 + !even as u32),
                _ if even => (k * (m32 + 1), k * m32 + 2),
                // the bottom cap a fan of 2k triangles: 2k spokes
                _ => (k * (m32 + 1) + 2 * k, k * m32 + 1 + 2 * k),
            };
            jb[v + 1] = jb[v] + edges;
            fb[v + 1] = fb[v] + faces;
            cb[v + 1] = cb[v] + (!even && k >= 3) as u32;
        }
        let n_ring = (n * self.n_halfedges()) as u32;
        debug_assert_eq!(pos.len(), n_ring as usize + cb[nv] as usize);
        let col_edges = 3 * n32 * ne as u32;
        let (n_edges, nf) = (col_edges as usize + jb[nv] as usize, n * ne + fb[nv] as usize);
        let ring = |h: u32, j: u32| n32 * h + j % n32;
        // the ring side (x, j), R(x, j) → R(x, j + 1), is first met in its column
        let side_e = |x: u32, j: u32| {
            let e = x >> 1;
            3 * n32 * e + if x & 1 == 0 { side_local(n32, j % n32, true) } else { side_local(n32, n32 - 1 - j % n32, false) }
        };
        let col_e = |e: u32, j: u32| 3 * n32 * e + col_local(n32, j % n32);
        let mut cols = Columns::unfilled(pos, 2 * n_edges, nf);
        {
            let vop = SyncPtr(cols.v_out.as_mut_ptr());
            let out = Out::of(&mut cols);
            // face f of corners (point, half-edge), started at its first
            let face = |c: &[(u32, u32)], f: u32| {
                // SAFETY: the ids above are a bijection onto the half-edges,
                // each written once below as some corner's and as one
                // corner's next (both inside face f), and each face by the
                // one task writing it
                unsafe {
                    out.start(f, c[0].1);
                    for (i, &(v, h)) in c.iter().enumerate() {
                        out.link(h, v, f, c[(i + 1) % c.len()].1);
                    }
                }
            };
            let first_at = |p: u32, h: u32| {
                // SAFETY: each ring point's first corner is in one column
                unsafe { *vop.get().add(p as usize) = h }
            };
            (0..ne as u32).into_par_iter().with_min_len(MIN_LEN / n).for_each(|e| {
                if crate::cancel::requested() {
                    return; // the check after the loops reports it
                }
                let (h, tw) = (2 * e, 2 * e + 1);
                for j in 0..n32 {
                    // R(h, j) → R(tw, n − j) → R(tw, n − j − 1) → R(h, j + 1)
                    let c0 = if j == 0 { 2 * col_e(e, 0) } else { 2 * col_e(e, j) + 1 };
                    let c2 = if j + 1 < n32 { 2 * col_e(e, j + 1) } else { 2 * col_e(e, 0) + 1 };
                    let c = [(ring(h, j), c0), (ring(tw, n32 - j), 2 * side_e(tw, n32 - j - 1)), (ring(tw, n32 - j - 1), c2), (ring(h, j + 1), 2 * side_e(h, j))];
                    face(&c, n32 * e + j);
                    // each ring point's first corner: R(h, 0) and R(tw, 0) in
                    // quad 0, R(h, j + 1) at c3, R(tw, n − j − 1) at c2
                    if j == 0 {
                        first_at(ring(h, 0), c0);
                        first_at(ring(tw, 0), c[1].1);
                    }
                    if j + 1 < n32 {
                        first_at(ring(h, j + 1), c[3].1);
                        first_at(ring(tw, n32 - j - 1), c2);
                    }
                }
            });
            let nfc = n32 * ne as u32;
            (0..nv).into_par_iter().with_min_len(MIN_LEN / n).for_each(|v| {
                if crate::cancel::requested() {
                    return;
                }
                let k = vl.valence(v);
                let (jb, fb) = (col_edges + jb[v], nfc + fb[v]);
                let h0 = self.v_out[v];
                let side2 = |x: u32, j: u32| 2 * side_e(x, j) + 1;
                if k == 1 {
                    let c: Vec<(u32, u32)> = (0..n32).map(|j| (ring(h0, j), side2(h0, j))).collect();
                    face(&c, fb);
                    return;
                }
                // the edge of rung kp of corner i (at a valence-2 vertex the
                // second corner's top, and for even n bottom, rung is the first's)
                let rung = |i: u32, kp: u32| {
                    if k == 2 && i == 1 && (kp == 0 || (even && kp == m32)) {
                        jb + rung_local(kp)
                    } else if k == 2 && i == 1 {
                        jb + m32 + 1 + kp - 1
                    } else {
                        jb + (m32 + 1) * i + rung_local(kp)
                    }
                };
                let mut h = h0;
                for i in 0..k {
                    let g = rot(h);
                    for q in 0..m32 {
                        // R(h, q) → R(h, q + 1) → R(g, n − q − 1) → R(g, n − q)
                        let top_first = !(k == 2 && i == 1 && even && q + 1 == m32);
                        let c1 = 2 * rung(i, q + 1) + !top_first as u32;
                        let c3_first = q == 0 && !(k == 2 && i == 1);
                        let c3 = 2 * rung(i, q) + !c3_first as u32;
                        let c = [(ring(h, q), side2(h, q)), (ring(h, q + 1), c1), (ring(g, n32 - q - 1), side2(g, n32 - q - 1)), (ring(g, n32 - q), c3)];
                        face(&c, fb + m32 * i + q);
                    }
                    h = g;
                }
                let mut f = fb + k * m32;
                if k > 2 {
                    // the top cap, in rotation order
                    let c: Vec<(u32, u32)> = (0..k).scan(h0, |h, i| {
                        let x = *h;
                        *h = rot(x);
                        Some((ring(x, 0), 2 * rung(i, 0) + 1))
                    }).collect();
                    face(&c, f);
                    f += 1;
                }
                if k > 2 || !even {
                    // the bottom cap, against the rotation: corner i meets
                    // the bottom rung of corner i − 1 (odd n: a fan, below)
                    let mut c = Vec::with_capacity(2 * k as usize);
                    let mut x = h0;
                    for s in 0..k {
                        let i = (k - s) % k;
                        let ip = (i + k - 1) % k;
                        if even {
                            c.push((ring(x, m32), 2 * rung(ip, m32) + 1));
                        } else {
                            c.push((ring(x, m32), side2(x, m32)));
                            c.push((ring(x, m32 + 1), 2 * rung(ip, m32) + 1));
                        }
                        x = unrot(x);
                    }
                    if even || k == 2 {
                        face(&c, f);
                        return;
                    }
                    // odd n, valence ≥ 3: triangle i = p_i → p_{i+1} → centre.
                    // Spoke j (centre – p_j) is met first in triangle j − 1
                    // as p_j → centre (spoke 0: in triangle 0, centre → p_0),
                    // so it is edge rung_local(j) after the rungs
                    let (spk, centre, kk) = (jb + k * (m32 + 1), n_ring + cb[v], 2 * k);
                    let spoke = |j: u32| 2 * (spk + rung_local(j));
                    for i in 0..kk {
                        let j = (i + 1) % kk;
                        let to_centre = if j == 0 { spoke(0) + 1 } else { spoke(j) };
                        let from_centre = if i == 0 { spoke(0) } else { spoke(i) + 1 };
                        face(&[c[i as usize], (c[j as usize].0, to_centre), (centre, from_centre)], f + i);
                    }
                    first_at(centre, spoke(0));
                }
            });
        }
        crate::cancel::check()?;
        // SAFETY: not cancelled, and the ids are a bijection onto the
        // half-edges (`columns_direct`'s SAFETY notes)
        unsafe { cols.assume_filled(2 * n_edges) };
        Mesh::from_columns(cols)
    }
}

/// Where column e's long edge j (R(2e, j) – R(2e+1, n − j)) is first met
/// among the column's 3n edges: quad 0 meets long edges 0 and 1, quad j ≥ 1
/// long edge j + 1 as its third corner's side.
fn col_local(n: u32, j: u32) -> u32 {
    debug_assert!(j < n);
    match j {
        0 => 0,
        1 => 2,
        _ => 4 + 3 * (j - 2) + 1,
    }
}

/// Where the ring side of quad j is first met among the column's 3n edges:
/// the side of the half-edge 2e (`own`, the quad's fourth corner) or of its
/// twin (the second corner).
fn side_local(n: u32, j: u32, own: bool) -> u32 {
    debug_assert!(j < n);
    match (j, own) {
        (0, false) => 1,
        (0, true) => 3,
        (j, false) => 4 + 3 * (j - 1),
        (j, true) if j + 1 == n => 3 * n - 1,
        (j, true) => 4 + 3 * (j - 1) + 2,
    }
}

/// Where a corner's rung k is first met among its m + 1: the first strip
/// meets rung 1, then rung 0; strip q ≥ 1 meets rung q + 1.
fn rung_local(k: u32) -> u32 {
    match k {
        0 => 1,
        1 => 0,
        k => k,
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::primitives;
    use std::collections::BTreeMap;
    use super::reference::reference;

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
                    if even == 1 {
                        *hist.entry(k).or_insert(0) += 1;
                    } else {
                        *hist.entry(3).or_insert(0) += 2 * k;
                    }
                }
            }
        }
        let quads = n as i64 * e + mm * (2 * e - v1) + (1 - even) * v2;
        *hist.entry(4).or_insert(0) += quads as usize;
        let n = n as i64;
        let s3 = 2 * e - v1 - 2 * v2;
        let odd = 1 - even;
        ((2 * n * e + odd * v3, 3 * n * e + (mm + 1) * (2 * e - v1) - (1 + even) * v2 + 2 * odd * s3, n * e + mm * (2 * e - v1) + (1 + even) * v3 + odd * (v2 + 2 * s3) + v1), hist)
    }

    #[test]
    fn direct_columns_are_the_keyed_builders() {
        // every column and position bit: valence 1 and 2, odd and even n,
        // non-convex faces, genus 3, open meshes
        let split = primitives::cube().subdivide_all_edges(1).unwrap();
        let mut cases = vec![primitives::cube(), primitives::tetrahedron(), primitives::dodecahedron(), primitives::torus(6, 4, 1.0, 0.4).unwrap(), primitives::genus_surface(3).unwrap(), split, dangling_cube(), grid_cube(2), crate::schemes::hosts::test_meshes::star_prism(), crate::schemes::hosts::test_meshes::handle_cube()];
        cases.extend(crate::schemes::hosts::test_meshes::open_meshes().into_iter().map(|(_, m)| m));
        let mut built = 0;
        for (c, m) in cases.iter().enumerate() {
            for n in [3, 4, 5, 6, 8] {
                let Ok(a) = m.wireframe_columns(0.02, n) else { continue };
                let b = reference(m, 0.02, n);
                assert_eq!(a, b, "case {c}, n={n}");
                built += 1;
            }
        }
        assert!(built >= 50, "only {built} builds compared");
    }

    fn dangling_cube() -> crate::Mesh {
        let mut d = primitives::cube();
        let h = d.face_halfedge(crate::FaceId(0)).unwrap();
        let (p, _) = d.create_vertex(glam::DVec3::new(-0.5, -0.3, -0.4)).unwrap();
        d.insert_edge(crate::Corner::Halfedge(h), crate::Corner::Point(p)).unwrap();
        d
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
    fn right_angles_do_not_fold_the_strips() {
        // TopMod's margin (0.001 t) left one crossing pair at every vertex of
        // a quad torus with n = 4 (module docs); the margin of 0.25 t none,
        // and none on the genus-2 surface at n = 4..6 (104, 128, 260 before)
        let cross = |m: &crate::Mesh, t: f64, n: usize| {
            let out = m.wireframe_columns(t, n).unwrap();
            crate::geometry::crossing::crossings_of_new_faces(&crate::Mesh::new(), &out)
        };
        let torus = primitives::torus(24, 12, 1.0, 0.4).unwrap();
        let g2 = primitives::genus_surface(2).unwrap();
        let shortest = |m: &crate::Mesh| m.edges().map(|e| { let h = e.halfedge(); (m.position(m.head(h)) - m.position(m.vertex(h))).length() }).fold(f64::INFINITY, f64::min);
        // n = 3: the bottom caps are fans (the 8-gons crossed the strips at
        // the inner ring's saddles: 285 pairs at 0.05 and 0.2 of the shortest edge)
        for n in [3, 4, 5, 6, 8] {
            assert_eq!(cross(&torus, 0.1 * shortest(&torus), n), 0, "torus, n = {n}");
        }
        for n in [4, 5, 6] {
            assert_eq!(cross(&g2, 0.1 * shortest(&g2), n), 0, "genus 2, n = {n}");
        }
        // the rings of one vertex keep apart: their closest points (the
        // facing points of two columns) by a fraction of the thickness, not
        // by rounding (0.0014 t with TopMod's margin)
        let t = 0.1;
        let c = primitives::cube();
        let out = c.wireframe_columns(t, 4).unwrap();
        let mut closest = f64::INFINITY;
        for v in c.vertices() {
            let hs: Vec<usize> = c.vertex_halfedges(v).map(|h| h.idx()).collect();
            for (i, &a) in hs.iter().enumerate() {
                for &b in &hs[i + 1..] {
                    for (j, k) in (0..4).flat_map(|j| (0..4).map(move |k| (j, k))) {
                        closest = closest.min((out.positions()[4 * a + j] - out.positions()[4 * b + k]).length());
                    }
                }
            }
        }
        assert!(closest > 0.2 * t, "rings of one vertex {closest} apart at thickness {t}");
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

/// The keyed builder the direct column fill replaced, kept as the reference.
#[cfg(test)]
#[path = "column_reference.rs"]
mod reference;
