//! The schemes whose every output vertex is born inside one input face:
//! each output corner takes its vertex's value, that face's mask of the
//! face's corner values (generic rule 1).

use super::{exported_rows, face_means, layout};
use crate::error::Result;
use crate::mesh::Mesh;

/// Per-output-vertex rows gathered onto `out`'s exported corners.
fn gather(out: &Mesh, vrows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    if vrows.len() != out.n_vertices() * k {
        return Ok(None);
    }
    exported_rows(out, k, |g, o| {
        for (h, o) in super::corners(out, g).zip(o.chunks_exact_mut(k.max(1))) {
            let v = out.he_vert[h as usize] as usize;
            o.copy_from_slice(&vrows[v * k..(v + 1) * k]);
        }
        true
    })
}

/// Doo-Sabin: output vertex `c` is the corner point of layout corner `c`,
/// Doo & Sabin's mask over its face ([`crate::schemes::doo_sabin`]).
pub fn doo_sabin(input: &Mesh, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    let pv = crate::schemes::doo_sabin::face_masks(input, &fl, rows, k, |c, _| c)?;
    gather(out, &pv, k)
}

/// Dual: output vertex `f` is the centroid of face `f`, the mean of its
/// corners.
pub fn dual(input: &Mesh, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    gather(out, &face_means(&fl, rows, k)?, k)
}

/// Honeycomb: output vertex `h` is eq. 2's point of half-edge `h`, over its
/// face's edge points read in that face ([`crate::schemes::honeycomb`]).
pub fn honeycomb(input: &Mesh, out: &Mesh, t: f64, tension: Option<f64>, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    let pv = crate::schemes::honeycomb::face_masks(input, &fl, t, tension, rows, k, |c, _| c)?;
    gather(out, &pv, k)
}
