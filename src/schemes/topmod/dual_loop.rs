//! Dual Loop (TopMod's `subdivideDualLoop` in `DLFLSubdiv.h`: dual, Loop,
//! dual) without Loop's output mesh (issue 16: Loop's step and the last
//! dual were nearly all of the time, the dual only walking Loop's mesh).
//!
//! Loop fans the dual's non-triangles first; call the fanned dual T (all
//! triangles, V_T vertices, E_T edges, F_T faces, H_T = 3F_T corners).
//! Loop's step (`schemes::primal_columns`, no face points) lays, per
//! face f of T and corner k (half-edge h = corner k from `f_start`), the
//! triangle 4f + k `[tail h, e(h), e(prev h)]` (corners a(h), slot 1, b(h))
//! and then the middle 4f + 3 `[e(h₀), e(h₁), e(h₂)]`; its vertices are
//! `[vertex points | edge points]`. The last dual turns every Loop vertex
//! into a face, walking its rotation from its first corner:
//!
//! * vertex point v: from a(g), g the outgoing half-edge of v first in face
//!   order, the triangles 4 face(h) + k(h) in T's rotation (h → twin prev h),
//!   crossing the child of edge(prev h) at v;
//! * edge point of e = {h, t}: the cycle slot1(h), b(next t), mid(t),
//!   slot1(t), b(next h), mid(h) (mid(x): the middle triangle of face(x)),
//!   from the lowest of Loop's candidate corners (slot 1 of a side at its
//!   corner 0 or 1, else b of the next corner), crossing the edges Loop's
//!   step lays there: the child of edge x at tail x (key x) and the inner
//!   edge of corner x (slot 1 of x, key H_T + x).
//!
//! So V' = 4F_T (every vertex 3-valent), E' = 2E_T + 3F_T, F' = V_T + E_T;
//! with V₃ input vertices of valence 3 and S the valence sum over the
//! others, V_T = F + V − V₃, E_T = E + S, F_T = V₃ + S.
//!
//! Neither T nor the first dual is built when the dual has faces to fan
//! (`dual_of_fanned_loop`): the dual's faces, corners and twins follow
//! from the input's rotations as [`dual`] walks them, and the fan
//! (`schemes::fan_columns`) lays T's corners per face of the dual in
//! order (a kept triangle's three, or per corner of a fanned face its
//! triangle `[side, spoke 1, spoke 2]`), so a corner's position P in that
//! layout gives its face P / 3 and its index P % 3, its edges are numbered
//! by first corner and its vertices are the dual's then the centroids, all
//! by index arithmetic on the input. A dual of triangles only (every input
//! vertex 3-valent) is not fanned: the walk runs over the dual itself.
//!
//! Positions are Loop's (the same masks and sums, [`loop_subdivision`];
//! a vertex point sums its neighbours from T's `v_out`, its lowest corner)
//! and the centroids of its triangles summed from their first corner, as
//! the dual sums; edges are numbered by first crossing (`DualWalk`), so
//! the output is the composition's bit for bit (the test below compares
//! every column; `keyed::hashes` hashes traced builds, which take the
//! composition). Holes, point-spheres and traced builds (face parents)
//! take the composition.
//!
//! [`loop_subdivision`]: crate::schemes::loop_subdivision

use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual::dual;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::face_parents::via_origins;
use crate::schemes::hosts::check_output_size;
use crate::schemes::loop_subdivision as l;
use glam::DVec3;

/// The composition `dual(loop(dual(m)))`, as TopMod writes it.
pub(crate) fn composed(m: &Mesh) -> Result<Mesh> {
    let d = dual(m)?;
    dual(&via_origins(&d, |r| l::loop_level(&d, r), || l::loop_subdivision(&d))?)
}

/// `composed`, the same output and errors, in one pass over the input
/// (or over its dual when that has triangles only).
pub(crate) fn dual_loop(m: &Mesh) -> Result<Mesh> {
    if m.n_faces() == 0 || m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) || crate::schemes::face_parents::recording() {
        return composed(m);
    }
    dual_of_fanned_loop(m)
}

/// Per corner of the fanned dual T, kept as its position P = 3 face + k in
/// T's corner layout (fan: per face of `d` in order, a kept triangle's
/// corners, or per corner of a fanned face its triangle `[side, spoke 1,
/// spoke 2]`): T's face and corner index are P / 3 and P % 3.
#[inline]
fn face_loc(p: usize) -> (u32, u32) {
    ((p / 3) as u32, (p % 3) as u32)
}

/// `dual_of_loop(&fan_triangulate(&dual(m)?)?.unwrap())` without the dual's
/// or the fan's mesh. The dual D of m is read off m: its face v lists, in
/// m's rotation from `v_out[v]`, one corner per outgoing half-edge g of v
/// (at the centroid of face g; call the corner g), as [`dual`] walks it, so
/// tail g = face g, prev g = next(twin g), twin g = next(twin prev g), and
/// g crosses the edge of prev g; D's vertex f turns round face f in `next`
/// order. The fan T of D is then named by its corners' positions P
/// (`face_loc`), its edges walked in its order (by first corner) and its
/// vertices (D's, then the centroids of the fanned faces) in theirs. Loop's
/// edge points are held per edge of m (the sides) and per corner g of a
/// fanned face (the spoke from head g).
fn dual_of_fanned_loop(m: &Mesh) -> Result<Mesh> {
    let (nfd, ned, nvd, nhd) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    check_output_size("dual", nhd, nvd)?;
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    // D's face layout: per face v (vertex v of m) its corners in order
    let mut fh = Vec::with_capacity(nhd);
    let mut off = Vec::with_capacity(nfd + 1);
    let mut cidx = vec![0u32; nhd];
    // per corner (in layout order): whether its side comes before its
    // twin's, whose face of D is the tail of prev g (2: the same face,
    // decided by cidx once all are known)
    let mut first = Vec::with_capacity(nhd);
    off.push(0u32);
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        let s = m.v_out[v];
        let mut h = s;
        loop {
            cidx[h as usize] = fh.len() as u32;
            fh.push(h);
            let p = prev[h as usize];
            let u = vert[p as usize] as usize;
            first.push(if u == v { 2u8 } else { (u > v) as u8 });
            h = p ^ 1;
            if h == s {
                break;
            }
        }
        off.push(fh.len() as u32);
    }
    if off.windows(2).all(|w| w[1] - w[0] == 3) {
        // a dual of triangles: Loop does not fan it
        return dual_of_loop(&dual(m)?);
    }
    let corners = |v: usize| &fh[off[v] as usize..off[v + 1] as usize];
    // D's positions (the centroids of m's faces, as the dual sums them),
    // and per corner g: its head (a vertex of D), its edge (one of m's)
    let dp = crate::schemes::dual::centroids(m)?;
    let head = |g: usize| face[(prev[g] ^ 1) as usize] as usize;
    let edge = |g: usize| (prev[g] >> 1) as usize;
    check_output_size("loop", 3 * nhd, nvd + nfd)?;
    // per face of D: its first corner in T (3 × its first face in T), and
    // its centroid's index among the centroids (KEPT for a triangle)
    const KEPT: u32 = u32::MAX;
    let mut base = Vec::with_capacity(nfd);
    let mut cent = Vec::with_capacity(nfd);
    let mut cpos = Vec::new();
    let mut b = 0usize;
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        let hs = corners(v);
        base.push(b as u32);
        if hs.len() == 3 {
            cent.push(KEPT);
            b += 3;
        } else {
            cent.push(cpos.len() as u32);
            let s: DVec3 = hs.iter().map(|&h| dp[face[h as usize] as usize]).sum();
            cpos.push(s / hs.len() as f64);
            b += 3 * hs.len();
        }
    }
    let (nh, nc) = (b, cpos.len());
    let (nv, ne, nf) = (nvd + nc, nh / 2, nh / 3);
    check_output_size("loop", 4 * nh, nv + ne)?;
    check_output_size("dual", 4 * nh, 4 * nf)?;
    // the side of corner g: its position
    let mut side = vec![0u32; nhd];
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        let step = if cent[v] == KEPT { 1 } else { 3 };
        for (k, &g) in corners(v).iter().enumerate() {
            side[g as usize] = base[v] + step * k as u32;
        }
    }
    // Loop's edge points: sides (per edge of m, crossed by D's corners
    // next(2e) and next(2e + 1)), then spokes (per corner g of a fanned
    // face, from head g to the centroid); the opposite corners of a side
    // are the centroid of a fanned face or the third corner of a kept
    // triangle (the tail of prev g = face(twin g))
    let mut ep = crate::mesh::zeroed_points(ned + nhd);
    let opp = |g: usize| {
        let v = vert[g] as usize;
        if cent[v] == KEPT { dp[face[g ^ 1] as usize] } else { cpos[cent[v] as usize] }
    };
    for (e, out) in ep[..ned].iter_mut().enumerate() {
        crate::cancel::poll(e)?;
        let (a, b) = (next[2 * e] as usize, next[2 * e + 1] as usize);
        let ab = dp[face[a] as usize] + dp[face[b] as usize];
        let cd = opp(a) + opp(b);
        *out = ab * 0.375 + cd * 0.125;
    }
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        if cent[v] == KEPT {
            continue;
        }
        let (hs, c) = (corners(v), cpos[cent[v] as usize]);
        for (k, &g) in hs.iter().enumerate() {
            let g1 = hs[(k + 1) % hs.len()] as usize;
            let ab = dp[head(g as usize)] + c;
            let cd = dp[face[g as usize] as usize] + dp[head(g1)];
            ep[ned + g as usize] = ab * 0.375 + cd * 0.125;
        }
    }
    // the centroids of Loop's middle triangles (from its edge points at
    // the corners side, spoke 1, spoke 2 of T's triangle); those of the
    // corner triangles are placed by the walk round their vertex point
    let mut pos = crate::mesh::zeroed_points(4 * nf);
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        let (hs, t0) = (corners(v), base[v] as usize / 3);
        let mean = |a: usize, b: usize, c: usize| {
            let mut s = DVec3::ZERO;
            s += ep[a];
            s += ep[b];
            s += ep[c];
            s / 3.0
        };
        if cent[v] == KEPT {
            pos[4 * t0 + 3] = mean(edge(hs[0] as usize), edge(hs[1] as usize), edge(hs[2] as usize));
        } else {
            let n = hs.len();
            for (k, &g) in hs.iter().enumerate() {
                let gp = hs[(k + n - 1) % n] as usize;
                pos[4 * (t0 + k) + 3] = mean(edge(g as usize), ned + g as usize, ned + gp);
            }
        }
    }
    let betas = l::Betas::new();
    let beta = |n: usize| betas.get(n);
    let tri = |p: u32| 4 * (p / 3) + p % 3;
    let mut walk = DualWalk::new(pos, 4 * nh, nv + ne, 2 * nh);
    // the faces of Loop's vertex points: per outgoing corner x of T, in
    // T's rotation from the lowest (T's v_out and Loop's first corner):
    // (x, its edge point, that of prev x, the head of x)
    let (mut ring, mut nbs): (Vec<[u32; 3]>, Vec<DVec3>) = (Vec::new(), Vec::new());
    let corner_face = |walk: &mut DualWalk, w: usize, vp: DVec3, ring: &[[u32; 3]], i0: usize| {
        let (n, mut last) = (ring.len(), NONE);
        for j in 0..n {
            let [x, e, ep_] = ring[(i0 + j) % n];
            let c = tri(x) as usize;
            let mut s = DVec3::ZERO;
            s += vp;
            s += ep[e as usize];
            s += ep[ep_ as usize];
            walk.positions_mut()[c] = s / 3.0;
            walk.put(w, c as u32, ring[(i0 + j + 1) % n][0] as usize, &mut last);
        }
        walk.close(w, last);
    };
    for f in 0..nvd {
        crate::cancel::poll(f)?;
        // T's rotation at D's vertex f: per outgoing g of D (round face f
        // of m), the side of g, then in a fanned face spoke 1 of prev g
        // (from f to the centroid; prev g = next(twin g), whose edge is g's)
        ring.clear();
        nbs.clear();
        let s = m.f_start[f] as usize;
        let mut g = s;
        loop {
            let v = vert[g] as usize;
            let hd = dp[head(g)];
            if cent[v] == KEPT {
                ring.push([side[g], edge(g) as u32, (g >> 1) as u32]);
                nbs.push(hd);
            } else {
                let gp = next[g ^ 1] as usize;
                ring.push([side[g], edge(g) as u32, (ned + gp) as u32]);
                ring.push([side[gp] + 1, (ned + gp) as u32, (g >> 1) as u32]);
                nbs.push(hd);
                nbs.push(cpos[cent[v] as usize]);
            }
            g = next[g] as usize;
            if g == s {
                break;
            }
        }
        let i0 = (0..ring.len()).min_by_key(|&i| ring[i][0]).unwrap_or(0);
        let n = ring.len();
        let mut sum = DVec3::ZERO;
        for j in 0..n {
            sum += nbs[(i0 + j) % n];
        }
        let bt = beta(n);
        let vp = dp[f] * (1.0 - n as f64 * bt) + sum * bt;
        corner_face(&mut walk, f, vp, &ring, i0);
    }
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        if cent[v] == KEPT {
            continue;
        }
        // a centroid: spoke 2 of each corner k (to tail h_k), from k = 0
        let (hs, b) = (corners(v), base[v]);
        let n = hs.len();
        ring.clear();
        let mut sum = DVec3::ZERO;
        for (k, &g) in hs.iter().enumerate() {
            let gp = hs[(k + n - 1) % n] as usize;
            let t = dp[face[g as usize] as usize];
            sum += t;
            ring.push([b + 3 * k as u32 + 2, (ned + gp) as u32, (ned + g as usize) as u32]);
        }
        let bt = beta(n);
        let vp = cpos[cent[v] as usize] * (1.0 - n as f64 * bt) + sum * bt;
        corner_face(&mut walk, nvd + cent[v] as usize, vp, &ring, 0);
    }
    // the faces of Loop's edge points, in T's edge order (by first
    // corner): per face of D and corner k, the side when its twin's comes
    // later, spoke 1 unless it is the last of n ≥ 2 (its twin is spoke 2
    // of k + 1), and at k = 0 spoke 2 (the twin of spoke 1 of n − 1)
    let mut w = nv;
    let mut edge_face = |walk: &mut DualWalk, h: u32, t: u32| {
        put_edge_face(walk, w, h as usize, t as usize, nh, face_loc, |x| 3 * (x / 3) + (x % 3 + 1) % 3);
        w += 1;
    };
    for v in 0..nfd {
        crate::cancel::poll(v)?;
        let (hs, b) = (corners(v), base[v]);
        let n = hs.len() as u32;
        for (k, &g) in hs.iter().enumerate() {
            let fst = first[off[v] as usize + k];
            let k = k as u32;
            if fst != 0 {
                let tw = next[(prev[g as usize] ^ 1) as usize] as usize;
                if fst == 1 || cidx[tw] > cidx[g as usize] {
                    edge_face(&mut walk, side[g as usize], side[tw]);
                }
            }
            if cent[v] != KEPT {
                if k + 1 < n || n == 1 {
                    edge_face(&mut walk, b + 3 * k + 1, b + 3 * ((k + 1) % n) + 2);
                }
                if k == 0 && n > 1 {
                    edge_face(&mut walk, b + 3 * (n - 1) + 1, b + 2);
                }
            }
        }
    }
    if w != nv + ne {
        return Err(MeshError::Invariant(format!("dual loop: the fan has {nh} corners but {} edges", w - nv)));
    }
    Mesh::from_columns(walk.finish()?)
}

/// `dual(loop_subdivision(t))` for a closed mesh `t` of triangles.
fn dual_of_loop(t: &Mesh) -> Result<Mesh> {
    let (nv, ne, nf, nh) = (t.n_vertices(), t.n_edges(), t.n_faces(), t.n_halfedges());
    check_output_size("loop", 4 * nh, nv + ne)?;
    check_output_size("dual", 4 * nh, 4 * nf)?;
    let (next, vert, face) = t.halfedge_columns();
    let prev = &t.he_prev;
    // corner index of every half-edge in its face (from f_start)
    let mut loc = vec![0u8; nh];
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let h0 = t.f_start[f];
        let h1 = next[h0 as usize];
        let h2 = next[h1 as usize];
        if h1 == h0 || h2 == h0 || next[h2 as usize] != h0 {
            return Err(MeshError::Invariant(format!("dual loop: face {f} of the fanned dual is not a triangle")));
        }
        loc[h1 as usize] = 1;
        loc[h2 as usize] = 2;
    }
    // Loop's edge points (its masks, `loop_subdivision`)
    let p = &t.pos;
    let mut ep = Vec::with_capacity(ne);
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (a, b) = (2 * e, 2 * e + 1);
        let ab = p[vert[a] as usize] + p[vert[b] as usize];
        let cd = p[vert[prev[a] as usize] as usize] + p[vert[prev[b] as usize] as usize];
        ep.push(ab * 0.375 + cd * 0.125);
    }
    // the centroids of Loop's middle triangles; those of the corner
    // triangles are placed by the walk round their vertex point
    let mut pos = crate::mesh::zeroed_points(4 * nf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let h0 = t.f_start[f] as usize;
        let h1 = next[h0] as usize;
        let h2 = next[h1] as usize;
        let mut s = DVec3::ZERO;
        s += ep[h0 >> 1];
        s += ep[h1 >> 1];
        s += ep[h2 >> 1];
        pos[4 * f + 3] = s / 3.0;
    }
    // Loop's triangle at corner h
    let tri = |h: usize| 4 * face[h] + loc[h] as u32;
    let betas = l::Betas::new();
    let mut walk = DualWalk::new(pos, 4 * nh, nv + ne, 2 * nh);
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = t.v_out[v] as usize;
        // Loop's vertex point (its neighbours summed from v_out, as Loop
        // sums), and the outgoing half-edge first in face order
        let (mut h, mut g, mut best, mut sum, mut n) = (s, s, u32::MAX, DVec3::ZERO, 0usize);
        loop {
            sum += p[vert[h ^ 1] as usize];
            n += 1;
            let c = 3 * face[h] + loc[h] as u32;
            if c < best {
                (best, g) = (c, h);
            }
            h = (prev[h] ^ 1) as usize;
            if h == s {
                break;
            }
        }
        let beta = betas.get(n);
        let vp = p[v] * (1.0 - n as f64 * beta) + sum * beta;
        let (mut h, mut last) = (g, NONE);
        loop {
            let q = prev[h] as usize;
            let x = tri(h);
            let mut c = DVec3::ZERO;
            c += vp;
            c += ep[h >> 1];
            c += ep[q >> 1];
            walk.positions_mut()[x as usize] = c / 3.0;
            walk.put(v, x, q ^ 1, &mut last);
            h = q ^ 1;
            if h == g {
                break;
            }
        }
        walk.close(v, last);
    }
    for e in 0..ne {
        crate::cancel::poll(e)?;
        put_edge_face(&mut walk, nv + e, 2 * e, 2 * e + 1, nh, |x| (face[x], loc[x] as u32), |x| next[x] as usize);
    }
    Mesh::from_columns(walk.finish()?)
}

/// The face of Loop's edge point of the fanned dual's edge with halves
/// `h`, `t` (corners of the fanned dual: `fl(x)` its face and corner index,
/// `next(x)`), as face `w` of the last dual: the ring slot1(h), b(next t),
/// mid(t), slot1(t), b(next h), mid(h) from Loop's first corner of the edge
/// point (per side x, slot 1 of x at corner 0 or 1, else b(next x), the
/// lower of the two), crossing the children (key x) and the inner edges
/// (key H + x) that Loop's step lays there.
#[inline]
fn put_edge_face(walk: &mut DualWalk, w: usize, h: usize, t: usize, nh: usize, fl: impl Fn(usize) -> (u32, u32), next: impl Fn(usize) -> usize) {
    let (nh_, nt) = (next(h), next(t));
    let tri = |x: usize| {
        let (f, k) = fl(x);
        4 * f + k
    };
    let mid = |x: usize| 4 * fl(x).0 + 3;
    let ring = [(tri(h), h), (tri(nt), nh + nt), (mid(t), nh + t), (tri(t), t), (tri(nh_), nh + nh_), (mid(h), nh + h)];
    let cand = |x: usize, at_slot1: usize, at_b: usize| {
        let (f, k) = fl(x);
        if k < 2 { (12 * f + 3 * k + 1, at_slot1) } else { (12 * f + 2, at_b) }
    };
    let (a, b) = (cand(h, 0, 4), cand(t, 3, 1));
    let j0 = if a.0 < b.0 { a.1 } else { b.1 };
    let mut last = NONE;
    for j in 0..6 {
        let (f, key) = ring[(j0 + j) % 6];
        walk.put(w, f, key, &mut last);
    }
    walk.close(w, last);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::{check_fused, jittered_torus, one_gon_two_gon_cube, open_meshes, same_bits as same};

    /// The one-pass build is the composition: the same columns and bits or
    /// the same error, on the corpus (non-convex faces, self-loops,
    /// two-gons, one-gons, genus 3, point-spheres, a Sierpinski output,
    /// valence-3 and other vertices), a Loop output (valence 6), a jittered
    /// torus, the bench's torus at a tenth of its size and open meshes
    /// (which take the composition); traced builds too (they take the
    /// composition, so `keyed::hashes`, which hashes traced builds, does
    /// not see the one pass: this test does).
    #[test]
    fn dual_loop_is_its_composition() {
        let mut ms = super::super::tests::meshes();
        ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
        ms.push(("loop_cube", l::loop_subdivision(&crate::primitives::cube()).unwrap()));
        ms.push(("jittered_torus", jittered_torus()));
        ms.push(("torus_40x25", crate::primitives::torus(40, 25, 3.0, 1.0).unwrap()));
        ms.push(("genus2", crate::primitives::genus_surface(2).unwrap()));
        ms.extend(open_meshes());
        // one-pass runs: over a dual of triangles only, over a fanned dual
        // with kept triangles (input vertices of valence 3 and others)
        let (mut fused_runs, mut tri_only, mut mixed) = (0, 0, 0);
        for (name, m) in &ms {
            if check_fused(name, m, &dual_loop, &composed) {
                fused_runs += 1;
                let vh = m.valence_histogram();
                tri_only += (vh.keys().all(|&k| k == 3)) as usize;
                mixed += (vh.contains_key(&3) && vh.keys().any(|&k| k != 3)) as usize;
            }
        }
        assert!(fused_runs >= 12 && tri_only >= 2 && mixed >= 2, "one pass: {fused_runs} meshes, {tri_only} with triangle duals, {mixed} mixed");
    }

    /// The comparison sees a change: one Loop point moved by one ulp
    /// changes the output.
    #[test]
    fn the_comparison_sees_one_ulp() {
        let m = crate::primitives::cube();
        let a = dual_loop(&m).unwrap();
        let mut b = a.clone();
        b.pos[5].y = f64::from_bits(b.pos[5].y.to_bits() ^ 1);
        assert!(!same(&a, &b));
        let mut c = a.clone();
        c.he_next.swap(0, 2);
        assert!(!same(&a, &c));
    }
}
