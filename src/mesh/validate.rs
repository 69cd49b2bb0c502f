//! `validate()`: every structural invariant of `docs/internals.md`, checked in
//! O(size), reporting the first one broken.

use super::{Mesh, NONE, POINT};
use crate::error::{MeshError, Result};
use rayon::prelude::*;

impl Mesh {
    /// Checks every invariant; `Err(MeshError::Invariant)` names the first
    /// broken one and the element. Run by the tests after every operator.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(MeshError::Invariant(m));
        let (nv, nh, nf) = (self.n_vertices(), self.n_halfedges(), self.n_faces());
        // I1 column lengths
        if self.v_out.len() != nv
            || self.he_prev.len() != nh
            || self.he_vert.len() != nh
            || self.he_face.len() != nh
            || self.f_hole.len() != nf
            || nh % 2 != 0
        {
            return bad("I1: column lengths disagree".into());
        }
        // I2–I4 per half-edge, in parallel over ranges; the message is the
        // one of the lowest half-edge, as in a sequential sweep
        if let Some(m) = (0..nh.div_ceil(CHUNK))
            .into_par_iter()
            .find_map_first(|k| self.check_halfedges(k * CHUNK..((k + 1) * CHUNK).min(nh)).err())
        {
            return bad(m);
        }
        // I5 face starts, and each face's cycle covers exactly its half-edges
        if !self.face_cycles_partition_halfedges() {
            self.check_face_cycles()?;
        }
        // I6–I7 per vertex, like I2–I4
        if let Some(m) = (0..nv.div_ceil(CHUNK))
            .into_par_iter()
            .find_map_first(|k| self.check_vertices(k * CHUNK..((k + 1) * CHUNK).min(nv)).err())
        {
            return bad(m);
        }
        // I8 one disk around every vertex
        self.check_vertex_umbrellas()
            .map_err(|e| MeshError::Invariant(format!("I8: {e}")))?;
        // I9 χ of every component is even (closed orientable surfaces)
        if let Some(c) = self.component_capped_euler_characteristics().iter().position(|c| c % 2 != 0) {
            return bad(format!("I9: component {c} has odd Euler characteristic"));
        }
        Ok(())
    }
}

/// Half-edges (or vertices) per task of the parallel checks.
const CHUNK: usize = 1 << 14;

impl Mesh {
    /// I2–I4 on a range of half-edges (columns of consistent lengths).
    fn check_halfedges(&self, range: std::ops::Range<usize>) -> std::result::Result<(), String> {
        let (nv, nh, nf) = (self.n_vertices(), self.n_halfedges(), self.n_faces());
        for h in range {
            let (n, p, v, f) = (self.he_next[h], self.he_prev[h], self.he_vert[h], self.he_face[h]);
            if n as usize >= nh || p as usize >= nh || v as usize >= nv || f as usize >= nf {
                return Err(format!("I2: half-edge {h} has an out-of-range or missing reference"));
            }
            if self.he_prev[n as usize] as usize != h || self.he_next[p as usize] as usize != h {
                return Err(format!("I2: half-edge {h}: next/prev are not inverse"));
            }
            // I3 faces are closed under next
            if self.he_face[n as usize] != f {
                return Err(format!("I3: half-edge {h} and its next lie in different faces"));
            }
            // I4 head of h is the tail of next(h), and the tail of twin(h)
            if self.he_vert[n as usize] != self.he_vert[h ^ 1] {
                return Err(format!("I4: half-edge {h}: head is not the tail of its next"));
            }
        }
        Ok(())
    }

    /// I6–I7 on a range of vertices.
    fn check_vertices(&self, range: std::ops::Range<usize>) -> std::result::Result<(), String> {
        let (nh, nf) = (self.n_halfedges(), self.n_faces());
        for v in range {
            let o = self.v_out[v];
            if o == NONE {
                return Err(format!("I6: vertex {v} has no corner"));
            }
            if o & POINT != 0 {
                let f = (o & !POINT) as usize;
                if f >= nf || self.f_start[f] != (POINT | v as u32) {
                    return Err(format!("I6: point-sphere vertex {v} and face {f} do not refer to each other"));
                }
            } else if o as usize >= nh || self.he_vert[o as usize] as usize != v {
                return Err(format!("I6: vertex {v}'s outgoing half-edge does not start at it"));
            }
            // I7 positions are finite
            if !self.pos[v].is_finite() {
                return Err(format!("I7: vertex {v} has a non-finite position"));
            }
        }
        Ok(())
    }

    /// I5 in parallel, as a yes/no answer, assuming I2–I4: then `next` is a
    /// permutation whose cycles stay in one face, so the face cycles are
    /// disjoint and never revisit a half-edge, and they cover every
    /// half-edge exactly when their lengths add up to H. When it says no,
    /// [`Mesh::check_face_cycles`] names the problem.
    fn face_cycles_partition_halfedges(&self) -> bool {
        let (nv, nh, nf) = (self.n_vertices(), self.n_halfedges(), self.n_faces());
        let cycle_len = |f: usize| -> Option<usize> {
            let s = self.f_start[f];
            if s == NONE {
                return None;
            }
            if s & POINT != 0 {
                let v = (s & !POINT) as usize;
                let ok = v < nv && self.v_out[v] == (POINT | f as u32) && !self.f_hole[f];
                return ok.then_some(0);
            }
            if s as usize >= nh || self.he_face[s as usize] as usize != f {
                return None;
            }
            let mut h = s;
            let mut k = 0;
            loop {
                k += 1;
                h = self.he_next[h as usize];
                if h == s {
                    return Some(k);
                }
            }
        };
        (0..nf).into_par_iter().with_min_len(CHUNK).map(cycle_len).sum::<Option<usize>>() == Some(nh)
    }

    /// I5, sequentially, naming the first problem.
    fn check_face_cycles(&self) -> Result<()> {
        let (nv, nh, nf) = (self.n_vertices(), self.n_halfedges(), self.n_faces());
        let mut seen = vec![false; nh];
        let mut covered = 0usize;
        for f in 0..nf {
            let s = self.f_start[f];
            if s == NONE {
                return Err(MeshError::Invariant(format!("I5: face {f} has no start")));
            }
            if s & POINT != 0 {
                let v = (s & !POINT) as usize;
                if v >= nv || self.v_out[v] != (POINT | f as u32) {
                    return Err(MeshError::Invariant(format!("I5: point-sphere face {f} and vertex {v} do not refer to each other")));
                }
                if self.f_hole[f] {
                    return Err(MeshError::Invariant(format!("I5: point-sphere face {f} is marked as a hole")));
                }
                continue;
            }
            if s as usize >= nh || self.he_face[s as usize] as usize != f {
                return Err(MeshError::Invariant(format!("I5: face {f} starts at a half-edge of another face")));
            }
            let mut h = s as usize;
            loop {
                if seen[h] {
                    return Err(MeshError::Invariant(format!("I5: half-edge {h} is reached twice walking face {f}")));
                }
                seen[h] = true;
                covered += 1;
                h = self.he_next[h] as usize;
                if h == s as usize {
                    break;
                }
            }
        }
        if covered != nh {
            return Err(MeshError::Invariant(format!(
                "I5: {} half-edges belong to no face cycle (first: {})",
                nh - covered,
                seen.iter().position(|&s| !s).unwrap_or(0)
            )));
        }
        Ok(())
    }
}
