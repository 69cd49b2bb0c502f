//! √3 subdivision (L. Kobbelt, "√3-subdivision", SIGGRAPH 2000, §2–3), one
//! level, generalised to polygon faces.
//!
//! Every face gets a new vertex at its centroid (for a triangle
//! `(a + b + c)/3`, Kobbelt's rule), each old edge is flipped (it now joins
//! the centroids of its two faces) and the centroid is joined to every corner.
//! Old vertices are smoothed with Kobbelt's rule
//! `v' = (1 − αₙ) v + αₙ/n Σ neighbours`, `αₙ = (4 − 2 cos(2π/n))/9`, over the
//! n ends of the old edges at v (a self-loop counts twice).
//!
//! Polygon generalisation: an n-gon is handled exactly like a triangle —
//! centroid, spokes, flipped edges — so every old half-edge `h` (from `a`, in
//! face `f`, its twin in face `g`) gives one output triangle
//! `[a, c_g, c_f]`. On triangle meshes this is Kobbelt's scheme; two steps
//! give the usual 1-to-9 triadic split.
//!
//! Counts (H = 2E): V' = V + F, E' = E + H = 3E, F' = H = 2E (all triangles).
//! Output vertices are `[smoothed old vertices | face centroids]`; output
//! triangle `h` is the one of half-edge `h`.

use super::hosts::{check_output_size, neighbor_sum, with_point_spheres, MIN_LEN};
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// One level of √3 subdivision. See the module docs.
pub fn sqrt3(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("sqrt3", m, step)
}

/// Kobbelt's αₙ.
#[inline]
pub fn sqrt3_alpha(n: usize) -> f64 {
    (4.0 - 2.0 * (std::f64::consts::TAU / n as f64).cos()) / 9.0
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("sqrt3", 3 * m.n_halfedges(), m.n_vertices() + m.n_faces())?;
    let (nv, nh, nf) = (m.n_vertices(), m.n_halfedges(), m.n_faces());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let mut pos = vec![DVec3::ZERO; nv + nf];
    let (vp, fp) = pos.split_at_mut(nv);
    rayon::join(
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (sum, n) = neighbor_sum(m, v);
                let a = sqrt3_alpha(n);
                *out = p[v] * (1.0 - a) + sum * (a / n as f64);
            })
        },
        || {
            fp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let s = m.f_start[f];
                let mut h = s;
                let mut sum = DVec3::ZERO;
                let mut n = 0usize;
                loop {
                    sum += p[vert[h as usize] as usize];
                    n += 1;
                    h = next[h as usize];
                    if h == s {
                        break;
                    }
                }
                *out = sum / n as f64;
            })
        },
    );
    crate::cancel::check()?;
    let nvu = nv as u32;
    let mut cv = vec![0u32; 3 * nh];
    let mut tw = vec![0u32; 3 * nh];
    cv.par_chunks_mut(3).zip(tw.par_chunks_mut(3)).with_min_len(MIN_LEN).enumerate().for_each(|(h, (c, t))| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let t_h = h ^ 1;
        c[0] = vert[h];
        c[1] = nvu + face[t_h];
        c[2] = nvu + face[h];
        t[0] = 3 * next[t_h] + 2;
        t[1] = 3 * t_h as u32 + 1;
        t[2] = 3 * (prev[h] ^ 1);
    });
    crate::cancel::check()?;
    let sizes = vec![3u32; nh];
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(sqrt3, |_, (v, e, f)| (v + f, 3 * e, 2 * e), |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 3), "{name} triangles");
        });
    }

    #[test]
    fn two_steps_are_triadic() {
        let m = crate::primitives::icosahedron();
        let r = sqrt3(&sqrt3(&m).unwrap()).unwrap();
        assert_eq!(r.n_faces(), 9 * m.n_faces());
    }
}
