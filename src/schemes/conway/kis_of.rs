//! Kis of join (meta, `m` = `kj`) and kis of the dual (needle, `n` =
//! `kd`) in one pass each, without the join's or the dual's mesh (issue 16:
//! it was built only for kis to fan its faces; meta was the slowest Conway
//! row per output corner after snub and volute).
//!
//! **Meta.** J's face e ([`super::dual_ambo::join`]) goes round ambo's vertex e from
//! the side h0 of e met first in face order: the corners w = [face(h0),
//! F + tail(h0), face(twin h0), F + tail(twin h0)] (F + v: the centroid of
//! vertex v's face), crossing ambo's keys h0, next(twin h0), twin h0,
//! next(h0), one key per edge of J. Kis ([`super::kis`]) keeps J's vertices
//! (join's centroids), adds one apex per face of J, at
//! [`super::kis::apex_of`] over the face's centroid (its four corners summed
//! from w₀), and lays per corner k the triangle [w_k, w_{k+1}, apex] whose
//! sides lie on J's edge of corner k, the spoke of corner k + 1 and the
//! spoke of corner k. The same faces, vertices and key pairs in the same
//! order as the composition, so the same bits
//! (`fused_builds_are_their_compositions`); holes, point-spheres and traced
//! builds (face parents) take the composition.
//!
//! **Needle.** The dual D's face v ([`crate::schemes::dual`]) goes round
//! input vertex v from `v_out[v]`: corners g₀, g₁ = twin(prev g₀), … at
//! the centroids of face(g_j), crossing the input's edge of prev g_j (one
//! edge of D each). Kis keeps D's vertices (the input's face centroids),
//! adds one apex per vertex v over D's face, and lays per corner j the
//! triangle [face(g_j), face(g_{j+1}), apex] on D's edge of corner j, the
//! spoke of g_{j+1} and the spoke of g_j; the same bits as the composition
//! on the same terms as meta.

use super::build::{reserve, reserve_from, In, Out};
use super::dual_ambo::{centroids, first_side, join};
use super::kis::{apex_of, kis};
use crate::budget::Counts;
use crate::error::Result;
use crate::schemes::dual::dual;
use crate::mesh::Mesh;
use crate::schemes::hosts::{check_output_size, fusable};
use glam::DVec3;

/// `kis(&join(m)?, None)`, the same output and errors.
pub(crate) fn meta(m: &Mesh) -> Result<Mesh> {
    if !fusable(m) {
        return kis(&join(m)?, None);
    }
    crate::cancel::check()?;
    let c = In::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // join's checks, then kis's on join's counts (V + F, 2E, E)
    reserve("ambo", m, ne, 2 * ne, nf + nv)?;
    check_output_size("dual", 2 * nh, nf + nv)?;
    reserve_from("kis", &Counts::plain((nf + nv) as u64, 2 * ne as u64, ne as u64), nf + nv + ne, 6 * ne, 4 * ne)?;
    let (next, vert, face) = (c.next, c.vert, c.face);
    let mut pos = centroids(&c)?;
    pos.reserve_exact(ne);
    let ring = |e: usize| {
        let h0 = first_side(&c, e) as usize;
        let t0 = h0 ^ 1;
        let w = [face[h0], nf as u32 + vert[h0], face[t0], nf as u32 + vert[t0]];
        (w, [h0, next[t0] as usize, t0, next[h0] as usize])
    };
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let a = apex_over(&ring(e).0.map(|w| pos[w as usize]));
        pos.push(a);
    }
    // keys: J's edges by ambo's key g, then the spoke of corner k of J's face e, nh + 4e + k
    let spoke = |e: usize, k: usize| (nh + 4 * e + k % 4) as u32;
    let mut out = Out::new(pos, nh + 4 * ne, 4 * ne, 12 * ne);
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (w, key) = ring(e);
        let a = (nf + nv + e) as u32;
        for k in 0..4 {
            out.face([(w[k], key[k] as u32), (w[(k + 1) % 4], spoke(e, k + 1)), (a, spoke(e, k))]);
        }
    }
    out.finish("kis")
}

/// Kis's apex over a polygon whose corners are at `p` (in cycle order from
/// its first corner), as kis computes it from the polygon's centroid.
fn apex_over(p: &[DVec3]) -> DVec3 {
    let cen: DVec3 = p.iter().copied().sum::<DVec3>() / p.len() as f64;
    apex_of(cen, || p.iter().copied())
}

/// `kis(&dual(m)?, None)` (needle), the same output and errors.
pub(crate) fn needle(m: &Mesh) -> Result<Mesh> {
    if !fusable(m) {
        return kis(&dual(m)?, None);
    }
    crate::cancel::check()?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    // the dual's check, then kis's on the dual's counts (F, E, V)
    check_output_size("dual", nh, nf)?;
    reserve_from("kis", &Counts::plain(nf as u64, ne as u64, nv as u64), nf + nv, ne + nh, nh)?;
    let (prev, face) = (&m.he_prev, &m.he_face);
    let mut pos = crate::schemes::dual::centroids(m)?;
    pos.reserve_exact(nv);
    // the rotation of v from v_out[v]: g, twin(prev g), … (as the dual walks it)
    let rotation = |v: usize, out: &mut Vec<u32>| crate::schemes::dual_walk::rotation(&m.he_next, m.v_out[v], out);
    let (mut ring, mut p) = (Vec::new(), Vec::new());
    for v in 0..nv {
        crate::cancel::poll(v)?;
        rotation(v, &mut ring);
        p.clear();
        p.extend(ring.iter().map(|&g| pos[face[g as usize] as usize]));
        let a = apex_over(&p);
        pos.push(a);
    }
    // keys: D's edges by the input's edge, then the spoke of corner g, ne + g
    let spoke = |g: u32| ne as u32 + g;
    let mut out = Out::new(pos, ne + nh, nh, 3 * nh);
    for v in 0..nv {
        crate::cancel::poll(v)?;
        rotation(v, &mut ring);
        let (k, a) = (ring.len(), (nf + v) as u32);
        for j in 0..k {
            let (g, g1) = (ring[j], ring[(j + 1) % k]);
            out.face([(face[g as usize], prev[g as usize] >> 1), (face[g1 as usize], spoke(g1)), (a, spoke(g))]);
        }
    }
    out.finish("kis")
}
