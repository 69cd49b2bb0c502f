//! Honeycomb subdivision (honeycomb paper: Akleman & Srinivasan, "Honeycomb
//! Subdivision").
//!
//! **Geometry** (section 2, eq. 1, and section 3, eq. 2). Every corner `n`
//! of an N-gon `f = (v_0 … v_{N-1})` — equivalently its edge `e_n` from `v_n`
//! to `v_{n+1}` — gets a new vertex
//!
//! ```text
//! v'_n = Σ_m a_{n,m} p_m,     p_m = (1 − t) v_m + t v_{m+1}   (a point on e_m)
//! a_{n,n} = a,   a_{n,m} = β_{n−m} (1 − a) / (3N − 5),   β_k = 3 + 2 cos(2kπ/N)
//! ```
//!
//! with `t ∈ [0, 1]` (Remark 1; 0.5 in the paper's figures) and tension
//! `a ∈ [0, 1]` (the range where every `a_{n,m} ≥ 0`, section 3's first
//! condition). The default tension is the paper's `a = 0.45 + 1.25/N`,
//! clamped to 1 for N = 2 (where it would be 1.075 and make a weight
//! negative). A one-gon has the single weight `a_{0,0}`, which must be 1 for
//! the weights to sum to 1 (section 3's second condition): its new vertex is
//! its old one, whatever `a`. The cosine sum is evaluated through
//! `cos(θ(n−m)) = cos θn cos θm + sin θn sin θm`, so a face costs O(N), not
//! O(N²).
//!
//! **Connectivity** (section 4). Each old face gives a front face (its new
//! vertices in the old order: an N-gon stays an N-gon) and a back face; each
//! old edge inserts one edge between the back corners of its two new
//! vertices. The back faces and inserted edges around an old vertex of
//! valence k merge into one 2k-gon. Every new vertex is 3-valent (two front
//! edges, one inserted edge). Counts (Remark 2 of section 2):
//!
//! ```text
//! V' = 2E,   E' = 3E,   F' = F + V,   χ' = χ (genus unchanged)
//! ```
//!
//! The dodecahedron gives 12 pentagons and 20 hexagons (the truncated
//! icosahedron of Fig. 1); the icosahedron 20 triangles and 12 decagons.
//!
//! Built in one pass, straight into the mesh columns
//! (`face_vertex_columns.rs`): new vertex `h` is the one of old half-edge `h`; faces are `[front faces in old face order |
//! vertex faces in old vertex order]`. Self-loops, one-gons, two-gons,
//! multi-edges and repeated vertices need no special case. Point-spheres
//! (no edge to act on) are copied unchanged. O(output) time and memory.
//!
//! **Open meshes.** A boundary loop (a face marked as a hole) is refined
//! like a face for the connectivity, and its front face is the new hole, so
//! every boundary loop stays one loop, through as many edges as before. Its
//! new vertices stay on the boundary edges: `v'_n = p_n` (weight `a = 1`),
//! the point at `t` along the boundary edge, not eq. 2's average over the
//! hole polygon, which would pull the boundary towards the hole's centroid
//! and grow a flange into the hole (a hole is no face to smooth). With F
//! counting real faces and b boundary loops, `V' = 2E, E' = 3E, F' = F + V,
//! b' = b`, so `χ' = V − E + F = χ` (`χ = 2c − 2g − b`) and the genus stays.
//!
//! **Stencils and correspondence** ([`honeycomb_level`]): for fixed `t` and
//! tension the new points are linear in the old ones; row `h` is
//! `Σ_m a_{n,m} ((1 − t) v_m + t v_{m+1})` over its face (2N terms), a
//! point-sphere's row the point itself. Origins: new vertex h lies inside
//! its face → (FACE, face(h)); the front face of f → (FACE, f) (a hole's
//! front face is the hole), the 2k-gon of v → (VERTEX, v); front-face
//! sides lie inside their face → (FACE, f), an inserted edge crosses its
//! old edge → (EDGE, e). Holes are kept on every path, so open meshes get
//! stencils and origins too; there is no sharpness to carry.

use super::hosts::{FaceLayout, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::{MeshError, Result};
use crate::mesh::{FaceId, Mesh};
use glam::DVec3;
use rayon::prelude::*;

/// The paper's default tension for an N-gon, `0.45 + 1.25/N`, clamped to
/// `[0, 1]` (section 3).
pub fn default_tension(n: usize) -> f64 {
    (0.45 + 1.25 / n as f64).min(1.0)
}

/// One step of honeycomb subdivision (see the module docs).
///
/// `t` is the position of the edge points (eq. 1), `tension` the weight `a`
/// of eq. 2 for every face, or `None` for the paper's `a = 0.45 + 1.25/N`.
///
/// Errors: `t` outside `[0, 1]` or `tension` outside `[0, 1]` (including NaN).
pub fn honeycomb(m: &Mesh, t: f64, tension: Option<f64>) -> Result<Mesh> {
    check_args(t, tension)?;
    honeycomb_on(m, &FaceLayout::new(m)?, t, tension)
}

/// [`honeycomb`] on `m`'s face layout (built once by the callers that
/// need it again: stencils, origins, data masks). Arguments checked.
fn honeycomb_on(m: &Mesh, fl: &FaceLayout, t: f64, tension: Option<f64>) -> Result<Mesh> {
    // ---- faces: [front faces (or copied point-spheres) | one 2k-gon per vertex],
    // written straight into the columns; the positions after them (issue 19:
    // the connectivity's scratch is gone by then)
    let cols = super::face_vertex_columns::honeycomb_columns(m, fl)?;
    cols.finish(m, positions(m, fl, t, tension)?)
}

/// [`honeycomb_level`] on an input the caller gives up (a previous level of
/// a multi-level call, issue 19): asked for no stencils or origins, the
/// connectivity is written first, then the face layout and what the
/// positions do not read of the input (previous half-edges, faces of the
/// half-edges, vertex starts) are freed before the positions exist, which
/// walk the face cycles themselves. Anything else is [`honeycomb_level`]'s.
/// The output is the same, bit for bit (`owned_level_equals_the_borrowed_one`).
pub fn honeycomb_level_owned(mut m: Mesh, t: f64, tension: Option<f64>, req: &Request) -> Result<Level> {
    if req.stencils || req.origins {
        return honeycomb_level(&m, t, tension, req);
    }
    check_args(t, tension)?;
    let fl = FaceLayout::new(&m)?;
    let cols = super::face_vertex_columns::honeycomb_columns(&m, &fl)?;
    drop(fl);
    (m.he_prev, m.he_face, m.v_out) = (Vec::new(), Vec::new(), Vec::new());
    let pos = positions_by(&m, t, tension, |f, buf| buf.extend(m.face_halfedges(FaceId(f as u32)).map(|h| h.idx() as u32)))?;
    Ok(Level::plain(cols.finish(&m, pos)?))
}

/// Honeycomb's new vertices, one per old half-edge (eq. 2; holes and
/// one-gons keep their edge points); shared with `topmod::root3_dual`.
pub(crate) fn positions(m: &Mesh, fl: &FaceLayout, t: f64, tension: Option<f64>) -> Result<Vec<DVec3>> {
    positions_by(m, t, tension, |f, buf| buf.extend_from_slice(fl.corners(f)))
}

/// [`positions`] with face `f`'s corners (its cycle from its first
/// half-edge; none for a point-sphere face) put in `buf` by `corners`.
fn positions_by(m: &Mesh, t: f64, tension: Option<f64>, corners: impl Fn(usize, &mut Vec<u32>) + Sync) -> Result<Vec<DVec3>> {
    let nh = m.n_halfedges();
    let nf = m.n_faces();
    let vert = &m.he_vert;
    let pos = m.positions();

    // ---- new positions, one per old half-edge, face by face: the sums of the
    // face's edge points p_m (relative to its first vertex), then eq. 2 per corner
    let mut new_pos = crate::mesh::zeroed_points(nh);
    let np = super::hosts::SyncPtr(new_pos.as_mut_ptr());
    (0..nf).into_par_iter().with_min_len(super::hosts::MIN_LEN / 4).for_each_init(Vec::new, |buf, f| {
        buf.clear();
        corners(f, buf);
        let hs = &buf[..];
        // cancelled: the check below reports it; a point-sphere face has no corner
        if crate::cancel::requested() || hs.is_empty() {
            return;
        }
        let nn = hs.len();
        let origin = pos[vert[hs[0] as usize] as usize];
        let (mut s, mut c, mut sn) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for (k, &h) in hs.iter().enumerate() {
            let h = h as usize;
            let p = edge_point(pos, vert[h], vert[h ^ 1], t) - origin;
            let (cos, sin) = super::hosts::turn_cos_sin(k, nn);
            s += p;
            c += p * cos;
            sn += p * sin;
        }
        // one-gons (section 3's second condition) and holes (module docs) keep p
        let a = if nn == 1 || m.is_hole(FaceId(f as u32)) { 1.0 } else { tension.unwrap_or_else(|| default_tension(nn)) };
        let c1 = (1.0 - a) / (3.0 * nn as f64 - 5.0);
        for (k, &h) in hs.iter().enumerate() {
            let h = h as usize;
            let p = edge_point(pos, vert[h], vert[h ^ 1], t);
            let q = if a == 1.0 {
                p
            } else {
                let p = p - origin;
                let (cos, sin) = super::hosts::turn_cos_sin(k, nn);
                let rest = 3.0 * s - 5.0 * p + 2.0 * (cos * c + sin * sn);
                origin + a * p + c1 * rest
            };
            // SAFETY: every half-edge belongs to one face, whose task alone writes it.
            unsafe { *np.get().add(h) = q };
        }
    });
    crate::cancel::check()?;
    Ok(new_pos)
}

/// One step with what `req` asks for (see the module docs); without
/// requests it is [`honeycomb`].
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn honeycomb_level(m: &Mesh, t: f64, tension: Option<f64>, req: &Request) -> Result<Level> {
    check_args(t, tension)?;
    level_on(m, &FaceLayout::new(m)?, t, tension, req)
}

/// [`honeycomb_level`] on `m`'s face layout. Arguments checked.
fn level_on(m: &Mesh, fl: &FaceLayout, t: f64, tension: Option<f64>, req: &Request) -> Result<Level> {
    let mesh = honeycomb_on(m, fl, t, tension)?;
    if !req.stencils && !req.origins {
        return Ok(Level::plain(mesh));
    }
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (_, vert, face) = m.halfedge_columns();
    let points: Vec<u32> = (0..nv as u32).filter(|&v| m.v_out[v as usize] & crate::mesh::POINT != 0).collect();
    let stencils = if req.stencils {
        Some(Stencils::build(nh + points.len(), nv, |i, row| {
            if i >= nh {
                row.add(points[i - nh], 1.0);
                return;
            }
            let f = face[i] as usize;
            let hs = fl.corners(f);
            let nn = hs.len();
            if req.skip_large_face_rows && nn > LARGE_FACE && !m.f_hole[f] {
                // a placeholder the caller's corner data replace (`large_corners`)
                row.add(vert[i], 1.0);
                return;
            }
            // as in `honeycomb`: one-gons and holes keep p (module docs)
            let a = if nn == 1 || m.f_hole[f] { 1.0 } else { tension.unwrap_or_else(|| default_tension(nn)) };
            let n = fl.local(i as u32, f as u32);
            if a == 1.0 {
                // the edge point alone: the other weights are 0, and their
                // cosines cost n² over an n-sided hole (8,000 sides: 7 s)
                let g = hs[n];
                row.add(vert[g as usize], 1.0 - t);
                row.add(vert[(g ^ 1) as usize], t);
                return;
            }
            for (mm, &g) in hs.iter().enumerate() {
                let w = if mm == n {
                    a
                } else {
                    let k = (n + nn - mm) % nn;
                    (3.0 + 2.0 * super::hosts::turn_cos(k, nn)) * (1.0 - a) / (3.0 * nn as f64 - 5.0)
                };
                if w != 0.0 {
                    row.add(vert[g as usize], w * (1.0 - t));
                    row.add(vert[(g ^ 1) as usize], w * t);
                }
            }
        })?)
    } else {
        None
    };
    let origins = if req.origins {
        let vl = VertexLayout::new(m)?;
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(FACE).take(nh).chain(std::iter::repeat(VERTEX).take(points.len())));
        o.vertex.extend(face.iter().copied().chain(points.iter().copied()));
        o.face_kind.extend(std::iter::repeat(FACE).take(nf));
        o.face.extend(0..nf as u32);
        for v in 0..nv {
            if vl.valence(v) > 0 {
                o.face_kind.push(VERTEX);
                o.face.push(v as u32);
            }
        }
        // corner layout of `honeycomb`: front faces (a point-sphere's keeps one corner), then 2 per slot
        let mut off = Vec::with_capacity(nf + 1);
        off.push(0u32);
        for f in 0..nf {
            off.push(off[f] + (fl.degree(f) as u32).max(1));
        }
        let vb = off[nf] as usize;
        let mut co = vec![(FACE, 0u32); vb + 2 * nh];
        for h in 0..nh {
            crate::cancel::poll(h)?;
            let f = face[h];
            co[(off[f as usize] as usize) + fl.local(h as u32, f)] = (FACE, f);
            let ce = vb + 2 * vl.vidx[h] as usize;
            co[ce] = (FACE, f);
            co[ce + 1] = (EDGE, m.he_prev[h] >> 1);
        }
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

/// Real faces of more corners than this: their points' stencil rows (n
/// each, n² per face) may be left to [`large_corners`].
const LARGE_FACE: usize = 64;

/// Whether [`large_corners`] writes anything for this input (and a level
/// may take `Request::skip_large_face_rows`): open (a closed mesh's corner
/// data take `corner_direct`), no point-spheres, a real face of more than
/// [`LARGE_FACE`] corners.
pub fn large_corners_apply(m: &Mesh) -> bool {
    super::corner_transfer::has_large_real_face(m, LARGE_FACE)
}

/// Corner data at the points of real faces of more than [`LARGE_FACE`]
/// corners (output vertex `h` for half-edge `h`), written over `out_rows`
/// (exported output corners by `k`) from the input's `rows` (exported input
/// corners): eq. 2 over the face's corner values, the value the generic
/// transfer gives them (its rule 1), in O(n) per face ([`face_masks`]) where
/// the transfer reads a dense row of n per point. With
/// `Request::skip_large_face_rows` those rows are placeholders and this is
/// what gives those corners their values.
pub fn large_corners(m: &Mesh, out: &Mesh, t: f64, tension: Option<f64>, rows: &[f64], out_rows: &mut [f64], k: usize) -> Result<()> {
    if k == 0 || !large_corners_apply(m) {
        return Ok(());
    }
    let fl = FaceLayout::new(m)?;
    let at = super::corner_transfer::layout_rows(m, &fl, rows, k, "honeycomb")?;
    let pv = face_masks(m, &fl, t, tension, rows, k, at)?;
    let face = &m.he_face;
    let nh = m.n_halfedges();
    let big = |v: usize| v < nh && !m.f_hole[face[v] as usize] && fl.degree(face[v] as usize) > LARGE_FACE;
    super::corner_transfer::write_vertex_rows(out, &pv, k, big, out_rows)
}

/// [`honeycomb_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays) by the scheme's own masks on a closed mesh without
/// point-spheres (no stencils built), else through the stencils.
pub fn honeycomb_level_with(m: &Mesh, t: f64, tension: Option<f64>, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    check_args(t, tension)?;
    // one face layout for the level and the masks
    let fl = FaceLayout::new(m)?;
    let vert = &m.he_vert;
    super::level::level_with_data(m, req, data, |m, r| level_on(m, &fl, t, tension, r), |a, k| {
        face_masks(m, &fl, t, tension, a, k, |_, h| vert[h as usize] as usize)
    })
}

/// Eq. 1–2 on rows of `k` numbers, one output row per half-edge `h` (new
/// vertex `h` of the level): with `x_i` the row `at(c, h)` of `a` for the
/// face's layout corner `c` (half-edge `h`), the edge points are
/// `p_i = (1 − t) x_i + t x_{i+1}` along the face and the new row
/// `a p_n + (1 − a)/(3N − 5) (3 Σp − 5 p_n + 2 (cos θn C + sin θn S))`,
/// `C, S = Σ p_m (cos, sin) θm`, as in [`honeycomb`]. `at` gives the
/// vertex's row for vertex data and the corner's own for corner data
/// (`super::corner_direct`), so a face reads its edge points in itself.
/// Holes and one-gons keep `p` (module docs).
pub(crate) fn face_masks(
    m: &Mesh,
    fl: &FaceLayout,
    t: f64,
    tension: Option<f64>,
    a: &[f64],
    k: usize,
    at: impl Fn(usize, u32) -> usize + Sync,
) -> Result<Vec<f64>> {
    check_args(t, tension)?;
    let (nf, nh) = (m.n_faces(), m.n_halfedges());
    let mut out = vec![0.0; nh * k];
    if k == 0 {
        return Ok(out);
    }
    let (next, _, _) = m.halfedge_columns();
    let row = |c: usize, h: u32| {
        let i = at(c, h);
        &a[i * k..(i + 1) * k]
    };
    // edge point of the face's corner `i` (layout corner c0 + i, half-edge h)
    let edge_point = |o: &mut [f64], c0: usize, n: usize, i: usize, h: u32| {
        let (x, y) = (row(c0 + i, h), row(c0 + (i + 1) % n, next[h as usize]));
        for ((o, x), y) in o.iter_mut().zip(x).zip(y) {
            *o = (1.0 - t) * x + t * y;
        }
    };
    // per face, in one pass (as `positions`): its edge points, Σp, C, S,
    // then eq. 2 for each of its corners, written to the corner's half-edge
    // row (every half-edge belongs to one face: one writer per row)
    let op = super::hosts::SyncPtr(out.as_mut_ptr());
    (0..nf).into_par_iter().with_min_len(MIN_LEN / 4).for_each_init(
        || (Vec::new(), vec![0.0; 3 * k]),
        |(ps, s), f| {
            let hs = fl.corners(f);
            if crate::cancel::requested() || hs.is_empty() {
                return; // cancelled: the check below reports it
            }
            let (n, c0) = (hs.len(), fl.off[f] as usize);
            ps.resize(n * k, 0.0);
            s.fill(0.0);
            for (i, &h) in hs.iter().enumerate() {
                let p = &mut ps[i * k..(i + 1) * k];
                edge_point(p, c0, n, i, h);
                let (cs, sn) = super::hosts::turn_cos_sin(i, n);
                for j in 0..k {
                    s[j] += p[j];
                    s[k + j] += p[j] * cs;
                    s[2 * k + j] += p[j] * sn;
                }
            }
            let a = if n == 1 || m.f_hole[f] { 1.0 } else { tension.unwrap_or_else(|| default_tension(n)) };
            let c1 = (1.0 - a) / (3.0 * n as f64 - 5.0);
            for (i, &h) in hs.iter().enumerate() {
                // SAFETY: row h is written by the task of h's face only
                let o = unsafe { std::slice::from_raw_parts_mut(op.get().add(h as usize * k), k) };
                let p = &ps[i * k..(i + 1) * k];
                if a == 1.0 {
                    o.copy_from_slice(p);
                    continue;
                }
                // from the table, as the positions (same bits as sin_cos)
                let (cs, sn) = super::hosts::turn_cos_sin(i, n);
                for j in 0..k {
                    o[j] = a * p[j] + c1 * (3.0 * s[j] - 5.0 * p[j] + 2.0 * (cs * s[k + j] + sn * s[2 * k + j]));
                }
            }
        },
    );
    crate::cancel::check()?;
    Ok(out)
}

#[inline]
fn edge_point(pos: &[DVec3], a: u32, b: u32, t: f64) -> DVec3 {
    (1.0 - t) * pos[a as usize] + t * pos[b as usize]
}

/// The argument checks of [`honeycomb`], for callers that iterate zero times.
pub fn check_args(t: f64, tension: Option<f64>) -> Result<()> {
    if !(0.0..=1.0).contains(&t) {
        return Err(MeshError::InvalidArgument(format!(
            "honeycomb: t = {} is outside [0, 1] (eq. 1 takes a point on each edge)",
            crate::error::num(t)
        )));
    }
    if let Some(a) = tension {
        if !(0.0..=1.0).contains(&a) {
            return Err(MeshError::InvalidArgument(format!(
                "honeycomb: tension = {} is outside [0, 1] (eq. 2 needs 0 <= a <= 1 for non-negative weights)",
                crate::error::num(a)
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owned_level_equals_the_borrowed_one() {
        use crate::schemes::hosts::test_meshes::{owned_level_cases, position_bits as bits};
        // the corpus (point-spheres, self-loops, two-gons), open meshes and a
        // second level; positions compared bit for bit
        for (name, m) in owned_level_cases() {
            for (t, tension) in [(0.5, None), (0.3, Some(0.8))] {
                let req = Request::plain();
                let a = honeycomb_level(&m, t, tension, &req).unwrap().mesh;
                let b = honeycomb_level_owned(m.clone(), t, tension, &req).unwrap().mesh;
                assert_eq!(a, b, "{name}");
                assert_eq!(bits(&a), bits(&b), "{name}");
                let c = honeycomb_level(&a, t, tension, &req).unwrap().mesh;
                let d = honeycomb_level_owned(a, t, tension, &req).unwrap().mesh;
                assert_eq!((&c, bits(&c)), (&d, bits(&d)), "{name} level 2");
            }
        }
    }

    #[test]
    fn tabled_cosines_are_the_expression_bit_for_bit() {
        for n in 1..=20usize {
            for k in 0..n {
                assert_eq!(super::super::hosts::turn_cos(k, n).to_bits(), (std::f64::consts::TAU * k as f64 / n as f64).cos().to_bits(), "n = {n}, k = {k}");
                let (c, s) = super::super::hosts::turn_cos_sin(k, n);
                let th = std::f64::consts::TAU * k as f64 / n as f64;
                assert_eq!((c.to_bits(), s.to_bits()), (th.cos().to_bits(), th.sin().to_bits()), "n = {n}, k = {k}");
            }
        }
    }
    use crate::mesh::BuildOptions;
    use crate::primitives::*;
    use crate::schemes::hosts::test_meshes::{check_output, cube_with_hole, handle_cube, one_gon_two_gon_cube, star_prism};

    fn check_step(m: &Mesh) -> Mesh {
        let (v, e, f) = (m.n_vertices(), m.n_edges(), m.n_faces());
        let h = honeycomb(m, 0.5, None).unwrap();
        check_output("honeycomb", m, &h, (2 * e, 3 * e, f + v));
        // every vertex 3-valent; n-gon -> n-gon; valence-k vertex -> 2k-gon
        assert_eq!(h.valence_histogram().keys().copied().collect::<Vec<_>>(), vec![3]);
        let mut want = m.face_size_histogram();
        for (k, c) in m.valence_histogram() {
            *want.entry(2 * k).or_default() += c;
        }
        assert_eq!(h.face_size_histogram(), want);
        h
    }

    #[test]
    fn counts_on_platonic_torus_genus() {
        for m in [tetrahedron(), cube(), octahedron(), dodecahedron(), icosahedron()] {
            let h = check_step(&m);
            let h2 = check_step(&h);
            assert!(h2.signed_volume() > 0.0);
        }
        check_step(&torus(8, 5, 2.0, 0.5).unwrap());
        check_step(&genus_surface(3).unwrap());
        check_step(&one_gon_two_gon_cube());
        check_step(&star_prism());
        check_step(&handle_cube());
    }

    #[test]
    fn dodecahedron_gives_soccer_ball() {
        let h = honeycomb(&dodecahedron(), 0.5, None).unwrap();
        let hist: Vec<_> = h.face_size_histogram().into_iter().collect();
        assert_eq!(hist, vec![(5, 12), (6, 20)]);
        let i = honeycomb(&icosahedron(), 0.5, None).unwrap();
        let hist: Vec<_> = i.face_size_histogram().into_iter().collect();
        assert_eq!(hist, vec![(3, 20), (10, 12)]);
    }

    /// The O(N) evaluation equals eq. (1)-(2) summed directly.
    #[test]
    fn positions_match_direct_formula() {
        let pos = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.1),
            DVec3::new(3.0, 1.0, -0.2),
            DVec3::new(2.0, 3.0, 0.3),
            DVec3::new(1.0, 1.5, 0.0),
            DVec3::new(-1.0, 2.0, 0.1),
            DVec3::new(1.0, 1.0, 2.0),
        ];
        // a non-convex hexagon and a fan of triangles closing it
        let mut sizes = vec![6i64];
        let mut idx = vec![0i64, 1, 2, 3, 4, 5];
        for k in 0..6 {
            sizes.push(3);
            idx.extend([(k + 1) % 6, k, 6]);
        }
        let m = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap();
        for (t, a) in [(0.5, None), (0.3, Some(0.7)), (0.9, Some(0.0)), (0.0, Some(1.0))] {
            let h = honeycomb(&m, t, a).unwrap();
            for hh in m.halfedges() {
                let f = m.face(hh);
                let cyc: Vec<_> = m.face_halfedges(f).collect();
                let nn = cyc.len();
                let n = cyc.iter().position(|&x| x == hh).unwrap();
                let aa = a.unwrap_or_else(|| default_tension(nn));
                let mut want = DVec3::ZERO;
                for (mm, &g) in cyc.iter().enumerate() {
                    let p = (1.0 - t) * m.position(m.vertex(g)) + t * m.position(m.head(g));
                    let w = if mm == n {
                        aa
                    } else {
                        let beta = 3.0 + 2.0 * (2.0 * (n as f64 - mm as f64) * std::f64::consts::PI / nn as f64).cos();
                        beta * (1.0 - aa) / (3.0 * nn as f64 - 5.0)
                    };
                    want += w * p;
                }
                let got = h.position(crate::VertexId(hh.0));
                assert!((got - want).length() < 1e-12, "{got} vs {want}");
            }
        }
    }

    /// Section 4's remeshing algorithm with the DLFL operators:
    /// CreateFaceManifold (CreateVertex + InsertEdge) per old face, then one
    /// InsertEdge per old edge between the back corners. New vertex `h` is
    /// created for old half-edge `h`, as in the one-pass builder.
    fn honeycomb_by_operators(m: &Mesh, t: f64) -> Mesh {
        let one_pass = honeycomb(m, t, None).unwrap();
        let mut out = Mesh::new();
        for h in m.halfedges() {
            out.create_vertex(one_pass.position(crate::VertexId(h.0))).unwrap();
        }
        // back corner of v'_h: its outgoing half-edge that is not on the front face
        let mut back = vec![crate::HalfedgeId(0); m.n_halfedges()];
        for f in m.faces() {
            let cyc: Vec<_> = m.face_halfedges(f).collect();
            let n = cyc.len();
            let mut fwd = Vec::with_capacity(n);
            for i in 0..n {
                let (a, b) = (crate::VertexId(cyc[i].0), crate::VertexId(cyc[(i + 1) % n].0));
                let corner = |o: &Mesh, v: crate::VertexId| match o.vertex_halfedge(v) {
                    None => crate::Corner::Point(v),
                    Some(h) => crate::Corner::Halfedge(h), // valence 1 (or the loop's): one corner
                };
                let e = out.insert_edge(corner(&out, a), corner(&out, b)).unwrap();
                fwd.push(e.halfedge());
            }
            for i in 0..n {
                // the twin of the front edge entering v'_i leaves v'_i on the back face
                back[cyc[i].idx()] = fwd[(i + n - 1) % n].twin();
            }
        }
        for e in m.edges() {
            let h = e.halfedge();
            out.insert_edge(crate::Corner::Halfedge(back[h.idx()]), crate::Corner::Halfedge(back[h.twin().idx()])).unwrap();
        }
        out
    }

    fn canonical_faces(m: &Mesh) -> Vec<Vec<u32>> {
        let mut faces: Vec<Vec<u32>> = m
            .faces()
            .map(|f| {
                let c: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect();
                (0..c.len()).map(|k| [&c[k..], &c[..k]].concat()).min().unwrap()
            })
            .collect();
        faces.sort();
        faces
    }

    #[test]
    fn one_pass_equals_section_4_operators() {
        for m in [cube(), dodecahedron(), torus(6, 4, 2.0, 0.5).unwrap(), genus_surface(2).unwrap(), one_gon_two_gon_cube(), handle_cube(), star_prism()] {
            let ops = honeycomb_by_operators(&m, 0.5);
            ops.validate().unwrap();
            let one = honeycomb(&m, 0.5, None).unwrap();
            assert_eq!(canonical_faces(&ops), canonical_faces(&one));
            assert_eq!(ops.genus(), m.genus());
        }
    }

    #[test]
    fn level_stencils_and_origins_on_corpus_and_open_meshes() {
        use crate::schemes::hosts::test_meshes::*;
        let full = crate::schemes::hosts::test_meshes::full_request();
        let mut meshes = corpus();
        meshes.extend(open_meshes());
        for (name, m) in meshes {
            for (t, a) in [(0.5, None), (0.3, Some(0.7)), (0.9, Some(1.0))] {
                let lv = honeycomb_level(&m, t, a, &full).unwrap();
                check_level(name, &m, &lv);
                let plain = honeycomb(&m, t, a).unwrap();
                assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
                assert_eq!(lv.mesh.positions(), plain.positions(), "{name}");
                assert_eq!((lv.mesh.n_holes(), open_euler(&lv.mesh)), (m.n_holes(), open_euler(&m)), "{name}");
                let o = lv.origins.as_ref().unwrap();
                let fl = FaceLayout::new(&m).unwrap();
                // n new vertices and n front sides per n-gon, one front face each; one vertex face
                // per vertex, one inserted edge per edge
                let (fv, ff, fe) = (
                    origin_counts(&o.vertex_kind, &o.vertex, FACE, m.n_faces()),
                    origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()),
                    origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces()),
                );
                for f in 0..m.n_faces() {
                    assert_eq!((fv[f], ff[f], fe[f]), (fl.degree(f), 1, fl.degree(f)), "{name} face {f}");
                }
                assert!(origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
                let vf = origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices());
                let vv = origin_counts(&o.vertex_kind, &o.vertex, VERTEX, m.n_vertices());
                for v in 0..m.n_vertices() {
                    let point = m.v_out[v] & crate::mesh::POINT != 0;
                    assert_eq!((vf[v], vv[v]), if point { (0, 1) } else { (1, 0) }, "{name} vertex {v}");
                }
                // the hole's front face is a hole and is born from it
                for f in 0..m.n_faces() {
                    assert_eq!(lv.mesh.f_hole[f], m.f_hole[f], "{name}");
                }
            }
        }
        assert!(honeycomb_level(&cube(), 2.0, None, &full).is_err());
    }

    #[test]
    fn bad_arguments() {
        let c = cube();
        assert!(honeycomb(&c, -0.1, None).is_err());
        assert!(honeycomb(&c, 1.5, None).is_err());
        assert!(honeycomb(&c, f64::NAN, None).is_err());
        assert!(honeycomb(&c, 0.5, Some(1.2)).is_err());
        assert!(honeycomb(&c, 0.5, Some(-0.2)).is_err());
    }

    #[test]
    fn point_spheres_and_holes_pass_through() {
        let mut m = cube();
        m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
        let h = honeycomb(&m, 0.5, None).unwrap();
        h.validate().unwrap();
        assert_eq!(h.n_components(), 2);
        assert_eq!(h.n_vertices(), 24 + 1);
        // an open box capped by a hole: the hole's front face stays a hole
        let open = cube_with_hole();
        let h = honeycomb(&open, 0.5, None).unwrap();
        h.validate().unwrap();
        assert_eq!(h.n_holes(), 1);
        assert_eq!((h.euler_characteristic(), h.n_boundary_loops()), (open.euler_characteristic(), 1));
        // the new boundary runs through the old boundary edges' points at t
        let old = open.positions();
        let mids: Vec<DVec3> = open.boundary_edges().iter().map(|&[a, b]| 0.25 * old[a as usize] + 0.75 * old[b as usize]).collect();
        let h = honeycomb(&open, 0.25, None).unwrap();
        let lp = h.boundary_loops();
        assert_eq!(lp[0].len(), 4);
        for v in &lp[0] {
            let p = h.position(*v);
            assert!(mids.iter().any(|q| (*q - p).length() < 1e-12), "{p} is not an edge point of the old boundary");
        }
    }

    /// Corner data through an open level whose large faces' rows are
    /// placeholders (`Request::skip_large_face_rows`) and then written by
    /// `large_corners` equal the generic transfer over the full rows
    /// within rounding (a cup with a 200-gon bottom, corner values with
    /// seams, 1 and 3 columns, default and set tension); the placeholders
    /// alone do not.
    #[test]
    fn large_face_corners_equal_the_full_transfer() {
        use crate::schemes::hosts::test_meshes::{assert_large_corners, cup};
        let cup = cup(200);
        assert!(large_corners_apply(&cup));
        for (t, a) in [(0.5, None), (0.3, Some(0.7))] {
            assert_large_corners(&cup, |r| honeycomb_level(&cup, t, a, r).unwrap(), |out, rows, got, k| large_corners(&cup, out, t, a, rows, got, k).unwrap());
        }
    }
}
