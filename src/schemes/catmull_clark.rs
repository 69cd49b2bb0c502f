//! Catmull-Clark subdivision (Catmull & Clark, "Recursively generated B-spline
//! surfaces on arbitrary topological meshes", CAD 10(6), 1978), one level.
//!
//! Masks (the original ones, as in OpenSubdiv's closed-surface rules):
//! * face point: the centroid of the face's corners;
//! * edge point: `(a + b + f₁ + f₂) / 4` (ends and the two adjacent face points);
//! * vertex point: `(Q + 2R + (n − 3) S) / n`, with `S` the old position, `n`
//!   its valence, `Q` the mean of the face points around it and `R` the mean
//!   of the midpoints of its edges, i.e. `(n − 2)/n · S + (Σ eⱼ + Σ fⱼ) / n²`.
//!
//! Every face of any size (one-gons and two-gons included) becomes n quads
//! `[v, e(h), f, e(prev h)]`, one per corner. All sums run over half-edges, so
//! a self-loop counts twice in its vertex's valence and its two sides get the
//! two face points of their own faces: a zero-length self-loop (Sierpinski
//! output) gets an edge point off the vertex and opens into a tube.
//!
//! Counts (H = 2E half-edges): V' = V + E + F, E' = 2E + H = 4E, F' = H.
//! Output vertices are laid out `[vertex points | edge points | face points]`.

use super::hosts::{check_output_size, face_centroids, primal_host, with_point_spheres, FaceLayout, MIN_LEN};
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// One level of Catmull-Clark subdivision. See the module docs.
pub fn catmull_clark(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("catmull_clark", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("catmull_clark", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, face) = m.halfedge_columns();
    let mut pos = vec![DVec3::ZERO; nv + ne + nf];
    let (vp, rest) = pos.split_at_mut(nv);
    let (ep, fp) = rest.split_at_mut(ne);
    face_centroids(m, &fl, fp);
    crate::cancel::check()?;
    let fp = &*fp;
    let p = &m.pos;
    rayon::join(
        || {
            ep.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, out)| {
                if crate::cancel::requested() {
                    return;
                }
                let (a, b) = (2 * e, 2 * e + 1);
                *out = (p[vert[a] as usize] + p[vert[b] as usize] + fp[face[a] as usize] + fp[face[b] as usize]) * 0.25;
            })
        },
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return;
                }
                let s = m.v_out[v];
                let mut h = s;
                let mut sum = DVec3::ZERO;
                let mut n = 0usize;
                loop {
                    sum += p[vert[(h ^ 1) as usize] as usize] + fp[face[h as usize] as usize];
                    n += 1;
                    h = m.he_prev[h as usize] ^ 1;
                    if h == s {
                        break;
                    }
                }
                let n = n as f64;
                *out = p[v] * ((n - 2.0) / n) + sum / (n * n);
            })
        },
    );
    crate::cancel::check()?;
    let face_point: Vec<u32> = (0..nf as u32).collect();
    primal_host(m, &fl, &face_point, pos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(catmull_clark, |_, (v, e, f)| (v + e + f, 4 * e, 2 * e), |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 4), "{name} quads");
        });
    }

    #[test]
    fn cube_vertex_point() {
        // the cube's corner (1,1,1): n = 3, Q = mean of three face centres,
        // R = mean of three edge midpoints
        let r = catmull_clark(&crate::primitives::cube()).unwrap();
        let q = DVec3::new(1.0, 1.0, 1.0) / 3.0;
        let rr = DVec3::new(2.0, 2.0, 2.0) / 3.0;
        let want = (q + 2.0 * rr) / 3.0;
        assert!(r.positions()[..8].iter().any(|p| (*p - want).length() < 1e-12));
    }

    #[test]
    fn self_loop_opens() {
        let m = cube_with_handle_loop();
        let r = catmull_clark(&m).unwrap();
        // the self-loop's edge point differs from its vertex's new point
        let e = m.edges().find(|&e| m.is_self_loop(e)).unwrap();
        let ep = r.positions()[m.n_vertices() + e.idx()];
        let v = m.vertex(e.halfedge()).idx();
        assert!((ep - r.positions()[v]).length() > 1e-3);
    }
}
