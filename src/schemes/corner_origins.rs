//! Edge origins of the levels built with [`Mesh::from_corner_twins`]: a
//! scheme states the origin of every output corner's side, and the output
//! half-edge of each corner gives the edge it names.

use super::level::Origins;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};

/// The output half-edge of every corner of `out`, in the order the corners
/// were given to [`Mesh::from_corner_twins`] (faces keep their first
/// corner); a point-sphere face's one corner gets `NONE`.
pub(crate) fn corner_halfedges(out: &Mesh) -> Result<Vec<u32>> {
    let mut fh = Vec::with_capacity(out.n_halfedges() + out.n_faces());
    for (f, &s) in out.f_start.iter().enumerate() {
        crate::cancel::poll(f)?;
        if s & POINT != 0 {
            fh.push(NONE);
            continue;
        }
        let mut h = s;
        loop {
            fh.push(h);
            h = out.he_next[h as usize];
            if h == s {
                break;
            }
        }
    }
    Ok(fh)
}

/// Edge origins of a level from a rule per output corner: `of(c)` is the
/// origin of the edge on the side leaving corner `c` (corners in build
/// order, a point-sphere face's corner included). Each edge takes the rule of its
/// even half-edge's corner; the rules of its two sides must agree.
pub(crate) fn edge_origins_by_corner(out: &Mesh, o: &mut Origins, of: impl Fn(usize) -> (u8, u32)) -> Result<()> {
    let fh = corner_halfedges(out)?;
    let ne = out.n_edges();
    o.edge_kind = vec![0; ne];
    o.edge = vec![0; ne];
    for (c, &h) in fh.iter().enumerate() {
        crate::cancel::poll(c)?;
        if h != NONE && h & 1 == 0 {
            let (k, i) = of(c);
            o.edge_kind[(h >> 1) as usize] = k;
            o.edge[(h >> 1) as usize] = i;
        }
    }
    if cfg!(debug_assertions) {
        for (c, &h) in fh.iter().enumerate() {
            if h != NONE && h & 1 == 1 {
                let e = (h >> 1) as usize;
                debug_assert_eq!(of(c), (o.edge_kind[e], o.edge[e]), "the two sides of output edge {e} disagree on its origin");
            }
        }
    }
    Ok(())
}
