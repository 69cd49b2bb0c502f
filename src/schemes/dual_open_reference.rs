//! The open dual as it was built before `dual_open.rs` (issue 19): a
//! corner list and its closed-form twins handed to
//! `Mesh::from_trusted_twins`. Kept for the tests, which compare the walk
//! with it column by column.

use super::hosts::{check_output_size, FaceLayout, VertexLayout};
use super::corner_origins::edge_origins_by_corner;
use super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE};

pub(crate) fn level_step_reference(m: &Mesh, req: &Request) -> Result<Level> {
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let hole = |h: usize| m.f_hole[face[h] as usize];
    // numbering: real faces' centroids, boundary edges' midpoints, boundary vertices
    let mut fidx = vec![NONE; nf];
    let mut real = Vec::with_capacity(nf);
    for f in 0..nf {
        if !m.f_hole[f] {
            fidx[f] = real.len() as u32;
            real.push(f as u32);
        }
    }
    let mut bidx = vec![NONE; ne];
    let mut bedges = Vec::new();
    for e in 0..ne {
        crate::cancel::poll(e)?;
        match (hole(2 * e), hole(2 * e + 1)) {
            (true, true) => {
                return Err(MeshError::Precondition(format!("dual: edge {e} has hole faces on both sides, so it has no dual edge")));
            }
            (false, false) => {}
            _ => {
                bidx[e] = (real.len() + bedges.len()) as u32;
                bedges.push(e as u32);
            }
        }
    }
    let mut vidx_b = vec![NONE; nv];
    let mut bverts = Vec::new();
    for h in 0..nh {
        let v = vert[h] as usize;
        if hole(h) && vidx_b[v] == NONE {
            vidx_b[v] = 0;
        }
    }
    for (v, slot) in vidx_b.iter_mut().enumerate() {
        if *slot != NONE {
            *slot = (real.len() + bedges.len() + bverts.len()) as u32;
            bverts.push(v as u32);
        }
    }
    let n_out = real.len() + bedges.len() + bverts.len();
    check_output_size("dual", nh + 4 * bedges.len(), n_out)?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    // corner base of every rotation slot (1 corner per real face, 3 per hole corner), then the holes'
    let mut cb = vec![0u32; nh + 1];
    for h in 0..nh {
        crate::cancel::poll(h)?;
        cb[vl.vidx[h] as usize + 1] = if hole(h) { 3 } else { 1 };
    }
    for s in 0..nh {
        cb[s + 1] += cb[s];
    }
    let mut hb = vec![NONE; nf];
    let mut nc = cb[nh];
    let mut sizes: Vec<u32> = (0..nv).map(|v| cb[vl.off[v + 1] as usize] - cb[vl.off[v] as usize]).collect();
    for f in 0..nf {
        if m.f_hole[f] {
            hb[f] = nc;
            nc += 2 * fl.degree(f) as u32;
            sizes.push(2 * fl.degree(f) as u32);
        }
    }
    let first = |g: usize| cb[vl.vidx[g] as usize];
    let last = |g: usize| cb[vl.vidx[g] as usize + 1] - 1;
    let hole_corner = |h: usize| hb[face[h] as usize] + 2 * fl.local(h as u32, face[h]) as u32;
    let mut cv = vec![0u32; nc as usize];
    let mut tw = vec![0u32; nc as usize];
    // per corner: the input edge its side comes from (origins)
    let mut ce = if req.origins { vec![0u32; nc as usize] } else { Vec::new() };
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let r = (prev[h] ^ 1) as usize;
        let c = first(h) as usize;
        if hole(h) {
            let p = prev[h] as usize;
            cv[c] = bidx[h >> 1];
            tw[c] = hole_corner(h);
            cv[c + 1] = vidx_b[vert[h] as usize];
            tw[c + 1] = hole_corner(p) + 1;
            cv[c + 2] = bidx[p >> 1];
            tw[c + 2] = last(next[r] as usize);
            if req.origins {
                ce[c..c + 3].copy_from_slice(&[(h >> 1) as u32, (p >> 1) as u32, (p >> 1) as u32]);
            }
        } else {
            cv[c] = fidx[face[h] as usize];
            tw[c] = last(next[r] as usize);
            if req.origins {
                ce[c] = (r >> 1) as u32;
            }
        }
    }
    for f in 0..nf {
        if !m.f_hole[f] {
            continue;
        }
        let hs = fl.corners(f);
        let b = hb[f] as usize;
        for (k, &h) in hs.iter().enumerate() {
            let h = h as usize;
            cv[b + 2 * k] = vidx_b[vert[h] as usize];
            tw[b + 2 * k] = first(h);
            cv[b + 2 * k + 1] = bidx[h >> 1];
            tw[b + 2 * k + 1] = first(hs[(k + 1) % hs.len()] as usize) + 1;
            if req.origins {
                ce[b + 2 * k] = (h >> 1) as u32;
                ce[b + 2 * k + 1] = (h >> 1) as u32;
            }
        }
    }
    crate::cancel::check()?;
    // the corner numbering is done with before the positions (issue 19)
    // (faces are walked through `next` from here: the layout's order)
    drop((fl, vl, cb, hb, fidx, bidx, vidx_b));
    let fill = |i: usize, row: &mut crate::schemes::stencil::Row| {
        if i < real.len() {
            super::hosts::face_mean_row(m, real[i] as usize, 1.0, row);
        } else if i < real.len() + bedges.len() {
            let e = bedges[i - real.len()] as usize;
            row.add(vert[2 * e], 0.5);
            row.add(vert[2 * e + 1], 0.5);
        } else {
            row.add(bverts[i - real.len() - bedges.len()], 1.0);
        }
    };
    // the rows are stored only when asked for (issue 19: peak memory); the
    // positions come after the connectivity, once the corner lists are freed
    let points = || {
        if m.n_holes() == 0 {
            // closed: the centroids exactly as the plain path sums them
            // (along each cycle from its first corner: the same bits)
            let mut p = crate::mesh::zeroed_points(nf);
            super::hosts::face_centroids_walk(m, &mut p);
            crate::cancel::check()?;
            Ok((p, if req.stencils { Some(Stencils::build(n_out, nv, fill)?) } else { None }))
        } else {
            Stencils::points_and_rows(n_out, nv, &m.pos, req.stencils, fill)
        }
    };
    // the twins are this function's closed forms (the faces after the
    // vertices' are the holes)
    let holes = (0..sizes.len()).map(|f| f >= nv).collect();
    let (mesh, stencils) = Mesh::from_trusted_twins(n_out, sizes, cv, tw, holes, points)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(n_out, mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(FACE).take(real.len()).chain(std::iter::repeat(EDGE).take(bedges.len())).chain(std::iter::repeat(VERTEX).take(bverts.len())));
        o.vertex.extend(real.iter().chain(&bedges).chain(&bverts).copied());
        o.face_kind.extend(std::iter::repeat(VERTEX).take(nv));
        o.face.extend(0..nv as u32);
        for f in 0..nf {
            if m.f_hole[f] {
                o.face_kind.push(FACE);
                o.face.push(f as u32);
            }
        }
        edge_origins_by_corner(&mesh, &mut o, |c| (EDGE, ce[c]))?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

