//! Loop subdivision (C. Loop, "Smooth subdivision surfaces based on
//! triangles", M.S. thesis, University of Utah, 1987), one level, extended to
//! polygon meshes.
//!
//! Masks: Loop's *original* weights (the ones trimesh, VTK and pymeshlab use;
//! libigl, Open3D and gpytoolbox use Warren's simplified β instead):
//! * vertex point: `(1 − nβ) v + β Σ neighbours`, with
//!   `β = (1/n) (5/8 − (3/8 + 1/4 cos(2π/n))²)` for valence n;
//! * edge point: `3/8 (a + b) + 1/8 (c + d)`, `c`, `d` the corners opposite
//!   the edge in its two triangles.
//!
//! Non-triangles ("extended Loop" of the Sierpinski paper, §6): every face
//! with n ≠ 3 corners (one-gons and two-gons included) is first fanned into n
//! triangles around a new vertex at its centroid
//! ([`super::hosts::fan_triangulate`]), then the Loop step above runs on the
//! all-triangle mesh; the centroid is an ordinary valence-n vertex there.
//! Meshes of triangles only skip the first step. Sums run over half-edges:
//! a self-loop counts twice in its vertex's valence.
//!
//! Counts on triangles: V' = V + E, E' = 2E + 3F, F' = 4F. With n-gons, apply
//! them to the fanned mesh: V + F_≠3 vertices, E + Σ_≠3 n edges, F_3 + Σ_≠3 n
//! triangles. Output vertices are `[vertex points | edge points]`.
//!
//! Open meshes, creases, stencils and correspondence ([`loop_level`]):
//! OpenSubdiv's Loop boundary and crease rules ([`super::creases`]; the
//! crease masks are Catmull-Clark's: midpoint, `3/4 v + 1/8 (a + b)`,
//! corner). Hole faces are not fanned and stay one hole of 2n corners; on
//! triangles with b boundary edges: V' = V + E, E' = 2E + 3F_r, F' = 4F_r.
//! With n-gons the level is the fan followed by the Loop step, and its
//! stencils and origins are the composition of the two. Corners (for the
//! edge-and-corner boundary) are those of the fanned triangles, as if the
//! mesh were triangulated before OpenSubdiv's Loop: a quad's boundary
//! corner has two triangles there and follows the crease rule; give it
//! vertex sharpness to pin it.

use super::creases::{Creases, EdgeRule, LevelSharpness, Rule};
use super::hosts::{check_output_size, fan_triangulate, primal_host_late, FaceLayout, HOLE, MIN_LEN};
use super::level::{primal_edge_origins, with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::{Row, Stencils};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use glam::DVec3;
use rayon::prelude::*;

/// One level of Loop subdivision; non-triangles are fanned around their
/// centroid first. See the module docs.
/// Open meshes follow OpenSubdiv's default boundary rule (edge and corner).
pub fn loop_subdivision(m: &Mesh) -> Result<Mesh> {
    loop_level(m, &Request::plain()).map(|l| l.mesh)
}

/// Loop's original β for valence `n`.
#[inline]
pub fn loop_beta(n: usize) -> f64 {
    let n = n as f64;
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
    (0.625 - c * c) / n
}

/// [`loop_beta`] of the valences below 64, computed once per call: a
/// cosine per vertex was 1.5 % of a level-3 step (`perf`); the same values.
pub(crate) struct Betas([f64; 64]);

impl Betas {
    pub(crate) fn new() -> Betas {
        Betas(std::array::from_fn(loop_beta))
    }
    #[inline]
    pub(crate) fn get(&self, n: usize) -> f64 {
        if n < 64 { self.0[n] } else { loop_beta(n) }
    }
}

/// One Loop step on a mesh of triangles.
fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("loop", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let face_point = vec![NONE; m.n_faces()];
    // positions last, once the builder's temporaries are gone (issue 19: peak memory)
    primal_host_late(m, fl, face_point, m.n_vertices() + m.n_edges(), || smooth_positions(m))
}

/// The closed-surface masks computed directly (no hole, no crease).
fn smooth_positions(m: &Mesh) -> Result<Vec<DVec3>> {
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let (_, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    // written in full below (no calloc: `unfilled_points`)
    let mut pos = crate::mesh::unfilled_points(nv + ne);
    let (vp, ep) = pos.spare_capacity_mut()[..nv + ne].split_at_mut(nv);
    let betas = Betas::new();
    rayon::join(
        || {
            ep.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (a, b) = (2 * e, 2 * e + 1);
                let ab = p[vert[a] as usize] + p[vert[b] as usize];
                let cd = p[vert[prev[a] as usize] as usize] + p[vert[prev[b] as usize] as usize];
                out.write(ab * 0.375 + cd * 0.125);
            })
        },
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return; // the check after the loop reports it
                }
                let (sum, n) = super::hosts::neighbor_sum(m, v);
                let beta = betas.get(n);
                out.write(p[v] * (1.0 - n as f64 * beta) + sum * beta);
            })
        },
    );
    crate::cancel::check()?;
    // SAFETY: not cancelled: both parts are written in full
    unsafe { pos.set_len(nv + ne) };
    Ok(pos)
}

/// One level with what `req` asks for: OpenSubdiv's boundary and crease
/// rules (holes stay open), the stencils, the origins and the output's
/// crease sharpness. Without holes, creases or requests it is
/// [`loop_subdivision`].
pub fn loop_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() == 0 && req.creases.is_none() && !req.stencils && !req.origins {
            return Ok(Level::plain(match fan_triangulate(m)? {
                Some(t) => step(&t)?,
                None => step(m)?,
            }));
        }
        let Some(fan) = fan_triangulate(m)? else {
            return triangle_level(m, req);
        };
        let fl = fan_level(m, &fan, req)?;
        let lv = triangle_level(&fan, &Request { creases: fl.creases.as_ref(), ..*req })?;
        let stencils = match (&lv.stencils, &fl.stencils) {
            (Some(s), Some(f)) => Some(s.compose(f)?),
            _ => None,
        };
        let origins = match (&lv.origins, &fl.origins) {
            (Some(o), Some(f)) => Some(o.compose(f)),
            _ => None,
        };
        Ok(Level { mesh: lv.mesh, stencils, origins, creases: lv.creases })
    })
}

/// [`loop_level`] that also interpolates vertex data (row-major `(rows,
/// k)` arrays): by the direct masks on a smooth closed mesh (through the
/// fan's centroids), else through the stencils.
pub fn loop_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    let fan = std::cell::OnceCell::new();
    super::level::level_with_data_linear(m, req, data, loop_level, |a, k| {
        let fan = super::level::once(&fan, || fan_triangulate(m))?;
        let Some(t) = fan else { return smooth_apply(m, a, k) };
        // the fan's centroids follow the input vertices, in face order
        let fl = FaceLayout::new(m)?;
        let (_, vert, _) = m.halfedge_columns();
        let mut b = a.to_vec();
        for f in 0..m.n_faces() {
            let hs = fl.corners(f);
            if hs.len() == 3 {
                continue;
            }
            let start = b.len();
            b.resize(start + k, 0.0);
            for &h in hs {
                for j in 0..k {
                    b[start + j] += a[vert[h as usize] as usize * k + j] / hs.len() as f64;
                }
            }
        }
        smooth_apply(t, &b, k)
    })
}

/// Loop's closed-surface masks on rows of `k` numbers, on triangles.
fn smooth_apply(m: &Mesh, a: &[f64], k: usize) -> Result<Vec<f64>> {
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let (_, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let mut out = vec![0.0; (nv + ne) * k];
    if k == 0 {
        return Ok(out);
    }
    let (vp, ep) = out.split_at_mut(nv * k);
    let row = |i: u32| &a[i as usize * k..(i as usize + 1) * k];
    rayon::join(
        || {
            ep.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
                let (x, y) = (row(vert[2 * e]), row(vert[2 * e + 1]));
                let (c, d) = (row(vert[prev[2 * e] as usize]), row(vert[prev[2 * e + 1] as usize]));
                for j in 0..k {
                    o[j] = (x[j] + y[j]) * 0.375 + (c[j] + d[j]) * 0.125;
                }
            })
        },
        || {
            vp.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
                let mut n = 0usize;
                for h in super::creases::ring(m, m.v_out[v]) {
                    let e = row(vert[(h ^ 1) as usize]);
                    for j in 0..k {
                        o[j] += e[j];
                    }
                    n += 1;
                }
                let beta = loop_beta(n);
                let s = row(v as u32);
                for j in 0..k {
                    o[j] = s[j] * (1.0 - n as f64 * beta) + o[j] * beta;
                }
            })
        },
    );
    crate::cancel::check()?;
    Ok(out)
}

/// The fan's own stencils, origins and creases (spokes and centroids are smooth).
fn fan_level(m: &Mesh, fan: &Mesh, req: &Request) -> Result<Level> {
    let fl = FaceLayout::new(m)?;
    let ofl = FaceLayout::new(fan)?;
    let (nv, nf) = (m.n_vertices(), m.n_faces());
    let (_, vert, _) = m.halfedge_columns();
    // per fanned edge: the input edge it is, or NONE for a spoke (with its face)
    let mut edge_of = vec![NONE; fan.n_edges()];
    let mut spoke_face = vec![NONE; fan.n_edges()];
    let mut face_of = Vec::with_capacity(fan.n_faces());
    let mut centroid_face = Vec::new();
    let mut of = 0usize;
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = fl.corners(f);
        if hs.len() == 3 || m.f_hole[f] {
            for (k, &h) in hs.iter().enumerate() {
                edge_of[(ofl.corners(of)[k] >> 1) as usize] = h >> 1;
            }
            face_of.push(f as u32);
            of += 1;
        } else {
            centroid_face.push(f as u32);
            for &h in hs {
                let c = ofl.corners(of);
                edge_of[(c[0] >> 1) as usize] = h >> 1;
                spoke_face[(c[1] >> 1) as usize] = f as u32;
                spoke_face[(c[2] >> 1) as usize] = f as u32;
                face_of.push(f as u32);
                of += 1;
            }
        }
    }
    let stencils = if req.stencils {
        Some(Stencils::build(fan.n_vertices(), nv, |i, row| {
            if i < nv {
                row.add(i as u32, 1.0);
            } else {
                let hs = fl.corners(centroid_face[i - nv] as usize);
                for &h in hs {
                    row.add(vert[h as usize], 1.0 / hs.len() as f64);
                }
            }
        })?)
    } else {
        None
    };
    let origins = req.origins.then(|| {
        let mut o = Origins::with_capacity(fan.n_vertices(), fan.n_edges(), fan.n_faces());
        o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(FACE).take(centroid_face.len())));
        o.vertex.extend((0..nv as u32).chain(centroid_face.iter().copied()));
        for (e, &x) in edge_of.iter().enumerate() {
            if x == NONE {
                o.edge_kind.push(FACE);
                o.edge.push(spoke_face[e]);
            } else {
                o.edge_kind.push(EDGE);
                o.edge.push(x);
            }
        }
        o.face_kind.extend(std::iter::repeat(FACE).take(face_of.len()));
        o.face.extend_from_slice(&face_of);
        o
    });
    let creases = req.creases.map(|c| Creases {
        edge: edge_of.iter().map(|&x| if x == NONE { 0.0 } else { c.edge(x as usize) }).collect(),
        vertex: (0..fan.n_vertices()).map(|v| if v < nv { c.vertex(v) } else { 0.0 }).collect(),
    });
    Ok(Level { mesh: Mesh::new(), stencils, origins, creases })
}

/// A level on a mesh whose real faces are triangles.
fn triangle_level(m: &Mesh, req: &Request) -> Result<Level> {
    check_output_size("loop", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let smooth = req.smooth_on(m);
    let face_point: Vec<u32> = m.f_hole.iter().map(|&h| if h { HOLE } else { NONE }).collect();
    let ls = LevelSharpness::new(m, req.creases, req.options);
    // stencils only when asked for: otherwise the positions of an open or
    // creased level are applied row by row, without storing the rows
    let stencils = if req.stencils { Some(stencils(m, &ls, req)?) } else { None };
    let direct = || if smooth { smooth_positions(m) } else { stencil_points(m, &ls, req) };
    let (mesh, creases) = super::level::primal_output(m, fl, face_point, &ls, req, stencils.as_ref(), smooth, direct)?;
    let origins = req.origins.then(|| {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(EDGE).take(ne)));
        o.vertex.extend((0..nv as u32).chain(0..ne as u32));
        for f in 0..nf {
            let k = if m.f_hole[f] { 1 } else { 4 };
            o.face_kind.extend(std::iter::repeat(FACE).take(k));
            o.face.extend(std::iter::repeat(f as u32).take(k));
        }
        primal_edge_origins(&mesh, &mut o);
        o
    });
    Ok(Level { mesh, stencils, origins, creases })
}

/// Rows `[vertex points | edge points]` over the input vertices.
fn stencils(m: &Mesh, ls: &LevelSharpness, req: &Request) -> Result<Stencils> {
    stencil_rows(m, ls, req, |n, n_cols, fill| Stencils::build(n, n_cols, fill))
}

/// The positions [`stencils`] gives, row by row without storing the rows
/// (bit for bit the same: [`Stencils::apply_rows_points`]).
fn stencil_points(m: &Mesh, ls: &LevelSharpness, req: &Request) -> Result<Vec<DVec3>> {
    stencil_rows(m, ls, req, |n, _, fill| Stencils::apply_rows_points(n, &m.pos, fill))
}

/// Hands the level's row filler (row count, column count, filler) to `run`.
fn stencil_rows<T>(m: &Mesh, ls: &LevelSharpness, req: &Request, run: impl FnOnce(usize, usize, &(dyn Fn(usize, &mut Row) + Sync)) -> T) -> T {
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let (_, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let head = |h: u32| vert[(h ^ 1) as usize];
    let mask = |v: usize, rule: Rule, ends: [u32; 2], w: f64, row: &mut Row| match rule {
        Rule::Smooth | Rule::Dart => {
            // the ring walked twice (its size first) instead of collected
            let n = super::creases::ring(m, m.v_out[v]).count();
            let beta = loop_beta(n);
            row.add(v as u32, w * (1.0 - n as f64 * beta));
            for h in super::creases::ring(m, m.v_out[v]) {
                row.add(head(h), w * beta);
            }
        }
        Rule::Crease => {
            row.add(v as u32, 0.75 * w);
            row.add(head(ends[0]), 0.125 * w);
            row.add(head(ends[1]), 0.125 * w);
        }
        Rule::Corner => row.add(v as u32, w),
    };
    let fill: &(dyn Fn(usize, &mut Row) + Sync) = &|i, row| {
        if i < nv {
            let r = ls.vertex_rule(m, i, req.options.crease_method);
            match r.child {
                None => mask(i, r.parent, r.parent_ends, 1.0, row),
                Some((crule, cends, pw)) => {
                    mask(i, r.parent, r.parent_ends, pw, row);
                    mask(i, crule, cends, 1.0 - pw, row);
                }
            }
        } else {
            let e = i - nv;
            let (a, b) = (2 * e, 2 * e + 1);
            let (wv, wo) = match ls.edge_rule(e) {
                EdgeRule::Smooth => (0.375, 0.125),
                EdgeRule::Crease => (0.5, 0.0),
                EdgeRule::Blend(s) => (0.5 * s + 0.375 * (1.0 - s), 0.125 * (1.0 - s)),
            };
            row.add(vert[a], wv);
            row.add(vert[b], wv);
            if wo != 0.0 {
                row.add(vert[prev[a] as usize], wo);
                row.add(vert[prev[b] as usize], wo);
            }
        }
    };
    run(nv + ne, nv, fill)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn beta_values() {
        let betas = Betas::new();
        for n in 0..70 {
            assert_eq!(betas.get(n).to_bits(), loop_beta(n).to_bits(), "valence {n}");
        }
        assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-15);
        assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        // the counts on triangles, applied to the fanned mesh
        let counts = |m: &Mesh, (v, e, _): (usize, usize, usize)| {
            let f3 = face_sizes(m).iter().filter(|&&s| s == 3).count();
            let ngons: Vec<usize> = m
                .faces()
                .filter(|&f| m.point_sphere_face(m.face_vertices(f).next().unwrap()) != Some(f))
                .map(|f| m.face_degree(f))
                .filter(|&s| s != 3)
                .collect();
            let (v, e, f) = (v + ngons.len(), e + ngons.iter().sum::<usize>(), f3 + ngons.iter().sum::<usize>());
            (v + e, 2 * e + 3 * f, 4 * f)
        };
        check_on_corpus(loop_subdivision, counts, |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 3), "{name} triangles");
        });
    }

    #[test]
    fn level_stencils_equal_the_direct_masks_on_corpus() {
        let full = crate::schemes::hosts::test_meshes::full_request();
        for (name, m) in corpus() {
            let lv = loop_level(&m, &full).unwrap();
            check_level(name, &m, &lv);
            let plain = loop_subdivision(&m).unwrap();
            assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
            for (a, b) in lv.mesh.positions().iter().zip(plain.positions()) {
                assert!((*a - *b).length() < 1e-12, "{name}");
            }
            // every input face is the origin of 4 triangles per fanned triangle
            let o = lv.origins.unwrap();
            for f in m.faces() {
                if m.point_sphere_face(m.face_vertices(f).next().unwrap()) == Some(f) {
                    continue;
                }
                let n = m.face_degree(f);
                let want = if n == 3 { 4 } else { 4 * n };
                assert_eq!(o.face.iter().zip(&o.face_kind).filter(|&(&i, &k)| k == FACE && i == f.0).count(), want, "{name} face {f:?}");
            }
        }
    }

    #[test]
    fn direct_data_masks_equal_the_stencils() {
        check_direct_data_on_corpus(3, 1e-11, loop_level, loop_level_with);
    }

    #[test]
    fn open_meshes_keep_their_holes_with_boundary_rules() {
        let full = crate::schemes::hosts::test_meshes::full_request();
        for (name, m) in [("grid", open_grid(3)), ("tube", open_tube(6, 2)), ("cube_with_hole", cube_with_hole())] {
            let lv = loop_level(&m, &full).unwrap();
            check_level(name, &m, &lv);
            assert_eq!(lv.mesh.n_holes(), m.n_holes(), "{name}");
            assert_eq!(open_euler(&lv.mesh), open_euler(&m), "{name}");
            // a second level on the all-triangle output: V' = V + E, F' = 4 F_r
            let r = &lv.mesh;
            let lv2 = loop_level(r, &full).unwrap();
            check_level(name, r, &lv2);
            assert_eq!(lv2.mesh.n_vertices(), r.n_vertices() + r.n_edges(), "{name}");
            assert_eq!(lv2.mesh.n_faces() - lv2.mesh.n_holes(), 4 * (r.n_faces() - r.n_holes()), "{name}");
            // boundary edge points are midpoints
            let p = r.positions();
            for e in 0..r.n_edges() {
                if r.f_hole[r.he_face[2 * e] as usize] || r.f_hole[r.he_face[2 * e + 1] as usize] {
                    let mid = (p[r.he_vert[2 * e] as usize] + p[r.he_vert[2 * e + 1] as usize]) * 0.5;
                    assert!((lv2.mesh.positions()[r.n_vertices() + e] - mid).length() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn regular_vertex_keeps_plane() {
        // a flat regular patch stays flat: the icosahedron's vertex points
        // stay on the symmetry axes
        let r = loop_subdivision(&crate::primitives::icosahedron()).unwrap();
        let m = crate::primitives::icosahedron();
        for v in 0..12 {
            let a = m.positions()[v].normalize();
            let b = r.positions()[v].normalize();
            assert!((a - b).length() < 1e-12);
        }
    }
}
