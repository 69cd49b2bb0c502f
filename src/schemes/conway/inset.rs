//! The inset family: chamfer (`c`) and loft (`l`, `lN`). Every corner g of
//! a face gets its own point `q(g)` between its vertex and the face
//! centroid.

use super::build::{reserve, Ctx, Out};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use crate::schemes::hosts::with_point_spheres;

/// Chamfer (`c`, polyhedronisme `chamfer`): every face shrinks to a copy on
/// its corner points `q(g)`, a third of the way from the vertex to the
/// centroid, every input vertex stays, and every edge becomes the hexagon
/// `[tail(h), q(next t), q(t), head(h), q(next h), q(h)]` (t = twin h).
/// V' = V + 2E, E' = 4E, F' = F + E; face sizes: the input's faces, E
/// hexagons.
///
/// polyhedronisme pushes the old vertices away from the origin and the face
/// copies along their normals; that presumes a polyhedron around the
/// origin, so here the copies move inwards instead (same topology).
pub fn chamfer(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("chamfer", m, |m| {
        let c = Ctx::new(m)?;
        reserve("chamfer", m, c.nv + c.nh, 4 * c.ne, c.nf + c.ne)?;
        let mut pos = Vec::with_capacity(c.nv + c.nh);
        pos.extend_from_slice(m.positions());
        pos.extend((0..c.nh).map(|g| c.p(c.tail(g)).lerp(c.cen[c.face[g] as usize], 1.0 / 3.0)));
        let q = |g: usize| (c.nv + g) as u32;
        // q(h)–q(next h): id h; the spoke tail(g)–q(g): nh + g
        let spoke = |g: usize| (c.nh + g) as u32;
        let mut out = Out::new(pos, 2 * c.nh, c.nf + c.ne, 4 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for f in 0..c.nf {
            out.from_face(f);
            out.face(c.corners(f).map(|h| (q(h), h as u32)));
        }
        for e in 0..c.ne {
            crate::cancel::poll(e)?;
            let (h, t) = (2 * e, 2 * e + 1);
            // the hexagon of edge e straddles both its faces: the first side's
            out.from_face(c.face[h] as usize);
            let (nh_, nt) = (c.next(h), c.next(t));
            out.face([
                (c.tail(h), spoke(nt)),
                (q(nt), t as u32),
                (q(t), spoke(t)),
                (c.tail(t), spoke(nh_)),
                (q(nh_), h as u32),
                (q(h), spoke(h)),
            ]);
        }
        out.finish("chamfer")
    })
}

/// Loft (`l`, `lN`; polyhedronisme `loft`, its `insetN` with inset 0.5 and
/// no pop-out): every chosen face (all, or those with `n` corners) gets a
/// copy on the midpoints between its corners and its centroid, joined to it
/// by the quads `[tail(h), head(h), i(next h), i(h)]`. With S the chosen
/// faces and Σ their corners:
///
/// ```text
/// V' = V + Σ,   E' = E + 2Σ,   F' = F + Σ    (all faces: V + 2E, 5E, F + 2E)
/// ```
///
/// Face sizes: the input's faces, Σ quads.
pub fn loft(m: &Mesh, n: Option<usize>) -> Result<Mesh> {
    with_point_spheres("loft", m, |m| {
        let c = Ctx::new(m)?;
        let chosen = |f: usize| match n {
            None => true,
            Some(n) => c.fl.degree(f) == n,
        };
        let sigma: usize = (0..c.nf).filter(|&f| chosen(f)).map(|f| c.fl.degree(f)).sum();
        reserve("loft", m, c.nv + sigma, c.ne + 2 * sigma, c.nf + sigma)?;
        let mut pos = Vec::with_capacity(c.nv + sigma);
        pos.extend_from_slice(m.positions());
        let mut inner = vec![NONE; c.nh];
        for f in 0..c.nf {
            if chosen(f) {
                for h in c.corners(f) {
                    inner[h] = pos.len() as u32;
                    pos.push(c.p(c.tail(h)).lerp(c.cen[f], 0.5));
                }
            }
        }
        crate::cancel::check()?;
        // edge ids: input edge e is e; spoke tail(g)–i(g) is nh + g; i(h)–i(next h) is 2nh + h
        let (spoke, ring) = (|g: usize| (c.nh + g) as u32, |h: usize| (2 * c.nh + h) as u32);
        let mut out = Out::new(pos, 3 * c.nh, c.nf + sigma, c.nh + 5 * sigma).of(&c);
        out.keeps_vertices(c.nv);
        for f in 0..c.nf {
            crate::cancel::poll(f)?;
            out.from_face(f);
            if !chosen(f) {
                out.face(c.corners(f).map(|h| (c.tail(h), (h >> 1) as u32)));
                continue;
            }
            for h in c.corners(f) {
                let nx = c.next(h);
                out.face([(c.tail(h), (h >> 1) as u32), (c.head(h), spoke(nx)), (inner[nx], ring(h)), (inner[h], spoke(h))]);
            }
            out.face(c.corners(f).map(|h| (inner[h], ring(h))));
        }
        out.finish("loft")
    })
}
