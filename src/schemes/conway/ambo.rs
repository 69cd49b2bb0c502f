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

/// Expand (`e` = `aa`, cantellation): `ambo(ambo(m))` in one pass, without
/// the inner ambo's mesh A (issue 16: A was built only for the outer ambo to
/// read it). A's edges are numbered by first corner, and every one first
/// appears in A's faces inside the faces of m, laid in face-layout order:
/// the edge of A with key `next h` (from mid(h) to mid(next h)) is edge
/// `cidx[h]`, its first side F(h) = 2 cidx[h] and its second side, in the
/// face around tail(h) at corner h, G(h) = 2 cidx[prev h] + 1 (the rotation
/// there is h, twin prev h, …, as the dual walks it). The outer
/// ambo then lays, with A's half-edges as keys and A's edges as vertices:
/// * per face f of m: corner h at edge cidx[h], key F(next h);
/// * per vertex v of m: corner g (in rotation order) at edge cidx[prev g],
///   key G(the next g in rotation);
/// * per edge e of m (A's vertex mid(e), from its first corner in A's face
///   order, the side h of e with the lower cidx): F(h), G(h), F(twin h),
///   G(twin h), each at its edge with itself as key.
/// The same faces, keys and order as the composition, so the same bits
/// (`fused_builds_are_their_compositions`); holes, point-spheres and traced
/// builds (face parents) take the composition.
pub fn expand(m: &Mesh) -> Result<Mesh> {
    if !crate::schemes::hosts::fusable(m) {
        return ambo(&ambo(m)?);
    }
    // no face centroids (`Ctx`): neither ambo reads them
    let c = super::build::In::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // the inner ambo's check, then the outer's on A's counts
    reserve("ambo", m, ne, 2 * ne, nf + nv)?;
    super::build::reserve_from("ambo", &crate::budget::Counts::plain(ne as u64, 2 * ne as u64, (nf + nv) as u64), 2 * ne, 4 * ne, nf + nv + ne)?;
    let cidx = &c.fl.cidx;
    let (next, prev, vert, p) = (c.next, c.prev, c.vert, &m.pos);
    let fs = |h: usize| 2 * cidx[h];
    let gs = |h: usize| 2 * cidx[prev[h] as usize] + 1;
    // A's vertices (m's midpoints, as `Ctx::mid`), then the midpoints of A's edges
    let a: Vec<_> = (0..ne).map(|e| (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5).collect();
    let mut pos = vec![glam::DVec3::ZERO; 2 * ne];
    for (j, &h) in c.fl.fh.iter().enumerate() {
        crate::cancel::poll(j)?;
        pos[j] = (a[(h >> 1) as usize] + a[(next[h as usize] >> 1) as usize]) * 0.5;
    }
    drop(a);
    let mut out = Out::new(pos, 2 * nh, nf + nv + ne, 4 * nh);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        out.face(c.fl.corners(f).iter().map(|&h| (cidx[h as usize], fs(next[h as usize] as usize))));
    }
    let mut ring = Vec::new();
    for v in 0..nv {
        crate::cancel::poll(v)?;
        crate::schemes::dual_walk::rotation(next, m.v_out[v], &mut ring);
        let k = ring.len();
        out.face((0..k).map(|j| (cidx[prev[ring[j] as usize] as usize], gs(ring[(j + 1) % k] as usize))));
    }
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let h = super::dual_ambo::first_side(&c, e) as usize;
        out.face([fs(h), gs(h), fs(h ^ 1), gs(h ^ 1)].map(|x| (x >> 1, x)));
    }
    out.finish("ambo")
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
