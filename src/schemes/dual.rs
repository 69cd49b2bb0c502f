//! The dual mesh, one level: a vertex at the centroid of every face, a face
//! around every vertex, an edge across every edge.
//!
//! The face of vertex v lists the centroids of the faces around v in
//! rotation order (counter-clockwise seen from outside), so orientation is
//! kept. A self-loop crosses into a dual edge between the centroids of its
//! two sides' faces; a one-gon becomes a valence-1 vertex, a valence-2 vertex
//! a two-gon, a point-sphere stays a point-sphere. Applying `dual` twice
//! gives back the input's connectivity (positions are the centroids of
//! centroids).
//!
//! Counts: V' = F, E' = E, F' = V. Output vertex f is the centroid of face f;
//! output face v is the one of vertex v.
//!
//! # Open meshes ([`dual_level`])
//!
//! Convention: Blender's Dual Mesh node with *Keep Boundaries* (geometry
//! nodes, `GeometryNodeDualMesh`, `keep_boundaries = True`): the boundary
//! stays where it is. A boundary edge gets a vertex at its midpoint, a
//! boundary vertex keeps a vertex at its own position, and the face of a
//! boundary vertex runs through the centroids of its real faces and closes
//! through `[m(e_in) … ] → m(e_out) → v → m(e_in)`: at each hole corner h of
//! v it lists `m(edge h), v, m(edge prev h)`. Hole faces get no centroid;
//! a hole of n corners becomes a hole of 2n corners
//! `[v₀, m(h₀), v₁, m(h₁), …]` (the input boundary split at its midpoints).
//! With F_r real faces, b boundary edges and V_b boundary vertices:
//!
//! ```text
//! V' = F_r + b + V_b,   E' = E + 2b,   F' = V real faces and the same holes
//! ```
//!
//! so χ = V' − E' + F'_r is unchanged (V_b = b on boundary loops without
//! pinched vertices). An edge with holes on both sides has no dual and is
//! refused.
//!
//! Stencils (the dual is linear): a centroid row is the mean of its face's
//! corners, a boundary midpoint `½ a + ½ b`, a boundary vertex itself.
//! Origins: centroid of f → (FACE, f), boundary midpoint → (EDGE, e),
//! boundary vertex → (VERTEX, v); the face of v → (VERTEX, v), a hole's
//! image → (FACE, hole); every dual edge and both boundary halves of a
//! boundary edge → (EDGE, that edge).

use super::hosts::{check_output_size, face_centroids, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use super::level::{with_point_spheres_level, Level, Request};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use crate::schemes::dual_walk::DualWalk;
pub use super::dual_in_place::dual_level_owned;
use glam::DVec3;
use rayon::prelude::*;

/// The dual mesh. See the module docs.
pub fn dual(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("dual", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("dual", m.n_halfedges(), m.n_faces())?;
    // the walk is ~5× faster than one thread of the parallel blocks (100k
    // quads: 3.6 ms against 18 ms, and 9 ms on two threads), so the blocks
    // only pay off on many threads
    let out = if rayon::current_num_threads() < PARALLEL_FROM { step_one_pass(m)? } else { step_parallel(m)? };
    record_parents(m.n_vertices(), m.n_faces());
    Ok(out)
}

/// The face parents of a closed dual step (when they are being recorded):
/// face v is born around vertex v, vertex f is face f's centroid.
pub(super) fn record_parents(nv: usize, nf: usize) {
    if super::face_parents::recording() {
        let v = super::face_parents::VERT;
        super::face_parents::record(Some(super::face_parents::Step { in_v: nv, in_f: nf, face: (0..nv as u32).map(|i| v | i).collect(), vertex: (0..nf as u32).collect() }));
    }
}

/// Threads from which [`step_parallel`] is used.
const PARALLEL_FROM: usize = 8;

/// The dual on one thread (issue 16: the dual is the common step of most
/// compositions, `t = dkd`, TopMod's "dual + X + dual"): one walk around
/// every vertex in order writes every column. The side leaving the corner
/// of half-edge h (the centroid of face(h)) crosses input edge
/// `edge(prev h)`, so that edge names the output edge, as the keyed
/// builder's keys do (`keyed::Out::finish`): its first visit numbers it,
/// the second is the twin. Visiting corners in output order (vertex, then
/// rotation from `v_out`) gives exactly the numbering of
/// [`step_parallel`] and of `from_corner_twins` (edges by first corner, a
/// centroid's first corner as its `v_out`); tests compare the two.
fn step_one_pass(m: &Mesh) -> Result<Mesh> {
    let (nv, ne, nh) = (m.n_vertices(), m.n_edges(), m.n_halfedges());
    let face = &m.he_face;
    let prev = &m.he_prev;
    // the walk needs no position: the centroids are summed beside it (on a
    // second thread when there is one; issue 19, the dual's two-thread rows)
    let walk = || -> Result<DualWalk> {
        // keys: the input's edges
        let mut walk = DualWalk::for_points(m.n_faces(), nh, nv, ne);
        for v in 0..nv {
            crate::cancel::poll(v)?;
            let s = m.v_out[v];
            let (mut h, mut last) = (s, NONE);
            loop {
                let p = prev[h as usize];
                let f = face[h as usize];
                walk.put(v, f, (p >> 1) as usize, &mut last);
                h = p ^ 1;
                if h == s {
                    break;
                }
            }
            walk.close(v, last);
        }
        Ok(walk)
    };
    let (pos, walk) = rayon::join(|| centroids(m), walk);
    Mesh::from_columns(walk?.finish_with(pos?)?)
}

/// The corner mean of every face in face order: the dual's positions,
/// which the fused builds that start with a dual (`compose::dual_dual`,
/// `dual_loop`, `conway::truncate`) read without building it.
pub(crate) fn centroids(m: &Mesh) -> Result<Vec<DVec3>> {
    centroids_of(&m.f_start, &m.he_next, &m.he_vert, &m.pos)
}

/// [`centroids`] from the columns alone (the in-place dual holds them
/// without a `Mesh`): each face's corner mean, summed from its first corner
/// (the same bits as [`face_centroids`]), faces in parallel (issue 19: a
/// serial loop here was 13 % of a one-thread dual under `perf`, a part the
/// second thread could not share).
pub(crate) fn centroids_of(f_start: &[u32], next: &[u32], vert: &[u32], pos: &[DVec3]) -> Result<Vec<DVec3>> {
    let out: Vec<DVec3> = f_start
        .par_iter()
        .with_min_len(MIN_LEN)
        .map(|&s| {
            if crate::cancel::requested() {
                return DVec3::ZERO; // the check after the loop reports it
            }
            let (mut h, mut sum, mut n) = (s, DVec3::ZERO, 0usize);
            loop {
                sum += pos[vert[h as usize] as usize];
                n += 1;
                h = next[h as usize];
                if h == s {
                    break;
                }
            }
            sum / n as f64
        })
        .collect();
    crate::cancel::check()?;
    Ok(out)
}

/// The dual in parallel blocks (several threads).
fn step_parallel(m: &Mesh) -> Result<Mesh> {
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let mut pos = crate::mesh::zeroed_points(nf);
    face_centroids(m, &fl, &mut pos);
    crate::cancel::check()?;
    // Connectivity straight into the columns (issue 19), numbered as
    // `from_corner_twins` numbered the corners it was given: face v lists
    // the rotation slots of v; the corner at slot(h) (centroid of face(h))
    // has its twin at slot(next(rotate h)), and edges are numbered by first
    // corner (the one before its twin). Pass 1 ranks, per vertex, the first
    // corners of its face (`rank << 1 | first`); a prefix over vertices gives
    // the edge base of every face; then each id is a lookup.
    let rot = |h: u32| prev[h as usize] ^ 1;
    let first = |h: u32| vl.vidx[next[rot(h) as usize] as usize] > vl.vidx[h as usize];
    let mut rank = vec![0u32; nh];
    let rp = super::hosts::SyncPtr(rank.as_mut_ptr());
    let cnt: Vec<u32> = (0..nv)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|v| {
            if crate::cancel::requested() {
                return 0; // the check after the loop reports it
            }
            let s = m.v_out[v];
            let (mut h, mut r) = (s, 0u32);
            loop {
                let fst = first(h);
                // SAFETY: every half-edge leaves one vertex, whose task alone writes it.
                unsafe { *rp.get().add(h as usize) = r << 1 | fst as u32 };
                r += fst as u32;
                h = rot(h);
                if h == s {
                    return r;
                }
            }
        })
        .collect();
    crate::cancel::check()?;
    let mut ebase = Vec::with_capacity(nv);
    let mut acc = 0u32;
    for c in cnt {
        ebase.push(acc);
        acc += c;
    }
    if 2 * acc as usize != nh {
        return Err(MeshError::Invariant(format!("dual: {nh} corners but {} half-edges", 2 * acc)));
    }
    let first_id = |h: u32| 2 * (ebase[vert[h as usize] as usize] + (rank[h as usize] >> 1));
    let id = |h: u32| if rank[h as usize] & 1 != 0 { first_id(h) } else { first_id(next[rot(h) as usize]) + 1 };
    let mut cols = Columns::unfilled(pos, nh, nv);
    {
        let cp = |c: &mut Vec<u32>| super::hosts::SyncPtr(c.as_mut_ptr());
        let (pn, pp, pv, pf, ps) = (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face), cp(&mut cols.f_start));
        (0..nh as u32).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() {
                return;
            }
            let (i, v) = (id(h), vert[h as usize]);
            let n = id(rot(h));
            // SAFETY: `id` is a bijection from the half-edges (corners) onto
            // 0..nh, and f_start[v] is written by v's outgoing v_out only.
            unsafe {
                *pn.get().add(i as usize) = n;
                *pp.get().add(n as usize) = i;
                *pv.get().add(i as usize) = face[h as usize];
                *pf.get().add(i as usize) = v;
                if m.v_out[v as usize] == h {
                    *ps.get().add(v as usize) = i;
                }
            }
        });
    }
    crate::cancel::check()?;
    // SAFETY: not cancelled, and `id` is a bijection onto 0..nh (above)
    unsafe { cols.assume_filled(nh) };
    // the centroid of face f first shows up at the lowest slot of its corners
    cols.v_out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
        let h = fl.corners(f).iter().copied().min_by_key(|&h| vl.vidx[h as usize]).unwrap_or(0);
        *o = id(h);
    });
    Mesh::from_columns(cols)
}

/// The dual with what `req` asks for; open meshes keep their boundary (see
/// the module docs). Closed and without requests it is [`dual`].
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn dual_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, level_step)
}

/// [`dual_level`] that also interpolates vertex data (`(rows, k)` row-major
/// arrays): on a closed mesh without point-spheres each face's mean of its
/// corners' rows (no stencils built), else through the stencils.
pub fn dual_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    let fl = std::cell::OnceCell::new();
    super::level::level_with_data(m, req, data, dual_level, |a, k| {
        let fl = super::level::once(&fl, || FaceLayout::new(m))?;
        let vert = &m.he_vert;
        let mut out = vec![0.0; m.n_faces() * k];
        out.par_chunks_mut(k.max(1)).with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
            let hs = fl.corners(f);
            let w = 1.0 / hs.len() as f64;
            for &h in hs {
                let v = vert[h as usize] as usize;
                o.iter_mut().zip(&a[v * k..(v + 1) * k]).for_each(|(o, x)| *o += x * w);
            }
        });
        crate::cancel::check()?;
        Ok(out)
    })
}

fn level_step(m: &Mesh, req: &Request) -> Result<Level> {
    if m.n_holes() == 0 && !req.stencils && !req.origins {
        return Ok(Level::plain(step(m)?));
    }
    super::dual_open::open_dual_level(super::dual_open::Given::Borrowed(m), req)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::level::{EDGE, FACE, VERTEX};
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(dual, |_, (v, e, f)| (f, e, v), |name, m, r| {
            let ps = n_point_spheres(m);
            let mut want: Vec<usize> = m.vertices().filter(|&x| m.point_sphere_face(x).is_none()).map(|x| m.valence(x)).collect();
            want.sort();
            let mut got = face_sizes(r);
            got.truncate(r.n_faces() - ps);
            got.sort();
            assert_eq!(got, want, "{name}");
            let rr = dual(r).unwrap();
            assert_eq!(rr.face_size_histogram(), m.face_size_histogram(), "{name} dual of dual");
        });
    }

    /// The one-thread walk and the parallel blocks build the same mesh
    /// (every column) on the corpus, a torus big enough for several blocks,
    /// and a Sierpinski output (self-loops).
    #[test]
    fn one_pass_equals_parallel() {
        let mut meshes: Vec<Mesh> = corpus().into_iter().map(|(_, m)| m).collect();
        meshes.push(crate::primitives::torus(300, 200, 3.0, 1.0).unwrap());
        meshes.push(crate::schemes::sierpinski::sierpinski_iterated(&crate::primitives::cube(), 2).unwrap());
        for m in meshes {
            let run = |one: bool| crate::schemes::hosts::with_point_spheres("dual", &m, |x| if one { step_one_pass(x) } else { step_parallel(x) });
            let (a, b) = (run(true).unwrap(), run(false).unwrap());
            assert!(a == b, "one-pass and parallel duals differ");
            assert!(a.pos.iter().zip(&b.pos).all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits)));
        }
    }

    fn full() -> Request<'static> {
        crate::schemes::hosts::test_meshes::full_request()
    }

    /// Each real face is the origin of one vertex, each vertex of one face,
    /// each interior edge of one edge and each boundary edge of three (its
    /// dual edge and its two boundary halves) and one vertex.
    fn check_origins(name: &str, m: &Mesh, lv: &Level) {
        let o = lv.origins.as_ref().unwrap();
        let count = origin_counts;
        let bnd = |e: usize| m.f_hole[m.he_face[2 * e] as usize] || m.f_hole[m.he_face[2 * e + 1] as usize];
        let fv = count(&o.vertex_kind, &o.vertex, FACE, m.n_faces());
        for f in 0..m.n_faces() {
            let point = m.f_start[f] & crate::mesh::POINT != 0;
            assert_eq!(fv[f], usize::from(!m.f_hole[f] && !point), "{name} face {f}");
        }
        let ev = count(&o.vertex_kind, &o.vertex, EDGE, m.n_edges());
        let ee = count(&o.edge_kind, &o.edge, EDGE, m.n_edges());
        for e in 0..m.n_edges() {
            assert_eq!((ev[e], ee[e]), if bnd(e) { (1, 3) } else { (0, 1) }, "{name} edge {e}");
        }
        assert_eq!(o.edge_kind.iter().filter(|&&k| k != EDGE).count(), 0, "{name}");
        let vf = count(&o.face_kind, &o.face, VERTEX, m.n_vertices());
        for (v, &c) in vf.iter().enumerate() {
            // a point-sphere keeps its face, born from that face
            assert_eq!(c, usize::from(m.v_out[v] & crate::mesh::POINT == 0), "{name} vertex {v}");
        }
        let hf = count(&o.face_kind, &o.face, FACE, m.n_faces());
        for f in 0..m.n_faces() {
            let point = m.f_start[f] & crate::mesh::POINT != 0;
            assert_eq!(hf[f], usize::from(m.f_hole[f] || point), "{name} face {f}");
        }
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        for (name, m) in corpus() {
            let lv = dual_level(&m, &full()).unwrap();
            check_level(name, &m, &lv);
            check_origins(name, &m, &lv);
            let plain = dual(&m).unwrap();
            assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
            // the same centroids, summed in the same order: the same bits
            assert_eq!(lv.mesh.positions(), plain.positions(), "{name}");
            let bare = dual_level(&m, &Request::plain()).unwrap();
            assert!(bare.stencils.is_none() && bare.origins.is_none());
            assert_eq!(bare.mesh.to_polygons(), plain.to_polygons(), "{name}");
        }
    }

    #[test]
    fn open_meshes_keep_their_boundary() {
        for (name, m) in open_meshes() {
            let lv = dual_level(&m, &full()).unwrap();
            check_level(name, &m, &lv);
            check_origins(name, &m, &lv);
            let r = &lv.mesh;
            let bnd: Vec<usize> = (0..m.n_edges()).filter(|&e| m.f_hole[m.he_face[2 * e] as usize] || m.f_hole[m.he_face[2 * e + 1] as usize]).collect();
            let b = bnd.len();
            let vb: std::collections::BTreeSet<u32> = bnd.iter().flat_map(|&e| [m.he_vert[2 * e], m.he_vert[2 * e + 1]]).collect();
            let (v, e, fr) = (m.n_vertices(), m.n_edges(), m.n_faces() - m.n_holes());
            assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces() - r.n_holes(), r.n_holes()), (fr + b + vb.len(), e + 2 * b, v, m.n_holes()), "{name}");
            assert_eq!(open_euler(r), open_euler(&m), "{name}");
            assert_eq!(r.n_components(), m.n_components(), "{name}");
            // the boundary is kept: boundary vertices stay, boundary edges split at their midpoints
            let p = m.positions();
            let o = lv.origins.as_ref().unwrap();
            let mut out_b = 0;
            for ov in 0..r.n_vertices() {
                let (k, i) = (o.vertex_kind[ov], o.vertex[ov] as usize);
                if k == VERTEX {
                    assert_eq!(r.positions()[ov], p[i], "{name}");
                    out_b += 1;
                } else if k == EDGE {
                    let mid = (p[m.he_vert[2 * i] as usize] + p[m.he_vert[2 * i + 1] as usize]) * 0.5;
                    assert!((r.positions()[ov] - mid).length() < 1e-15, "{name}");
                    out_b += 1;
                }
            }
            let rb = (0..r.n_edges()).filter(|&x| r.f_hole[r.he_face[2 * x] as usize] || r.f_hole[r.he_face[2 * x + 1] as usize]).count();
            assert_eq!((rb, out_b), (2 * b, 2 * b), "{name}");
            // dual of an interior vertex: the centroids of its faces
            let lv2 = dual_level(r, &full()).unwrap();
            check_level(name, r, &lv2);
            assert_eq!(open_euler(&lv2.mesh), open_euler(&m), "{name}");
        }
        assert!(dual(&cube_with_hole()).is_err());
    }

    #[test]
    fn cube_dual_is_octahedron() {
        let r = dual(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert!(r.signed_volume() > 0.0);
    }
}
