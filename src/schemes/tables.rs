//! Numbering tables for the one-pass schemes: where every half-edge sits in
//! its face cycle and in its tail's rotation, as prefix offsets, so that the
//! corners of a new mesh can be addressed by index arithmetic.
//!
//! Built in O(E + F + V). Point-spheres have no half-edge: their face and
//! their vertex count zero corners here.

use crate::mesh::{FaceStart, Mesh, POINT};

/// Positions of half-edges in face cycles and vertex rotations.
pub(crate) struct Tables {
    /// `face_off[f]..face_off[f + 1]` are the corners of face `f` (prefix of
    /// face degrees; a point-sphere face has 0).
    pub face_off: Vec<u32>,
    /// Position of each half-edge in its face cycle, from the face's first corner.
    pub in_face: Vec<u32>,
    /// `vert_off[v]..vert_off[v + 1]` are the outgoing half-edges of `v`
    /// (prefix of valences; a point-sphere vertex has 0).
    pub vert_off: Vec<u32>,
    /// Position of each half-edge in its tail's rotation (`Mesh::rotate`
    /// order), from the vertex's first outgoing half-edge.
    pub in_vert: Vec<u32>,
}

impl Tables {
    pub fn new(m: &Mesh) -> Tables {
        let nh = m.n_halfedges();
        let (next, _, _) = m.halfedge_columns();
        let mut face_off = Vec::with_capacity(m.n_faces() + 1);
        let mut in_face = vec![0u32; nh];
        face_off.push(0u32);
        let mut acc = 0u32;
        for f in m.faces() {
            if let FaceStart::Halfedge(h0) = m.face_start(f) {
                let mut h = h0.0;
                let mut k = 0u32;
                loop {
                    in_face[h as usize] = k;
                    k += 1;
                    h = next[h as usize];
                    if h == h0.0 {
                        break;
                    }
                }
                acc += k;
            }
            face_off.push(acc);
        }
        let mut vert_off = Vec::with_capacity(m.n_vertices() + 1);
        let mut in_vert = vec![0u32; nh];
        vert_off.push(0u32);
        let mut acc = 0u32;
        for v in 0..m.n_vertices() {
            let o = m.v_out[v];
            if o & POINT == 0 {
                let mut h = o;
                let mut k = 0u32;
                loop {
                    in_vert[h as usize] = k;
                    k += 1;
                    h = m.he_prev[h as usize] ^ 1;
                    if h == o {
                        break;
                    }
                }
                acc += k;
            }
            vert_off.push(acc);
        }
        Tables { face_off, in_face, vert_off, in_vert }
    }

    /// Number of corners of face `f` (0 for a point-sphere face).
    #[inline]
    pub fn face_degree(&self, f: usize) -> u32 {
        self.face_off[f + 1] - self.face_off[f]
    }

    /// Number of outgoing half-edges of `v` (0 for a point-sphere vertex).
    #[inline]
    pub fn valence(&self, v: usize) -> u32 {
        self.vert_off[v + 1] - self.vert_off[v]
    }
}

/// Meshes and checks shared by the scheme tests.
#[cfg(test)]
pub(crate) mod test_support {
    use crate::mesh::{BuildOptions, Corner, FaceId, Mesh};
    use glam::DVec3;

    /// A cube whose faces 0 and 1 are merged by InsertEdge (genus 1): the
    /// merged face runs along both sides of the new edge.
    pub fn handle_cube() -> Mesh {
        let mut m = crate::primitives::cube();
        let a = m.face_halfedge(FaceId(0)).unwrap();
        let b = m.face_halfedge(FaceId(1)).unwrap();
        m.insert_edge(Corner::Halfedge(a), Corner::Halfedge(b)).unwrap();
        assert_eq!(m.genus(), 1);
        m
    }

    /// A prism over a counter-clockwise simple polygon (may be non-convex):
    /// planar faces, every vertex 3-valent.
    pub fn prism(profile: &[[f64; 2]], height: f64) -> Mesh {
        let n = profile.len() as i64;
        let mut pos: Vec<DVec3> = profile.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
        pos.extend(profile.iter().map(|p| DVec3::new(p[0], p[1], height)));
        let mut sizes = vec![n, n];
        let mut idx: Vec<i64> = (0..n).rev().collect();
        idx.extend(n..2 * n);
        for i in 0..n {
            let j = (i + 1) % n;
            sizes.push(4);
            idx.extend([i, j, n + j, n + i]);
        }
        Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
    }

    /// A five-pointed star prism (non-convex planar faces).
    pub fn star_prism() -> Mesh {
        let pts: Vec<[f64; 2]> = (0..10)
            .map(|k| {
                let r = if k % 2 == 0 { 1.0 } else { 0.4 };
                let a = std::f64::consts::PI * k as f64 / 5.0;
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        prism(&pts, 0.5)
    }

    pub fn counts(m: &Mesh) -> (usize, usize, usize) {
        (m.n_vertices(), m.n_edges(), m.n_faces())
    }

    /// A cube with a self-loop (a one-gon inside a quad, made by InsertEdge
    /// on one corner twice) and a two-gon (an edge doubling a cube edge).
    pub fn one_gon_two_gon_cube() -> Mesh {
        let mut m = crate::primitives::cube();
        let h = m.face_halfedge(FaceId(0)).unwrap();
        m.insert_edge(Corner::Halfedge(h), Corner::Halfedge(h)).unwrap();
        let g = m.face_halfedge(FaceId(3)).unwrap();
        let g2 = m.next(g);
        m.insert_edge(Corner::Halfedge(g), Corner::Halfedge(g2)).unwrap();
        m.validate().unwrap();
        assert_eq!(m.n_self_loops(), 1);
        let hist = m.face_size_histogram();
        assert_eq!(hist.get(&1), Some(&1));
        assert_eq!(hist.get(&2), Some(&1));
        m
    }
}
