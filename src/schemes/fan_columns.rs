//! The fan triangulation ([`super::hosts::fan_triangulate`], Loop's first
//! step on faces other than triangles) written straight into the mesh
//! columns (issue 19, item 1): on a quad mesh the corner-and-twin build was
//! most of the fan, and the fan a third of Loop's level.
//!
//! The result is what [`Mesh::from_corner_twins`] built from the old corner
//! lists (kept test-only in `twin_reference.rs`), bit for bit. Its corners:
//! a kept face (triangle or hole) of n corners has one *side* corner per
//! input corner; a fanned face has three per input corner `h` (local index
//! k), the triangle `[tail h → head h (side), head h → c (spoke 1), c → tail h
//! (spoke 2)]`. `from_corner_twins` numbers edges by their first corner (the
//! one whose twin comes later): that corner gets `2e`, with `e` the number of
//! first corners before it, its twin `2e + 1`.
//! * A side corner is first when its twin, the side of `twin h`, comes
//!   later: `cidx(twin h) > cidx(h)` (corners are laid out in input face
//!   order, within a face in cycle order).
//! * In a fanned face of n ≥ 2 corners, spoke 1 of corner k pairs with spoke
//!   2 of corner k + 1: first for k < n − 1, and spoke 2 of corner 0 is first
//!   (its twin is spoke 1 of corner n − 1). A one-gon's spokes pair with each
//!   other, spoke 1 first.
//! So per input corner `rank << 1 | first(side)` (rank: first corners of
//! its face before it), one prefix over faces, and every id is a lookup.

use super::face_vertex_columns::Out;
use super::hosts::{check_output_size, FaceLayout, SyncPtr, MIN_LEN};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, POINT};
use glam::DVec3;
use rayon::prelude::*;

/// Per input face: where its output starts.
#[derive(Clone, Copy, Default)]
struct FaceInfo {
    /// First output corner (for the vertices' first corners).
    base: u32,
    /// First output face.
    fbase: u32,
    /// Number of first corners (output edges) before the face's block.
    ebase: u32,
    /// Its centroid's vertex, or `u32::MAX` for a kept face.
    cent: u32,
}

const KEPT: u32 = u32::MAX;

/// [`super::hosts::fan_triangulate`]: `None` when every face is a triangle.
pub(crate) fn fan_columns(m: &Mesh) -> Result<Option<Mesh>> {
    let nf = m.n_faces();
    let (next, vert, face) = m.halfedge_columns();
    if m.f_start.par_iter().with_min_len(MIN_LEN).any(|&s| s & POINT != 0) {
        return Err(MeshError::Invariant("fan triangulation: point-spheres are set aside by the caller".into()));
    }
    let all_triangles = m.f_start.par_iter().zip(&m.f_hole).with_min_len(MIN_LEN).all(|(&s, &hole)| {
        if hole {
            return true;
        }
        let h1 = next[s as usize];
        let h2 = next[h1 as usize];
        h1 != s && h2 != s && next[h2 as usize] == s
    });
    if all_triangles {
        return Ok(None);
    }
    check_output_size("loop", 3 * m.n_halfedges(), m.n_vertices() + nf)?;
    let fl = FaceLayout::new(m)?;
    let nv = m.n_vertices();
    let cidx = &fl.cidx;
    let fanned = |f: usize| fl.degree(f) != 3 && !m.f_hole[f];
    // pass 1: per input corner `rank << 1 | first(side)`, per face its first corners
    let mut rm = vec![0u32; m.n_halfedges()];
    let rp = SyncPtr(rm.as_mut_ptr());
    let cnt: Vec<u32> = (0..nf)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|f| {
            if crate::cancel::requested() {
                return 0; // the check after the loop reports it
            }
            let fan = fanned(f);
            let mut r = 0u32;
            for (k, &h) in fl.corners(f).iter().enumerate() {
                let c = cidx[h as usize];
                let first = cidx[(h ^ 1) as usize] > c;
                // SAFETY: corner c belongs to face f, whose task alone writes it.
                unsafe { *rp.get().add(c as usize) = r << 1 | first as u32 };
                r += first as u32;
                if fan {
                    // spoke 1 (first unless it is the last of n ≥ 2), and spoke 2 of corner 0
                    r += 1 + (k == 0 && fl.degree(f) > 1) as u32 - (k + 1 == fl.degree(f) && k > 0) as u32;
                }
            }
            r
        })
        .collect();
    crate::cancel::check()?;
    // prefixes: corners, faces, edges, centroids
    let mut fi = Vec::with_capacity(nf);
    let (mut b, mut fb, mut eb, mut cv) = (0u32, 0u32, 0u32, nv as u32);
    for (f, c) in cnt.into_iter().enumerate() {
        let n = fl.degree(f) as u32;
        let fan = fanned(f);
        fi.push(FaceInfo { base: b, fbase: fb, ebase: eb, cent: if fan { cv } else { KEPT } });
        b += if fan { 3 * n } else { n };
        fb += if fan { n } else { 1 };
        eb += c;
        cv += fan as u32;
    }
    if 2 * eb != b {
        return Err(MeshError::Invariant(format!("fan triangulation: {b} corners but {} half-edges", 2 * eb)));
    }
    // positions: the input's, then the centroids in face order
    let mut pos = Vec::with_capacity(cv as usize);
    pos.extend_from_slice(&m.pos);
    pos.resize(cv as usize, DVec3::ZERO);
    {
        let (_, cents) = pos.split_at_mut(nv);
        let fans: Vec<u32> = (0..nf as u32).filter(|&f| fi[f as usize].cent != KEPT).collect();
        cents.par_iter_mut().with_min_len(MIN_LEN).zip(&fans).for_each(|(p, &f)| {
            let hs = fl.corners(f as usize);
            let s: DVec3 = hs.iter().map(|&h| m.pos[vert[h as usize] as usize]).sum();
            *p = s / hs.len() as f64;
        });
    }
    let rank = |h: u32| rm[cidx[h as usize] as usize];
    let side_first = |h: u32| 2 * (fi[face[h as usize] as usize].ebase + (rank(h) >> 1));
    let side = |h: u32| if rank(h) & 1 != 0 { side_first(h) } else { side_first(h ^ 1) + 1 };
    // spokes of local corner k (half-edge h) of fanned face f of n corners
    let spoke1 = |f: &FaceInfo, h: u32, k: usize, n: usize, h0: u32| {
        if n == 1 || k + 1 < n {
            let r = rank(h);
            2 * (f.ebase + (r >> 1) + (r & 1))
        } else {
            2 * (f.ebase + (rank(h0) & 1) + 1) + 1
        }
    };
    let spoke2 = |f: &FaceInfo, hs: &[u32], k: usize| {
        let n = hs.len();
        if n == 1 {
            spoke1(f, hs[0], 0, 1, hs[0]) + 1
        } else if k == 0 {
            2 * (f.ebase + (rank(hs[0]) & 1) + 1)
        } else {
            spoke1(f, hs[k - 1], k - 1, n, hs[0]) + 1
        }
    };
    let mut cols = Columns::unfilled(pos, b as usize, fb as usize);
    let out = Out::of(&mut cols);
    let fhole = SyncPtr(cols.f_hole.as_mut_ptr());
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        if crate::cancel::requested() {
            return;
        }
        let info = &fi[f];
        let hs = fl.corners(f);
        let n = hs.len();
        // SAFETY: the corners of face f's block (a bijection onto their ids),
        // its output faces and their hole marks are written by this task only.
        unsafe {
            if info.cent == KEPT {
                let of = info.fbase;
                out.start(of, side(hs[0]));
                for (k, &h) in hs.iter().enumerate() {
                    out.link(side(h), vert[h as usize], of, side(hs[if k + 1 == n { 0 } else { k + 1 }]));
                }
                *fhole.get().add(of as usize) = m.f_hole[f];
            } else {
                for (k, &h) in hs.iter().enumerate() {
                    let of = info.fbase + k as u32;
                    let (a, s1, s2) = (side(h), spoke1(info, h, k, n, hs[0]), spoke2(info, hs, k));
                    out.start(of, a);
                    out.link(a, vert[h as usize], of, s1);
                    out.link(s1, vert[next[h as usize] as usize], of, s2);
                    out.link(s2, info.cent, of, a);
                }
            }
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled: every face's block wrote its corners, a
    // bijection onto the b half-edges
    unsafe { cols.assume_filled(b as usize) };
    // an input vertex first shows up at the lowest of its corners: per
    // outgoing g, its side corner, or in a fanned face past the first corner
    // spoke 1 of the corner before (head(prev g) = tail g), which comes earlier
    let (vo, co) = cols.v_out.split_at_mut(nv);
    vo.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        if crate::cancel::requested() {
            return;
        }
        let s = m.v_out[v];
        let (mut g, mut best) = (s, (u32::MAX, 0u32));
        loop {
            let f = face[g as usize] as usize;
            let info = &fi[f];
            let k = (cidx[g as usize] - fl.off[f]) as usize;
            let cand = if info.cent != KEPT && k > 0 {
                let hs = fl.corners(f);
                (info.base + 3 * (k as u32 - 1) + 1, spoke1(info, hs[k - 1], k - 1, hs.len(), hs[0]))
            } else if info.cent != KEPT {
                (info.base, side(g))
            } else {
                (info.base + k as u32, side(g))
            };
            if cand.0 < best.0 {
                best = cand;
            }
            g = m.he_prev[g as usize] ^ 1;
            if g == s {
                break;
            }
        }
        *o = best.1;
    });
    // a centroid first shows up at spoke 2 of its face's first corner
    let fans: Vec<u32> = (0..nf as u32).filter(|&f| fi[f as usize].cent != KEPT).collect();
    co.par_iter_mut().with_min_len(MIN_LEN).zip(&fans).for_each(|(o, &f)| {
        *o = spoke2(&fi[f as usize], fl.corners(f as usize), 0);
    });
    crate::cancel::check()?;
    Mesh::from_columns(cols).map(Some)
}

#[cfg(test)]
mod tests {
    use super::super::hosts::test_meshes as tm;
    use super::super::twin_reference as old;
    use super::*;

    /// The corpus without point-spheres (the caller sets them aside), the
    /// open meshes, one-gons, two-gons, mixed faces and meshes whose stored
    /// corners are not their first, and again after one Loop level of each:
    /// the same mesh as the corner-and-twin build.
    #[test]
    fn columns_equal_the_twin_build() {
        let mut meshes: Vec<(&str, Mesh)> = tm::corpus().into_iter().filter(|(_, m)| !m.v_out.iter().any(|&o| o & POINT != 0)).collect();
        meshes.extend(tm::open_meshes());
        meshes.push(("handle_cube", tm::handle_cube()));
        meshes.push(("one_two_gon", tm::one_gon_two_gon_cube()));
        meshes.push(("star_prism", tm::star_prism()));
        meshes.push(("torus", crate::primitives::torus(7, 5, 1.0, 0.3).unwrap()));
        let mut fanned = 0;
        for (name, m) in &meshes {
            let a = fan_columns(m).unwrap();
            let b = old::fan_triangulate(m).unwrap();
            assert_eq!(a.is_some(), b.is_some(), "{name}");
            if let (Some(a), Some(b)) = (a, b) {
                a.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(a == b, "{name}");
                fanned += 1;
                // a Doo-Sabin step gives faces of every size around the fans
                let ds = crate::schemes::doo_sabin::doo_sabin_level(&a, &crate::schemes::level::Request::plain()).unwrap().mesh;
                let (a2, b2) = (fan_columns(&ds).unwrap().unwrap(), old::fan_triangulate(&ds).unwrap().unwrap());
                assert!(a2 == b2, "{name} after Doo-Sabin");
            }
        }
        assert!(fanned >= 8, "only {fanned} meshes had faces to fan");
        let mut p = crate::primitives::cube();
        p.create_vertex(DVec3::ONE).unwrap();
        assert!(fan_columns(&p).is_err());
    }
}
