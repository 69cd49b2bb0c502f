//! Doo-Sabin's step on open meshes: the Chaikin boundary of the module docs
//! (`super`), half-edge ids in closed form.

use super::*;

/// Doo-Sabin on a mesh with holes, with the Chaikin boundary of the module
/// docs. Positions are `S · P`.
pub(super) fn open_step(m: &Mesh, req: &Request) -> Result<Level> {
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let hole = |h: usize| m.f_hole[face[h] as usize];
    // qb(h), the Chaikin point near the head of hole half-edge h, is vertex nh + hidx[h]
    let mut hidx = vec![u32::MAX; nh];
    let mut holes_he = Vec::new();
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if hole(h) {
            if hole(h ^ 1) {
                return Err(crate::error::MeshError::Precondition(format!(
                    "doo_sabin: edge {} has hole faces on both sides, so its boundary rule is undefined",
                    h >> 1
                )));
            }
            hidx[h] = holes_he.len() as u32;
            holes_he.push(h as u32);
        }
    }
    let b = holes_he.len();
    check_output_size("doo_sabin", 4 * nh + 4 * b, nh + b)?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let cidx = &fl.cidx;
    let hu = nh as u32;
    let qb = |h: usize| hu + hidx[h];
    // corner bases: [F-faces and holes (2 per hole corner) in face order | E-faces | V-faces (2 per hole slot)]
    let mut fb = Vec::with_capacity(nf + 1);
    fb.push(0u32);
    for f in 0..nf {
        let d = fl.degree(f) as u32;
        fb.push(fb[f] + if m.f_hole[f] { 2 * d } else { d });
    }
    let eb = fb[nf];
    let mut vb = vec![0u32; nh + 1];
    for h in 0..nh {
        vb[vl.vidx[h] as usize + 1] = if hole(h) { 2 } else { 1 };
    }
    vb[0] = eb + 4 * ne as u32;
    for s in 0..nh {
        vb[s + 1] += vb[s];
    }
    let nc = vb[nh] as usize;
    // the corner of half-edge h in its F-face (or the first of its two in its hole)
    let fcorner = |h: usize| {
        let f = face[h] as usize;
        let k = fl.local(h as u32, face[h]) as u32;
        fb[f] + if m.f_hole[f] { 2 * k } else { k }
    };
    let vfirst = |x: usize| vb[vl.vidx[x] as usize];
    let vlast = |x: usize| vb[vl.vidx[x] as usize + 1] - 1;
    let mut sizes = Vec::with_capacity(nf + ne + nv);
    sizes.extend((0..nf).map(|f| fb[f + 1] - fb[f]));
    sizes.extend(std::iter::repeat(4u32).take(ne));
    sizes.extend((0..nv).map(|v| vb[vl.off[v + 1] as usize] - vb[vl.off[v] as usize]));
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    let mut co = if req.origins { vec![(EDGE, 0u32); nc] } else { Vec::new() };
    let e_side = |h: usize| eb + 4 * (h >> 1) as u32 + 2 * (h & 1) as u32;
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let c = fcorner(h) as usize;
        if hole(h) {
            // Chaikin points of boundary edge h, then the cut at head(h)
            cv[c] = cidx[h];
            tw[c] = e_side(h);
            cv[c + 1] = qb(h);
            tw[c + 1] = vfirst(next[h] as usize);
            if req.origins {
                co[c] = (EDGE, (h >> 1) as u32);
                co[c + 1] = (VERTEX, vert[h ^ 1]);
            }
        } else {
            cv[c] = cidx[h];
            tw[c] = e_side(h);
            if req.origins {
                co[c] = (FACE, face[h]);
            }
        }
        // V-face slot of h: p(h), or for a hole corner qa(h) then qb(prev h)
        let s = vfirst(h) as usize;
        let r = (prev[h] ^ 1) as usize;
        let to_e = eb + 4 * (r >> 1) as u32 + 1 + 2 * (r & 1) as u32;
        cv[s] = cidx[h];
        if hole(h) {
            let p = prev[h] as usize;
            tw[s] = fcorner(p) + 1;
            cv[s + 1] = qb(p);
            tw[s + 1] = to_e;
            if req.origins {
                co[s] = (VERTEX, vert[h]);
                co[s + 1] = (EDGE, (r >> 1) as u32);
            }
        } else {
            tw[s] = to_e;
            if req.origins {
                co[s] = (EDGE, (r >> 1) as u32);
            }
        }
    }
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (a, bb) = (2 * e, 2 * e + 1);
        let (na, nb) = (next[a] as usize, next[bb] as usize);
        let c = (eb + 4 * e as u32) as usize;
        // [p(na), p(a), p(nb), p(b)], a hole side's p(n·) replaced by its qb
        cv[c] = if hole(a) { qb(a) } else { cidx[na] };
        cv[c + 1] = cidx[a];
        cv[c + 2] = if hole(bb) { qb(bb) } else { cidx[nb] };
        cv[c + 3] = cidx[bb];
        tw[c] = fcorner(a);
        tw[c + 1] = vlast(nb);
        tw[c + 2] = fcorner(bb);
        tw[c + 3] = vlast(na);
        if req.origins {
            co[c] = if hole(a) { (EDGE, e as u32) } else { (FACE, face[a]) };
            co[c + 1] = (EDGE, e as u32);
            co[c + 2] = if hole(bb) { (EDGE, e as u32) } else { (FACE, face[bb]) };
            co[c + 3] = (EDGE, e as u32);
        }
    }
    // rows: corner points of real faces (Doo-Sabin), qa of hole corners, then qb
    // the rows are stored only when asked for (issue 19: peak memory); the
    // positions are the same bits either way
    let (pos, stencils) = Stencils::points_and_rows(nh + b, nv, &m.pos, req.stencils, |i, row| {
        if i >= nh {
            let h = holes_he[i - nh] as usize;
            row.add(vert[h], 0.25);
            row.add(vert[h ^ 1], 0.75);
            return;
        }
        let h = fl.fh[i] as usize;
        if hole(h) {
            row.add(vert[h], 0.75);
            row.add(vert[h ^ 1], 0.25);
            return;
        }
        let f = face[h] as usize;
        let hs = fl.corners(f);
        let (n, k) = (hs.len(), i - fl.off[f] as usize);
        for (j, &g) in hs.iter().enumerate() {
            row.add(vert[g as usize], if n == 1 { 1.0 } else { doo_sabin_weight(n, (j + n - k) % n) });
        }
    })?;
    // half-edge ids in closed form, the numbering `from_corner_twins` gave
    // these corners (edges by first corner, whose twin comes later): every
    // F-block corner is first (its twin lies in the E or V block), so corner
    // c < eb gets 2c; an E-face's sides 1 and 3 (towards the V block) are
    // first, ranked 2e and 2e + 1 after the F block; every other corner's
    // twin comes earlier, and it gets that twin's id + 1
    let first_id = |c: usize| {
        if c < eb as usize {
            2 * c as u32
        } else {
            let (e, j) = ((c - eb as usize) / 4, (c - eb as usize) % 4);
            2 * (eb + 2 * e as u32 + (j == 3) as u32)
        }
    };
    let ids: Vec<u32> = (0..nc).into_par_iter().with_min_len(MIN_LEN).map(|c| {
        let t = tw[c] as usize;
        if t > c { first_id(c) } else { first_id(t) + 1 }
    }).collect();
    let mut holes = vec![false; sizes.len()];
    holes[..nf].copy_from_slice(&m.f_hole);
    let mesh = Mesh::from_corner_ids(pos, &sizes, &cv, &ids, holes)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(nh + b, mesh.n_edges(), nf + ne + nv);
        o.vertex_kind.extend(fl.fh.iter().map(|&h| if hole(h as usize) { EDGE } else { FACE }));
        o.vertex.extend(fl.fh.iter().map(|&h| if hole(h as usize) { h >> 1 } else { face[h as usize] }));
        o.vertex_kind.extend(std::iter::repeat(EDGE).take(b));
        o.vertex.extend(holes_he.iter().map(|&h| h >> 1));
        o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(VERTEX).take(nv)));
        o.face.extend((0..nf as u32).chain(0..ne as u32).chain(0..nv as u32));
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}
