//! Wireframe modelling (TopMod's `makeWireframe` and `makeWireframe2`,
//! `include/dlflaux/DLFLCrust.cc`, the only description): a modified
//! corner cutting of every face (`modifiedCornerCuttingSubdivide`,
//! DLFLSubdiv.cc) at `width`, an offset shell at `thickness`
//! (`createCrustForWireframe`) and a hole punched through every shrunken
//! face (`punchHoles`), leaving a tube of four sides along every edge,
//! joined at every vertex. TopMod's first variant uses the thickness as
//! the width too.
//!
//! Built in one pass, not by TopMod's sequence of operators: per corner
//! (v, f) of the input an outer vertex, inset into f at distance width/2
//! from both sides of the corner (TopMod's `x = sqrt(t² / (1 − cos²))`
//! along the sum of the side directions), and an inner vertex, thickness
//! below it along the averaged normal of v (TopMod's crust uses the
//! normal of the two neighbouring edge strips there instead).
//!
//! Counts for an input with V, E, F (H = 2E corners): V' = 2H = 4E,
//! E' = 10E, F' = 2V + 4E (per layer V vertex faces and E edge quads,
//! then one pipe quad per corner); χ' = 2V − 2E, so a connected input of
//! genus g gives genus E − V + 1 = 2g + F − 1 (the graph's cycle rank).

use crate::error::{MeshError, Result};
use crate::mesh::{Columns, HalfedgeId, Mesh};
use crate::schemes::face_vertex_columns::Out;
use crate::schemes::hosts::{VertexLayout, MIN_LEN};
use glam::DVec3;
use rayon::prelude::*;

impl Mesh {
    /// **Wireframe** of the mesh: a tube of four sides along every edge,
    /// strips `width` wide in each face and `thickness` deep (module docs).
    /// `width = None` uses the thickness (TopMod's first variant).
    ///
    /// Errors: non-positive or non-finite parameters; an open mesh; a
    /// point-sphere; a vertex whose averaged normal vanishes.
    pub fn wireframe(&self, thickness: f64, width: Option<f64>) -> Result<Mesh> {
        let width = width.unwrap_or(thickness);
        for (name, x) in [("thickness", thickness), ("width", width)] {
            if !(x.is_finite() && x > 0.0) {
                return Err(MeshError::InvalidArgument(format!("wireframe: {name} = {} must be finite and positive", crate::error::num(x))));
            }
        }
        // meshes at 1e±300 are framed at unit size, their lengths with them
        crate::geometry::scale_free(self, |m, s| m.wireframe_unscaled(thickness / s, width / s))
    }

    fn wireframe_unscaled(&self, thickness: f64, width: f64) -> Result<Mesh> {
        let pos = self.wireframe_points(thickness, width)?;
        crate::cancel::check()?;
        self.wireframe_columns_direct(pos)
    }

    /// Outer points o(h) = h and inner points i(h) = H + h (module docs),
    /// each corner independent of the others.
    fn wireframe_points(&self, thickness: f64, width: f64) -> Result<Vec<DVec3>> {
        self.refuse_open("wireframe", "a wireframe needs every edge between two faces")?;
        if let Some(f) = self.faces().find(|&f| self.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("wireframe: face {} is a point-sphere (no edges to frame)", f.0)));
        }
        let normals = self.vertex_normals();
        if let Some(v) = normals.iter().position(|n| *n == DVec3::ZERO) {
            return Err(MeshError::Precondition(format!("wireframe: vertex {v} has no averaged normal (its faces cancel)")));
        }
        let nh = self.n_halfedges();
        let centroids = self.face_centroids();
        let mut pos = crate::mesh::zeroed_points(2 * nh);
        let (outer, inner) = pos.split_at_mut(nh);
        outer.par_iter_mut().zip(inner.par_iter_mut()).with_min_len(MIN_LEN).enumerate().for_each(|(h, (po, pi))| {
            if crate::cancel::requested() {
                return; // the caller's check reports it
            }
            let h = HalfedgeId(h as u32);
            let v0 = self.position(self.vertex(h));
            let v1 = self.position(self.vertex(self.prev(h)));
            let v2 = self.position(self.head(h));
            let (n1, n2) = ((v1 - v0).normalize_or_zero(), (v2 - v0).normalize_or_zero());
            let t = width / 2.0;
            let c = n1.dot(n2);
            let p = if n1 == DVec3::ZERO || n2 == DVec3::ZERO || c <= -1.0 + 1e-12 || c >= 1.0 - 1e-12 {
                // a straight (or folded) corner: towards the centroid, as TopMod
                v0 + t * (centroids[self.face(h).idx()] - v0).normalize_or_zero()
            } else {
                v0 + (t / (1.0 - c * c).sqrt()) * (n1 + n2)
            };
            *po = p;
            *pi = p - thickness * normals[self.vertex(h).idx()];
        });
        Ok(pos)
    }

    /// The connectivity written straight into the columns (issue 16: the
    /// general builder was half of the tool's time), numbered exactly as
    /// `Mesh::from_corner_twins` numbered the faces `tests::reference` gives
    /// it (tested equal, and the Python outputs' hashes are unchanged).
    ///
    /// Faces, in order: outer vertex faces (v), outer edge quads (V + e),
    /// inner vertex faces (V + E + v), inner edge quads (2V + E + e), pipes
    /// (2V + 2E + x). An edge is numbered by its first corner, its half-edge
    /// there is 2k and the twin 2k + 1. The firsts, in corner order: every
    /// outer vertex-face side (edge `vidx(k)`, the rotation slot of k); two
    /// sides per outer quad (H + x for the side o(next x) → o(x)); every
    /// inner vertex-face side (the reversed face's corner order); two sides
    /// per inner quad (3H + (x ^ 1) for i(x) → i(next x)); and of the side
    /// pairs o(next x) ↔ i(next x) between two pipes, whichever pipe comes
    /// first (4H + a running count over the pipes).
    fn wireframe_columns_direct(&self, pos: Vec<DVec3>) -> Result<Mesh> {
        let (nv, ne, nh) = (self.n_vertices(), self.n_edges(), self.n_halfedges());
        let vl = VertexLayout::new(self)?;
        let (next, prev, vert) = (&self.he_next, &self.he_prev, &self.he_vert);
        let hh = nh as u32;
        // pipe x's side o(next x) → i(next x) is a first when x <= next x, its
        // side i(x) → o(x) when x < prev x; `run[x]` counts the firsts before pipe x
        let a = |x: usize| next[x] as usize >= x;
        let b = |x: usize| (prev[x] as usize) > x;
        let mut run = vec![0u32; nh];
        let mut acc = 0u32;
        for (x, r) in run.iter_mut().enumerate() {
            *r = acc;
            acc += a(x) as u32 + b(x) as u32;
        }
        debug_assert_eq!(acc as usize, nh);
        let rot = |k: usize| (prev[k] ^ 1) as usize;
        let unrot = |k: usize| next[k ^ 1] as usize;
        let vf0 = |k: usize| 2 * vl.vidx[k];
        let vf1 = |k: usize| {
            let v = vert[k] as usize;
            2 * (2 * hh + vl.off[v] + vl.off[v + 1] - 1 - vl.vidx[k])
        };
        let q0 = |x: usize| 2 * (hh + x as u32);
        let q1 = |x: usize| 2 * (3 * hh + (x as u32 ^ 1));
        let p1 = |x: usize| {
            let nx = next[x] as usize;
            if a(x) { 2 * (4 * hh + run[x]) } else { 2 * (4 * hh + run[nx] + a(nx) as u32) + 1 }
        };
        let p3 = |x: usize| {
            let px = prev[x] as usize;
            if b(x) { 2 * (4 * hh + run[x] + a(x) as u32) } else { 2 * (4 * hh + run[px]) + 1 }
        };
        let (nvu, neu) = (nv as u32, ne as u32);
        let nf = 2 * nv + 2 * ne + nh;
        let mut cols = Columns::unfilled(pos, 10 * nh, nf);
        {
            let out = Out::of(&mut cols);
            // SAFETY: the ids above are a bijection onto 0..10H, each written
            // once below as some corner's and as one corner's next
            let put = |i: u32, n: u32, v: u32, f: u32| unsafe { out.link(i, v, f, n) };
            (0..ne).into_par_iter().with_min_len(MIN_LEN / 2).for_each(|e| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (h, g) = (2 * e, 2 * e + 1);
                let (nh_, ng) = (next[h] as usize, next[g] as usize);
                let e32 = e as u32;
                // the two vertex-face sides and pipes of this edge's half-edges
                for x in [h, g] {
                    let v = vert[x];
                    let x32 = x as u32;
                    put(vf0(x), vf0(rot(x)), x32, v);
                    put(vf1(x), vf1(unrot(x)), hh + rot(x) as u32, nvu + neu + v);
                    let (nx, f) = (next[x] as usize, 2 * nvu + 2 * neu + x32);
                    put(q0(x) + 1, p1(x), x32, f);
                    put(p1(x), q1(x) + 1, nx as u32, f);
                    put(q1(x) + 1, p3(x), hh + nx as u32, f);
                    put(p3(x), q0(x) + 1, hh + x32, f);
                }
                // outer quad o(next h) → o(h) → o(next g) → o(g)
                let f = nvu + e32;
                put(q0(h), vf0(ng) + 1, nh_ as u32, f);
                put(vf0(ng) + 1, q0(g), h as u32, f);
                put(q0(g), vf0(nh_) + 1, ng as u32, f);
                put(vf0(nh_) + 1, q0(h), g as u32, f);
                // inner quad, reversed: i(next h) → i(g) → i(next g) → i(h)
                let f = 2 * nvu + neu + e32;
                put(vf1(nh_) + 1, q1(g), hh + nh_ as u32, f);
                put(q1(g), vf1(ng) + 1, hh + g as u32, f);
                put(vf1(ng) + 1, q1(h), hh + ng as u32, f);
                put(q1(h), vf1(nh_) + 1, hh + h as u32, f);
            });
        }
        crate::cancel::check()?;
        // SAFETY: not cancelled, and the ids are a bijection onto 0..10H
        unsafe { cols.assume_filled(10 * nh) };
        // each face starts at its first corner, each point at its first corner
        for v in 0..nv {
            cols.f_start[v] = 2 * vl.off[v];
            cols.f_start[nv + ne + v] = 2 * (2 * hh + vl.off[v]);
        }
        for e in 0..ne {
            cols.f_start[nv + e] = q0(2 * e);
            cols.f_start[2 * nv + ne + e] = vf1(next[2 * e] as usize) + 1;
        }
        for x in 0..nh {
            cols.f_start[2 * nv + 2 * ne + x] = q0(x) + 1;
            cols.v_out[x] = vf0(x);
            cols.v_out[nh + x] = vf1(unrot(x));
        }
        Mesh::from_columns(cols)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::primitives;

    /// The tool as it was built through the general `Builder`: the
    /// numbering the direct columns reproduce.
    fn reference(m: &crate::Mesh, thickness: f64, width: f64) -> crate::Mesh {
        use super::super::builder::{tag, Builder};
        use crate::mesh::HalfedgeId;
        let pos = m.wireframe_points(thickness, width).unwrap();
        let nh = m.n_halfedges();
        let mut b = Builder::with_positions(pos);
        let o = |h: HalfedgeId| h.0;
        let i = |h: HalfedgeId| nh as u32 + h.0;
        // classes of sides: 1 vertex face / edge quad, 2 edge quad / pipe,
        // 3 pipe / pipe; inner layer +4
        for layer in 0..2u64 {
            let at = |h: HalfedgeId| if layer == 0 { o(h) } else { i(h) };
            let cl = |c: u64| c + 4 * layer;
            for v in m.vertices() {
                let start = m.vertex_halfedge(v).unwrap();
                let (mut vs, mut ts) = (Vec::new(), Vec::new());
                let mut h = start;
                loop {
                    vs.push(at(h));
                    ts.push(tag(cl(1), h.idx()));
                    h = m.rotate(h);
                    if h == start {
                        break;
                    }
                }
                if layer == 0 { b.face(&vs, &ts) } else { b.face_reversed(&vs, &ts) }
            }
            for e in m.edges() {
                let h = e.halfedge();
                let g = h.twin();
                let (nh_, ng) = (m.next(h), m.next(g));
                let vs = [at(nh_), at(h), at(ng), at(g)];
                let ts = [tag(cl(2), h.idx()), tag(cl(1), ng.idx()), tag(cl(2), g.idx()), tag(cl(1), nh_.idx())];
                if layer == 0 { b.face(&vs, &ts) } else { b.face_reversed(&vs, &ts) }
            }
        }
        for x in m.halfedges() {
            let nx = m.next(x);
            b.face(&[o(x), o(nx), i(nx), i(x)], &[tag(2, x.idx()), tag(3, nx.idx()), tag(6, x.idx()), tag(3, x.idx())]);
        }
        b.build("wireframe").unwrap()
    }

    #[test]
    fn direct_columns_are_the_builders() {
        // every column and every position bit, on the corpus (self-loops,
        // two-gons, one-gons, non-convex faces, genus 3) and a torus
        let mut cases: Vec<(String, crate::Mesh)> = crate::schemes::hosts::test_meshes::corpus().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
        cases.push(("torus".into(), primitives::torus(12, 8, 3.0, 1.0).unwrap()));
        let mut checked = 0;
        for (name, m) in cases {
            // (the point-sphere has no edges, the Sierpinski output a vertex without averaged normal)
            let Ok(w) = m.wireframe(0.05, Some(0.1)) else { continue };
            let r = reference(&m, 0.05, 0.1);
            assert_eq!(w, r, "{name}");
            let bits = |x: &crate::Mesh| x.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&w), bits(&r), "{name}");
            w.validate().unwrap();
            checked += 1;
        }
        assert_eq!(checked, 11, "corpus meshes framed");
    }

    #[test]
    fn wireframe_counts_and_genus() {
        for m in [primitives::cube(), primitives::dodecahedron(), primitives::torus(6, 4, 1.0, 0.4).unwrap(), primitives::tetrahedron()] {
            let (v, e, f, _, g) = counts(&m);
            let w = m.wireframe(0.1, None).unwrap();
            assert_eq!(counts(&w), (4 * e, 10 * e, 2 * v + 4 * e, 1, e - v + 1));
            assert_eq!(e - v + 1, 2 * g + f - 1);
            let w2 = m.wireframe(0.05, Some(0.2)).unwrap();
            assert_eq!(counts(&w2), counts(&w));
        }
        assert!(primitives::cube().wireframe(0.0, None).is_err());
        assert!(primitives::cube().wireframe(0.1, Some(f64::NAN)).is_err());
    }
}
