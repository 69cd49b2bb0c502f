//! Truncate, `dual(kis(dual(m)))` (Hart: `t = dkd`), without building the
//! first dual (issue 16: [`super::dual_kis`] already skips kis's mesh, but
//! truncate still built the dual D of m and its face layout only for
//! `dual_kis` to read them).
//!
//! D is read off m as [`dual`]'s one-pass walk lays it: its face v lists,
//! in m's rotation from `v_out[v]` (g → `rot g = twin prev g`), one corner
//! per outgoing half-edge g of v, at the centroid of face g (call it corner
//! g), so in D: tail g = face g, head g = face(rot g), next g = rot g,
//! prev g = `next(twin g)`, twin g = `next(twin prev g)`, and g's side
//! crosses the edge of prev g. D's face layout (`dual_kis`'s corner order)
//! is that walk's order: corner g's index k(g) is its rank in the walk, so
//! the corners of D's face v are the consecutive ranks of v's rotation.
//!
//! `dual_kis` over D then gives, per corner g (output vertex k(g)), the
//! centroid of kis's triangle `[face g, face(rot g), apex v]`, the apex over
//! D's face v as [`super::kis::apex`] computes it (centroid of the ring of
//! face centroids, Newell normal, mean distance, in the ring's order); and
//! the faces:
//!
//! * around D's vertex f (face f of m; output face f), from the first kis
//!   corner of f in D's face order: the tail corner of T(g) (crossing the
//!   spoke of g) is followed by the head corner of T(prev g), that one
//!   (crossing D's edge of g, m's edge of prev g) by the tail corner of
//!   T(twin g);
//! * around the apex of D's face v (output face F + v): the ranks of v's
//!   rotation in turn, crossing the spoke of the next corner.
//!
//! Keys name edges only to number them by first crossing (`DualWalk`), so
//! any bijective renaming numbers them alike: D's edge of g is named by m's
//! edge of prev g, g's spoke by E + k(g). Positions are summed in the
//! composition's order (`dual.rs`'s face centroids, `kis::apex` over D's
//! face from its first corner, `dual_kis`'s triangle sums), so the output
//! is the composition's bit for bit: every column, vertex order, half-edge
//! numbering and position bits (the test below; `keyed::hashes`). Holes,
//! point-spheres and faceless meshes take the composition; a traced build
//! records the composition's two steps as one.

use super::build::reserve_from;
use super::dual_kis::{dual_kis, vertex_ring};
use crate::budget::Counts;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual::{centroids, dual};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `dual_kis(&dual(m)?)` (truncate), the same output, errors and face
/// parents.
pub(crate) fn truncate(m: &Mesh) -> Result<Mesh> {
    if m.n_faces() == 0 || m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) {
        return dual_kis(&dual(m)?);
    }
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    // the first dual's check
    check_output_size("dual", nh, nf)?;
    let (next, _, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let rot = |g: u32| prev[g as usize] ^ 1;
    // D's face layout: the rank k(g) of every corner, and where each face's
    // ranks start; D's triangles (valence-3 vertices of m) for its counts
    let mut k = vec![0u32; nh];
    let mut off = Vec::with_capacity(nv + 1);
    let mut f3 = 0u64;
    let mut r = 0u32;
    off.push(0u32);
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = m.v_out[v];
        let mut g = s;
        loop {
            k[g as usize] = r;
            r += 1;
            g = rot(g);
            if g == s {
                break;
            }
        }
        f3 += (r - off[v] == 3) as u64;
        off.push(r);
    }
    // kis's checks on D's counts (`Counts::of(D)`: D's self-loops cross
    // edges with one face on both sides), then the last dual's
    let loops = (0..ne).filter(|&e| face[2 * e] == face[2 * e + 1]).count() as u64;
    let dc = Counts::closed(nf as u64, ne as u64, nv as u64, f3, loops);
    reserve_from("kis", &dc, nf + nv, ne + nh, nh)?;
    check_output_size("dual", 2 * (ne + nh), nh)?;
    // D's positions, as the dual sums them
    let dp = centroids(m)?;
    // per face v of D: its ring of centroids (corner order), its centroid
    // and kis's apex over it, then the triangle centroids in corner order
    // (`dual_kis`: tail, head, apex, from zero); and the first kis corner
    // of every vertex of D in D's face order (tail corner of T(g) as 2g,
    // head corner as 2g + 1)
    let mut pos = Vec::with_capacity(nh);
    let mut first = vec![NONE; nf];
    let mut ring: Vec<DVec3> = Vec::new();
    for v in 0..nv {
        crate::cancel::poll(v)?;
        ring.clear();
        let s = m.v_out[v];
        let mut g = s;
        loop {
            let (t, d) = (face[g as usize] as usize, face[rot(g) as usize] as usize);
            ring.push(dp[t]);
            if first[t] == NONE {
                first[t] = 2 * g;
            }
            if first[d] == NONE {
                first[d] = 2 * g + 1;
            }
            g = rot(g);
            if g == s {
                break;
            }
        }
        // `Ctx::new(D)`'s centroid (`face_centroids`: a sum from zero)
        let cen = ring.iter().copied().sum::<DVec3>() / ring.len() as f64;
        let a = super::kis::apex_of(cen, || ring.iter().copied());
        let n = ring.len();
        for i in 0..n {
            let mut s = DVec3::ZERO;
            s += ring[i];
            s += ring[if i + 1 == n { 0 } else { i + 1 }];
            s += a;
            pos.push(s / 3.0);
        }
    }
    drop(dp);
    // keys: D's edge of g as m's edge of prev g, g's spoke as ne + k(g)
    let mut walk = DualWalk::new(pos, 2 * (ne + nh), nf + nv, ne + nh);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let last = vertex_ring(&mut walk, f, first[f], |g, head| {
            let gi = g as usize;
            if head {
                // head corner of T(g): crosses D's edge of g, then the tail
                // corner of T(twin g), twin g = next(twin prev g)
                (k[gi], (prev[gi] >> 1) as usize, 2 * next[(prev[gi] ^ 1) as usize])
            } else {
                // tail corner of T(g): crosses g's spoke, then the head
                // corner of T(prev g), prev g = next(twin g)
                (k[gi], ne + k[gi] as usize, 2 * next[gi ^ 1] + 1)
            }
        });
        walk.close(f, last);
    }
    drop(k);
    // the apex faces: D's face v's ranks in turn, each side crossing the
    // spoke of the next corner
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let (a, b) = (off[v], off[v + 1]);
        let mut last = NONE;
        for x in a..b {
            let n = if x + 1 == b { a } else { x + 1 };
            walk.put(nf + v, x, ne + n as usize, &mut last);
        }
        walk.close(nf + v, last);
    }
    let cols = walk.finish()?;
    if fp::recording() {
        // dual then dual_kis, composed (`face_parents::then`): face f is
        // born around D's vertex f (face f), face F + v around the apex of
        // D's face v (vertex v); vertex k(g) inside D's face tail g
        let face = (0..nf as u32).chain((0..nv as u32).map(|v| VERT | v)).collect();
        let vertex = (0..nv).flat_map(|v| std::iter::repeat(VERT | v as u32).take((off[v + 1] - off[v]) as usize)).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face, vertex }));
    }
    Mesh::from_columns(cols)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    fn composed(m: &Mesh) -> Result<Mesh> {
        dual_kis(&dual(m)?)
    }

    /// The one-pass truncate is the composition: the same columns and bits,
    /// face parents or error, on the scheme corpus (non-convex faces,
    /// self-loops, two-gons, one-gons, genus 3, point-spheres), open
    /// meshes, a Sierpinski and a Loop output, a jittered torus and genus
    /// 2, traced and untraced; and the comparison sees one ulp.
    #[test]
    fn truncate_is_its_composition() {
        let mut ms = crate::schemes::topmod::tests::meshes();
        ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
        ms.push(("sierpinski_cube", crate::schemes::sierpinski::sierpinski_iterated(&crate::primitives::cube(), 2).unwrap()));
        ms.push(("loop_cube", crate::schemes::loop_subdivision::loop_subdivision(&crate::primitives::cube()).unwrap()));
        ms.push(("jittered_torus", jittered_torus()));
        ms.push(("genus2", crate::primitives::genus_surface(2).unwrap()));
        ms.push(("genus3", crate::primitives::genus_surface(3).unwrap()));
        ms.extend(open_meshes());
        let fused_runs = ms.iter().filter(|(name, m)| check_fused(name, m, &truncate, &composed)).count();
        assert!(fused_runs >= 12, "one pass on {fused_runs} meshes");
    }
}
