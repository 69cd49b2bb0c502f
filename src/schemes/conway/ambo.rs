//! The edge-midpoint family: ambo (`a`), Conway subdivide (`u`) and quinto
//! (`q`). Every new vertex on an edge is its midpoint; the corner edge
//! `C(g)` joins the midpoints of the two edges at corner `g`
//! (`mid(prev g)`–`mid(g)`).

use super::build::{reserve, Ctx, Out};
use crate::error::Result;
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;

/// Ambo (rectify, polyhedronisme `ambo`): a vertex at every edge midpoint,
/// a face inside every face (same size) and a face around every vertex
/// (size = valence). V' = E, E' = 2E, F' = F + V.
pub fn ambo(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("ambo", m, |m| {
        let c = Ctx::new(m)?;
        reserve("ambo", m, c.ne, 2 * c.ne, c.nf + c.nv)?;
        let pos = (0..c.ne).map(|e| c.mid(e)).collect();
        let mut out = Out::new(pos, c.nh, c.nf + c.nv, 2 * c.nh).of(&c);
        // the midpoint of edge e is born from it: the face of its first side
        out.vertex_origins(|| (0..c.ne).map(|e| c.face[2 * e]).collect());
        face_faces(&c, &mut out, 0);
        for v in 0..c.nv {
            crate::cancel::poll(v)?;
            out.from_vertex(v);
            // side mid(g) -> mid(rotate g) = mid(prev g): C(g) against the face's way
            out.face(c.rotation(v).map(|g| ((g >> 1) as u32, g as u32)));
        }
        out.finish("ambo")
    })
}

/// The face inside every face: corners at the midpoints of its edges, the
/// side `mid(h) → mid(next h)` along `C(next h)`. Midpoint of edge e is
/// output vertex `base + e`.
fn face_faces(c: &Ctx, out: &mut Out, base: usize) {
    for f in 0..c.nf {
        out.from_face(f);
        out.face(c.corners(f).map(|h| ((base + (h >> 1)) as u32, c.next[h])));
    }
}

/// Conway subdivide (`u`, the dual of chamfer: `u = dcd`): ambo keeping the
/// input vertices. Each face keeps an inner face on its edge midpoints, and
/// each corner `g` becomes the triangle `[tail g, mid(g), mid(prev g)]`.
/// V' = V + E, E' = 4E, F' = F + 2E; face sizes: the input's faces, 2E
/// triangles.
pub fn subdivide(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("conway_subdivide", m, |m| {
        let c = Ctx::new(m)?;
        reserve("conway_subdivide", m, c.nv + c.ne, 4 * c.ne, c.nf + c.nh)?;
        let mut pos = Vec::with_capacity(c.nv + c.ne);
        pos.extend_from_slice(m.positions());
        pos.extend((0..c.ne).map(|e| c.mid(e)));
        // edge ids: C(g) = g, the half S(g) = tail(g)–mid(g) is nh + g
        let half = |g: usize| (c.nh + g) as u32;
        let mut out = Out::new(pos, 2 * c.nh, c.nf + c.nh, 4 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        out.vertex_origins(|| (0..c.nv as u32).map(|v| super::super::face_parents::VERT | v).chain((0..c.ne).map(|e| c.face[2 * e])).collect());
        face_faces(&c, &mut out, c.nv);
        for g in 0..c.nh {
            crate::cancel::poll(g)?;
            // the corner triangle lies in the face of its corner
            out.from_face(c.face[g] as usize);
            let p = c.prev[g] as usize;
            let mid = |h: usize| (c.nv + (h >> 1)) as u32;
            out.face([(c.tail(g), half(g)), (mid(g), g as u32), (mid(p), half(p ^ 1))]);
        }
        out.finish("conway_subdivide")
    })
}

/// Quinto (`q`, polyhedronisme `quinto`): a pentagon at every corner and a
/// smaller copy of every face. New vertices: the edge midpoints, and for
/// every half-edge h the inner point halfway between mid(h) and its face's
/// centroid. The corner between h and next h becomes
/// `[in(h), mid(h), head(h), mid(next h), in(next h)]`, the inner face runs
/// through the `in(h)`.
/// V' = V + 3E, E' = 6E, F' = F + 2E; face sizes: the input's faces, 2E
/// pentagons.
pub fn quinto(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("quinto", m, |m| {
        let c = Ctx::new(m)?;
        reserve("quinto", m, c.nv + 3 * c.ne, 6 * c.ne, c.nf + c.nh)?;
        let mut pos = Vec::with_capacity(c.nv + c.ne + c.nh);
        pos.extend_from_slice(m.positions());
        pos.extend((0..c.ne).map(|e| c.mid(e)));
        pos.extend((0..c.nh).map(|h| (c.mid(h >> 1) + c.cen[c.face[h] as usize]) * 0.5));
        let mid = |h: usize| (c.nv + (h >> 1)) as u32;
        let inner = |h: usize| (c.nv + c.ne + h) as u32;
        // edge ids: in(h)–mid(h) is h, the half tail(g)–mid(g) is nh + g,
        // in(h)–in(next h) is 2nh + h
        let (half, ring) = (|g: usize| (c.nh + g) as u32, |h: usize| (2 * c.nh + h) as u32);
        let mut out = Out::new(pos, 3 * c.nh, c.nf + c.nh, 6 * c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for h in 0..c.nh {
            crate::cancel::poll(h)?;
            // the pentagon at the corner between h and next h lies in their face
            out.from_face(c.face[h] as usize);
            let nx = c.next(h);
            out.face([(inner(h), h as u32), (mid(h), half(h ^ 1)), (c.head(h), half(nx)), (mid(nx), nx as u32), (inner(nx), ring(h))]);
        }
        for f in 0..c.nf {
            out.from_face(f);
            out.face(c.corners(f).map(|h| (inner(h), ring(h))));
        }
        out.finish("quinto")
    })
}
