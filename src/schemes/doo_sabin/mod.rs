//! Doo-Sabin subdivision (D. Doo & M. Sabin, "Behaviour of recursive division
//! surfaces near extraordinary points", CAD 10(6), 1978), one level.
//!
//! Mask: Doo & Sabin's weights. Corner k of an n-gon with corners
//! `x₀ … x_{n−1}` gets the new point `Σᵢ αᵢ₋ₖ xᵢ`, with
//! `α₀ = 1/4 + 5/(4n)` and `αᵢ = (3 + 2 cos(2πi/n))/(4n)` (i ≠ 0).
//! Computed in O(n) per face (one `sin_cos` per face, the multiples by
//! rotation) as
//! `x_k/4 + 3/(4n) Σ x + 1/(2n) (cos θ_k C + sin θ_k S)`, `θ_k = 2πk/n`,
//! `C = Σ cos θᵢ xᵢ`, `S = Σ sin θᵢ xᵢ`. The weights sum to 1 for n ≥ 2; a
//! one-gon's point is its vertex.
//!
//! Connectivity (the dual host): one new vertex per corner; each old n-gon
//! gives an n-gon of its corner points (F-face), each old edge a quad
//! (E-face) and each old valence-k vertex a k-gon (V-face). Self-loops and
//! two-gons need nothing special: a zero-length self-loop (Sierpinski
//! output) separates corners of two different faces, whose points differ,
//! so the loop opens into a tube (the Sierpinski paper, §6 and Fig. 11–14).
//!
//! Counts (H = 2E): V' = H, E' = 2H = 4E, F' = F + E + V; every new vertex is
//! 4-valent. Output vertex `c` is the corner `c` in face order; faces are
//! laid out `[F-faces | E-faces | V-faces]`.
//!
//! Stencils and correspondence ([`doo_sabin_level`]): the scheme is linear;
//! the row of corner k of an n-gon is `Σᵢ αᵢ₋ₖ xᵢ` (n terms). Origins: an
//! output element comes from the lowest-dimensional input element it lies
//! in: a corner point lies inside its face → (FACE, f) (not its vertex: it
//! is a point of the face's refinement, one per corner); the F-face of f →
//! (FACE, f), the E-face of e → (EDGE, e), the V-face of v → (VERTEX, v);
//! an F-face's sides lie inside f → (FACE, f), the other edges (between an
//! E-face and a V-face) cross edge e → (EDGE, e).
//!
//! # Open meshes ([`doo_sabin_level`])
//!
//! The boundary follows A. H. Nasri, "Polyhedral subdivision methods for
//! free-form surfaces", ACM TOG 6(1), 1987: the boundary polygon is refined
//! on its own as a uniform quadratic B-spline (Chaikin's corner cutting),
//! so the limit boundary is the quadratic B-spline curve of the input
//! boundary polygon. Each boundary edge a → b (a hole half-edge h) gets the
//! two Chaikin points `qa = ¾ a + ¼ b` and `qb = ¼ a + ¾ b`; the corner
//! points of real faces keep Doo & Sabin's mask (faces beside the boundary
//! included: Nasri instead adjusts the boundary faces' own corner points;
//! here they stay interior and the Chaikin points form an extra ring). The
//! E-face of a boundary edge is `[p, p', qb, qa]` (two corner points of
//! the real face, two Chaikin points); the V-face of a boundary vertex runs
//! through the corner points of its real faces and its two Chaikin points;
//! a hole of n corners becomes a hole of 2n corners, the Chaikin polygon
//! `[qa(h₀), qb(h₀), qa(h₁), …]`. With b boundary edges:
//!
//! ```text
//! V' = H + b,   E' = 4E + b,   F' = F_r + E + V real faces and the same holes
//! ```
//!
//! and χ = V − E + F_r is unchanged. Chaikin points come from their edge
//! (EDGE, e), a boundary segment along edge e → (EDGE, e), the segment
//! cutting the boundary at vertex v → (VERTEX, v). An edge with holes on
//! both sides is refused. The plain [`doo_sabin`] still refuses holes.

use super::hosts::{check_output_size, with_point_spheres, FaceLayout, SyncPtr, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Columns, Mesh};
use glam::DVec3;
use rayon::prelude::*;

mod open;
#[cfg(test)]
mod tests;

use open::open_step;
pub use open::{open_large_corners, open_large_corners_apply};

/// One level of Doo-Sabin subdivision. See the module docs.
pub fn doo_sabin(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("doo_sabin", m, step)
}

/// Doo & Sabin's weight αᵢ for an n-gon (its cosine from
/// [`super::hosts::turn_cos`]'s table).
pub fn doo_sabin_weight(n: usize, i: usize) -> f64 {
    let nf = n as f64;
    let w = (3.0 + 2.0 * super::hosts::turn_cos(i, n)) / (4.0 * nf);
    if i == 0 {
        w + 0.25
    } else {
        w
    }
}

/// The Doo-Sabin points of the corners of a face with corners `hs` (n ≥ 2,
/// in layout order), in O(n): with αⱼ = (3 + 2 cos(2πj/n)) / 4n (plus 1/4
/// at j = 0), Σⱼ α₍ⱼ₋ₖ₎ pⱼ = pₖ/4 + 3Σp/4n + (C cos θₖ + S sin θₖ)/2n with
/// C = Σ pⱼ cos θⱼ, S = Σ pⱼ sin θⱼ (θⱼ = 2πj/n), the cosines and sines
/// by the angle-addition recurrence.
fn face_corner_points(p: &[DVec3], vert: &[u32], hs: &[u32], mut put: impl FnMut(usize, DVec3)) {
    let n = hs.len();
    let [s, c, sn] = {
        let mut s = [DVec3::ZERO; 3];
        // (the table's entry for k = 1 is this expression's bits; a
        // `sincos` per face was 4 % of a level under `perf`)
        let (dc, ds) = super::hosts::turn_cos_sin(1, n);
        let (mut cs, mut sn) = (1.0, 0.0);
        for &h in hs {
            let x = p[vert[h as usize] as usize];
            s[0] += x;
            s[1] += x * cs;
            s[2] += x * sn;
            // (cos, sin) of the next multiple of 2π/n
            (cs, sn) = (cs * dc - sn * ds, sn * dc + cs * ds);
        }
        s
    };
    let nf64 = n as f64;
    let base = s * (0.75 / nf64);
    let (dc, ds) = super::hosts::turn_cos_sin(1, n);
    let (mut ck, mut sk) = (1.0, 0.0);
    for (k, &h) in hs.iter().enumerate() {
        put(k, p[vert[h as usize] as usize] * 0.25 + base + (c * ck + sn * sk) * (0.5 / nf64));
        (ck, sk) = (ck * dc - sk * ds, sk * dc + ck * ds);
    }
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("doo_sabin", 4 * m.n_halfedges(), m.n_halfedges())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;

    // --- positions: per face Σx, C, S, then per corner (in one task per
    // face: no per-face table of sums, 72 B per input face, alive at the peak)
    // written in full below (no calloc: `unfilled_points`)
    let mut pos = crate::mesh::unfilled_points(nh);
    // corner c belongs to the face whose range holds it: walk faces in parallel
    // by splitting the buffer along face offsets
    let mut chunks: Vec<&mut [std::mem::MaybeUninit<DVec3>]> = Vec::with_capacity(nf);
    let mut rest = &mut pos.spare_capacity_mut()[..nh];
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let (a, b) = rest.split_at_mut(fl.degree(f));
        chunks.push(a);
        rest = b;
    }
    chunks.into_par_iter().with_min_len(MIN_LEN).enumerate().for_each(|(f, out)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let hs = fl.corners(f);
        let n = hs.len();
        if n == 1 {
            out[0].write(p[vert[hs[0] as usize] as usize]);
            return;
        }
        face_corner_points(p, vert, hs, |k, x| {
            out[k].write(x);
        });
    });

    crate::cancel::check()?;
    // SAFETY: not cancelled: the faces' chunks cover the nh corners, each
    // written in full by its face's task
    unsafe { pos.set_len(nh) };
    // --- connectivity, straight into the columns (issue 19). The corners
    // `from_corner_twins` was given: F-faces (layout corner c), E-faces
    // `[p(next a), p(a), p(next b), p(b)]`, V-faces (rotation slots). An
    // F-face corner's twin is an E-face corner (later), a V-face corner's an
    // E-face corner (earlier), and the 2nd and 4th E-face corners come
    // before their twins: so its numbering (edges by first corner) is in
    // closed form. Edge c is F-face corner c's side (half-edges 2c, 2c + 1),
    // edges nh + 2e, nh + 2e + 1 the V-sides of E-face e; the V-face corner
    // at x has half-edge 2(nh + r) + 1, r = rotate(x) = twin(prev x).
    let (hu, eu, fu) = (nh as u32, ne as u32, nf as u32);
    // the corner list is done with: freed before the columns (issue 19: peak)
    let FaceLayout { fh, off, cidx } = fl;
    drop(fh);
    let mut cols = Columns::unfilled(pos, 4 * nh, nf + ne + nv);
    let cidx = &cidx;
    let v_id = |x: usize| 2 * (hu + (prev[x] ^ 1)) + 1;
    {
        let cp = |c: &mut Vec<u32>| SyncPtr(c.as_mut_ptr());
        let (pn, pp, pv, pf, ps) = (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face), cp(&mut cols.f_start));
        // SAFETY (all three loops): the ids above are a bijection from the
        // output corners onto 0..4nh, each face is written by one task, so
        // every entry is written once.
        let put = |id: u32, idn: u32, v: u32, f: u32| unsafe {
            *pn.get().add(id as usize) = idn;
            *pp.get().add(idn as usize) = id;
            *pv.get().add(id as usize) = v;
            *pf.get().add(id as usize) = f;
        };
        (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
            if crate::cancel::requested() {
                return; // the check after the loops reports it
            }
            let (s, e) = (off[f], off[f + 1]);
            unsafe { *ps.get().add(f) = 2 * s };
            for c in s..e {
                put(2 * c, 2 * if c + 1 == e { s } else { c + 1 }, c, f as u32);
            }
        });
        (0..ne).into_par_iter().with_min_len(MIN_LEN).for_each(|e| {
            if crate::cancel::requested() {
                return;
            }
            let (a, b) = (2 * e, 2 * e + 1);
            let (na, nb) = (next[a] as usize, next[b] as usize);
            let ids = [2 * cidx[a] + 1, 2 * (hu + 2 * e as u32), 2 * cidx[b] + 1, 2 * (hu + 2 * e as u32 + 1)];
            let vs = [cidx[na], cidx[a], cidx[nb], cidx[b]];
            unsafe { *ps.get().add(nf + e) = ids[0] };
            for j in 0..4 {
                put(ids[j], ids[(j + 1) % 4], vs[j], fu + e as u32);
            }
        });
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|x| {
            if crate::cancel::requested() {
                return;
            }
            let v = vert[x] as usize;
            if m.v_out[v] as usize == x {
                unsafe { *ps.get().add(nf + ne + v) = v_id(x) };
            }
            put(v_id(x), v_id((prev[x] ^ 1) as usize), cidx[x], fu + eu + v as u32);
        });
    }
    crate::cancel::check()?;
    // SAFETY: not cancelled, and the ids are a bijection onto 0..4nh (above)
    unsafe { cols.assume_filled(4 * nh) };
    // every output vertex (an input corner) first shows up in its F-face
    cols.v_out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(c, o)| *o = 2 * c as u32);
    Mesh::from_columns(cols)
}

/// [`doo_sabin_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays) with the level's weights: by the scheme's own masks on
/// a closed mesh without point-spheres (no stencils built), else through the
/// stencils.
pub fn doo_sabin_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    let fl = std::cell::OnceCell::new();
    super::level::level_with_data_linear(m, req, data, doo_sabin_level, |a, k| {
        let fl = super::level::once(&fl, || FaceLayout::new(m))?;
        direct_data(m, fl, a, k)
    })
}

/// The closed-mesh masks of [`step`] on vertex rows of `k` numbers.
fn direct_data(m: &Mesh, fl: &FaceLayout, a: &[f64], k: usize) -> Result<Vec<f64>> {
    let vert = &m.he_vert;
    face_masks(m, fl, a, k, |_, h| vert[h as usize] as usize)
}

/// The masks of [`step`] on rows of `k` numbers, one output row per layout
/// corner (an output vertex of the closed-mesh level): per corner `k` of an
/// n-gon, `x_k/4 + 3/(4n) Σx + 1/(2n) (C cos θk + S sin θk)` with
/// `C, S = Σ x_i (cos, sin) θi`, `θ = 2π/n` (the weights αᵢ expanded by
/// `cos θ(i−k) = cos θi cos θk + sin θi sin θk`), so a face costs O(n k).
/// The face's `x_i` is row `at(c, h)` of `a` for its layout corner `c`
/// (half-edge `h`): the vertex's row for vertex data, the corner's own for
/// corner data (`super::corner_direct`).
pub(crate) fn face_masks(m: &Mesh, fl: &FaceLayout, a: &[f64], k: usize, at: impl Fn(usize, u32) -> usize + Sync) -> Result<Vec<f64>> {
    let (nf, nh) = (m.n_faces(), fl.fh.len());
    let mut out = vec![0.0; nh * k];
    if k == 0 {
        return Ok(out);
    }
    let mut chunks: Vec<&mut [f64]> = Vec::with_capacity(nf);
    let mut rest: &mut [f64] = &mut out;
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let (x, y) = std::mem::take(&mut rest).split_at_mut(fl.degree(f) * k);
        chunks.push(x);
        rest = y;
    }
    let row = |c: usize, h: u32| {
        let i = at(c, h);
        &a[i * k..(i + 1) * k]
    };
    chunks.into_par_iter().with_min_len(MIN_LEN).enumerate().for_each_init(Vec::new, |sums, (f, o)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let hs = fl.corners(f);
        let n = hs.len();
        let c0 = fl.off[f] as usize;
        if n == 1 {
            o.copy_from_slice(row(c0, hs[0]));
            return;
        }
        sums.clear();
        sums.resize(3 * k, 0.0);
        let (dc, ds) = super::hosts::turn_cos_sin(1, n);
        let (mut cs, mut sn) = (1.0, 0.0);
        for (i, &h) in hs.iter().enumerate() {
            for (j, x) in row(c0 + i, h).iter().enumerate() {
                sums[j] += x;
                sums[k + j] += x * cs;
                sums[2 * k + j] += x * sn;
            }
            (cs, sn) = (cs * dc - sn * ds, sn * dc + cs * ds);
        }
        let nf64 = n as f64;
        let (b, w) = (0.75 / nf64, 0.5 / nf64);
        let (mut ck, mut sk) = (1.0, 0.0);
        for (c, &h) in hs.iter().enumerate() {
            for (j, (o, x)) in o[c * k..(c + 1) * k].iter_mut().zip(row(c0 + c, h)).enumerate() {
                *o = x * 0.25 + sums[j] * b + (sums[k + j] * ck + sums[2 * k + j] * sk) * w;
            }
            (ck, sk) = (ck * dc - sk * ds, sk * dc + ck * ds);
        }
    });
    crate::cancel::check()?;
    Ok(out)
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`doo_sabin`].
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn doo_sabin_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() > 0 {
            return open_step(m, req);
        }
        let mesh = step(m)?;
        if !req.stencils && !req.origins {
            return Ok(Level::plain(mesh));
        }
        let fl = FaceLayout::new(m)?;
        let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            Some(Stencils::build(nh, nv, |c, row| {
                let f = face[fl.fh[c] as usize] as usize;
                let hs = fl.corners(f);
                let (n, k) = (hs.len(), c - fl.off[f] as usize);
                for (i, &h) in hs.iter().enumerate() {
                    row.add(vert[h as usize], if n == 1 { 1.0 } else { doo_sabin_weight(n, (i + n - k) % n) });
                }
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let mut o = Origins::with_capacity(nh, mesh.n_edges(), nf + ne + nv);
            o.vertex_kind = vec![FACE; nh];
            o.vertex.extend(fl.fh.iter().map(|&h| face[h as usize]));
            o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(VERTEX).take(nv)));
            o.face.extend((0..nf as u32).chain(0..ne as u32).chain(0..nv as u32));
            // corners: [F-faces (fh order) | E-faces, 4 per edge | V-faces]; the V-face sides are
            // the E-faces' sides 1 and 3, so they cross edges too
            let (ef, vf) = (nh, nh + 4 * ne);
            let vl = VertexLayout::new(m)?;
            let mut slot_he = vec![0u32; nh];
            for h in 0..nh {
                slot_he[vl.vidx[h] as usize] = h as u32;
            }
            edge_origins_by_corner(&mesh, &mut o, |c| {
                if c < ef {
                    (FACE, face[fl.fh[c] as usize])
                } else if c < vf {
                    let (e, k) = ((c - ef) / 4, (c - ef) % 4);
                    match k {
                        0 => (FACE, face[2 * e]),
                        2 => (FACE, face[2 * e + 1]),
                        _ => (EDGE, e as u32),
                    }
                } else {
                    // slot of x: its side pairs with the E-face of rotate(x)
                    let r = m.he_prev[slot_he[c - vf] as usize] ^ 1;
                    (EDGE, r >> 1)
                }
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}
