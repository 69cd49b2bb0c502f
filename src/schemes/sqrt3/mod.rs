//! √3 subdivision (L. Kobbelt, "√3-subdivision", SIGGRAPH 2000, §2–3), one
//! level, generalised to polygon faces.
//!
//! Every face gets a new vertex at its centroid (for a triangle
//! `(a + b + c)/3`, Kobbelt's rule), each old edge is flipped (it now joins
//! the centroids of its two faces) and the centroid is joined to every corner.
//! Old vertices are smoothed with Kobbelt's rule
//! `v' = (1 − αₙ) v + αₙ/n Σ neighbours`, `αₙ = (4 − 2 cos(2π/n))/9`, over the
//! n ends of the old edges at v (a self-loop counts twice).
//!
//! Polygon generalisation: an n-gon is handled exactly like a triangle —
//! centroid, spokes, flipped edges — so every old half-edge `h` (from `a`, in
//! face `f`, its twin in face `g`) gives one output triangle
//! `[a, c_g, c_f]`. On triangle meshes this is Kobbelt's scheme; two steps
//! give the usual 1-to-9 triadic split.
//!
//! Counts (H = 2E): V' = V + F, E' = E + H = 3E, F' = H = 2E (all triangles).
//! Output vertices are `[smoothed old vertices | face centroids]`; output
//! triangle `h` is the one of half-edge `h`.
//!
//! Open meshes: Kobbelt's §4 boundary rule, in [`boundary`] (through
//! [`sqrt3_level`] only: it needs the level's parity).
//!
//! Stencils and correspondence ([`sqrt3_level`]): the scheme is linear; a
//! vertex row is `(1 − αₙ) v + αₙ/n Σ neighbours`, a centroid row the mean
//! of the face's corners. Origins: old vertex → (VERTEX, v), centroid →
//! (FACE, f); triangle h straddles the flipped edge e = h/2 (it covers
//! parts of both faces beside e) → (EDGE, e), two per edge; the flipped
//! edge → (EDGE, e); a spoke lies inside its face → (FACE, f).

mod boundary;
mod boundary_columns;
#[cfg(test)]
mod boundary_tests;
/// The builder [`columns`] replaced, kept as the reference it must equal.
#[cfg(test)]
mod reference;

use super::hosts::{check_output_size, neighbor_sum, with_point_spheres, FaceLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Columns, Mesh};
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// One level of √3 subdivision of a closed mesh. See the module docs; open
/// meshes go through [`sqrt3_level`] (the boundary rule needs the level's
/// parity).
pub fn sqrt3(m: &Mesh) -> Result<Mesh> {
    super::hosts::refuse_holes("sqrt3", m)?;
    with_point_spheres("sqrt3", m, step)
}

/// Kobbelt's αₙ.
#[inline]
pub fn sqrt3_alpha(n: usize) -> f64 {
    // cos(2π/n) from the table of turns (the same bits as computing it)
    (4.0 - 2.0 * super::hosts::turn_cos(1, n)) / 9.0
}

/// The stencil row of old vertex `v`: `(1 − αₙ) v + αₙ/n Σ neighbours`
/// over its n ring ends (a self-loop counts twice).
pub(super) fn kobbelt_row(m: &Mesh, vert: &[u32], v: usize, row: &mut super::stencil::Row) {
    // the ring walked twice (its size first) instead of collected
    let n = super::creases::ring(m, m.v_out[v]).count();
    let a = sqrt3_alpha(n);
    row.add(v as u32, 1.0 - a);
    for h in super::creases::ring(m, m.v_out[v]) {
        row.add(vert[(h ^ 1) as usize], a / n as f64);
    }
}

/// Connectivity first, positions last: the edge numbering's scratch
/// (`base`, 4 B per output triangle) is freed before the positions exist.
fn step(m: &Mesh) -> Result<Mesh> {
    build(Cow::Borrowed(m))
}

/// [`step`] on a level's input that nobody else holds (the previous level
/// of a multi-level call, issue 19: "input freed as soon as it is no
/// longer needed"): once the output's connectivity is written, the input's
/// face column and hole flags go before the output's positions are
/// allocated, since [`positions`] walks only rings (`v_out`, `he_prev`),
/// face cycles (`f_start`, `he_next`) and `he_vert`. The output is
/// [`step`]'s, bit for bit (`owned_level_equals_the_borrowed_one`).
fn step_owned(m: Mesh) -> Result<Mesh> {
    build(Cow::Owned(m))
}

fn build(mut src: Cow<'_, Mesh>) -> Result<Mesh> {
    check_output_size("sqrt3", 3 * src.n_halfedges(), src.n_vertices() + src.n_faces())?;
    let mut cols = columns(&src)?;
    if let Cow::Owned(m) = &mut src {
        (m.he_face, m.f_hole) = (Vec::new(), Vec::new());
    }
    cols.pos = positions(&src)?;
    drop(src);
    Mesh::from_columns(cols)
}

/// The closed-mesh output positions `[V | F]`: Kobbelt's smoothed old
/// vertices and the face centroids.
pub(super) fn positions(m: &Mesh) -> Result<Vec<DVec3>> {
    let (nv, nf) = (m.n_vertices(), m.n_faces());
    let p = &m.pos;
    // written in full below (no calloc: `unfilled_points`)
    let mut pos = crate::mesh::unfilled_points(nv + nf);
    let (vp, fp) = pos.spare_capacity_mut()[..nv + nf].split_at_mut(nv);
    rayon::join(
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (sum, n) = neighbor_sum(m, v);
                let a = sqrt3_alpha(n);
                out.write(p[v] * (1.0 - a) + sum * (a / n as f64));
            })
        },
        || {
            // the check after the join reports a cancellation
            super::hosts::face_centroids_into(m, fp)
        },
    );
    crate::cancel::check()?;
    // SAFETY: not cancelled: both parts are written in full
    unsafe { pos.set_len(nv + nf) };
    Ok(pos)
}

/// Elements per task of the edge-numbering scan.
const SCAN_CHUNK: usize = 1 << 14;

/// The output connectivity written straight into the columns (issue 19),
/// numbered as `from_corner_twins` numbered the corners it was given
/// (`reference::step_via_twins`, held to it by a test and by
/// `output_hashes`): triangle h has corners 3h, 3h + 1, 3h + 2 (at a, c_g,
/// c_f), and each edge is numbered by its first corner, the one before its
/// twin. The flipped edge's corners are 3h + 1 and 3(h ^ 1) + 1 (the even
/// h's first); spoke corner 3h pairs with 3j + 2, j = next(h ^ 1), and 3h
/// is first exactly when h ≤ j. A prefix over the triangles of their first
/// corners gives every edge id; then each column entry is a lookup.
/// The positions are left for the caller (`pos` empty, `v_out` sized).
fn columns(m: &Mesh) -> Result<Columns> {
    let (nv, nh) = (m.n_vertices(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let first0 = |h: usize| h <= next[h ^ 1] as usize;
    let first2 = |h: usize| h < (prev[h] ^ 1) as usize;
    let count = |h: usize| (h & 1 == 0) as u32 + first0(h) as u32 + first2(h) as u32;
    let sums: Vec<u32> = (0..nh.div_ceil(SCAN_CHUNK))
        .into_par_iter()
        .map(|k| if crate::cancel::requested() { 0 } else { (k * SCAN_CHUNK..((k + 1) * SCAN_CHUNK).min(nh)).map(count).sum() })
        .collect();
    crate::cancel::check()?;
    let mut acc = 0u32;
    let starts: Vec<u32> = sums
        .iter()
        .map(|&c| {
            let s = acc;
            acc += c;
            s
        })
        .collect();
    if 2 * acc as usize != 3 * nh {
        return Err(crate::error::MeshError::Invariant(format!("sqrt3: {} corners but {} half-edges", 3 * nh, 2 * acc)));
    }
    // the first edge id of triangle h
    let mut base = vec![0u32; nh];
    base.par_chunks_mut(SCAN_CHUNK).enumerate().for_each(|(k, ch)| {
        let mut e = starts[k];
        for (i, b) in ch.iter_mut().enumerate() {
            *b = e;
            e += count(k * SCAN_CHUNK + i);
        }
    });
    let e1 = |h: usize| base[h] + first0(h) as u32;
    let e2 = |h: usize| e1(h) + (h & 1 == 0) as u32;
    // output half-edge of corners 3h, 3h + 1, 3h + 2
    let id0 = |h: usize| if first0(h) { 2 * base[h] } else { 2 * e2(next[h ^ 1] as usize) + 1 };
    let id1 = |h: usize| if h & 1 == 0 { 2 * e1(h) } else { 2 * e1(h ^ 1) + 1 };
    let id2 = |h: usize| if first2(h) { 2 * e2(h) } else { 2 * base[(prev[h] ^ 1) as usize] + 1 };
    let mut cols = Columns::for_points_unfilled(nv + m.n_faces(), 3 * nh, nh);
    let nvu = nv as u32;
    {
        let cp = |c: &mut Vec<u32>| super::hosts::SyncPtr(c.as_mut_ptr());
        let (pn, pp, pv, pf) = (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face));
        cols.f_start.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(h, fs)| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let ids = [id0(h), id1(h), id2(h)];
            let verts = [vert[h], nvu + face[h ^ 1], nvu + face[h]];
            *fs = ids[0];
            for k in 0..3 {
                let (i, n) = (ids[k] as usize, ids[(k + 1) % 3]);
                // SAFETY: the ids are a bijection from the 3H corners onto
                // 0..3H, so every half-edge is written (and is a next) once.
                unsafe {
                    *pn.get().add(i) = n;
                    *pp.get().add(n as usize) = i as u32;
                    *pv.get().add(i) = verts[k];
                    *pf.get().add(i) = h as u32;
                }
            }
        });
    }
    crate::cancel::check()?;
    // SAFETY: not cancelled, and the ids are a bijection onto 0..3H (above)
    unsafe { cols.assume_filled(3 * nh) };
    // a vertex leaves from its first corner: old vertex v from the corner
    // 3h of its lowest outgoing h; centroid f from the lowest of 3(k ^ 1) + 1
    // and 3k + 2 over the half-edges k of f
    let (vo, fo) = cols.v_out.split_at_mut(nv);
    vo.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        let h = super::creases::ring(m, m.v_out[v]).min().unwrap_or(0) as usize;
        *o = id0(h);
    });
    fo.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
        let s = m.f_start[f];
        let (mut k, mut best) = (s, u32::MAX);
        loop {
            best = best.min(3 * (k ^ 1) + 1).min(3 * k + 2);
            k = next[k as usize];
            if k == s {
                break;
            }
        }
        let h = (best / 3) as usize;
        *o = if best % 3 == 1 { id1(h) } else { id2(h) };
    });
    Ok(cols)
}

/// [`sqrt3_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays) with the level's weights: by the closed-mesh masks on
/// a closed mesh without point-spheres (no stencils built), else through
/// the stencils.
pub fn sqrt3_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    super::level::level_with_data(m, req, data, sqrt3_level, |a, k| direct_data(m, a, k))
}

/// Kobbelt's masks on rows of `k` numbers, output `[V | F]` as [`step`]:
/// `(1 − αₙ) v + αₙ/n Σ neighbours` (§2, eq. 3) and the face centroids.
fn direct_data(m: &Mesh, a: &[f64], k: usize) -> Result<Vec<f64>> {
    let (nv, nf) = (m.n_vertices(), m.n_faces());
    let vert = &m.he_vert;
    let mut out = vec![0.0; (nv + nf) * k];
    if k == 0 {
        return Ok(out);
    }
    let row = |v: u32| &a[v as usize * k..(v as usize + 1) * k];
    let (vp, fp) = out.split_at_mut(nv * k);
    rayon::join(
        || {
            vp.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
                if crate::cancel::requested() {
                    return; // the check after the join reports it
                }
                let mut n = 0usize;
                for h in super::creases::ring(m, m.v_out[v]) {
                    o.iter_mut().zip(row(vert[(h ^ 1) as usize])).for_each(|(o, x)| *o += x);
                    n += 1;
                }
                let al = sqrt3_alpha(n);
                let w = al / n as f64;
                o.iter_mut().zip(row(v as u32)).for_each(|(o, x)| *o = x * (1.0 - al) + *o * w);
            })
        },
        || {
            fp.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
                if crate::cancel::requested() {
                    return;
                }
                let (s, mut h, mut n) = (m.f_start[f], m.f_start[f], 0usize);
                loop {
                    o.iter_mut().zip(row(vert[h as usize])).for_each(|(o, x)| *o += x);
                    n += 1;
                    h = m.he_next[h as usize];
                    if h == s {
                        break;
                    }
                }
                let w = 1.0 / n as f64;
                o.iter_mut().for_each(|o| *o *= w);
            })
        },
    );
    crate::cancel::check()?;
    Ok(out)
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`sqrt3`]. Open meshes follow Kobbelt's boundary rule
/// ([`boundary`]), whose parity is `req.level`.
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn sqrt3_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() > 0 {
            return boundary::open_level(Cow::Borrowed(m), req);
        }
        let mesh = step(m)?;
        let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            let fl = FaceLayout::new(m)?;
            Some(Stencils::build(nv + nf, nv, |i, row| {
                if i < nv {
                    kobbelt_row(m, vert, i, row);
                } else {
                    let hs = fl.corners(i - nv);
                    for &h in hs {
                        row.add(vert[h as usize], 1.0 / hs.len() as f64);
                    }
                }
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let mut o = Origins::with_capacity(nv + nf, mesh.n_edges(), nh);
            o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(FACE).take(nf)));
            o.vertex.extend((0..nv as u32).chain(0..nf as u32));
            o.face_kind = vec![EDGE; nh];
            o.face.extend((0..nh as u32).map(|h| h >> 1));
            // triangle h = [a, c_g, c_f]: spoke in g, the flipped edge, spoke in f
            edge_origins_by_corner(&mesh, &mut o, |c| {
                let h = c / 3;
                match c % 3 {
                    0 => (FACE, face[h ^ 1]),
                    1 => (EDGE, (h >> 1) as u32),
                    _ => (FACE, face[h]),
                }
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}

/// [`sqrt3_level`] on an input the caller gives up (a previous level of a
/// multi-level call). Without point-spheres and asked for no stencils or
/// origins, it frees part of the input before the output's positions exist:
/// a closed mesh through [`step_owned`], an open one through
/// `boundary::open_level`; anything else is [`sqrt3_level`]'s.
pub fn sqrt3_level_owned(m: Mesh, req: &Request) -> Result<Level> {
    crate::cancel::check()?;
    if req.stencils || req.origins || m.has_point_spheres() {
        return sqrt3_level(&m, req);
    }
    if m.n_holes() > 0 {
        return boundary::open_level(Cow::Owned(m), req);
    }
    Ok(Level { mesh: step_owned(m)?, stencils: None, origins: None, creases: None })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direct_data_equals_the_stencils_on_corpus() {
        crate::schemes::hosts::test_meshes::check_direct_data_on_corpus(2, 1e-12, sqrt3_level, sqrt3_level_with);
    }
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(sqrt3, |_, (v, e, f)| (v + f, 3 * e, 2 * e), |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 3), "{name} triangles");
        });
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        level_matches_plain_on_corpus(sqrt3, sqrt3_level, |name, m, lv| {
            let o = lv.origins.as_ref().unwrap();
            let fl = FaceLayout::new(m).unwrap();
            let ps = n_point_spheres(m);
            let fv = origin_counts(&o.vertex_kind, &o.vertex, FACE, m.n_faces());
            let fe = origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces());
            for f in 0..m.n_faces() {
                // one centroid and n spokes per real n-gon
                assert_eq!((fv[f], fe[f]), if is_point_face(m, f) { (0, 0) } else { (1, fl.degree(f)) }, "{name} face {f}");
            }
            assert!(origin_counts(&o.vertex_kind, &o.vertex, VERTEX, m.n_vertices()).iter().all(|&c| c == 1), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, EDGE, m.n_edges()).iter().all(|&c| c == 2), "{name}");
            assert!(origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
            assert_eq!(o.face_kind.iter().filter(|&&k| k == FACE).count(), ps, "{name}");
        });
    }

    #[test]
    fn owned_level_equals_the_borrowed_one() {
        // closed and open inputs (both consumed) and point-sphere ones (the
        // borrowed path); positions compared bit for bit
        let mut cases: Vec<(String, Mesh)> = corpus().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
        cases.extend(open_meshes().into_iter().map(|(n, m)| (n.to_string(), m)));
        for (name, m) in cases {
            for level in 0..2 {
                let req = Request { level, ..Request::plain() };
                // the even step (level 1) refuses open inputs that no odd step
                // made: both paths alike
                let a = match sqrt3_level(&m, &req) {
                    Ok(l) => l.mesh,
                    Err(e) => {
                        assert_eq!(sqrt3_level_owned(m.clone(), &req).unwrap_err().to_string(), e.to_string(), "{name}");
                        continue;
                    }
                };
                let b = sqrt3_level_owned(m.clone(), &req).unwrap().mesh;
                assert_eq!(a, b, "{name} level {level}");
                assert_eq!(a.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>(),
                    b.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>(), "{name}");
            }
        }
        // the owned path is the one taken on a closed mesh: same output as the plain step
        let t = crate::primitives::torus(12, 8, 3.0, 1.0).unwrap();
        assert_eq!(step_owned(t.clone()).unwrap(), step(&t).unwrap());
    }

    #[test]
    fn two_steps_are_triadic() {
        let m = crate::primitives::icosahedron();
        let r = sqrt3(&sqrt3(&m).unwrap()).unwrap();
        assert_eq!(r.n_faces(), 9 * m.n_faces());
    }
}
