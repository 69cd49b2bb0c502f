//! The schemes whose output vertices lie on input edges or at input
//! vertices: such a point has one value per face beside it, so each output
//! corner reads it in its home face (generic rules 2 and 3): the input face
//! its output face lies in, or, for a face around an old vertex, the face
//! whose corner the corner's outgoing side cuts.

use super::{corners, exported_rows, face_means, layout, lerp};
use crate::error::Result;
use crate::mesh::Mesh;
use crate::schemes::hosts::{FaceLayout, MIN_LEN};
use rayon::prelude::*;

/// Per layout corner `c`: the point at `t` along its side in its face,
/// `(1 − t) x_c + t x_next(c)`.
fn along_sides(input: &Mesh, fl: &FaceLayout, rows: &[f64], k: usize, t: f64) -> Result<Vec<f64>> {
    let next = &input.he_next;
    let mut out = vec![0.0; rows.len()];
    out.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(c, o)| {
        let cn = fl.cidx[next[fl.fh[c] as usize] as usize] as usize;
        lerp(o, &rows[c * k..(c + 1) * k], &rows[cn * k..(cn + 1) * k], t);
    });
    crate::cancel::check()?;
    Ok(out)
}

/// Row `i` of `a`.
#[inline]
fn row(a: &[f64], i: usize, k: usize) -> &[f64] {
    &a[i * k..(i + 1) * k]
}

/// Simplest: output half-edge `2c` is F-face corner `c` (the midpoint of
/// corner `c`'s side, in its face); `2c + 1` is the V-face corner at the
/// midpoint of `x = next(fh[c])`'s side, whose outgoing side cuts the
/// corner of `x`'s face, so it reads that midpoint in `x`'s face
/// ([`crate::schemes::simplest`]'s numbering).
pub fn simplest(input: &Mesh, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    if out.n_halfedges() != 2 * input.n_halfedges() {
        return Ok(None);
    }
    let mid = along_sides(input, &fl, rows, k, 0.5)?;
    let next = &input.he_next;
    exported_rows(out, k, |g, o| {
        for (h, o) in corners(out, g).zip(o.chunks_exact_mut(k)) {
            let c = (h >> 1) as usize;
            let (x, src) = if h & 1 == 0 {
                (fl.fh[c], c)
            } else {
                let x = next[fl.fh[c] as usize];
                (x, fl.cidx[x as usize] as usize)
            };
            if out.he_vert[h as usize] != x >> 1 {
                return false;
            }
            o.copy_from_slice(row(&mid, src, k));
        }
        true
    })
}

/// Vertex truncation at `ratio`: old face `f`'s image lists, per corner `c`
/// (half-edge `h`), the cut point of `h` near its tail and (below 1/2) the
/// one near its head, read along `h`'s side in `f`; the face of vertex `v`
/// lists the cut points of its outgoing half-edges `g` in rotation order,
/// each read in `g`'s face, whose corner its outgoing side cuts
/// ([`crate::schemes::vertex_truncation`]'s numbering).
pub fn truncation(input: &Mesh, out: &Mesh, ratio: f64, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    let merge = ratio == 0.5;
    let (nf, nv) = (input.n_faces(), input.n_vertices());
    if out.n_faces() != nf + nv {
        return Ok(None);
    }
    let near_tail = along_sides(input, &fl, rows, k, ratio)?;
    let near_head = if merge { Vec::new() } else { along_sides(input, &fl, rows, k, 1.0 - ratio)? };
    let prev = &input.he_prev;
    let point = |h: u32| if merge { h >> 1 } else { h };
    exported_rows(out, k, |g, o| {
        let mut rows_out = o.chunks_exact_mut(k);
        if g < nf {
            let per = if merge { 1 } else { 2 };
            for (j, h) in corners(out, g).enumerate() {
                let c = fl.off[g] as usize + j / per;
                if c >= fl.off[g + 1] as usize {
                    return false;
                }
                let hin = fl.fh[c];
                let (want, src) = if j % per == 0 { (point(hin), &near_tail) } else { (hin ^ 1, &near_head) };
                let (Some(o), true) = (rows_out.next(), out.he_vert[h as usize] == want) else {
                    return false;
                };
                o.copy_from_slice(row(src, c, k));
            }
        } else {
            let mut x = input.v_out[g - nf];
            for h in corners(out, g) {
                let Some(o) = rows_out.next() else { return false };
                if out.he_vert[h as usize] != point(x) {
                    return false;
                }
                o.copy_from_slice(row(&near_tail, fl.cidx[x as usize] as usize, k));
                x = prev[x as usize] ^ 1;
            }
        }
        true
    })
}

/// √3: output triangle `h` is `[vert h, c_g, c_f]` (`f` = face of `h`, `g`
/// of its twin); the centroids take their face's mean, the old vertex its
/// value in `g`, where its outgoing side (the spoke to `c_g`) lies
/// ([`crate::schemes::sqrt3`]'s numbering).
pub fn sqrt3(input: &Mesh, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    let (nv, nh) = (input.n_vertices() as u32, input.n_halfedges());
    if out.n_faces() != nh {
        return Ok(None);
    }
    let means = face_means(&fl, rows, k)?;
    let (next, vert, face) = input.halfedge_columns();
    exported_rows(out, k, |h, o| {
        let (f, g) = (face[h], face[h ^ 1]);
        let want = [vert[h], nv + g, nv + f];
        let a = fl.cidx[next[h ^ 1] as usize] as usize;
        let src = [row(rows, a, k), row(&means, g as usize, k), row(&means, f as usize, k)];
        let mut n = 0;
        for ((x, o), (w, s)) in corners(out, h).zip(o.chunks_exact_mut(k)).zip(want.iter().zip(src)) {
            if out.he_vert[x as usize] != *w {
                return false;
            }
            o.copy_from_slice(s);
            n += 1;
        }
        n == 3
    })
}

/// Sierpinski on a mesh without self-loops: the piece of half-edge `h`
/// (output face `h`) is `[m(h), head h, m(next h)]`, all read in `h`'s face;
/// the back face of each vertex (its cone, ordered by lowest outgoing
/// half-edge, walked by `σ(b) = next(twin b)`) has two corners at each
/// midpoint `m(b)`: the self-loop's, read in `b`'s face (where its incoming
/// side, the previous cut, lies), then the cut's, read in `twin b`'s face
/// ([`crate::schemes::sierpinski`]'s numbering). `None` on self-loops.
pub fn sierpinski(input: &Mesh, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fl) = layout(input, rows, k)? else { return Ok(None) };
    let (nv, nh) = (input.n_vertices(), input.n_halfedges());
    let (next, vert, _) = input.halfedge_columns();
    if (0..nh / 2).into_par_iter().any(|e| vert[2 * e] == vert[2 * e + 1]) {
        return Ok(None);
    }
    // cones in order of their lowest half-edge: each vertex's
    let mut lowest = vec![u32::MAX; nv];
    for h in (0..nh as u32).rev() {
        lowest[vert[h as usize] as usize] = h;
    }
    let cones: Vec<u32> = (0..nh as u32).filter(|&h| lowest[vert[h as usize] as usize] == h).collect();
    if out.n_faces() != nh + cones.len() || out.n_vertices() != nv + nh / 2 {
        return Ok(None);
    }
    let mid = along_sides(input, &fl, rows, k, 0.5)?;
    let m = |h: u32| (nv + (h >> 1) as usize) as u32;
    let ci = |h: u32| fl.cidx[h as usize] as usize;
    exported_rows(out, k, |g, o| {
        let mut rows_out = o.chunks_exact_mut(k);
        if g < nh {
            let h = g as u32;
            let hn = next[g];
            let want = [m(h), vert[hn as usize], m(hn)];
            let src = [row(&mid, ci(h), k), row(rows, ci(hn), k), row(&mid, ci(hn), k)];
            let mut n = 0;
            for ((x, o), (w, s)) in corners(out, g).zip(&mut rows_out).zip(want.iter().zip(src)) {
                if out.he_vert[x as usize] != *w {
                    return false;
                }
                o.copy_from_slice(s);
                n += 1;
            }
            return n == 3 && rows_out.next().is_none();
        }
        let mut b = cones[g - nh];
        for (j, x) in corners(out, g).enumerate() {
            let Some(o) = rows_out.next() else { return false };
            if out.he_vert[x as usize] != m(b) {
                return false;
            }
            if j % 2 == 0 {
                o.copy_from_slice(row(&mid, ci(b), k));
            } else {
                o.copy_from_slice(row(&mid, ci(b ^ 1), k));
                b = next[(b ^ 1) as usize];
            }
        }
        true
    })
}
