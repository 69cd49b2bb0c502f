//! The chiral family: gyro (`g`), propellor (`p`) and whirl (`w`). Each
//! half-edge h gets the point `p(h)` a third of the way from its tail
//! (polyhedronisme's `oneThird`), so an edge carries two points and its
//! middle third `p(h)–p(twin h)`. Which way the new faces turn follows the
//! face order (counter-clockwise seen from outside), never a geometric
//! choice: the result of the mirror image is the mirror image of the result
//! on every genus, and orientation stays consistent.
//!
//! polyhedronisme projects the old vertices and the face centres onto the
//! unit sphere; here they stay where they are (the input may be a torus),
//! and `canonicalize` gives Hart's shape on convex genus-0 results.
//!
//! Edge ids shared by the three: the middle third of edge e is `nh + e`,
//! the outer third `tail(g)–p(g)` is `2nh + g`.

use super::build::{reserve, Ctx, Out};
use crate::error::Result;
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

fn third_points(c: &Ctx, pos: &mut Vec<DVec3>) {
    pos.extend((0..c.nh).map(|h| c.third(h)));
}

/// The corners `p(h) → p(twin h) → head(h) → p(next h)` every new face of
/// the three shares, with `pt(h)` the output vertex of `p(h)`.
#[inline]
fn edge_run(c: &Ctx, h: usize, pt: impl Fn(usize) -> u32) -> [(u32, u32); 3] {
    let nx = c.next(h);
    let (mid, outer) = ((c.nh + (h >> 1)) as u32, |g: usize| (2 * c.nh + g) as u32);
    [(pt(h), mid), (pt(h ^ 1), outer(h ^ 1)), (c.head(h), outer(nx))]
}

/// Gyro (`g`, polyhedronisme `gyro`; the dual of snub): a vertex at every
/// face centroid and two on every edge; every half-edge h becomes the
/// pentagon `[centre(f), p(h), p(twin h), head(h), p(next h)]`.
/// V' = V + F + 2E, E' = 5E, F' = 2E; face sizes: 2E pentagons.
pub fn gyro(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("gyro", m, |m| {
        let c = Ctx::new(m)?;
        reserve("gyro", m, c.nv + c.nf + c.nh, 5 * c.ne, c.nh)?;
        let mut pos = Vec::with_capacity(c.nv + c.nf + c.nh);
        pos.extend_from_slice(m.positions());
        pos.extend_from_slice(&c.cen);
        third_points(&c, &mut pos);
        let base = c.nv + c.nf;
        let pt = |h: usize| (base + h) as u32;
        // spoke centre(f)–p(h): id h
        let mut out = Out::new(pos, 3 * c.nh, c.nh, 5 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for h in 0..c.nh {
            crate::cancel::poll(h)?;
            // every face built per half-edge lies in that half-edge's face
            out.from_face(c.face[h] as usize);
            let [a, b, d] = edge_run(&c, h, pt);
            let nx = c.next(h);
            out.face([((c.nv + c.face[h] as usize) as u32, h as u32), a, b, d, (pt(nx), nx as u32)]);
        }
        out.finish("gyro")
    })
}

/// Propellor (`p`, polyhedronisme `propellor`): two points on every edge, a
/// twisted copy of every face through its `p(h)`, and the quad
/// `[p(h), p(twin h), head(h), p(next h)]` for every half-edge h.
/// V' = V + 2E, E' = 5E, F' = F + 2E; face sizes: the input's faces, 2E
/// quads.
pub fn propellor(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("propellor", m, |m| {
        let c = Ctx::new(m)?;
        reserve("propellor", m, c.nv + c.nh, 5 * c.ne, c.nf + c.nh)?;
        let mut pos = Vec::with_capacity(c.nv + c.nh);
        pos.extend_from_slice(m.positions());
        third_points(&c, &mut pos);
        let pt = |h: usize| (c.nv + h) as u32;
        // inner side p(h)–p(next h): id h
        let mut out = Out::new(pos, 3 * c.nh, c.nf + c.nh, 5 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for h in 0..c.nh {
            crate::cancel::poll(h)?;
            out.from_face(c.face[h] as usize);
            let [a, b, d] = edge_run(&c, h, pt);
            out.face([a, b, (d.0, d.1), (pt(c.next(h)), h as u32)]);
        }
        for f in 0..c.nf {
            out.from_face(f);
            out.face(c.corners(f).map(|h| (pt(h), h as u32)));
        }
        out.finish("propellor")
    })
}

/// Whirl (`w`, polyhedronisme `whirl`): propellor with the twisted copy of
/// every face shrunk towards the centroid: the inner point `q(h)` lies a
/// third of the way from the centroid to `p(h)`, and every half-edge h
/// becomes the hexagon `[q(h), p(h), p(twin h), head(h), p(next h), q(next h)]`.
/// V' = V + 4E, E' = 7E, F' = F + 2E; face sizes: the input's faces, 2E
/// hexagons.
pub fn whirl(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("whirl", m, |m| {
        let c = Ctx::new(m)?;
        reserve("whirl", m, c.nv + 2 * c.nh, 7 * c.ne, c.nf + c.nh)?;
        let mut pos = Vec::with_capacity(c.nv + 2 * c.nh);
        pos.extend_from_slice(m.positions());
        third_points(&c, &mut pos);
        pos.extend((0..c.nh).map(|h| c.cen[c.face[h] as usize].lerp(c.third(h), 1.0 / 3.0)));
        let pt = |h: usize| (c.nv + h) as u32;
        let q = |h: usize| (c.nv + c.nh + h) as u32;
        // q(h)–q(next h): id h; q(h)–p(h): 3nh + h
        let qp = |h: usize| (3 * c.nh + h) as u32;
        let mut out = Out::new(pos, 4 * c.nh, c.nf + c.nh, 7 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for h in 0..c.nh {
            crate::cancel::poll(h)?;
            out.from_face(c.face[h] as usize);
            let [a, b, d] = edge_run(&c, h, pt);
            let nx = c.next(h);
            out.face([(q(h), qp(h)), a, b, d, (pt(nx), qp(nx)), (q(nx), h as u32)]);
        }
        for f in 0..c.nf {
            out.from_face(f);
            out.face(c.corners(f).map(|h| (q(h), h as u32)));
        }
        out.finish("whirl")
    })
}
