//! Vertex truncation (vertex truncation paper: Akleman, Edmundson & Ozener,
//! "A Generalized Vertex Truncation Scheme to Construct Intriguing
//! Polyhedral Shapes").
//!
//! Every edge is cut at `ratio` of its length from each end, and every old
//! vertex is replaced by the polygon through the cut points of its edges
//! (section 3.1, Fig. 2):
//!
//! * [`Truncation::Chaikin`] — the paper's scheme (section 3.2): cuts at 1/4
//!   and 3/4 of every edge, Chaikin's corner cutting applied to every face
//!   boundary. Stationary; in the limit the faces are bounded by quadratic
//!   B-spline curves.
//! * [`Truncation::Polyhedral`] — classic polyhedral truncation at a given
//!   `ratio ∈ (0, 1/2]` (section 3.1). A regular n-gon becomes a regular
//!   2n-gon for `ratio = 1 / (2 + 2 cos(π/n))`: 1/3 on triangles (truncated
//!   tetrahedron, icosahedron), `1/(2 + √2)` on squares (truncated cube).
//!
//! **Counts** for `ratio < 1/2` (section 3.1): an n-gon becomes a 2n-gon, a
//! valence-m vertex an m-gon, every new vertex is 3-valent:
//!
//! ```text
//! V' = 2E,   E' = 3E,   F' = F + V,   χ' = χ (genus unchanged)
//! ```
//!
//! **`ratio = 1/2`** (rectification): the two cut points of an edge coincide
//! at its midpoint and are merged into one vertex, giving the rectified
//! (cuboctahedral) mesh instead of a mesh with zero-length edges: an n-gon
//! stays an n-gon, a valence-m vertex becomes an m-gon, every new vertex is
//! 4-valent (cube → cuboctahedron, dodecahedron → icosidodecahedron):
//!
//! ```text
//! V' = E,   E' = 2E,   F' = F + V
//! ```
//!
//! **Planarity** (section 3.2): the cut points of a face lie on its edges, so
//! a planar face stays planar; the new face of a 3-valent vertex is a
//! triangle. Planar faces with 3-valent vertices therefore give planar faces
//! at every iteration; the regular octahedron and icosahedron do too by
//! symmetry (Fig. 5). Other input may give non-planar vertex faces.
//!
//! Built in one pass, straight into the mesh columns
//! (`face_vertex_columns.rs`): for `ratio < 1/2` new
//! vertex `h` is the cut point of old half-edge `h` near its tail; for
//! `ratio = 1/2` new vertex `e` is the midpoint of old edge `e`. Faces are
//! `[old faces in order | vertex faces in old vertex order]`. Self-loops,
//! one-gons, two-gons, multi-edges and non-convex faces need no special case;
//! point-spheres are copied unchanged; hole faces stay holes. O(output).
//!
//! **Open meshes.** A boundary loop (a hole face) is cut like a face: its
//! cut points are those of the boundary edges, so the new boundary is the
//! old one with its corners cut off (a 2n-gon hole for an n-gon, the same
//! n-gon at `ratio = 1/2`) and every loop stays one loop. A boundary vertex
//! becomes the polygon through the cut points of its edges, boundary edges
//! included. With F counting real faces and b boundary loops the counts
//! above hold as they are (`F' = F + V`, `b' = b`), so `χ' = V − E + F = χ`
//! (`χ = 2c − 2g − b`) and the genus stays.
//!
//! **Stencils and correspondence** ([`vertex_truncation_level`]): cut
//! points are linear, row h is `(1 − r) tail + r head` (`½ a + ½ b` when
//! merged), a point-sphere's row the point. Origins: a cut point lies on
//! its edge → (EDGE, e); the image of face f → (FACE, f) (a hole's image is
//! the hole), the face of v → (VERTEX, v); an edge along an old edge →
//! (EDGE, e), a cut (it cuts a corner of a face) → (FACE, that face). Holes
//! are kept on every path, so open meshes get stencils and origins too.

use super::hosts::{FaceLayout, VertexLayout};
use super::corner_origins::edge_origins_by_corner;
use super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// Where vertex truncation cuts the edges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Truncation {
    /// The paper's Chaikin-based scheme: cuts at 1/4 and 3/4 (section 3.2).
    Chaikin,
    /// Classic polyhedral truncation: cuts at `ratio` and `1 − ratio`,
    /// `ratio ∈ (0, 1/2]`; `1/2` merges the two cuts (rectification).
    Polyhedral { ratio: f64 },
}

impl Truncation {
    /// The fraction of each edge cut off at each end.
    pub fn ratio(self) -> f64 {
        match self {
            Truncation::Chaikin => 0.25,
            Truncation::Polyhedral { ratio } => ratio,
        }
    }

    /// Errors unless the ratio is in `(0, 1/2]`.
    pub fn check(self) -> Result<()> {
        let r = self.ratio();
        if r > 0.0 && r <= 0.5 {
            Ok(())
        } else {
            Err(MeshError::InvalidArgument(format!(
                "vertex_truncation: ratio = {} is outside (0, 0.5] (the fraction of each edge cut off at each end)",
                crate::error::num(r)
            )))
        }
    }
}

/// One step of vertex truncation (see the module docs).
///
/// Errors: a polyhedral `ratio` outside `(0, 1/2]` (including NaN).
pub fn vertex_truncation(m: &Mesh, mode: Truncation) -> Result<Mesh> {
    mode.check()?;
    // ---- faces: [old faces (2n-gons, or n-gons when merged) | one m-gon per vertex],
    // written straight into the columns; the positions after them (issue 19:
    // the face layout is gone by then)
    let fl = FaceLayout::new(m)?;
    let cols = super::face_vertex_columns::truncation_columns(m, &fl, mode.ratio() == 0.5)?;
    drop(fl);
    cols.finish(m, cut_points(m, mode.ratio())?)
}

/// The cut points: per half-edge h, `(1 − r) vert(h) + r vert(twin h)`, or
/// per edge its midpoint when `r = 1/2` (the cuts merged). Reads only the
/// positions and the vertex column.
fn cut_points(m: &Mesh, r: f64) -> Result<Vec<DVec3>> {
    let (pos, vert) = (&m.pos, &m.he_vert);
    let nh = vert.len();
    // (cancelled: zeros, the check below reports it)
    let stop = crate::cancel::requested;
    let new_pos: Vec<DVec3> = if r == 0.5 {
        (0..nh / 2).into_par_iter().map(|e| if stop() { DVec3::ZERO } else { 0.5 * (pos[vert[2 * e] as usize] + pos[vert[2 * e + 1] as usize]) }).collect()
    } else {
        (0..nh).into_par_iter().map(|h| if stop() { DVec3::ZERO } else { (1.0 - r) * pos[vert[h] as usize] + r * pos[vert[h ^ 1] as usize] }).collect()
    };
    crate::cancel::check()?;
    Ok(new_pos)
}

/// [`vertex_truncation_level`] on an input the caller gives up (a previous
/// level of a multi-level call, issue 19): asked for no stencils or
/// origins, the connectivity is written first, then the input keeps only
/// its positions, vertex column and hole flags while the cut points are
/// computed. Anything else is [`vertex_truncation_level`]'s. The output is
/// the same, bit for bit (`owned_level_equals_the_borrowed_one`).
pub fn vertex_truncation_level_owned(mut m: Mesh, mode: Truncation, req: &Request) -> Result<Level> {
    if req.stencils || req.origins {
        return vertex_truncation_level(&m, mode, req);
    }
    mode.check()?;
    let fl = FaceLayout::new(&m)?;
    let cols = super::face_vertex_columns::truncation_columns(&m, &fl, mode.ratio() == 0.5)?;
    drop(fl);
    (m.he_next, m.he_prev, m.he_face, m.v_out, m.f_start) = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let pos = cut_points(&m, mode.ratio())?;
    Ok(Level::plain(cols.finish(&m, pos)?))
}

/// One step with what `req` asks for (see the module docs); without
/// requests it is [`vertex_truncation`].
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn vertex_truncation_level(m: &Mesh, mode: Truncation, req: &Request) -> Result<Level> {
    let mesh = vertex_truncation(m, mode)?;
    if !req.stencils && !req.origins {
        return Ok(Level::plain(mesh));
    }
    let r = mode.ratio();
    let merge = r == 0.5;
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (_, vert, face) = m.halfedge_columns();
    let points: Vec<u32> = (0..nv as u32).filter(|&v| m.v_out[v as usize] & crate::mesh::POINT != 0).collect();
    let n_cut = if merge { nh / 2 } else { nh };
    let stencils = if req.stencils {
        Some(Stencils::build(n_cut + points.len(), nv, |i, row| {
            if i >= n_cut {
                row.add(points[i - n_cut], 1.0);
            } else if merge {
                row.add(vert[2 * i], 0.5);
                row.add(vert[2 * i + 1], 0.5);
            } else {
                row.add(vert[i], 1.0 - r);
                row.add(vert[i ^ 1], r);
            }
        })?)
    } else {
        None
    };
    let origins = if req.origins {
        let fl = FaceLayout::new(m)?;
        let vl = VertexLayout::new(m)?;
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind.extend(std::iter::repeat(EDGE).take(n_cut).chain(std::iter::repeat(VERTEX).take(points.len())));
        o.vertex.extend((0..n_cut as u32).map(|i| if merge { i } else { i >> 1 }).chain(points.iter().copied()));
        o.face_kind.extend(std::iter::repeat(FACE).take(nf));
        o.face.extend(0..nf as u32);
        for v in 0..nv {
            if vl.valence(v) > 0 {
                o.face_kind.push(VERTEX);
                o.face.push(v as u32);
            }
        }
        // corner layout of `vertex_truncation`: face images (a point-sphere's keeps one corner), then one per slot
        let per_corner = if merge { 1 } else { 2 };
        let mut off = Vec::with_capacity(nf + 1);
        off.push(0u32);
        for f in 0..nf {
            off.push(off[f] + (per_corner * fl.degree(f) as u32).max(1));
        }
        let vb = off[nf] as usize;
        let mut co = vec![(FACE, 0u32); vb + nh];
        for h in 0..nh {
            crate::cancel::poll(h)?;
            let f = face[h];
            let c = off[f as usize] as usize + per_corner as usize * fl.local(h as u32, f);
            if merge {
                co[c] = (FACE, f);
            } else {
                co[c] = (EDGE, (h >> 1) as u32);
                co[c + 1] = (FACE, f);
            }
            co[vb + vl.vidx[h] as usize] = (FACE, f);
        }
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives::*;
    use crate::schemes::hosts::test_meshes::{check_output, counts, cube_with_hole, handle_cube, one_gon_two_gon_cube, prism, star_prism};

    #[test]
    fn owned_level_equals_the_borrowed_one() {
        use crate::schemes::hosts::test_meshes::{owned_level_cases, position_bits as bits};
        // the corpus (point-spheres, self-loops, two-gons), open meshes and a
        // second level, cuts apart and merged; positions compared bit for bit
        for (name, m) in owned_level_cases() {
            for mode in [Truncation::Chaikin, Truncation::Polyhedral { ratio: 0.5 }, Truncation::Polyhedral { ratio: 0.3 }] {
                let req = Request::plain();
                let a = vertex_truncation_level(&m, mode, &req).unwrap().mesh;
                let b = vertex_truncation_level_owned(m.clone(), mode, &req).unwrap().mesh;
                assert_eq!((&a, bits(&a)), (&b, bits(&b)), "{name}");
                let c = vertex_truncation_level(&a, mode, &req).unwrap().mesh;
                let d = vertex_truncation_level_owned(a, mode, &req).unwrap().mesh;
                assert_eq!((&c, bits(&c)), (&d, bits(&d)), "{name} level 2");
            }
        }
    }

    /// Largest distance of a face's corners from the plane through its
    /// centroid with its Newell normal, relative to the face's bounding-box
    /// diagonal.
    pub(crate) fn max_planarity_deviation(m: &Mesh) -> f64 {
        let mut worst: f64 = 0.0;
        for f in m.faces() {
            let ps: Vec<DVec3> = m.face_vertices(f).map(|v| m.position(v)).collect();
            if ps.len() < 4 {
                continue;
            }
            let n = m.face_unit_normal(f);
            let c = ps.iter().sum::<DVec3>() / ps.len() as f64;
            let (lo, hi) = ps.iter().fold((ps[0], ps[0]), |(a, b), &p| (a.min(p), b.max(p)));
            let size = (hi - lo).length();
            for p in &ps {
                worst = worst.max((*p - c).dot(n).abs() / size);
            }
        }
        worst
    }

    fn check_step(m: &Mesh, mode: Truncation) -> Mesh {
        let (v, e, f) = counts(m);
        let t = vertex_truncation(m, mode).unwrap();
        let merged = mode.ratio() == 0.5;
        // n-gon -> 2n-gon (n-gon when merged); valence-m vertex -> m-gon
        let mut want = crate::mesh::Histogram::new();
        for (k, c) in m.face_size_histogram() {
            *want.entry(if merged { k } else { 2 * k }).or_default() += c;
        }
        for (k, c) in m.valence_histogram() {
            *want.entry(k).or_default() += c;
        }
        assert_eq!(t.face_size_histogram(), want);
        if merged {
            check_output("rectification", m, &t, (e, 2 * e, f + v));
            assert_eq!(t.valence_histogram().keys().copied().collect::<Vec<_>>(), vec![4]);
        } else {
            check_output("truncation", m, &t, (2 * e, 3 * e, f + v));
            assert_eq!(t.valence_histogram().keys().copied().collect::<Vec<_>>(), vec![3]);
        }
        t
    }

    #[test]
    fn counts_on_corpus() {
        let corpus = [
            tetrahedron(),
            cube(),
            octahedron(),
            dodecahedron(),
            icosahedron(),
            torus(8, 5, 2.0, 0.5).unwrap(),
            genus_surface(3).unwrap(),
            one_gon_two_gon_cube(),
            star_prism(),
            handle_cube(),
        ];
        for m in &corpus {
            for mode in [Truncation::Chaikin, Truncation::Polyhedral { ratio: 0.1 }, Truncation::Polyhedral { ratio: 0.5 }] {
                let t = check_step(m, mode);
                check_step(&t, mode);
            }
        }
    }

    #[test]
    fn planar_input_stays_planar() {
        // (genus_surface is planar-faced but has non-symmetric 4-valent rim vertices)
        let l_prism = prism(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]], 0.7);
        for m in [tetrahedron(), cube(), dodecahedron(), octahedron(), icosahedron(), l_prism, star_prism()] {
            assert!(m.signed_volume() > 0.0);
            let mut t = m;
            for _ in 0..4 {
                t = vertex_truncation(&t, Truncation::Chaikin).unwrap();
                assert!(max_planarity_deviation(&t) < 1e-12, "{}", max_planarity_deviation(&t));
            }
        }
        // a non-planar valence-4 vertex face: a torus vertex's four cut points
        let t = vertex_truncation(&torus(8, 5, 2.0, 0.5).unwrap(), Truncation::Chaikin).unwrap();
        assert!(max_planarity_deviation(&t) > 1e-3);
    }

    #[test]
    fn archimedean_truncations_are_equilateral() {
        let edge_lengths = |m: &Mesh| -> (f64, f64) {
            m.edges().map(|e| (m.position(m.vertex(e.halfedge())) - m.position(m.head(e.halfedge()))).length()).fold(
                (f64::INFINITY, 0.0f64),
                |(a, b), l| (a.min(l), b.max(l)),
            )
        };
        let regular = |n: f64| 1.0 / (2.0 + 2.0 * (std::f64::consts::PI / n).cos());
        for (m, n) in [(tetrahedron(), 3.0), (cube(), 4.0), (dodecahedron(), 5.0), (icosahedron(), 3.0), (octahedron(), 3.0)] {
            for r in [regular(n), 0.5] {
                let t = vertex_truncation(&m, Truncation::Polyhedral { ratio: r }).unwrap();
                let (lo, hi) = edge_lengths(&t);
                assert!((hi - lo) / hi < 1e-12, "ratio {r}: {lo} .. {hi}");
            }
        }
        let co = vertex_truncation(&cube(), Truncation::Polyhedral { ratio: 0.5 }).unwrap();
        assert_eq!(co.face_size_histogram().into_iter().collect::<Vec<_>>(), vec![(3, 8), (4, 6)]);
    }

    #[test]
    fn positions_are_cut_points() {
        let m = cube();
        let t = vertex_truncation(&m, Truncation::Polyhedral { ratio: 0.2 }).unwrap();
        for h in m.halfedges() {
            let want = 0.8 * m.position(m.vertex(h)) + 0.2 * m.position(m.head(h));
            assert!((t.position(crate::VertexId(h.0)) - want).length() < 1e-15);
        }
        assert!(t.signed_volume() > 0.0 && t.signed_volume() < m.signed_volume());
    }

    #[test]
    fn level_stencils_and_origins_on_corpus_and_open_meshes() {
        use crate::schemes::hosts::test_meshes::*;
        let full = crate::schemes::hosts::test_meshes::full_request();
        let mut meshes = corpus();
        meshes.extend(open_meshes());
        for (name, m) in meshes {
            for mode in [Truncation::Chaikin, Truncation::Polyhedral { ratio: 0.1 }, Truncation::Polyhedral { ratio: 0.5 }] {
                let lv = vertex_truncation_level(&m, mode, &full).unwrap();
                check_level(name, &m, &lv);
                let plain = vertex_truncation(&m, mode).unwrap();
                assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
                assert_eq!(lv.mesh.positions(), plain.positions(), "{name}");
                assert_eq!((lv.mesh.n_holes(), open_euler(&lv.mesh)), (m.n_holes(), open_euler(&m)), "{name}");
                let o = lv.origins.as_ref().unwrap();
                let fl = FaceLayout::new(&m).unwrap();
                let merged = mode.ratio() == 0.5;
                // per edge: 2 cut points (1 merged) and the edge along it (none merged); per n-gon:
                // one face and n cuts; one face per vertex
                let ev = origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges());
                let ee = origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges());
                assert!(ev.iter().zip(&ee).all(|(&a, &b)| (a, b) == if merged { (1, 0) } else { (2, 1) }), "{name}");
                let ff = origin_counts(&o.face_kind, &o.face, FACE, m.n_faces());
                let fe = origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces());
                for f in 0..m.n_faces() {
                    assert_eq!((ff[f], fe[f]), (1, fl.degree(f)), "{name} face {f}");
                }
                let vf = origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices());
                assert!(vf.iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
            }
        }
    }

    #[test]
    fn bad_ratio() {
        for r in [0.0, -0.1, 0.51, f64::NAN] {
            assert!(vertex_truncation(&cube(), Truncation::Polyhedral { ratio: r }).is_err());
        }
    }

    #[test]
    fn point_spheres_and_holes_pass_through() {
        let mut m = cube();
        m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
        let t = vertex_truncation(&m, Truncation::Chaikin).unwrap();
        t.validate().unwrap();
        assert_eq!((t.n_components(), t.n_vertices()), (2, 25));
        let open = cube_with_hole();
        for mode in [Truncation::Chaikin, Truncation::Polyhedral { ratio: 0.5 }] {
            let t = vertex_truncation(&open, mode).unwrap();
            t.validate().unwrap();
            assert_eq!(t.n_holes(), 1);
        }
    }
}
