//! The builder `step` used before it wrote the half-edge columns itself
//! (issue 19): corners and twins handed to [`Mesh::from_corner_twins`]. The
//! direct fill must give the same mesh, element order included.

use super::super::hosts::{check_output_size, MIN_LEN};
use crate::error::Result;
use crate::mesh::Mesh;
use rayon::prelude::*;

pub(super) fn step_via_twins(m: &Mesh) -> Result<Mesh> {
    check_output_size("sqrt3", 3 * m.n_halfedges(), m.n_vertices() + m.n_faces())?;
    let (nv, nh) = (m.n_vertices(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let pos = super::positions(m)?;
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
    use crate::schemes::hosts::with_point_spheres;

    #[test]
    fn columns_equal_the_twin_builder() {
        for (name, m) in corpus() {
            let (mut a, mut b) = (m.clone(), m.clone());
            for level in 1..=2 {
                let (na, nb) = (with_point_spheres("sqrt3", &a, super::super::step).unwrap(), with_point_spheres("sqrt3", &b, step_via_twins).unwrap());
                assert_eq!(na, nb, "{name} level {level}");
                (a, b) = (na, nb);
            }
        }
    }
}
