//! Catmull-Clark subdivision (Catmull & Clark, "Recursively generated B-spline
//! surfaces on arbitrary topological meshes", CAD 10(6), 1978), one level.
//!
//! Masks (the original ones, as in OpenSubdiv's closed-surface rules):
//! * face point: the centroid of the face's corners;
//! * edge point: `(a + b + f₁ + f₂) / 4` (ends and the two adjacent face points);
//! * vertex point: `(Q + 2R + (n − 3) S) / n`, with `S` the old position, `n`
//!   its valence, `Q` the mean of the face points around it and `R` the mean
//!   of the midpoints of its edges, i.e. `(n − 2)/n · S + (Σ eⱼ + Σ fⱼ) / n²`.
//!
//! Every face of any size (one-gons and two-gons included) becomes n quads
//! `[v, e(h), f, e(prev h)]`, one per corner. All sums run over half-edges, so
//! a self-loop counts twice in its vertex's valence and its two sides get the
//! two face points of their own faces: a zero-length self-loop (Sierpinski
//! output) gets an edge point off the vertex and opens into a tube.
//!
//! Counts (H = 2E half-edges): V' = V + E + F, E' = 2E + H = 4E, F' = H.
//! Output vertices are laid out `[vertex points | edge points | face points]`.
//!
//! Open meshes, creases, stencils and correspondence ([`catmull_clark_level`]):
//! boundary and crease rules are OpenSubdiv's (see [`super::creases`]); a
//! hole face of n corners stays one hole of 2n corners and gets no face
//! point, so with b boundary edges (H_r = H − b corners in real faces):
//! V' = V + E + F_r, E' = 2E + H_r, F' = H_r real faces and the same holes.
//! The positions are then `S · P` with the level's stencils `S`, which are
//! also the rows of the subdivision matrix; closed meshes without creases
//! keep the direct computation above (the same weights, tested equal).

use super::creases::{EdgeRule, LevelSharpness, Rule};
use super::hosts::{check_output_size, face_centroids_into, primal_host_late, FaceLayout, HOLE, MIN_LEN};
use super::level::{primal_edge_origins, with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::{Row, Stencils};
use crate::error::Result;
use crate::mesh::{FaceId, Mesh};
use glam::DVec3;
use rayon::prelude::*;

/// One level of Catmull-Clark subdivision, open meshes with OpenSubdiv's
/// default boundary rule (edge and corner). See the module docs.
pub fn catmull_clark(m: &Mesh) -> Result<Mesh> {
    catmull_clark_level(m, &Request::plain()).map(|l| l.mesh)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("catmull_clark", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let face_point: Vec<u32> = (0..m.n_faces() as u32).collect();
    // positions last, once the builder's temporaries are gone (issue 19: peak memory)
    primal_host_late(m, fl, face_point, m.n_vertices() + m.n_edges() + m.n_faces(), || smooth_positions(m))
}

/// The closed-surface masks computed directly (no hole, no crease).
fn smooth_positions(m: &Mesh) -> Result<Vec<DVec3>> {
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, face) = m.halfedge_columns();
    // written in full below (no calloc: `unfilled_points`)
    let mut pos = crate::mesh::unfilled_points(nv + ne + nf);
    let (vp, rest) = pos.spare_capacity_mut()[..nv + ne + nf].split_at_mut(nv);
    let (ep, fp) = rest.split_at_mut(ne);
    face_centroids_into(m, fp);
    crate::cancel::check()?;
    // SAFETY: not cancelled, so every centroid is written
    let fp = unsafe { crate::mesh::written(fp) };
    let p = &m.pos;
    rayon::join(
        || {
            ep.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, out)| {
                if crate::cancel::requested() {
                    return;
                }
                let (a, b) = (2 * e, 2 * e + 1);
                out.write((p[vert[a] as usize] + p[vert[b] as usize] + fp[face[a] as usize] + fp[face[b] as usize]) * 0.25);
            })
        },
        || {
            vp.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, out)| {
                if crate::cancel::requested() {
                    return;
                }
                let s = m.v_out[v];
                let mut h = s;
                let mut sum = DVec3::ZERO;
                let mut n = 0usize;
                loop {
                    sum += p[vert[(h ^ 1) as usize] as usize] + fp[face[h as usize] as usize];
                    n += 1;
                    h = m.he_prev[h as usize] ^ 1;
                    if h == s {
                        break;
                    }
                }
                let n = n as f64;
                out.write(p[v] * ((n - 2.0) / n) + sum / (n * n));
            })
        },
    );
    crate::cancel::check()?;
    // SAFETY: not cancelled: the three parts are written in full
    unsafe { pos.set_len(nv + ne + nf) };
    Ok(pos)
}

/// One level with what `req` asks for: OpenSubdiv's boundary and crease
/// rules (holes stay open), the stencils, the origins and the output's
/// crease sharpness. Without holes, creases or requests it is
/// [`catmull_clark`].
pub fn catmull_clark_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, level_step)
}

fn level_step(m: &Mesh, req: &Request) -> Result<Level> {
    let smooth = req.smooth_on(m);
    if smooth && !req.stencils && !req.origins && req.creases.is_none() {
        return Ok(Level::plain(step(m)?));
    }
    check_output_size("catmull_clark", 4 * m.n_halfedges(), m.n_vertices() + m.n_edges() + m.n_faces())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let mut face_point = vec![HOLE; nf];
    // the hole faces, not the real ones: 4 bytes per hole instead of per
    // face at the level's peak ([`RealFaces`])
    let mut holes = Vec::new();
    for f in 0..nf {
        if m.f_hole[f] {
            holes.push(f as u32);
        } else {
            face_point[f] = (f - holes.len()) as u32;
        }
    }
    let real = RealFaces { holes, n: nf };
    let ls = LevelSharpness::new(m, req.creases, req.options);
    // stencils only when asked for: otherwise the positions of an open or
    // creased level are applied row by row, without storing the rows
    let stencils = if req.stencils { Some(stencils(m, &ls, req, &real)?) } else { None };
    let direct = || if smooth { smooth_positions(m) } else { stencil_points(m, &ls, req, &real) };
    // the layout and face points go to the host, which frees them before
    // the output's columns (issue 19: an open level's peak)
    let (mesh, creases) = super::level::primal_output(m, fl, face_point, &ls, req, stencils.as_ref(), smooth, direct)?;
    let origins = req.origins.then(|| {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(VERTEX).take(nv).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(FACE).take(real.len())));
        o.vertex.extend((0..nv as u32).chain(0..ne as u32).chain((0..nf as u32).filter(|&f| !m.f_hole[f as usize])));
        for f in 0..nf {
            let k = if m.f_hole[f] { 1 } else { m.face_degree(FaceId(f as u32)) };
            o.face_kind.extend(std::iter::repeat(FACE).take(k));
            o.face.extend(std::iter::repeat(f as u32).take(k));
        }
        primal_edge_origins(&mesh, &mut o);
        o
    });
    Ok(Level { mesh, stencils, origins, creases })
}

/// [`catmull_clark_level`] that also interpolates vertex data (`(rows,
/// k)` row-major arrays) with the level's weights: by the direct masks on a
/// smooth closed mesh (no stencils built), else through the stencils.
pub fn catmull_clark_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    let fl = std::cell::OnceCell::new();
    super::level::level_with_data_linear(m, req, data, catmull_clark_level, |a, k| {
        let fl = super::level::once(&fl, || FaceLayout::new(m))?;
        smooth_apply(m, fl, a, k)
    })
}

/// The closed-surface masks on rows of `k` numbers (vertex data).
fn smooth_apply(m: &Mesh, fl: &FaceLayout, a: &[f64], k: usize) -> Result<Vec<f64>> {
    let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
    let (_, vert, face) = m.halfedge_columns();
    let mut out = vec![0.0; (nv + ne + nf) * k];
    if k == 0 {
        return Ok(out);
    }
    let (vp, rest) = out.split_at_mut(nv * k);
    let (ep, fp) = rest.split_at_mut(ne * k);
    let row = |i: u32| &a[i as usize * k..(i as usize + 1) * k];
    fp.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(f, o)| {
        let hs = fl.corners(f);
        for &h in hs {
            o.iter_mut().zip(row(vert[h as usize])).for_each(|(o, x)| *o += x);
        }
        let w = 1.0 / hs.len() as f64;
        o.iter_mut().for_each(|o| *o *= w);
    });
    crate::cancel::check()?;
    let fp = &*fp;
    let frow = |f: u32| &fp[f as usize * k..(f as usize + 1) * k];
    rayon::join(
        || {
            ep.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
                let (x, y, f1, f2) = (row(vert[2 * e]), row(vert[2 * e + 1]), frow(face[2 * e]), frow(face[2 * e + 1]));
                for j in 0..k {
                    o[j] = (x[j] + y[j] + f1[j] + f2[j]) * 0.25;
                }
            })
        },
        || {
            vp.par_chunks_mut(k).with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
                let mut n = 0usize;
                for h in super::creases::ring(m, m.v_out[v]) {
                    let (e, f) = (row(vert[(h ^ 1) as usize]), frow(face[h as usize]));
                    for j in 0..k {
                        o[j] += e[j] + f[j];
                    }
                    n += 1;
                }
                let n = n as f64;
                let s = row(v as u32);
                for j in 0..k {
                    o[j] = s[j] * ((n - 2.0) / n) + o[j] / (n * n);
                }
            })
        },
    );
    crate::cancel::check()?;
    Ok(out)
}

/// The level's stencils: rows `[vertex points | edge points | face points
/// of the real faces]` over the input vertices.
fn stencils(m: &Mesh, ls: &LevelSharpness, req: &Request, real: &RealFaces) -> Result<Stencils> {
    stencil_rows(m, ls, req, real, |n, n_cols, fill| Stencils::build(n, n_cols, fill))
}

/// The positions [`stencils`] gives, row by row without storing the rows
/// (bit for bit the same: [`Stencils::apply_rows_points`]).
fn stencil_points(m: &Mesh, ls: &LevelSharpness, req: &Request, real: &RealFaces) -> Result<Vec<DVec3>> {
    stencil_rows(m, ls, req, real, |n, _, fill| Stencils::apply_rows_points(n, &m.pos, fill))
}

/// The real (not hole) faces in order, held as the sorted hole faces.
struct RealFaces {
    holes: Vec<u32>,
    /// All faces, holes included.
    n: usize,
}

impl RealFaces {
    fn len(&self) -> usize {
        self.n - self.holes.len()
    }
    /// The `j`-th real face: `j` plus the holes before it. Hole `i` precedes
    /// it exactly when `holes[i] - i <= j` (a nondecreasing sequence).
    fn face(&self, j: usize) -> usize {
        let (mut lo, mut hi) = (0, self.holes.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.holes[mid] as usize - mid <= j {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        j + lo
    }
}

/// Real faces with more corners than this enter positions-only rows as
/// their mean (`stencil_rows`); their stored rows keep every term.
const MEAN_ROW_MAX: usize = 64;

/// Hands the level's row filler (row count, column count, filler) to `run`.
fn stencil_rows<T>(
    m: &Mesh,
    ls: &LevelSharpness,
    req: &Request,
    real: &RealFaces,
    run: impl FnOnce(usize, usize, &(dyn Fn(usize, &mut Row) + Sync)) -> T,
) -> T {
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let (_, vert, face) = m.halfedge_columns();
    // each face's cycle walked from its first corner, as a face layout
    // lists it (same terms in the same order: the same bits); a real face
    // above MEAN_ROW_MAX corners enters an applied row as its mean, computed
    // once: its n terms in each of the rows of its n edges and vertices
    // cost n² (a 32,000-gon of an open mesh took 3.3 s)
    let means: rustc_hash::FxHashMap<u32, DVec3> = (0..m.n_faces())
        .filter(|&f| !m.f_hole[f] && m.f_start[f] & crate::mesh::POINT == 0 && m.face_degree(FaceId(f as u32)) > MEAN_ROW_MAX)
        .map(|f| {
            let (s, n) = super::hosts::face_vertex_sum(m, f);
            (f as u32, s / n as f64)
        })
        .collect();
    let face_row = |f: usize, w: f64, row: &mut Row| match means.get(&(f as u32)) {
        Some(&x) if row.applying() => row.add_applied(x, w),
        _ => super::hosts::face_mean_row(m, f, w, row),
    };
    let head = |h: u32| vert[(h ^ 1) as usize];
    let mask = |v: usize, rule: Rule, ends: [u32; 2], w: f64, row: &mut Row| match rule {
        Rule::Smooth | Rule::Dart => {
            // the ring walked twice (its size first) instead of collected:
            // no allocation per vertex, the same terms in the same order
            let n = super::creases::ring(m, m.v_out[v]).count() as f64;
            row.add(v as u32, w * (n - 2.0) / n);
            for h in super::creases::ring(m, m.v_out[v]) {
                row.add(head(h), w / (n * n));
                face_row(face[h as usize] as usize, w / (n * n), row);
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
        } else if i < nv + ne {
            let e = i - nv;
            let (a, b) = (vert[2 * e], vert[2 * e + 1]);
            let (wv, wf) = match ls.edge_rule(e) {
                EdgeRule::Smooth => (0.25, 0.25),
                EdgeRule::Crease => (0.5, 0.0),
                EdgeRule::Blend(s) => (0.5 * s + 0.25 * (1.0 - s), 0.25 * (1.0 - s)),
            };
            row.add(a, wv);
            row.add(b, wv);
            if wf != 0.0 {
                face_row(face[2 * e] as usize, wf, row);
                face_row(face[2 * e + 1] as usize, wf, row);
            }
        } else {
            face_row(real.face(i - nv - ne), 1.0, row);
        }
    };
    run(nv + ne + real.len(), nv, fill)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn real_faces_from_the_holes_list_every_real_face_in_order() {
        let mut rng = crate::test_rng::Xorshift::new(7);
        for n in [0usize, 1, 2, 5, 40] {
            for _ in 0..50 {
                let hole: Vec<bool> = (0..n).map(|_| rng.next_u64() % 3 == 0).collect();
                let holes: Vec<u32> = (0..n as u32).filter(|&f| hole[f as usize]).collect();
                let want: Vec<usize> = (0..n).filter(|&f| !hole[f]).collect();
                let r = RealFaces { holes, n };
                assert_eq!(r.len(), want.len());
                assert_eq!((0..r.len()).map(|j| r.face(j)).collect::<Vec<_>>(), want, "{hole:?}");
            }
        }
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(catmull_clark, |_, (v, e, f)| (v + e + f, 4 * e, 2 * e), |name, _, r| {
            assert!(all_faces_but_one_gons_have(r, 4), "{name} quads");
        });
    }

    fn full() -> Request<'static> {
        crate::schemes::hosts::test_meshes::full_request()
    }

    /// A real face above `MEAN_ROW_MAX` corners enters the positions-only
    /// rows as its mean: the positions stay within rounding of the stored
    /// rows' `S · P` (open mesh, and a closed one with creases), and its
    /// face point is its mean.
    #[test]
    fn large_faces_enter_applied_rows_as_their_means() {
        let full = crate::schemes::hosts::test_meshes::full_request();
        let plain = Request::plain();
        let cup = cup(300);
        let creased = crate::schemes::conway::seeds::prism(300).unwrap();
        let mut edge = vec![0.0; creased.n_edges()];
        edge[0] = 2.0;
        edge[1] = 1.0;
        let cr = crate::schemes::creases::Creases { edge, vertex: Vec::new() };
        for (name, m, creases) in [("cup", &cup, None), ("creased prism", &creased, Some(&cr))] {
            let (rf, rp) = (Request { creases, ..full }, Request { creases, ..plain });
            let lf = catmull_clark_level(m, &rf).unwrap();
            check_level(name, m, &lf);
            let lp = catmull_clark_level(m, &rp).unwrap();
            let (a, b) = (lp.mesh.positions(), lf.mesh.positions());
            let worst = a.iter().zip(b).map(|(x, y)| (*x - *y).length()).fold(0.0, f64::max);
            assert!(worst <= 1e-12, "{name}: positions-only rows differ from S·P by {worst}");
            assert!(a.iter().zip(b).any(|(x, y)| x != y), "{name}: the large face did not take its mean");
        }
    }

    /// Data on a mesh with a large real face go through the positions-only
    /// level (`level_with_data_linear`): within rounding of the stencils
    /// applied to them, for 1 and 4 columns (a partial chunk of three),
    /// open and creased, Catmull-Clark, Doo-Sabin and Loop (its centroid fan
    /// first); data with a NaN take
    /// the stencils (a level refuses non-finite positions).
    #[test]
    fn data_on_large_faces_go_through_the_positions() {
        let cup = cup(300);
        let creased = crate::schemes::conway::seeds::prism(300).unwrap();
        let mut edge = vec![0.0; creased.n_edges()];
        edge[0] = 2.0;
        let cr = crate::schemes::creases::Creases { edge, vertex: Vec::new() };
        type With = fn(&Mesh, &Request, &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)>;
        let schemes: [(&str, With, fn(&Mesh, &Request) -> Result<Level>); 3] = [
            ("catmull_clark", catmull_clark_level_with, catmull_clark_level),
            ("doo_sabin", crate::schemes::doo_sabin::doo_sabin_level_with, crate::schemes::doo_sabin::doo_sabin_level),
            ("loop", crate::schemes::loop_subdivision::loop_level_with, crate::schemes::loop_subdivision::loop_level),
        ];
        for (name, m, creases) in [("cup", &cup, None), ("creased prism", &creased, Some(&cr))] {
            let nv = m.n_vertices();
            let one: Vec<f64> = (0..nv).map(|v| (v as f64 * 0.37).sin()).collect();
            let four: Vec<f64> = (0..4 * nv).map(|i| (i as f64 * 0.11).cos()).collect();
            let mut nan = four.clone();
            nan[4 * 7 + 3] = f64::NAN;
            let data = vec![(one, 1), (four, 4), (nan, 4)];
            let req = Request { creases, ..Request::plain() };
            for (s, with, level) in schemes {
                if creases.is_some() && s == "doo_sabin" {
                    continue; // Doo-Sabin has no crease rules
                }
                let (lv, got) = with(m, &req, &data).unwrap();
                let st = level(m, &Request { stencils: true, ..req }).unwrap().stencils.unwrap();
                assert_eq!(lv.stencils.is_none(), true);
                for ((a, k), g) in data.iter().zip(&got) {
                    let want = st.apply(a, *k).unwrap();
                    assert_eq!(g.len(), want.len());
                    for (i, (x, y)) in g.iter().zip(&want).enumerate() {
                        assert!(x.is_nan() == y.is_nan() && (x.is_nan() || (x - y).abs() <= 1e-12 * (1.0 + y.abs())), "{s} on {name}, {k} columns, entry {i}: {x} vs {y}");
                    }
                }
            }
        }
    }

    #[test]
    fn level_stencils_equal_the_direct_masks_on_corpus() {
        for (name, m) in corpus() {
            let lv = catmull_clark_level(&m, &full()).unwrap();
            check_level(name, &m, &lv);
            let plain = catmull_clark(&m).unwrap();
            assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
            for (a, b) in lv.mesh.positions().iter().zip(plain.positions()) {
                assert!((*a - *b).length() < 1e-12, "{name}");
            }
        }
    }

    #[test]
    fn direct_data_masks_equal_the_stencils() {
        check_direct_data_on_corpus(2, 1e-11, catmull_clark_level, catmull_clark_level_with);
    }

    #[test]
    fn open_meshes_keep_their_holes_with_boundary_rules() {
        use crate::schemes::creases::{Boundary, SubdivOptions};
        for (name, m) in [("grid", open_grid(4)), ("tube", open_tube(8, 3)), ("cube_with_hole", cube_with_hole())] {
            let b: usize = (0..m.n_edges()).filter(|&e| m.f_hole[m.he_face[2 * e] as usize] || m.f_hole[m.he_face[2 * e + 1] as usize]).count();
            let (v, e, f, hr) = (m.n_vertices(), m.n_edges(), m.n_faces() - m.n_holes(), m.n_halfedges() - b);
            for boundary in [Boundary::EdgeOnly, Boundary::EdgeAndCorner] {
                let req = Request { options: SubdivOptions { boundary, ..Default::default() }, ..full() };
                let lv = catmull_clark_level(&m, &req).unwrap();
                check_level(name, &m, &lv);
                let r = &lv.mesh;
                assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces() - r.n_holes(), r.n_holes()), (v + e + f, 2 * e + hr, hr, m.n_holes()), "{name}");
                assert_eq!(open_euler(r), open_euler(&m), "{name}");
                // boundary edge points are midpoints; boundary vertices follow (a + 6v + b)/8 or stay (corners)
                let p = m.positions();
                for ed in 0..m.n_edges() {
                    let (h0, h1) = (2 * ed, 2 * ed + 1);
                    if m.f_hole[m.he_face[h0] as usize] || m.f_hole[m.he_face[h1] as usize] {
                        let mid = (p[m.he_vert[h0] as usize] + p[m.he_vert[h1] as usize]) * 0.5;
                        assert!((r.positions()[v + ed] - mid).length() < 1e-12, "{name} edge {ed}");
                    }
                }
                for vv in 0..v {
                    let ring: Vec<u32> = crate::schemes::creases::ring(&m, m.v_out[vv]).collect();
                    let bnd: Vec<u32> = ring.iter().copied().filter(|&h| m.f_hole[m.he_face[h as usize] as usize] || m.f_hole[m.he_face[(h ^ 1) as usize] as usize]).collect();
                    if bnd.len() != 2 {
                        continue;
                    }
                    let corner = ring.len() == 2 && boundary == Boundary::EdgeAndCorner;
                    let want = if corner {
                        p[vv]
                    } else {
                        (p[vv] * 6.0 + p[m.he_vert[(bnd[0] ^ 1) as usize] as usize] + p[m.he_vert[(bnd[1] ^ 1) as usize] as usize]) / 8.0
                    };
                    assert!((r.positions()[vv] - want).length() < 1e-12, "{name} vertex {vv}");
                }
            }
        }
    }

    #[test]
    fn sharp_edges_decay_by_one_per_level() {
        use crate::schemes::creases::{Creases, INFINITE};
        let m = crate::primitives::cube();
        let mut c = Creases { edge: vec![0.0; m.n_edges()], vertex: vec![0.0; m.n_vertices()] };
        c.edge[0] = INFINITE;
        c.edge[1] = 1.5;
        let lv = catmull_clark_level(&m, &Request { creases: Some(&c), ..full() }).unwrap();
        check_level("creased cube", &m, &lv);
        let nv = m.n_vertices();
        let p = m.positions();
        let mid = |e: usize| (p[m.he_vert[2 * e] as usize] + p[m.he_vert[2 * e + 1] as usize]) * 0.5;
        assert!((lv.mesh.positions()[nv] - mid(0)).length() < 1e-12);
        assert!((lv.mesh.positions()[nv + 1] - mid(1)).length() < 1e-12);
        let out = lv.creases.as_ref().unwrap();
        assert_eq!(out.edge.len(), lv.mesh.n_edges());
        let mut got: Vec<f64> = out.edge.iter().copied().filter(|&s| s > 0.0).collect();
        got.sort_by(f64::total_cmp);
        assert_eq!(got, vec![0.5, 0.5, INFINITE, INFINITE]);
        // level 2: the 0.5 children blend and die; the infinite crease has 4 children
        let lv2 = catmull_clark_level(&lv.mesh, &Request { creases: Some(out), ..full() }).unwrap();
        check_level("creased cube 2", &lv.mesh, &lv2);
        let out2 = lv2.creases.unwrap();
        assert_eq!(out2.edge.iter().filter(|&&s| s > 0.0).count(), 4);
        assert!(out2.edge.iter().all(|&s| s == 0.0 || s == INFINITE));
    }

    #[test]
    fn cube_vertex_point() {
        // the cube's corner (1,1,1): n = 3, Q = mean of three face centres,
        // R = mean of three edge midpoints
        let r = catmull_clark(&crate::primitives::cube()).unwrap();
        let q = DVec3::new(1.0, 1.0, 1.0) / 3.0;
        let rr = DVec3::new(2.0, 2.0, 2.0) / 3.0;
        let want = (q + 2.0 * rr) / 3.0;
        assert!(r.positions()[..8].iter().any(|p| (*p - want).length() < 1e-12));
    }

    #[test]
    fn self_loop_opens() {
        let m = cube_with_handle_loop();
        let r = catmull_clark(&m).unwrap();
        // the self-loop's edge point differs from its vertex's new point
        let e = m.edges().find(|&e| m.is_self_loop(e)).unwrap();
        let ep = r.positions()[m.n_vertices() + e.idx()];
        let v = m.vertex(e.halfedge()).idx();
        assert!((ep - r.positions()[v]).length() > 1e-3);
    }
}
