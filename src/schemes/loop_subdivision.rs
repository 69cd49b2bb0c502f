//! Loop subdivision (C. Loop, "Smooth subdivision surfaces based on
//! triangles", M.S. thesis, University of Utah, 1987), one level, extended to
//! polygon meshes.
//!
//! Masks: Loop's *original* weights (the ones trimesh, VTK and pymeshlab use;
//! libigl, Open3D and gpytoolbox use Warren's simplified β instead):
//! * vertex point: `(1 − nβ) v + β Σ neighbours`, with
//!   `β = (1/n) (5/8 − (3/8 + 1/4 cos(2π/n))²)` for valence n;
//! * edge point: `3/8 (a + b) + 1/8 (c + d)`, `c`, `d` the corners opposite
//!   the edge in its two triangles.
//!
//! Non-triangles ("extended Loop" of the Sierpinski paper, §6): every face
//! with n ≠ 3 corners (one-gons and two-gons included) is first fanned into n
//! triangles around a new vertex at its centroid
//! ([`super::hosts::fan_triangulate`]), then the Loop step above runs on the
//! all-triangle mesh; the centroid is an ordinary valence-n vertex there.
//! Meshes of triangles only skip the first step. Sums run over half-edges:
//! a self-loop counts twice in its vertex's valence.
//!
//! Counts on triangles: V' = V + E, E' = 2E + 3F, F' = 4F. With n-gons, apply
//! them to the fanned mesh: V + F_≠3 vertices, E + Σ_≠3 n edges, F_3 + Σ_≠3 n
//! triangles. Output vertices are `[vertex points | edge points]`.

use super::hosts::{check_output_size, fan_triangulate, primal_host, with_point_spheres, FaceLayout, MIN_LEN};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// One level of Loop subdivision; non-triangles are fanned around their
/// centroid first. See the module docs.
pub fn loop_subdivision(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("loop", m, |m| match fan_triangulate(m)? {
        Some(t) => step(&t),
        None => step(m),
    })
}

/// Loop's original β for valence `n`.
#[inline]
pub fn loop_beta(n: usize) -> f64 {
    let n = n as f64;
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
    (0.625 - c * c) / n
}

/// One Loop step on a mesh of triangles.
fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("loop", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let mut pos = vec![DVec3::ZERO; nv + ne];
    let (vp, ep) = pos.split_at_mut(nv);
    rayon::join(
        || {
            ep.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (a, b) = (2 * e, 2 * e + 1);
                let ab = p[vert[a] as usize] + p[vert[b] as usize];
                let cd = p[vert[prev[a] as usize] as usize] + p[vert[prev[b] as usize] as usize];
                *out = ab * 0.375 + cd * 0.125;
            })
        },
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (sum, n) = super::hosts::neighbor_sum(m, v);
                let beta = loop_beta(n);
                *out = p[v] * (1.0 - n as f64 * beta) + sum * beta;
            })
        },
    );
    crate::cancel::check()?;
    let face_point = vec![NONE; nf];
    primal_host(m, &fl, &face_point, pos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn beta_values() {
        assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-15);
        assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        // the counts on triangles, applied to the fanned mesh
        let counts = |m: &Mesh, (v, e, _): (usize, usize, usize)| {
            let f3 = face_sizes(m).iter().filter(|&&s| s == 3).count();
            let ngons: Vec<usize> = m
                .faces()
                .filter(|&f| m.point_sphere_face(m.face_vertices(f).next().unwrap()) != Some(f))
                .map(|f| m.face_degree(f))
                .filter(|&s| s != 3)
                .collect();
            let (v, e, f) = (v + ngons.len(), e + ngons.iter().sum::<usize>(), f3 + ngons.iter().sum::<usize>());
            (v + e, 2 * e + 3 * f, 4 * f)
        };
        check_on_corpus(loop_subdivision, counts, |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 3), "{name} triangles");
        });
    }

    #[test]
    fn regular_vertex_keeps_plane() {
        // a flat regular patch stays flat: the icosahedron's vertex points
        // stay on the symmetry axes
        let r = loop_subdivision(&crate::primitives::icosahedron()).unwrap();
        let m = crate::primitives::icosahedron();
        for v in 0..12 {
            let a = m.positions()[v].normalize();
            let b = r.positions()[v].normalize();
            assert!((a - b).length() < 1e-12);
        }
    }
}
