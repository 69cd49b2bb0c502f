//! The direct constructor: columns filled by the caller (a scheme's index
//! arithmetic), taken as they are after a proportional, parallel check.
//!
//! [`Mesh::from_corner_twins`] pairs corners, numbers half-edges and picks
//! every vertex's first corner; a scheme that knows its output's structure
//! can compute all of that in closed form and write the columns at once
//! (issue 19: the builder was most of a large level). The mesh module stays
//! scheme-agnostic: it hands out exactly-sized columns ([`Columns`]) and
//! checks what it gets back.

use super::{Mesh, NONE, POINT};
use crate::error::{MeshError, Result};
use glam::DVec3;
use rayon::prelude::*;

/// The columns of a mesh under construction, exactly sized, with every
/// entry still to be written by the caller (see [`Mesh`] for their meaning).
pub struct Columns {
    pub pos: Vec<DVec3>,
    pub v_out: Vec<u32>,
    pub he_next: Vec<u32>,
    pub he_prev: Vec<u32>,
    pub he_vert: Vec<u32>,
    pub he_face: Vec<u32>,
    pub f_start: Vec<u32>,
    pub f_hole: Vec<bool>,
}

impl Columns {
    /// Columns for `n_halfedges` half-edges and `n_faces` faces around the
    /// given positions. The integer columns are zeroed (calloc'd, so their
    /// pages are first touched by the caller's parallel fill, not here).
    pub fn new(pos: Vec<DVec3>, n_halfedges: usize, n_faces: usize) -> Columns {
        let nv = pos.len();
        Columns {
            pos,
            v_out: vec![0; nv],
            he_next: vec![0; n_halfedges],
            he_prev: vec![0; n_halfedges],
            he_vert: vec![0; n_halfedges],
            he_face: vec![0; n_halfedges],
            f_start: vec![0; n_faces],
            f_hole: vec![false; n_faces],
        }
    }
}

/// Elements per task of the range check.
const CHUNK: usize = 1 << 15;

/// Whether every entry of `col` is below `bound` (point-sphere links, which
/// carry [`POINT`], are allowed where `point_below` is given), in parallel.
fn in_range(col: &[u32], bound: usize, point_below: Option<usize>) -> bool {
    col.par_chunks(CHUNK).all(|ch| match point_below {
        // branch-free folds vectorize; the point case is rare
        None => (ch.iter().fold(0u32, |a, &x| a.max(x)) as usize) < bound,
        Some(pb) => ch.iter().all(|&x| if x & POINT != 0 { ((x & !POINT) as usize) < pb } else { (x as usize) < bound }),
    }) || col.is_empty()
}

impl Mesh {
    /// Takes columns a scheme filled by index arithmetic. Checked here, in
    /// time proportional to the size and in parallel: column lengths, an
    /// even number of half-edges, and every reference in range (so no later
    /// lookup can fail); debug builds run the full [`Mesh::validate`].
    /// Everything else (the invariants I2–I9) is the caller's contract,
    /// which its tests check with `validate`.
    pub fn from_columns(c: Columns) -> Result<Mesh> {
        let (nv, nh, nf) = (c.pos.len(), c.he_next.len(), c.f_start.len());
        let bad = |what: &str| Err(MeshError::Invariant(format!("direct build: {what}")));
        if c.v_out.len() != nv || c.he_prev.len() != nh || c.he_vert.len() != nh || c.he_face.len() != nh || c.f_hole.len() != nf || nh % 2 != 0 {
            return bad("column lengths disagree");
        }
        if nv > super::MAX_ELEMENTS || nh > super::MAX_ELEMENTS || nf > super::MAX_ELEMENTS {
            return bad("too many elements for 31-bit ids");
        }
        let ok = || {
            let (a, b) = rayon::join(|| in_range(&c.he_next, nh, None) && in_range(&c.he_prev, nh, None), || in_range(&c.he_vert, nv, None) && in_range(&c.he_face, nf, None));
            let (d, e) = rayon::join(|| in_range(&c.v_out, nh, Some(nf)), || in_range(&c.f_start, nh, Some(nv)));
            a && b && d && e
        };
        if !ok() {
            return bad("a reference is out of range");
        }
        debug_assert!(!c.v_out.contains(&NONE));
        let m = Mesh {
            pos: c.pos,
            v_out: c.v_out,
            he_next: c.he_next,
            he_prev: c.he_prev,
            he_vert: c.he_vert,
            he_face: c.he_face,
            f_start: c.f_start,
            f_hole: c.f_hole,
        };
        #[cfg(debug_assertions)]
        m.validate()?;
        Ok(m)
    }

    /// Gives the columns back for reuse (e.g. as the next level's scratch).
    pub fn into_columns(self) -> Columns {
        Columns {
            pos: self.pos,
            v_out: self.v_out,
            he_next: self.he_next,
            he_prev: self.he_prev,
            he_vert: self.he_vert,
            he_face: self.he_face,
            f_start: self.f_start,
            f_hole: self.f_hole,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    #[test]
    fn columns_round_trip_and_bad_references_are_refused() {
        let m = primitives::cube();
        let back = Mesh::from_columns(m.clone().into_columns()).unwrap();
        assert_eq!(back, m);
        let mut c = m.clone().into_columns();
        c.he_next[3] = c.he_next.len() as u32;
        assert!(Mesh::from_columns(c).unwrap_err().to_string().contains("out of range"));
        let mut c = m.clone().into_columns();
        c.he_face.pop();
        assert!(Mesh::from_columns(c).unwrap_err().to_string().contains("lengths"));
        assert_eq!(Mesh::from_columns(Mesh::new().into_columns()).unwrap(), Mesh::new());
    }
}
