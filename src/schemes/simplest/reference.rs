//! The builders `simplest` used before it wrote the half-edge columns
//! itself (issue 19): corners and twins handed to
//! [`Mesh::from_corner_twins`] (closed) and
//! [`Mesh::from_corner_twins_with_holes`] (open). The direct fills must give
//! the same meshes, element order included; the tests here compare them.

use super::super::corner_origins::edge_origins_by_corner;
use super::super::hosts::{check_output_size, FaceLayout, VertexLayout, MIN_LEN};
use super::super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// The builder [`step`] replaced (corners and twins through
/// [`Mesh::from_corner_twins`]), kept as the reference it must equal.
pub(super) fn step_via_twins(m: &Mesh) -> Result<Mesh> {
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let pos: Vec<_> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    let hu = nh as u32;
    let mut cv = vec![0u32; 2 * nh];
    let mut tw = vec![0u32; 2 * nh];
    {
        let (cf, cvf) = cv.split_at_mut(nh);
        let (tf, tvf) = tw.split_at_mut(nh);
        cf.par_iter_mut().zip(tf.par_iter_mut()).with_min_len(MIN_LEN).enumerate().for_each(|(c, (v, t))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let h = fl.fh[c];
            *v = h >> 1;
            *t = hu + vl.vidx[next[h as usize] as usize];
        });
        let (pc, pt) = (super::super::hosts::SyncPtr(cvf.as_mut_ptr()), super::super::hosts::SyncPtr(tvf.as_mut_ptr()));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|x| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let slot = vl.vidx[x] as usize;
            // SAFETY: vidx is a permutation of 0..nh.
            unsafe {
                *pc.get().add(slot) = (x >> 1) as u32;
                *pt.get().add(slot) = fl.cidx[prev[x] as usize];
            }
        });
    }
    crate::cancel::check()?;
    let mut sizes = Vec::with_capacity(nf + nv);
    sizes.extend((0..nf).map(|f| fl.degree(f) as u32));
    sizes.extend((0..nv).map(|v| vl.valence(v)));
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

/// One level on a mesh with hole faces (no point-spheres): boundary
/// vertices kept, boundary edges split (module docs). Faces are
/// `[F-faces of real faces | V-faces | holes]`.
pub(super) fn open_level_via_twins(m: &Mesh, req: &Request) -> Result<Level> {
    use crate::mesh::NONE;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    check_output_size("simplest", 2 * nh + nh, ne + nv)?;
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let hole = |h: u32| m.f_hole[face[h as usize] as usize];
    // boundary vertices, in vertex order, after the edge midpoints
    let mut bidx = vec![NONE; nv];
    let mut bverts = Vec::new();
    for h in 0..nh as u32 {
        let v = vert[h as usize] as usize;
        if hole(h) && bidx[v] == NONE {
            bidx[v] = bverts.len() as u32;
            bverts.push(v as u32);
        }
    }
    // corner numbering
    let (mut fc, mut vc, mut vx, mut ca) = (vec![NONE; nh], vec![NONE; nh], vec![NONE; nh], vec![NONE; nh]);
    let mut sizes = Vec::with_capacity(nf + nv);
    let mut holes = Vec::with_capacity(nf + nv);
    let mut c = 0u32;
    let cycle = |f: usize| {
        let s = m.f_start[f];
        let mut h = s;
        let mut out = Vec::new();
        loop {
            out.push(h);
            h = next[h as usize];
            if h == s {
                break out;
            }
        }
    };
    for f in 0..nf {
        crate::cancel::poll(f)?;
        if !m.f_hole[f] {
            let hs = cycle(f);
            for &h in &hs {
                fc[h as usize] = c;
                c += 1;
            }
            sizes.push(hs.len() as u32);
            holes.push(false);
        }
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let start = c;
        for x in super::super::creases::ring(m, m.v_out[v]) {
            vc[x as usize] = c;
            c += 1;
            if hole(x) {
                vx[x as usize] = c; // the kept boundary vertex, after m(x)
                c += 1;
            }
        }
        sizes.push(c - start);
        holes.push(false);
    }
    let mut hole_faces = Vec::new();
    for f in 0..nf {
        if m.f_hole[f] {
            let hs = cycle(f);
            for &k in &hs {
                ca[k as usize] = c; // [w, m(k)]: the two halves of side k
                c += 2;
            }
            sizes.push(2 * hs.len() as u32);
            holes.push(true);
            hole_faces.push(f as u32);
        }
    }
    let n = c as usize;
    let (mut cv, mut tw) = (vec![0u32; n], vec![0u32; n]);
    let mut co = vec![(0u8, 0u32); if req.origins { n } else { 0 }];
    let bv = |w: u32| (ne as u32) + bidx[w as usize];
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let hu = h as u32;
        let mid = hu >> 1;
        if !hole(hu) {
            // F-face side m(h) → m(next h), cutting the corner at vert[next h]
            let i = fc[h] as usize;
            cv[i] = mid;
            tw[i] = vc[next[h] as usize];
            // V-face side m(h) → m(prev h) inside face[h]
            let j = vc[h] as usize;
            cv[j] = mid;
            tw[j] = fc[prev[h] as usize];
            if req.origins {
                co[i] = (FACE, face[h]);
                co[j] = (FACE, face[h]);
            }
        } else {
            // V-face of w = vert[h]: m(h) → w → m(prev h) along the boundary
            let (j, x) = (vc[h] as usize, vx[h] as usize);
            cv[j] = mid;
            tw[j] = ca[h];
            cv[x] = bv(vert[h]);
            tw[x] = ca[prev[h] as usize] + 1;
            // the hole: w → m(h) → (next corner)
            let a = ca[h] as usize;
            cv[a] = bv(vert[h]);
            tw[a] = vc[h];
            cv[a + 1] = mid;
            tw[a + 1] = vx[next[h] as usize];
            if req.origins {
                co[j] = (EDGE, mid);
                co[x] = (EDGE, prev[h] >> 1);
                co[a] = (EDGE, mid);
                co[a + 1] = (EDGE, mid);
            }
        }
    }
    let st = Stencils::build(ne + bverts.len(), nv, super::open::open_point_row(&m.he_vert, &bverts))?;
    let pos = st.apply_points(&m.pos)?;
    let mesh = Mesh::from_corner_twins_with_holes(pos, &sizes, &cv, &tw, holes)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind = std::iter::repeat(EDGE).take(ne).chain(std::iter::repeat(VERTEX).take(bverts.len())).collect();
        o.vertex = (0..ne as u32).chain(bverts.iter().copied()).collect();
        let real: Vec<u32> = (0..nf as u32).filter(|&f| !m.f_hole[f as usize]).collect();
        o.face_kind = std::iter::repeat(FACE).take(real.len()).chain(std::iter::repeat(VERTEX).take(nv)).chain(std::iter::repeat(FACE).take(hole_faces.len())).collect();
        o.face = real.iter().copied().chain(0..nv as u32).chain(hole_faces.iter().copied()).collect();
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils: req.stencils.then_some(st), origins, creases: None })
}

#[cfg(test)]
mod tests {
    use super::super::{open_level, step};
    use super::*;
    use crate::schemes::hosts::test_meshes::*;
    use crate::schemes::hosts::with_point_spheres;

    #[test]
    fn closed_columns_equal_the_twin_builder() {
        for (name, m) in corpus() {
            let (mut a, mut b) = (m.clone(), m.clone());
            for level in 1..=2 {
                let (na, nb) = (with_point_spheres("simplest", &a, step).unwrap(), with_point_spheres("simplest", &b, step_via_twins).unwrap());
                assert_eq!(na, nb, "{name} level {level}");
                (a, b) = (na, nb);
            }
        }
    }

    #[test]
    fn open_columns_equal_the_twin_builder() {
        let mut meshes = open_meshes();
        meshes.push(("open_grid_5", open_grid(5)));
        meshes.push(("open_tube", open_tube(6, 3)));
        for (name, m) in meshes {
            for req in [Request::plain(), full_request()] {
                let (mut a, mut b) = (m.clone(), m.clone());
                for level in 1..=2 {
                    let (la, lb) = (open_level(&a, &req).unwrap(), open_level_via_twins(&b, &req).unwrap());
                    assert_eq!(la.mesh, lb.mesh, "{name} level {level}");
                    assert_eq!(la.origins, lb.origins, "{name} level {level}");
                    assert_eq!(la.stencils, lb.stencils, "{name} level {level}");
                    (a, b) = (la.mesh, lb.mesh);
                }
            }
        }
    }
}
