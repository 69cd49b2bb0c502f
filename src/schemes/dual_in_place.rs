//! The dual of a closed mesh the caller gives up (a previous level of a
//! multi-level call), written over the input's own columns (issue 19's
//! memory target: at most twice the exported arrays during a level).
//!
//! The dual is as large as its input, so building it beside its input, as
//! [`super::dual`] does, held both: 3.2× the exported arrays from the second
//! level on. Here the input's `he_prev` goes first (the walk rotates with
//! `he_next` alone), the centroids replace the positions, and only the
//! output's vertex column is new; every other output column takes over an
//! input column once that column's last read is done:
//!
//! | output column | written into | by |
//! | --- | --- | --- |
//! | `he_vert` | a new column | the walk: `face(h)` at the id of corner h |
//! | `he_next` | input `he_vert` | the walk: the id of the next corner around v |
//! | `f_start` | input `v_out` | the walk: the id of v's first corner |
//! | `v_out` | input `f_start` | the walk: each face's first corner |
//! | `he_face`, `he_prev` | input `he_face`, `he_next` | the output faces walked from `f_start` |
//!
//! Measured (`examples/peak_levels.rs`, `examples/ab_dual_owned.rs`): 105
//! bytes per output face on the 100k-quad torus from the second level on,
//! 1.64× the exported arrays (1.92× at the sphere's triangle levels).
//! Time, from Python, `dual(iterations=3)` on that torus, one thread: first
//! calls in a fresh process 18.3 → 16.8 ms (no fresh output columns to
//! fault in), repeated warm calls 10.8 → 13.4 ms (this walk collects each
//! rotation backwards through `he_next` and makes one more pass over the
//! output faces: 4.2 ms per level against the borrowed dual's 2.9).
//!
//! The numbering is the one-pass walk's ([`super::dual`]'s `step_one_pass`,
//! vertices in order, each from `v_out` in rotation order, edges numbered by
//! first crossing), so the output is the borrowed path's, bit for bit (the
//! tests compare them).

use super::dual_walk::faces_and_prev;
use super::level::{Level, Request};
use crate::error::Result;
use crate::mesh::{Columns, Mesh, NONE};

/// [`super::dual::dual_level`] on an input the caller gives up (a previous level of a
/// multi-level call), the same output bit for bit: a closed mesh without
/// point-spheres, asked for no stencils or origins, is dualized over its own
/// columns ([`dual_in_place`]); an open one, or one asked for stencils or
/// origins, lends its columns to the open walk (`dual_open.rs`); a mesh
/// with point-spheres is [`super::dual::dual_level`]'s.
pub fn dual_level_owned(m: Mesh, req: &Request) -> Result<Level> {
    crate::cancel::check()?;
    if m.has_point_spheres() {
        return super::dual::dual_level(&m, req);
    }
    if req.stencils || req.origins || m.n_holes() > 0 {
        return super::dual_open::open_dual_level(super::dual_open::Given::Owned(m), req);
    }
    let (nv, nf) = (m.n_vertices(), m.n_faces());
    let out = dual_in_place(m)?;
    super::dual::record_parents(nv, nf);
    Ok(Level::plain(out))
}

/// The dual of `m` (closed, without point-spheres: the caller checks), its
/// columns reused.
fn dual_in_place(m: Mesh) -> Result<Mesh> {
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    super::hosts::check_output_size("dual", nh, nf)?;
    let Mesh { pos, mut v_out, he_next: mut next, he_prev, he_vert: mut vert, he_face: mut face, mut f_start, f_hole } = m;
    // the walk below rotates with `next` alone
    drop(he_prev);
    drop(f_hole);
    let cpos = super::dual::centroids_of(&f_start, &next, &vert, &pos)?;
    drop(pos);
    // The walk. Around vertex v the corners come in rotation order h₀, h₁, …
    // (h_{j+1} = prev(h_j) ^ 1; collected backwards with rot⁻¹(g) =
    // next(g ^ 1)). Corner h_j's side crosses edge(prev h_j) = h_{j+1} >> 1:
    // its first crossing numbers the output edge, the second is the twin
    // (`slot`, as `DualWalk` keys it).
    let mut out_vert = vec![0u32; nh];
    let mut slot = vec![0u32; nh / 2];
    let (mut n_out, mut cyc, mut ids) = (0u32, Vec::new(), Vec::new());
    f_start.fill(NONE); // becomes v_out: each centroid's first corner
    for v in 0..nv {
        crate::cancel::poll(v)?;
        super::dual_walk::rotation(&next, v_out[v], &mut cyc);
        ids.clear();
        let k = cyc.len();
        for j in 0..k {
            let (h, after) = (cyc[j], if j + 1 < k { cyc[j + 1] } else { cyc[0] });
            let i = super::dual_walk::crossing(&mut slot[(after >> 1) as usize], &mut n_out);
            ids.push(i);
            let f = face[h as usize];
            out_vert[i as usize] = f;
            let w = &mut f_start[f as usize];
            if *w == NONE {
                *w = i;
            }
        }
        for j in 1..k {
            vert[ids[j - 1] as usize] = ids[j];
        }
        vert[ids[k - 1] as usize] = ids[0];
        v_out[v] = ids[0];
    }
    drop(slot);
    super::dual_walk::all_crossed(nh, n_out)?;
    let (out_next, out_f_start, out_v_out) = (vert, v_out, f_start);
    // he_face into the input's `face` and he_prev into its `next` (neither
    // read any more)
    faces_and_prev(&out_next, &out_f_start, &mut face, &mut next)?;
    let out_prev = next;
    crate::cancel::check()?;
    Mesh::from_columns(Columns { pos: cpos, v_out: out_v_out, he_next: out_next, he_prev: out_prev, he_vert: out_vert, he_face: face, f_start: out_f_start, f_hole: vec![false; nv] })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The owned level (written over the input's columns) is the borrowed
    /// one, every column and position bit: closed inputs of the corpus
    /// (self-loops, one-gons, two-gons, valence 1 and 2), a torus, a
    /// Sierpinski output, a level's output given up again, and the inputs it
    /// hands to the borrowed path (open, point-spheres).
    #[test]
    fn owned_level_equals_the_borrowed_one() {
        use crate::schemes::hosts::test_meshes::{owned_level_cases, position_bits as bits};
        let mut cases = owned_level_cases();
        cases.push(("sierpinski".into(), crate::schemes::sierpinski::sierpinski_iterated(&crate::primitives::cube(), 2).unwrap()));
        let req = Request::plain();
        let mut in_place = 0;
        for (name, m) in cases {
            let a = crate::schemes::dual::dual_level(&m, &req).unwrap().mesh;
            in_place += (m.n_holes() == 0 && !m.has_point_spheres()) as usize;
            let b = dual_level_owned(m.clone(), &req).unwrap().mesh;
            assert_eq!(a, b, "{name}");
            assert_eq!(bits(&a), bits(&b), "{name}");
            let c = crate::schemes::dual::dual_level(&a, &req).unwrap().mesh;
            let d = dual_level_owned(a, &req).unwrap().mesh;
            assert_eq!(c, d, "{name} level 2");
            assert_eq!(bits(&c), bits(&d), "{name} level 2");
        }
        assert!(in_place >= 10, "the cases must reach the in-place path: {in_place}");
    }
}
