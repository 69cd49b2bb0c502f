//! The dual mesh, one level: a vertex at the centroid of every face, a face
//! around every vertex, an edge across every edge.
//!
//! The face of vertex v lists the centroids of the faces around v in
//! rotation order (counter-clockwise seen from outside), so orientation is
//! kept. A self-loop crosses into a dual edge between the centroids of its
//! two sides' faces; a one-gon becomes a valence-1 vertex, a valence-2 vertex
//! a two-gon, a point-sphere stays a point-sphere. Applying `dual` twice
//! gives back the input's connectivity (positions are the centroids of
//! centroids).
//!
//! Counts: V' = F, E' = E, F' = V. Output vertex f is the centroid of face f;
//! output face v is the one of vertex v.

use super::hosts::{check_output_size, face_centroids, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// The dual mesh. See the module docs.
pub fn dual(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("dual", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("dual", m.n_halfedges(), m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (next, _, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let mut pos = vec![DVec3::ZERO; nf];
    face_centroids(m, &fl, &mut pos);
    crate::cancel::check()?;
    let mut cv = vec![0u32; nh];
    let mut tw = vec![0u32; nh];
    let (pc, pt) = (super::hosts::SyncPtr(cv.as_mut_ptr()), super::hosts::SyncPtr(tw.as_mut_ptr()));
    (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let slot = vl.vidx[h] as usize;
        // side face(h) -> face(rotate h) crosses edge(prev h); its twin is the
        // side at next(rotate h) around the other end
        let r = prev[h] ^ 1;
        // SAFETY: vidx is a permutation of 0..nh.
        unsafe {
            *pc.get().add(slot) = face[h];
            *pt.get().add(slot) = vl.vidx[next[r as usize] as usize];
        }
    });
    crate::cancel::check()?;
    let sizes: Vec<u32> = (0..nv).map(|v| vl.valence(v)).collect();
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(dual, |_, (v, e, f)| (f, e, v), |name, m, r| {
            let ps = n_point_spheres(m);
            let mut want: Vec<usize> = m.vertices().filter(|&x| m.point_sphere_face(x).is_none()).map(|x| m.valence(x)).collect();
            want.sort();
            let mut got = face_sizes(r);
            got.truncate(r.n_faces() - ps);
            got.sort();
            assert_eq!(got, want, "{name}");
            let rr = dual(r).unwrap();
            assert_eq!(rr.face_size_histogram(), m.face_size_histogram(), "{name} dual of dual");
        });
    }

    #[test]
    fn cube_dual_is_octahedron() {
        let r = dual(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert!(r.signed_volume() > 0.0);
    }
}
