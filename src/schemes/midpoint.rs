//! Midpoint (linear) subdivision, one level: refinement without smoothing.
//!
//! * A triangle splits 1 → 4 at its edge midpoints: `[v, m(h), m(prev h)]`
//!   per corner and the middle `[m(h₀), m(h₁), m(h₂)]`. On triangle meshes
//!   this is `trimesh.remesh.subdivide` (and pymeshlab's / libigl's midpoint
//!   upsampling) up to vertex order.
//! * Any other face (n ≠ 3, one-gons and two-gons included) splits into n
//!   quads `[v, m(h), c, m(prev h)]` around its centroid `c` (the linear
//!   Catmull-Clark split; pmp-library's quad-tri linear subdivision does the
//!   same on quad/triangle meshes).
//!
//! Old vertices keep their positions; edge points are midpoints (a self-loop's
//! is its vertex), face points centroids of the corners.
//!
//! Counts: V' = V + E + F_≠3, E' = 2E + 3F₃ + Σ_≠3 n, F' = 4F₃ + Σ_≠3 n.
//! Output vertices are `[old vertices | edge midpoints | centroids of the
//! non-triangles, in face order]`.

use super::hosts::{check_output_size, primal_host, with_point_spheres, FaceLayout, MIN_LEN};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// One level of midpoint subdivision. See the module docs.
pub fn midpoint(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("midpoint", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("midpoint", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, _) = m.halfedge_columns();
    let mut face_point = vec![NONE; nf];
    let mut k = 0u32;
    for (f, fp) in face_point.iter_mut().enumerate() {
        crate::cancel::poll(f)?;
        if fl.degree(f) != 3 {
            *fp = k;
            k += 1;
        }
    }
    let p = &m.pos;
    let mut pos = Vec::with_capacity(nv + ne + k as usize);
    pos.extend_from_slice(p);
    pos.par_extend((0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }));
    for f in 0..nf {
        crate::cancel::poll(f)?;
        if face_point[f] != NONE {
            let hs = fl.corners(f);
            let s: DVec3 = hs.iter().map(|&h| p[vert[h as usize] as usize]).sum();
            pos.push(s / hs.len() as f64);
        }
    }
    primal_host(m, &fl, &face_point, pos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        let counts = |m: &Mesh, (v, e, _): (usize, usize, usize)| {
            let ps = n_point_spheres(m);
            let sizes: Vec<usize> = face_sizes(m);
            let f3 = sizes.iter().filter(|&&s| s == 3).count();
            let ng: Vec<usize> = sizes.iter().copied().filter(|&s| s != 3).collect();
            // point-sphere faces have size 1 but are carried over, not split
            let (ngn, ngsum) = (ng.len() - ps, ng.iter().sum::<usize>() - ps);
            (v + e + ngn, 2 * e + 3 * f3 + ngsum, 4 * f3 + ngsum)
        };
        check_on_corpus(midpoint, counts, |_, m, r| {
            // old vertices stay put
            let v = m.n_vertices() - n_point_spheres(m);
            assert_eq!(&r.positions()[..v], &m.positions()[..v]);
        });
    }
}
