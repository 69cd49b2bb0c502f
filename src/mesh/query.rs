//! Counts, topology (components, genus) and per-face geometry; χ and
//! boundaries are in `boundary.rs`.

use super::{FaceStart, Mesh};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// value -> how many elements have it, in increasing value order.
pub type Histogram = BTreeMap<usize, usize>;

impl Mesh {
    /// Component label per vertex (0..n_components), in order of first vertex.
    pub fn vertex_components(&self) -> (Vec<u32>, usize) {
        let nv = self.n_vertices();
        let mut parent: Vec<u32> = (0..nv as u32).collect();
        for e in 0..self.n_edges() {
            let (a, b) = (self.he_vert[2 * e], self.he_vert[2 * e + 1]);
            crate::union_find::union(&mut parent, a, b);
        }
        let mut label = vec![u32::MAX; nv];
        let mut n = 0u32;
        let mut out = vec![0u32; nv];
        for v in 0..nv {
            let r = crate::union_find::root(&mut parent, v as u32) as usize;
            if label[r] == u32::MAX {
                label[r] = n;
                n += 1;
            }
            out[v] = label[r];
        }
        (out, n as usize)
    }

    pub fn n_components(&self) -> usize {
        self.vertex_components().1
    }

    /// Genus of each component (in the order of [`Mesh::vertex_components`]).
    pub fn component_genera(&self) -> Vec<i64> {
        // the capped surface is closed and orientable: χ = 2 − 2g (the open
        // one has the same genus, χ = 2 − 2g − b)
        self.component_capped_euler_characteristics().into_iter().map(|c| (2 - c) / 2).collect()
    }

    /// Sum of the component genera: the genus of the 2-manifold (ch. II.1).
    pub fn genus(&self) -> i64 {
        // Σ (2 − χ_c)/2 = components − χ/2, no per-component pass needed
        self.n_components() as i64 - self.capped_euler_characteristic() / 2
    }

    pub fn n_self_loops(&self) -> usize {
        self.he_vert.chunks_exact(2).filter(|p| p[0] == p[1]).count()
    }

    /// Face sizes (point-sphere faces have size 1), holes included.
    pub fn face_size_histogram(&self) -> Histogram {
        let mut h = Histogram::new();
        for f in self.faces() {
            *h.entry(self.face_degree(f)).or_default() += 1;
        }
        h
    }

    /// Edge ends per vertex (a self-loop counts twice; point-spheres 0).
    pub fn valence_histogram(&self) -> Histogram {
        let mut deg = vec![0usize; self.n_vertices()];
        for &v in &self.he_vert {
            deg[v as usize] += 1;
        }
        let mut h = Histogram::new();
        for d in deg {
            *h.entry(d).or_default() += 1;
        }
        h
    }

    /// Average of each face's corner positions (repeats counted).
    pub fn face_centroids(&self) -> Vec<DVec3> {
        (0..self.n_faces() as u32)
            .into_par_iter()
            .map(|f| {
                let f = super::FaceId(f);
                match self.face_start(f) {
                    FaceStart::Point(v) => self.pos[v.idx()],
                    FaceStart::Halfedge(_) => {
                        let (s, n) = self
                            .face_halfedges(f)
                            .fold((DVec3::ZERO, 0usize), |(s, n), h| (s + self.pos[self.he_vert[h.idx()] as usize], n + 1));
                        s / n as f64
                    }
                }
            })
            .collect()
    }

    /// Newell's vector of a face: its direction is the face normal and its
    /// length twice the area of a planar face. Zero for point-spheres and
    /// degenerate faces.
    pub fn face_newell(&self, f: super::FaceId) -> DVec3 {
        let mut n = DVec3::ZERO;
        for h in self.face_halfedges(f) {
            let p = self.pos[self.vertex(h).idx()];
            let q = self.pos[self.head(h).idx()];
            n += p.cross(q);
        }
        n
    }

    /// Unit normals by Newell's method (zero vector for degenerate faces).
    pub fn face_normals(&self) -> Vec<DVec3> {
        (0..self.n_faces() as u32)
            .into_par_iter()
            .map(|f| self.face_unit_normal(super::FaceId(f)))
            .collect()
    }

    /// Unit Newell normal of face `f` (zero for a degenerate face), also
    /// for coordinates whose products overflow or underflow f64
    /// ([`crate::geometry::unit_newell`]).
    pub fn face_unit_normal(&self, f: super::FaceId) -> DVec3 {
        let n = self.face_newell(f);
        crate::geometry::unit_newell(n, || self.face_halfedges(f).map(|h| self.pos[self.vertex(h).idx()]))
    }

    /// Area-weighted vertex normals: the sum of the Newell vectors of the
    /// corners' faces, one term per corner, normalized. Hole faces are no
    /// faces of the surface and add nothing (a flat open patch's hole would
    /// otherwise turn its boundary normals over).
    pub fn vertex_normals(&self) -> Vec<DVec3> {
        let fnv: Vec<DVec3> = (0..self.n_faces() as u32)
            .into_par_iter()
            .map(|f| if self.f_hole[f as usize] { DVec3::ZERO } else { self.face_newell(super::FaceId(f)) })
            .collect();
        let mut vn = crate::mesh::zeroed_points(self.n_vertices());
        for (h, &v) in self.he_vert.iter().enumerate() {
            vn[v as usize] += fnv[self.he_face[h] as usize];
        }
        vn.into_iter().map(|n| n.normalize_or_zero()).collect()
    }

    /// Signed volume enclosed (divergence theorem over a fan of every face);
    /// positive for an outward-oriented closed mesh.
    pub fn signed_volume(&self) -> f64 {
        let mut vol = 0.0;
        for f in self.faces() {
            let mut it = self.face_halfedges(f).map(|h| self.pos[self.vertex(h).idx()]);
            let Some(p0) = it.next() else { continue };
            let mut prev = match it.next() {
                Some(p) => p,
                None => continue,
            };
            for p in it {
                vol += p0.dot(prev.cross(p));
                prev = p;
            }
        }
        vol / 6.0
    }
}
