//! `dual(honeycomb(x, 0.5))` (root-3 after its first dual) without building
//! honeycomb's output (issue 16: that build was about half of root-3's
//! time, only for the dual to walk it). Honeycomb (see `honeycomb` and
//! `face_vertex_columns`) lays the front face F(f) of every face (its new
//! vertices h in the old order), then the face V(v) of every vertex (per
//! rotation slot g from `v_out`: g, prev g); new vertex h comes first in its
//! front face, so the dual's face h goes F(face h), V(tail h), V(head h),
//! crossing the sides that enter those corners: the front side of prev h,
//! the inserted edge of h's edge, the front side of h. The dual's vertex of
//! each face is its centroid (summed from its first corner, as the dual
//! sums). Edges are numbered by first crossing, as [`crate::schemes::dual`]
//! does, so the output is the composition's bit for bit (`keyed::hashes`);
//! holes and point-spheres take the composition.

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::{corner_mean, DualWalk};
use crate::schemes::dual::dual;
use crate::schemes::hosts::{check_output_size, FaceLayout};
use glam::DVec3;

/// `dual(&honeycomb(x, t, None)?)`, the same output.
pub(crate) fn dual_of_honeycomb(x: &Mesh, t: f64) -> Result<Mesh> {
    use crate::schemes::honeycomb;
    if x.n_holes() > 0 || x.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&honeycomb::honeycomb(x, t, None)?);
    }
    honeycomb::check_args(t, None)?;
    let (nv, ne, nf, nh) = (x.n_vertices(), x.n_edges(), x.n_faces(), x.n_halfedges());
    let (_, vert, face) = x.halfedge_columns();
    let prev = &x.he_prev;
    check_output_size("dual", 6 * ne, nf + nv)?;
    let fl = FaceLayout::new(x)?;
    let hp = honeycomb::positions(x, &fl, t, None)?;
    // the dual's vertices: centroids of F(f), then V(v)
    let mut pos = Vec::with_capacity(nf + nv);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = fl.corners(f);
        pos.push(corner_mean(hs, |h| hp[h]));
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let g0 = x.v_out[v] as usize;
        let (mut g, mut s, mut n) = (g0, DVec3::ZERO, 0usize);
        loop {
            let p = prev[g] as usize;
            s += hp[g];
            s += hp[p];
            n += 2;
            g = p ^ 1;
            if g == g0 {
                break;
            }
        }
        pos.push(s / n as f64);
    }
    drop((hp, fl));
    let n_out_he = 6 * ne;
    // keys: the front side of h (h), the inserted edge of edge e (H + e)
    let mut walk = DualWalk::new(pos, n_out_he, nh, nh + ne);
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let ring = [(face[h] as usize, prev[h] as usize), (nf + vert[h] as usize, nh + (h >> 1)), (nf + vert[h ^ 1] as usize, h)];
        let mut last = NONE;
        for (hf, key) in ring {
            walk.put(h, hf as u32, key, &mut last);
        }
        walk.close(h, last);
    }
    // honeycomb records no face parents, so the composition had none
    crate::schemes::face_parents::record(None);
    Mesh::from_columns(walk.finish()?)
}
