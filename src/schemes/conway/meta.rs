//! Meta (`m` = `kj`): kis of join in one pass, without join's mesh J
//! (issue 16: J was built only for kis to fan its faces; meta was the
//! slowest Conway row per output corner after snub and volute).
//!
//! J's face e ([`super::dual_ambo::join`]) goes round ambo's vertex e from
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

use super::build::{reserve, reserve_from, In, Out};
use super::dual_ambo::{centroids, first_side, join};
use super::kis::{apex_of, kis};
use crate::budget::Counts;
use crate::error::Result;
use crate::mesh::{Mesh, POINT};
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `kis(&join(m)?, None)`, the same output and errors.
pub(crate) fn meta(m: &Mesh) -> Result<Mesh> {
    if m.n_faces() == 0 || m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) || crate::schemes::face_parents::recording() {
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
        let p = ring(e).0.map(|w| pos[w as usize]);
        let cen: DVec3 = p.iter().copied().sum::<DVec3>() / 4.0;
        let a = apex_of(cen, || p.into_iter());
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
