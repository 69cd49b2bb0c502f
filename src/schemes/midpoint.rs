//! Midpoint (linear) subdivision, one level: refinement without smoothing.
//!
//! * A triangle splits 1 → 4 at its edge midpoints: `[v, m(h), m(prev h)]`
//!   per corner and the middle `[m(h₀), m(h₁), m(h₂)]`. On triangle meshes
//!   this is `trimesh.remesh.subdivide` (and pymeshlab's / libigl's midpoint
//!   upsampling) up to vertex order.
//! * Any other face (n ≠ 3, one-gons and two-gons included) splits into n
//!   quads `[v, m(h), c, m(prev h)]` around its centroid `c` (the linear
//!   Catmull-Clark split; pmp-library's quad-tri linear subdivision does the
//!   same on quad/triangle meshes).
//!
//! Old vertices keep their positions; edge points are midpoints (a self-loop's
//! is its vertex), face points centroids of the corners.
//!
//! Counts: V' = V + E + F_≠3, E' = 2E + 3F₃ + Σ_≠3 n, F' = 4F₃ + Σ_≠3 n.
//! Output vertices are `[old vertices | edge midpoints | centroids of the
//! non-triangles, in face order]`.
//!
//! Open meshes, stencils and correspondence ([`midpoint_level`]). The
//! boundary rule is the interior one (the scheme is linear interpolation,
//! so a boundary edge splits at its midpoint and its ends stay put, as in
//! every midpoint/linear upsampler: trimesh, libigl, pmp-library); a hole
//! face of n corners stays one hole of 2n corners `[v₀, m(h₀), v₁, …]` and
//! gets no face point. With F₃ and Σ_≠3 n counted over the real faces:
//! V' = V + E + F_≠3, E' = 2E + 3F₃ + Σ_≠3 n, F' = 4F₃ + Σ_≠3 n real faces
//! and the same holes (χ and the boundary loops unchanged).
//!
//! Stencils (the scheme is linear): a vertex row is the vertex, an edge row
//! `½ a + ½ b`, a face row the corners' mean. Origins: old vertex v →
//! (VERTEX, v), edge midpoint → (EDGE, e), centroid → (FACE, f); every
//! output face, and the edges inside a face (the middle triangle's and the
//! spokes), come from their input face (a hole's image from the hole);
//! the two halves of an edge from that edge.

use super::hosts::{check_output_size, face_vertex_sum, primal_host, primal_host_late, with_point_spheres, FaceLayout, HOLE, MIN_LEN};
use super::level::{primal_edge_origins, with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// One level of midpoint subdivision. See the module docs.
pub fn midpoint(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("midpoint", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("midpoint", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let (face_point, k) = face_points(m, &fl)?;
    // positions last, once the builder's temporaries are gone (issue 19: peak memory)
    let n_points = m.n_vertices() + m.n_edges() + k as usize;
    primal_host_late(m, fl, face_point, n_points, || positions(m, k))
}

/// `face_point` of [`primal_host`]: triangles none, holes [`HOLE`], the
/// other faces numbered in order; and their number.
fn face_points(m: &Mesh, fl: &FaceLayout) -> Result<(Vec<u32>, u32)> {
    let mut face_point = vec![NONE; m.n_faces()];
    let mut k = 0u32;
    for (f, fp) in face_point.iter_mut().enumerate() {
        crate::cancel::poll(f)?;
        if m.f_hole[f] {
            *fp = HOLE;
        } else if fl.degree(f) != 3 {
            *fp = k;
            k += 1;
        }
    }
    Ok((face_point, k))
}

/// Vertex points, edge midpoints, then the centroid of every face that is
/// neither a hole nor a triangle (the faces [`face_points`] numbers), in
/// face order. Reads the mesh only (no face layout or face points, which
/// [`step`] frees before it runs); each centroid is summed along the
/// face's cycle from its first half-edge, the order of the layout's corners.
fn positions(m: &Mesh, k: u32) -> Result<Vec<DVec3>> {
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, _) = m.halfedge_columns();
    let p = &m.pos;
    let mut pos = Vec::with_capacity(nv + ne + k as usize);
    crate::mesh::populate(&mut pos, nv + ne + k as usize);
    pos.extend_from_slice(p);
    pos.par_extend((0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }));
    for f in 0..nf {
        crate::cancel::poll(f)?;
        if m.f_hole[f] {
            continue;
        }
        let (s, n) = face_vertex_sum(m, f);
        if n != 3 {
            pos.push(s / n as f64);
        }
    }
    crate::cancel::check()?;
    Ok(pos)
}

/// One level with what `req` asks for; open meshes keep their holes (see
/// the module docs). Closed and without requests it is [`midpoint`].
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn midpoint_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, level_step)
}

/// [`midpoint_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays): on a closed mesh without point-spheres the rows of
/// [`positions`] (old rows, edge midpoints, centroids of the non-triangles;
/// no stencils built), else through the stencils.
pub fn midpoint_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    let fl = std::cell::OnceCell::new();
    super::level::level_with_data(m, req, data, midpoint_level, |a, k| {
        let fl = super::level::once(&fl, || FaceLayout::new(m))?;
        let (nv, ne) = (m.n_vertices(), m.n_edges());
        let vert = &m.he_vert;
        let row = |v: u32| &a[v as usize * k..(v as usize + 1) * k];
        let mut out = Vec::with_capacity((nv + ne + m.n_faces()) * k);
        out.extend_from_slice(&a[..nv * k]);
        out.resize((nv + ne) * k, 0.0);
        out[nv * k..].par_chunks_mut(k.max(1)).with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
            for ((o, x), y) in o.iter_mut().zip(row(vert[2 * e])).zip(row(vert[2 * e + 1])) {
                *o = (x + y) * 0.5;
            }
        });
        for f in 0..m.n_faces() {
            crate::cancel::poll(f)?;
            let hs = fl.corners(f);
            if hs.len() == 3 {
                continue;
            }
            let start = out.len();
            out.resize(start + k, 0.0);
            let w = 1.0 / hs.len() as f64;
            for &h in hs {
                out[start..].iter_mut().zip(row(vert[h as usize])).for_each(|(o, x)| *o += x * w);
            }
        }
        crate::cancel::check()?;
        Ok(out)
    })
}

fn level_step(m: &Mesh, req: &Request) -> Result<Level> {
    // open meshes too: holes are faces the host leaves as they are, and the
    // plain step computes its positions last (issue 19: peak memory)
    if !req.stencils && !req.origins {
        return Ok(Level::plain(step(m)?));
    }
    check_output_size("midpoint", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (face_point, k) = face_points(m, &fl)?;
    let pos = positions(m, k)?;
    let mesh = primal_host(m, &fl, &face_point, pos)?;
    let mut centroid_of = Vec::with_capacity(k as usize);
    centroid_of.extend((0..nf as u32).filter(|&f| face_point[f as usize] != NONE && face_point[f as usize] != HOLE));
    let (_, vert, _) = m.halfedge_columns();
    let stencils = if req.stencils {
        Some(Stencils::build(nv + ne + k as usize, nv, |i, row| {
            if i < nv {
                row.add(i as u32, 1.0);
            } else if i < nv + ne {
                let e = i - nv;
                row.add(vert[2 * e], 0.5);
                row.add(vert[2 * e + 1], 0.5);
            } else {
                let hs = fl.corners(centroid_of[i - nv - ne] as usize);
                let w = 1.0 / hs.len() as f64;
                for &h in hs {
                    row.add(vert[h as usize], w);
                }
            }
        })?)
    } else {
        None
    };
    let origins = if req.origins {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(FACE).take(k as usize)));
        o.vertex.extend((0..nv as u32).chain(0..ne as u32).chain(centroid_of.iter().copied()));
        for f in 0..nf {
            crate::cancel::poll(f)?;
            let n = match face_point[f] {
                HOLE => 1,
                NONE => 4,
                _ => fl.degree(f),
            };
            o.face_kind.extend(std::iter::repeat(FACE).take(n));
            o.face.extend(std::iter::repeat(f as u32).take(n));
        }
        primal_edge_origins(&mesh, &mut o);
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        let counts = |m: &Mesh, (v, e, _): (usize, usize, usize)| {
            let ps = n_point_spheres(m);
            let sizes: Vec<usize> = face_sizes(m);
            let f3 = sizes.iter().filter(|&&s| s == 3).count();
            let ng: Vec<usize> = sizes.iter().copied().filter(|&s| s != 3).collect();
            // point-sphere faces have size 1 but are carried over, not split
            let (ngn, ngsum) = (ng.len() - ps, ng.iter().sum::<usize>() - ps);
            (v + e + ngn, 2 * e + 3 * f3 + ngsum, 4 * f3 + ngsum)
        };
        check_on_corpus(midpoint, counts, |_, m, r| {
            // old vertices stay put
            let v = m.n_vertices() - n_point_spheres(m);
            assert_eq!(&r.positions()[..v], &m.positions()[..v]);
        });
    }

    fn full() -> Request<'static> {
        crate::schemes::hosts::test_meshes::full_request()
    }

    /// The origins partition the output as the counts say: V vertex points,
    /// E edge points, one centroid per real non-triangle; 4 faces per
    /// triangle, n per other real n-gon, one per hole; every input edge is
    /// the origin of exactly two output edges.
    fn check_origins(name: &str, m: &Mesh, lv: &Level) {
        let o = lv.origins.as_ref().unwrap();
        let count = origin_counts;
        assert!(count(&o.vertex_kind, &o.vertex, VERTEX, m.n_vertices()).iter().all(|&c| c == 1), "{name}");
        assert!(count(&o.vertex_kind, &o.vertex, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
        let fl = FaceLayout::new(m).unwrap();
        let fv = count(&o.vertex_kind, &o.vertex, FACE, m.n_faces());
        let ff = count(&o.face_kind, &o.face, FACE, m.n_faces());
        for f in 0..m.n_faces() {
            let (d, hole, point) = (fl.degree(f), m.f_hole[f], m.f_start[f] & crate::mesh::POINT != 0);
            assert_eq!(fv[f], usize::from(!hole && d != 3 && !point), "{name} face {f}");
            assert_eq!(ff[f], if hole || point { 1 } else if d == 3 { 4 } else { d }, "{name} face {f}");
        }
        assert!(count(&o.edge_kind, &o.edge, EDGE, m.n_edges()).iter().all(|&c| c == 2), "{name}");
        assert_eq!(o.face_kind.iter().filter(|&&k| k != FACE).count(), 0);
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        for (name, m) in corpus() {
            let lv = midpoint_level(&m, &full()).unwrap();
            check_level(name, &m, &lv);
            check_origins(name, &m, &lv);
            let plain = midpoint(&m).unwrap();
            assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
            assert_eq!(lv.mesh.positions(), plain.positions(), "{name}");
            let bare = midpoint_level(&m, &Request::plain()).unwrap();
            assert!(bare.stencils.is_none() && bare.origins.is_none() && bare.creases.is_none());
            assert_eq!(bare.mesh.to_polygons(), plain.to_polygons(), "{name}");
        }
    }

    #[test]
    fn open_meshes_keep_their_holes() {
        for (name, m) in open_meshes() {
            let lv = midpoint_level(&m, &full()).unwrap();
            check_level(name, &m, &lv);
            check_origins(name, &m, &lv);
            let r = &lv.mesh;
            let fl = FaceLayout::new(&m).unwrap();
            let real: Vec<usize> = (0..m.n_faces()).filter(|&f| !m.f_hole[f]).map(|f| fl.degree(f)).collect();
            let f3 = real.iter().filter(|&&d| d == 3).count();
            let ng: Vec<usize> = real.iter().copied().filter(|&d| d != 3).collect();
            let (v, e) = (m.n_vertices(), m.n_edges());
            let want = (v + e + ng.len(), 2 * e + 3 * f3 + ng.iter().sum::<usize>(), 4 * f3 + ng.iter().sum::<usize>(), m.n_holes());
            assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces() - r.n_holes(), r.n_holes()), want, "{name}");
            assert_eq!(open_euler(r), open_euler(&m), "{name}");
            assert_eq!(r.n_components(), m.n_components(), "{name}");
            // the boundary: every boundary edge's midpoint sits on it, its ends stay
            let p = m.positions();
            let bnd = |x: &Mesh| (0..x.n_edges()).filter(|&ed| x.f_hole[x.he_face[2 * ed] as usize] || x.f_hole[x.he_face[2 * ed + 1] as usize]).collect::<Vec<_>>();
            let (b_in, b_out) = (bnd(&m), bnd(r));
            assert_eq!(b_out.len(), 2 * b_in.len(), "{name}");
            for ed in b_in {
                let mid = (p[m.he_vert[2 * ed] as usize] + p[m.he_vert[2 * ed + 1] as usize]) * 0.5;
                assert_eq!(r.positions()[v + ed], mid, "{name}");
            }
            assert_eq!(&r.positions()[..v], p, "{name}");
        }
        // the plain call still refuses (it has no level to report holes through)
        assert!(midpoint(&cube_with_hole()).is_err());
    }
}
