//! Cubic pentagonalization (TopMod's `subdivideCubicPentagonal`:
//! pentagonalization, dual, dual) in one pass, without pentagonalization's
//! mesh (issue 16: after `compose::dual_dual` dropped the middle dual, the
//! keyed build of pentagonalization's 2E pentagons, only to be walked by
//! `dual_dual`, was still half of the time).
//!
//! Pentagonalization ([`super::pentagonal::pentagonalize`]) lays, per input
//! corner h in face-layout order (corner index j), the pentagon
//! `[p(h), p(twin h), head h, p(next h), c(face h)]`; its vertices are the
//! input's, then p(h) at V + h, then the centroids at V + H + f. Name its
//! corner k of face j `5j + k`: every corner's vertex and the corner of its
//! twin side follow by index arithmetic (below), and `dual_dual` only reads
//! corners, twins, `v_out` (the first corner of each vertex in face order)
//! and `f_start` (corner 0); pentagonalization's half-edge ids never matter
//! (its keys only name edges, numbered by first crossing). So the walk of
//! `dual_dual` runs here over those corners with the same arithmetic, and
//! the output is the composition's bit for bit (`keyed::hashes`). Holes,
//! point-spheres, a bad offset and traced builds (face parents) take the
//! composition.

use super::compose::dual_dual;
use super::pentagonal::pentagonalize;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::hosts::check_output_size;
use crate::schemes::keyed::In;
use glam::DVec3;

/// `dual_dual(&pentagonalize(m, offset)?)`, the same output and errors.
pub(crate) fn cubic_pentagonalize(m: &Mesh, offset: f64) -> Result<Mesh> {
    let plain = !(offset.is_finite() && (0.0..=1.0).contains(&offset)) || m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0);
    if plain || crate::schemes::face_parents::recording() {
        return dual_dual(&pentagonalize(m, offset)?);
    }
    crate::cancel::check()?;
    let i = In::new(m)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    // pentagonalization's counts: V + H + F vertices, 5H corners, H faces
    let (nvp, nhp, nfp) = (nv + nh + nf, 5 * nh, nh);
    check_output_size("pentagonalize", nhp, nvp)?;
    check_output_size("dual", nhp, nfp)?;
    check_output_size("dual", nhp, nvp)?;
    let (next, prev, vert, face) = (i.next, i.prev, i.vert, i.face);
    let (fh, cidx) = (&i.fl.fh, &i.fl.cidx);
    // pentagonalization's positions, the same arithmetic
    let cent = i.centroids();
    let mut ppos = i.positions(nh + nf);
    for h in 0..nh {
        let p = i.p(h).lerp(i.q(h), 1.0 / 3.0);
        ppos.push(p.lerp(cent[face[h] as usize], offset));
    }
    ppos.extend_from_slice(&cent);
    drop(cent);
    crate::cancel::check()?;
    let (pt, cf) = (nv as u32, (nv + nh) as u32);
    // corner 5j + k of the pentagon of h = fh[j]: its vertex and its key,
    // as pentagonalization keys it (segment at tail(g): g; middle of edge
    // e: H + e; spoke of corner g: H + E + g)
    let (kmid, kspoke) = (nh as u32, (nh + ne) as u32);
    let corners = |h: u32| -> [(u32, u32); 5] {
        let (t, nx) = (h ^ 1, next[h as usize]);
        [(pt + h, kmid + (h >> 1)), (pt + t, t), (vert[t as usize], nx), (pt + nx, kspoke + nx), (cf + face[h as usize], kspoke + h)]
    };
    // the corner of its twin side, the other side of its key: the middle
    // third of edge(h) in the pentagon of twin h; the segment at head(h) in
    // the pentagons of prev(twin h) and next(h)'s twin; the spokes in those
    // of next h and prev h. Stored at the corner after it: rot[x] is
    // twin(prev x), the step of a rotation round x's vertex.
    // (written per pentagon into a sized column: `extend` with a 5-array
    // compiled to a memmove call per pentagon, 4 % of the call under `perf`)
    let mut rot = vec![0u32; nhp];
    for (r, &h) in rot.chunks_exact_mut(5).zip(fh.iter()) {
        let (t, nx, pr) = (h ^ 1, next[h as usize], prev[h as usize]);
        r[0] = 5 * cidx[pr as usize] + 3;
        r[1] = 5 * cidx[t as usize];
        r[2] = 5 * cidx[prev[t as usize] as usize] + 2;
        r[3] = 5 * cidx[(nx ^ 1) as usize] + 1;
        r[4] = 5 * cidx[nx as usize] + 4;
    }
    // pentagonalization's v_out (each vertex's first corner in face order)
    // and centroids (summed from corner 0, as `dual_dual` sums them)
    let mut v_out = vec![NONE; nvp];
    let mut cen = Vec::with_capacity(nfp);
    for (j, &h) in fh.iter().enumerate() {
        crate::cancel::poll(j)?;
        let mut s = DVec3::ZERO;
        for (k, (v, _)) in corners(h).into_iter().enumerate() {
            s += ppos[v as usize];
            let o = &mut v_out[v as usize];
            if *o == NONE {
                *o = (5 * j + k) as u32;
            }
        }
        cen.push(s / 5usize as f64);
    }
    // dual_dual (see there): per vertex the mean of the centroids round
    // it, and the corner c0 at which each pentagon is first met
    let mut pos = Vec::with_capacity(nvp);
    let mut c0 = vec![NONE; nfp];
    for &s in &v_out {
        let (mut x, mut sum, mut k) = (s, DVec3::ZERO, 0usize);
        loop {
            let f = (x / 5) as usize;
            sum += cen[f];
            k += 1;
            if c0[f] == NONE {
                c0[f] = x;
            }
            x = rot[x as usize];
            if x == s {
                break;
            }
        }
        pos.push(sum / k as f64);
    }
    drop(cen);
    drop(rot);
    crate::cancel::check()?;
    let mut walk = DualWalk::new(pos, nhp, nfp, 2 * nh + ne);
    for (j, &s) in c0.iter().enumerate() {
        crate::cancel::poll(j)?;
        let cs = corners(fh[j]);
        let (k0, mut last) = (s as usize - 5 * j, NONE);
        for (v, k) in cs[k0..].iter().chain(&cs[..k0]) {
            walk.put(j, *v, *k as usize, &mut last);
        }
        walk.close(j, last);
    }
    Mesh::from_columns(walk.finish()?)
}
