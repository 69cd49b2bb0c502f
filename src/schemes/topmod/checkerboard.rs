//! Checkerboard remeshing (TopMod's *Checkerboard*,
//! `checkerBoardRemeshing(obj, thickness)`), read from TopMod's source
//! (`include/dlflaux/DLFLSubdiv.cc`, and `extrudeFacePlanarOffset` in
//! `DLFLExtrude.cc` for the inset), the only description of it.
//!
//! Each face is inset (corner x moves by `thickness·((x_prev − x) +
//! (x_next − x))`, reversed at concave corners, along the inward
//! perpendicular at straight ones); each edge is trisected at `thickness`
//! from both ends; each corner becomes the quad `[v, p(h), i(h), p'(prev
//! h)]` of the vertex, its two nearby trisection points and its inset
//! point; each side h the quad `[p(h), p(twin h), i(next h), i(h)]`; each
//! face keeps its inset n-gon. V' = V + 4E, E' = 9E, F' = F + 4E;
//! histogram: the input's face sizes plus 4E quads. Vertex layout: old
//! vertices, trisection point of h near tail(h) at V + h, inset point of
//! corner h at V + 2E + h. Dual checkerboard is `dual ∘ checkerboard ∘ dual`
//! (`MainWindow::subdivideDualCheckerBoard`), in `compose`.

use crate::schemes::keyed::{In, Out};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;

/// TopMod's checkerboard with `thickness` in (0, 0.5] (TopMod clamps to
/// it; default 0.33). See the module docs.
pub fn checkerboard(m: &Mesh, thickness: f64) -> Result<Mesh> {
    if !(thickness.is_finite() && thickness > 0.0 && thickness <= 0.5) {
        return Err(MeshError::InvalidArgument(format!("checkerboard: thickness = {} must be in (0, 0.5]", crate::error::num(thickness))));
    }
    with_point_spheres("checkerboard", m, |m| {
        let i = In::new(m)?;
        let (v, nh, ne) = (i.nv, i.nh, i.ne);
        let pos = positions(&i, thickness);
        let (tp, ip) = (|h: usize| (v + h) as u32, |h: usize| (v + nh + h) as u32);
        // keys: [0, H) segment at tail(h), [H, H+E) middle segment, [H+E, 2H+E)
        // inset side of corner h, then p(h)–i(h), then i(h)–p(twin prev h)
        let (km, ki, ka, kb) = (nh, nh + ne, 2 * nh + ne, 3 * nh + ne);
        let mut o = Out::new(pos, 4 * nh + ne, i.nf + 2 * nh, 9 * nh).of(&i);
        o.keeps_vertices(i.nv);
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                o.c(ip(h as usize), (ki + h as usize) as u32);
            }
            o.end();
            for &h in i.fl.corners(f) {
                let (h, p) = (h as usize, i.prev[h as usize] as usize);
                let nx = i.next[h] as usize;
                o.c(i.vert[h], h as u32);
                o.c(tp(h), (ka + h) as u32);
                o.c(ip(h), (kb + h) as u32);
                o.c(tp(p ^ 1), (p ^ 1) as u32);
                o.end();
                o.c(tp(h), (km + (h >> 1)) as u32);
                o.c(tp(h ^ 1), (kb + nx) as u32);
                o.c(ip(nx), (ki + h) as u32);
                o.c(ip(h), (ka + h) as u32);
                o.end();
            }
        }
        o.finish("checkerboard")
    })
}

/// Checkerboard's vertices (old ones, trisection points at V + h, inset
/// points at V + 2E + h); shared with [`super::checkerboard_dual`].
pub(crate) fn positions(i: &In<'_>, thickness: f64) -> Vec<glam::DVec3> {
    let (v, nh) = (i.nv, i.nh);
    let normals = i.normals();
    let mut pos = i.positions(2 * nh);
    for h in 0..nh {
        pos.push(i.p(h).lerp(i.q(h), thickness));
    }
    pos.resize(v + 2 * nh, glam::DVec3::ZERO);
    for f in 0..i.nf {
        let n = normals[f];
        for &h in i.fl.corners(f) {
            let h = h as usize;
            let x = i.p(h);
            let (pv, nv) = (i.p(i.prev[h] as usize) - x, i.q(h) - x);
            // sides past ~1e150 or below ~1e-150 overflow or underflow
            // the lengths: the same offset from the sides divided by their
            // largest coordinate (ordinary sides keep their bits)
            let k = pv.abs().max_element().max(nv.abs().max_element());
            let off = if crate::geometry::squares_leave_f64(k) {
                inset_offset(pv / k, nv / k, n, thickness) * k
            } else {
                inset_offset(pv, nv, n, thickness)
            };
            pos[v + nh + h] = x + off;
        }
    }
    pos
}

/// The inset point's offset from a corner whose sides run along `pv`
/// (to the previous corner) and `nv` (to the next), in a face of normal `n`.
#[inline]
fn inset_offset(pv: glam::DVec3, nv: glam::DVec3, n: glam::DVec3, thickness: f64) -> glam::DVec3 {
    let s = pv + nv;
    let scale = pv.length().max(nv.length());
    if s.length() > 1e-9 * scale {
        if nv.cross(pv).dot(n) < 0.0 {
            -thickness * s
        } else {
            thickness * s
        }
    } else {
        thickness * nv.length() * n.cross(nv).normalize_or_zero()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};

    #[test]
    fn counts() {
        check("checkerboard", |m| checkerboard(m, 0.33), |_, (v, e, f)| (v + 4 * e, 9 * e, f + 4 * e), |m, (_, e, _)| {
            let mut h = hist_of(m);
            *h.entry(4).or_insert(0) += 4 * e;
            h
        });
        assert!(checkerboard(&crate::primitives::cube(), 0.6).is_err());
    }
}
