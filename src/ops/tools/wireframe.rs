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

use super::builder::{tag, Builder};
use crate::error::{MeshError, Result};
use crate::mesh::{HalfedgeId, Mesh};
use glam::DVec3;

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
                return Err(MeshError::InvalidArgument(format!("wireframe: {name} = {x} must be finite and positive")));
            }
        }
        // meshes at 1e±300 are framed at unit size, their lengths with them
        crate::geometry::scale_free(self, |m, s| m.wireframe_unscaled(thickness / s, width / s))
    }

    fn wireframe_unscaled(&self, thickness: f64, width: f64) -> Result<Mesh> {
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
        for h in self.halfedges() {
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
            pos[h.idx()] = p;
            pos[nh + h.idx()] = p - thickness * normals[self.vertex(h).idx()];
        }
        let mut b = Builder::with_positions(pos);
        let o = |h: HalfedgeId| h.0;
        let i = |h: HalfedgeId| nh as u32 + h.0;
        // classes of sides: 1 vertex face / edge quad, 2 edge quad / pipe,
        // 3 pipe / pipe; inner layer +4
        for layer in 0..2u64 {
            let at = |h: HalfedgeId| if layer == 0 { o(h) } else { i(h) };
            let cl = |c: u64| c + 4 * layer;
            // vertex faces: o(h), o(rotate h), ...
            for v in self.vertices() {
                let start = self.vertex_halfedge(v).expect("no point-spheres");
                let mut vs = Vec::new();
                let mut ts = Vec::new();
                let mut h = start;
                loop {
                    vs.push(at(h));
                    ts.push(tag(cl(1), h.idx()));
                    h = self.rotate(h);
                    if h == start {
                        break;
                    }
                }
                if layer == 0 { b.face(&vs, &ts) } else { b.face_reversed(&vs, &ts) }
            }
            // edge quads: o(next h) → o(h) → o(next g) → o(g)
            for e in self.edges() {
                let h = e.halfedge();
                let g = h.twin();
                let (nh_, ng) = (self.next(h), self.next(g));
                let vs = [at(nh_), at(h), at(ng), at(g)];
                let ts = [tag(cl(2), h.idx()), tag(cl(1), ng.idx()), tag(cl(2), g.idx()), tag(cl(1), nh_.idx())];
                if layer == 0 { b.face(&vs, &ts) } else { b.face_reversed(&vs, &ts) }
            }
        }
        // pipes through the shrunken faces: o(x) → o(next x) → i(next x) → i(x)
        for x in self.halfedges() {
            let nx = self.next(x);
            b.face(&[o(x), o(nx), i(nx), i(x)], &[tag(2, x.idx()), tag(3, nx.idx()), tag(6, x.idx()), tag(3, x.idx())]);
        }
        b.build("wireframe")
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::primitives;

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
