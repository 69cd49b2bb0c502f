//! Loop-style remeshing (TopMod's *Loop-Style Remeshing*,
//! `loopStyleSubdivide(obj, length)`) and root-4 (`root4Subdivide(obj, a,
//! twist)`, TopMod's *Dual Loop-Style Remeshing* and *Hexagon Preserving*
//! menu entries), read from TopMod's source (`include/dlflaux/DLFLSubdiv.cc`),
//! the only description of both.
//!
//! * [`loop_style`] — every edge split at its midpoint, every corner cut off
//!   by an edge between the midpoints of its two sides: an n-gon gives n
//!   corner triangles `[m(prev h), tail(h), m(h)]` and the n-gon of its
//!   midpoints (Loop's connectivity on any face). Old vertices move to
//!   `length·v + (1 − length)·mean(m(h))` over their outgoing half-edges h.
//!   V' = V + E, E' = 4E, F' = F + 2E; histogram: the input's plus 2E
//!   triangles. Vertex layout: old vertices, then edge midpoints.
//! * [`root4`] — each face gets an inner n-gon whose corner k is
//!   `Σ_j w_{kj} μ_j` with TopMod's weights (those of
//!   `corner_cutting::cut_face` with α = 1/√2 − 1/4 + 5/(4n)) over the
//!   twisted edge points `μ_j = (1 − twist) x_j + twist x_{j+1}`; every old
//!   vertex is joined to the inner corners at it and every old edge deleted,
//!   so the two sides of edge a→b form the hexagon
//!   `[b, i(next h), i(h), a, i(next t), i(t)]`. Old vertices move to
//!   `weight·mean(neighbours) + (1 − weight)·v`. V' = V + 2E, E' = 4E,
//!   F' = F + E; histogram: the input's plus E hexagons. Vertex layout: old
//!   vertices, then one inner point per half-edge (V + h).

use crate::schemes::keyed::{In, Out};
use super::corner_cutting::cut_face;
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

fn unit(name: &str, what: &str, x: f64) -> Result<()> {
    if x.is_finite() && (0.0..=1.0).contains(&x) {
        Ok(())
    } else {
        Err(MeshError::InvalidArgument(format!("{name}: {what} = {} must be in [0, 1]", crate::error::num(x))))
    }
}

/// TopMod's Loop-style remeshing; `length` in [0, 1] (default 1: old
/// vertices stay). See the module docs.
pub fn loop_style(m: &Mesh, length: f64) -> Result<Mesh> {
    unit("loop_style", "length", length)?;
    with_point_spheres("loop_style", m, |m| {
        let i = In::new(m)?;
        let (v, nh) = (i.nv, i.nh);
        let mut pos = i.positions(i.ne);
        for e in 0..i.ne {
            pos.push((i.p(2 * e) + i.q(2 * e)) * 0.5);
        }
        if length != 1.0 {
            for x in 0..v {
                let h0 = m.v_out[x] as usize;
                let (mut s, mut n, mut k) = (DVec3::ZERO, 0.0, h0);
                loop {
                    s += pos[v + (k >> 1)];
                    n += 1.0;
                    k = i.rot(k);
                    if k == h0 {
                        break;
                    }
                }
                pos[x] = length * m.pos[x] + (1.0 - length) * (s / n);
            }
        }
        let mid = |h: usize| (v + (h >> 1)) as u32;
        // keys: [0, H) the half of edge(h) at tail(h), [H, 2H) the inner side of corner h
        let mut o = Out::new(pos, 2 * nh, i.nf + nh, 4 * nh).of(&i);
        o.keeps_vertices(v);
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                o.c(mid(h as usize), nh as u32 + h);
            }
            o.end();
        }
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                let (h, p) = (h as usize, i.prev[h as usize] as usize);
                o.c(mid(p), (p ^ 1) as u32);
                o.c(i.vert[h], h as u32);
                o.c(mid(h), (nh + p) as u32);
                o.end();
            }
        }
        o.finish("loop_style")
    })
}

/// TopMod's root-4 with `weight` and `twist` in [0, 1] (defaults 0). See the
/// module docs.
pub fn root4(m: &Mesh, weight: f64, twist: f64) -> Result<Mesh> {
    unit("root4", "weight", weight)?;
    unit("root4", "twist", twist)?;
    with_point_spheres("root4", m, |m| {
        let i = In::new(m)?;
        let (v, nh) = (i.nv, i.nh);
        let pos = root4_positions(&i, weight, twist);
        let inner = |h: usize| (v + h) as u32;
        // keys: [0, H) the inner side of corner h, [H, 2H) the spoke tail(h)–i(h)
        let mut o = Out::new(pos, 2 * nh, i.nf + i.ne, 4 * nh).of(&i);
        o.keeps_vertices(v);
        for f in 0..i.nf {
            o.from_face(f);
            for &h in i.fl.corners(f) {
                o.c(inner(h as usize), h);
            }
            o.end();
        }
        for e in 0..i.ne {
            let (h, t) = (2 * e, 2 * e + 1);
            // the hexagon of edge e straddles both its faces: the first side's
            o.from_face(i.face[h] as usize);
            let (nx, nt) = (i.next[h] as usize, i.next[t] as usize);
            o.c(i.vert[t], (nh + nx) as u32);
            o.c(inner(nx), h as u32);
            o.c(inner(h), (nh + h) as u32);
            o.c(i.vert[h], (nh + nt) as u32);
            o.c(inner(nt), t as u32);
            o.c(inner(t), (nh + t) as u32);
            o.end();
        }
        o.finish("root4")
    })
}

/// Root-4's vertices: the input's (moved by `weight`), then the inner
/// point of each corner h at V + h; shared with [`super::root4_dual`].
pub(crate) fn root4_positions(i: &In<'_>, weight: f64, twist: f64) -> Vec<DVec3> {
    let (v, nh) = (i.nv, i.nh);
    let mut pos = i.positions(nh);
    if weight != 0.0 {
        for x in 0..v {
            let h0 = i.m.v_out[x] as usize;
            let (mut s, mut n, mut k) = (DVec3::ZERO, 0.0, h0);
            loop {
                s += i.q(k);
                n += 1.0;
                k = i.rot(k);
                if k == h0 {
                    break;
                }
            }
            pos[x] = weight * (s / n) + (1.0 - weight) * i.m.pos[x];
        }
    }
    pos.resize(v + nh, DVec3::ZERO);
    let (mut mu, mut out) = (Vec::new(), Vec::new());
    for f in 0..i.nf {
        let hs = i.fl.corners(f);
        mu.clear();
        out.clear();
        mu.extend(hs.iter().map(|&h| i.p(h as usize).lerp(i.q(h as usize), twist)));
        let alpha = std::f64::consts::FRAC_1_SQRT_2 - 0.25 + 5.0 / (4.0 * hs.len() as f64);
        cut_face(&mu, alpha, &mut out);
        for (&h, p) in hs.iter().zip(&out) {
            pos[v + h as usize] = *p;
        }
    }
    pos
}

/// TopMod's fractal remeshing (`fractalSubdivide(obj, offset)`): edges
/// split at their midpoints, every corner cut off as in [`loop_style`], and
/// the midpoints' polygon of each face fanned to a centre raised along the
/// face's unit normal by `offset·√max(0, l₂² − l₁²)`, with TopMod's
/// lengths l₂ = |m₀ − m₁| (adjacent midpoints) and l₁ = half the distance
/// from m₀ to the corner n steps further round the split face.
/// V' = V + E + F, E' = 6E, F' = 4E, all triangles. `offset` in [0, 2]
/// (TopMod's range, default 1). Vertex layout: old vertices, midpoints,
/// centres.
pub fn fractal(m: &Mesh, offset: f64) -> Result<Mesh> {
    if !(offset.is_finite() && (0.0..=2.0).contains(&offset)) {
        return Err(MeshError::InvalidArgument(format!("fractal: offset = {} must be in [0, 2]", crate::error::num(offset))));
    }
    with_point_spheres("fractal", m, |m| {
        let i = In::new(m)?;
        let (v, nh) = (i.nv, i.nh);
        let mut pos = i.positions(i.ne + i.nf);
        for e in 0..i.ne {
            pos.push((i.p(2 * e) + i.q(2 * e)) * 0.5);
        }
        let normals = i.normals();
        let mut cyc = Vec::new();
        for f in 0..i.nf {
            // the split face [v₀, m₀, v₁, m₁, …] as TopMod walks it
            cyc.clear();
            for &h in i.fl.corners(f) {
                cyc.push(i.p(h as usize));
                cyc.push(pos[v + (h as usize >> 1)]);
            }
            let n2 = cyc.len();
            let c = cyc.iter().sum::<DVec3>() / n2 as f64;
            let l1 = (cyc[1] - cyc[(1 + n2 / 2) % n2]).length() / 2.0;
            let l2 = (cyc[1] - cyc[3 % n2]).length();
            let d = (l2 * l2 - l1 * l1).max(0.0).sqrt() * offset;
            pos.push(c + d * normals[f]);
        }
        let mid = |h: usize| (v + (h >> 1)) as u32;
        // keys: [0, H) the half of edge(h) at tail(h), [H, 2H) the inner side
        // of corner h, [2H, 3H) the spoke centre–m(h)
        let mut o = Out::new(pos, 3 * nh, 2 * nh, 6 * nh).of(&i);
        o.keeps_vertices(v);
        for f in 0..i.nf {
            o.from_face(f);
            let c = (v + i.ne + f) as u32;
            for &h in i.fl.corners(f) {
                let (h, p, nx) = (h as usize, i.prev[h as usize] as usize, i.next[h as usize]);
                o.c(mid(p), (p ^ 1) as u32);
                o.c(i.vert[h], h as u32);
                o.c(mid(h), (nh + p) as u32);
                o.end();
                o.c(mid(h), (nh + h) as u32);
                o.c(mid(nx as usize), 2 * nh as u32 + nx);
                o.c(c, (2 * nh + h) as u32);
                o.end();
            }
        }
        o.finish("fractal")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};

    #[test]
    fn loop_style_counts() {
        for len in [1.0, 0.5] {
            check("loop_style", |m| loop_style(m, len), |_, (v, e, f)| (v + e, 4 * e, f + 2 * e), |m, (_, e, _)| {
                let mut h = hist_of(m);
                *h.entry(3).or_default() += 2 * e;
                h
            });
        }
        // on triangles it is Loop's connectivity
        let t = crate::primitives::octahedron();
        let a = loop_style(&t, 1.0).unwrap();
        let b = crate::schemes::loop_subdivision::loop_subdivision(&t).unwrap();
        assert_eq!((a.n_vertices(), a.n_edges(), a.n_faces()), (b.n_vertices(), b.n_edges(), b.n_faces()));
        assert!(loop_style(&t, 1.5).is_err());
    }

    #[test]
    fn fractal_counts() {
        check("fractal", |m| fractal(m, 1.0), |_, (v, e, f)| (v + e + f, 6 * e, 4 * e), |_, (_, e, _)| std::collections::BTreeMap::from([(3, 4 * e)]));
        // the cube's centres rise: the volume grows with the offset
        let c = crate::primitives::cube();
        assert!(fractal(&c, 1.0).unwrap().signed_volume() > fractal(&c, 0.0).unwrap().signed_volume() + 1e-6);
    }

    #[test]
    fn root4_counts() {
        for (w, tw) in [(0.0, 0.0), (0.5, 0.25)] {
            check("root4", |m| root4(m, w, tw), |_, (v, e, f)| (v + 2 * e, 4 * e, f + e), |m, (_, e, _)| {
                let mut h = hist_of(m);
                *h.entry(6).or_default() += e;
                h
            });
        }
        assert!(root4(&crate::primitives::cube(), -0.1, 0.0).is_err());
        assert!(root4(&crate::primitives::cube(), 0.0, 2.0).is_err());
    }
}
