//! Face-varying (corner) data through Catmull-Clark and Loop: UVs with
//! seams, as OpenSubdiv's face-varying channels.
//!
//! The corner values live on their own mesh, the *face-varying mesh*: the
//! same faces in the same order, whose vertices are the runs of corners
//! around each vertex joined across non-seam edges (an edge is a seam when
//! its two sides disagree on a value at either end), and whose boundary is
//! the mesh's boundary plus both sides of every seam. Subdividing the data
//! is subdividing that mesh with the level's own scheme and stencils; its
//! real faces and their children line up with the geometry's, corner for
//! corner, so the output corners read their values from it.
//!
//! Interpolation choices (OpenSubdiv's `FVarLinearInterpolation`):
//! * `Smooth` (`FVAR_LINEAR_NONE`): smooth everywhere, seams and
//!   boundaries follow the crease (B-spline curve) rule;
//! * `CornersOnly` (`FVAR_LINEAR_CORNERS_ONLY`): as smooth, and corners of
//!   the face-varying mesh (a run of one face) stay put;
//! * `CornersPlus1` (`FVAR_LINEAR_CORNERS_PLUS1`, Blender's "Keep Corners,
//!   Junctions"): as `CornersOnly`, and every value of a vertex stays put
//!   where more than two values meet (a junction of three or more UV
//!   islands), or where two meet and either one's run of faces holds an
//!   infinitely sharp edge;
//! * `CornersPlus2` (`FVAR_LINEAR_CORNERS_PLUS2`, "… and Concave"): as
//!   `CornersPlus1`, and both values of a two-value vertex stay put when
//!   either is a corner (the other island is concave there), and so does
//!   the one value of an interior vertex where a seam ends (a dart);
//! * `Boundaries` (`FVAR_LINEAR_BOUNDARIES`): linear along seams and
//!   boundaries (their vertices are corners, their edge points midpoints);
//! * `All` (`FVAR_LINEAR_ALL`, OpenSubdiv's default): linear everywhere
//!   (bilinear inside each face).
//!
//! The geometry's crease sharpness applies to the data too (edges and
//! vertices map one to one), as in OpenSubdiv.
//!
//! The two `CornersPlus` rules are OpenSubdiv's
//! `FVarLevel::completeTopologyFromFaceValues` (opensubdiv/vtr/fvarLevel.cpp,
//! 3.x), recomputed at every level on the refined data (a junction's child is
//! a junction, a seam's new points have two runs of two faces, so this
//! matches OpenSubdiv's propagation of the tags to child values). Two
//! differences by design, both outside ordinary UV layouts: a value met in
//! two disjoint runs at one vertex (a "bowtie" in UV space) counts as two
//! values here (OpenSubdiv: one, marked non-manifold and sharp), and
//! OpenSubdiv's *dependent* sharpness (one of two values semi-sharp makes
//! the other semi-sharp too) is not applied: the other value follows its own
//! run's rule.

use super::creases::{Boundary, Creases, SubdivOptions, INFINITE};
use super::hosts::FaceLayout;
use super::level::{Level, Request};
use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE, POINT};
use glam::DVec3;

/// OpenSubdiv's face-varying linear interpolation choices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    Smooth,
    CornersOnly,
    CornersPlus1,
    CornersPlus2,
    Boundaries,
    #[default]
    All,
}

/// Corner data on its face-varying mesh: vertex `i` of `mesh` has the
/// value row `values[i * k..(i + 1) * k]`.
#[derive(Clone, Debug)]
pub struct FaceVarying {
    pub mesh: Mesh,
    pub values: Vec<f64>,
    pub k: usize,
    /// The crease sharpness the data sees (the geometry's, mapped).
    pub creases: Option<Creases>,
}

/// The half-edges of the real (non-hole) faces of `m`, in export order.
pub(crate) fn real_corners(m: &Mesh, fl: &FaceLayout) -> Vec<u32> {
    (0..m.n_faces()).filter(|&f| !m.f_hole[f]).flat_map(|f| fl.corners(f).iter().copied()).collect()
}

impl FaceVarying {
    /// From a value id per exported corner (aligned with `m`'s face
    /// indices) and the value table (`n × k`, row-major).
    pub fn new(m: &Mesh, corner_value: &[u32], values: &[f64], k: usize, creases: Option<&Creases>) -> Result<FaceVarying> {
        if m.v_out.iter().any(|&o| o & POINT != 0) {
            return Err(MeshError::Precondition("corner attributes: the mesh has point-spheres, whose lone corner has no face-varying neighbourhood".into()));
        }
        let fl = FaceLayout::new(m)?;
        let rc = real_corners(m, &fl);
        if rc.len() != corner_value.len() {
            return Err(MeshError::InvalidArgument(format!("corner attributes: {} corner values for {} corners", corner_value.len(), rc.len())));
        }
        let nh = m.n_halfedges();
        // value id per half-edge of a real face
        let mut val = vec![NONE; nh];
        let mut corner_of = vec![NONE; nh];
        for (c, &h) in rc.iter().enumerate() {
            val[h as usize] = corner_value[c];
            corner_of[h as usize] = c as u32;
        }
        let (next, _, _) = m.halfedge_columns();
        // an edge joins its two sides' values when both are real and agree at both ends
        let joined = |h: u32| -> bool {
            let t = h ^ 1;
            val[h as usize] != NONE
                && val[t as usize] != NONE
                && val[h as usize] == val[next[t as usize] as usize]
                && val[next[h as usize] as usize] == val[t as usize]
        };
        // runs of corners around each vertex: union across joined edges
        let mut parent: Vec<u32> = (0..rc.len() as u32).collect();
        fn find(p: &mut [u32], mut x: u32) -> u32 {
            while p[x as usize] != x {
                p[x as usize] = p[p[x as usize] as usize];
                x = p[x as usize];
            }
            x
        }
        for &h in &rc {
            // h' = rotate(h) = twin(prev h) shares edge prev(h) with h
            let p = m.he_prev[h as usize];
            let h2 = p ^ 1;
            if val[h2 as usize] != NONE && joined(p) {
                let (a, b) = (find(&mut parent, corner_of[h as usize]), find(&mut parent, corner_of[h2 as usize]));
                if a != b {
                    parent[a as usize] = b;
                }
            }
        }
        let mut vid = vec![NONE; rc.len()];
        let mut n_f = 0u32;
        let mut table = Vec::new();
        let mut vertex_of = Vec::new(); // geometry vertex of each face-varying vertex
        let mut fv = vec![0i64; rc.len()];
        for c in 0..rc.len() {
            let r = find(&mut parent, c as u32) as usize;
            if vid[r] == NONE {
                vid[r] = n_f;
                n_f += 1;
                let row = corner_value[c] as usize;
                if (row + 1) * k > values.len() {
                    return Err(MeshError::InvalidArgument(format!("corner attributes: corner {c} refers to value {row}, the table has {}", values.len() / k.max(1))));
                }
                table.extend_from_slice(&values[row * k..(row + 1) * k]);
                vertex_of.push(m.he_vert[rc[c] as usize]);
            }
            fv[c] = vid[r] as i64;
        }
        let twins: Vec<i64> = rc.iter().map(|&h| if joined(h) { corner_of[(h ^ 1) as usize] as i64 } else { -1 }).collect();
        let sizes: Vec<i64> = (0..m.n_faces()).filter(|&f| !m.f_hole[f]).map(|f| fl.degree(f) as i64).collect();
        let fm = Mesh::from_corner_twins_i64(vec![DVec3::ZERO; n_f as usize], &sizes, &fv, &twins)?;
        // the geometry's creases, mapped corner by corner and vertex by vertex
        let creases = creases.map(|cr| {
            let ffl = FaceLayout::new(&fm).expect("not cancelled: built just now");
            let frc = real_corners(&fm, &ffl);
            let mut edge = vec![0.0; fm.n_edges()];
            for (c, &fh) in frc.iter().enumerate() {
                edge[(fh >> 1) as usize] = cr.edge((rc[c] >> 1) as usize);
            }
            // seam sides are boundaries of the face-varying mesh: infinite there anyway
            let vertex = vertex_of.iter().map(|&v| cr.vertex(v as usize)).collect();
            Creases { edge, vertex }
        });
        Ok(FaceVarying { mesh: fm, values: table, k, creases })
    }

    /// One level of `scheme` (Catmull-Clark's or Loop's level function) on
    /// the data, with the interpolation choice.
    pub fn level(&self, scheme: impl Fn(&Mesh, &Request) -> Result<Level>, interp: Interpolation, geometry: SubdivOptions) -> Result<FaceVarying> {
        let m = &self.mesh;
        let mut c = self.creases.clone().unwrap_or_else(|| Creases { edge: vec![0.0; m.n_edges()], vertex: vec![0.0; m.n_vertices()] });
        c.edge.resize(m.n_edges(), 0.0);
        c.vertex.resize(m.n_vertices(), 0.0);
        match interp {
            Interpolation::All => {
                c.edge.iter_mut().for_each(|s| *s = INFINITE);
                c.vertex.iter_mut().for_each(|s| *s = INFINITE);
            }
            Interpolation::Boundaries => {
                for h in 0..m.n_halfedges() {
                    if m.f_hole[m.he_face[h] as usize] {
                        c.vertex[m.he_vert[h] as usize] = INFINITE;
                    }
                }
            }
            // the plus rules' extra corners are in `c.vertex` already (`with_creases`)
            Interpolation::Smooth | Interpolation::CornersOnly | Interpolation::CornersPlus1 | Interpolation::CornersPlus2 => {}
        }
        let boundary = if interp == Interpolation::Smooth { Boundary::EdgeOnly } else { Boundary::EdgeAndCorner };
        let req = Request { stencils: true, origins: false, creases: Some(&c), options: SubdivOptions { boundary, ..geometry }, level: 0, skip_large_face_rows: false };
        let lv = scheme(m, &req)?;
        let s = lv.stencils.as_ref().expect("requested");
        let values = s.apply(&self.values, self.k)?;
        // the overrides were for this level only; the caller maps the
        // geometry's creases again before the next one (`with_creases`)
        Ok(FaceVarying { mesh: lv.mesh, values, k: self.k, creases: None })
    }

    /// Replaces the crease sharpness the data sees by the geometry's
    /// (`geometry` has the same real faces, corner for corner), including
    /// the corners the geometry's boundary rule sharpens: face-varying data
    /// is smooth only where the surface is (OpenSubdiv).
    pub fn with_creases(mut self, geometry: &Mesh, creases: Option<&Creases>, options: SubdivOptions) -> Result<FaceVarying> {
        let eff = super::creases::LevelSharpness::new(geometry, creases, options);
        let gfl = FaceLayout::new(geometry)?;
        let grc = real_corners(geometry, &gfl);
        let ffl = FaceLayout::new(&self.mesh)?;
        let frc = real_corners(&self.mesh, &ffl);
        let mut edge = vec![0.0; self.mesh.n_edges()];
        let mut vertex = vec![0.0; self.mesh.n_vertices()];
        for (c, &fh) in frc.iter().enumerate() {
            let (ge, gv) = ((grc[c] >> 1) as usize, geometry.he_vert[grc[c] as usize] as usize);
            edge[(fh >> 1) as usize] = eff.edge[ge];
            vertex[self.mesh.he_vert[fh as usize] as usize] = eff.vertex[gv];
        }
        self.creases = Some(Creases { edge, vertex });
        Ok(self)
    }

    /// Adds the vertices the `CornersPlus1` / `CornersPlus2` rules pin (see
    /// the module docs) to the data's vertex sharpness, as infinitely sharp;
    /// `geometry` has the same real faces, corner for corner. Other choices
    /// leave the data as it is.
    pub fn with_plus_corners(mut self, geometry: &Mesh, interp: Interpolation) -> Result<FaceVarying> {
        let plus2 = match interp {
            Interpolation::CornersPlus1 => false,
            Interpolation::CornersPlus2 => true,
            _ => return Ok(self),
        };
        let fm = &self.mesh;
        let gfl = FaceLayout::new(geometry)?;
        let grc = real_corners(geometry, &gfl);
        let ffl = FaceLayout::new(fm)?;
        let frc = real_corners(fm, &ffl);
        let nf = fm.n_vertices();
        // geometry vertex and run size (faces) of every face-varying vertex
        let mut gv = vec![NONE; nf];
        let mut run = vec![0u32; nf];
        for (c, &fh) in frc.iter().enumerate() {
            let w = fm.he_vert[fh as usize] as usize;
            gv[w] = geometry.he_vert[grc[c] as usize];
            run[w] += 1;
        }
        let mut n_values = vec![0u32; geometry.n_vertices()];
        for &g in &gv {
            if g != NONE {
                n_values[g as usize] += 1;
            }
        }
        let mut g_boundary = vec![false; geometry.n_vertices()];
        for h in 0..geometry.n_halfedges() {
            if geometry.f_hole[geometry.he_face[h] as usize] {
                g_boundary[geometry.he_vert[h] as usize] = true;
            }
        }
        // face-varying boundary vertices, and runs holding an infinitely sharp (inner) edge
        let mut f_boundary = vec![false; nf];
        let mut inf_edge = vec![false; nf];
        let edge = self.creases.as_ref().map(|c| &c.edge);
        for h in 0..fm.n_halfedges() {
            let w = fm.he_vert[h] as usize;
            if fm.f_hole[fm.he_face[h] as usize] {
                f_boundary[w] = true;
            } else if !fm.f_hole[fm.he_face[h ^ 1] as usize] && edge.is_some_and(|e| e.get(h >> 1).is_some_and(|&s| s >= INFINITE)) {
                inf_edge[w] = true;
            }
        }
        // per geometry vertex: whether a two-value vertex's runs pin both
        let mut pin_pair = vec![false; geometry.n_vertices()];
        for w in 0..nf {
            let g = gv[w];
            if g != NONE && n_values[g as usize] == 2 && (inf_edge[w] || (plus2 && run[w] == 1)) {
                pin_pair[g as usize] = true;
            }
        }
        let c = self.creases.get_or_insert_with(|| Creases { edge: vec![0.0; fm.n_edges()], vertex: vec![0.0; nf] });
        c.vertex.resize(nf, 0.0);
        for w in 0..nf {
            let g = gv[w];
            if g == NONE {
                continue;
            }
            let n = n_values[g as usize];
            let dart = plus2 && n == 1 && f_boundary[w] && !g_boundary[g as usize];
            if n > 2 || (n == 2 && pin_pair[g as usize]) || dart {
                c.vertex[w] = INFINITE;
            }
        }
        Ok(self)
    }

    /// The value row of every exported corner (aligned with the geometry's
    /// face indices).
    pub fn corner_rows(&self) -> Result<Vec<u32>> {
        let fl = FaceLayout::new(&self.mesh)?;
        Ok(real_corners(&self.mesh, &fl).iter().map(|&h| self.mesh.he_vert[h as usize]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::catmull_clark::catmull_clark_level;

    /// The cube's faces with one value per (face, corner): every edge a seam.
    fn cube_all_seams() -> (Mesh, Vec<u32>, Vec<f64>) {
        let m = crate::primitives::cube();
        let n = m.n_halfedges();
        let ids: Vec<u32> = (0..n as u32).collect();
        let vals: Vec<f64> = m.to_polygons().indices.iter().flat_map(|&v| {
            let p = m.positions()[v as usize];
            [p.x + 2.0 * p.y, p.z]
        }).collect();
        (m, ids, vals)
    }

    #[test]
    fn shared_values_make_one_face_varying_vertex_per_vertex() {
        let m = crate::primitives::cube();
        let idx: Vec<u32> = m.to_polygons().indices.clone();
        let vals: Vec<f64> = (0..8).map(|v| v as f64).collect();
        let fv = FaceVarying::new(&m, &idx, &vals, 1, None).unwrap();
        assert_eq!((fv.mesh.n_vertices(), fv.mesh.n_edges(), fv.mesh.n_holes()), (8, 12, 0));
        // linear data subdivides like positions with every crease infinite: bilinear
        let lv = fv.level(catmull_clark_level, Interpolation::All, SubdivOptions::default()).unwrap();
        assert_eq!(lv.mesh.n_vertices(), 26);
    }

    /// The cube's cross unfolding (tests/osd/fixtures.py): vertices 0 and 1
    /// hold three values, 2 and 3 two, the top four one.
    fn cross_cube() -> (Mesh, Vec<u32>, Vec<f64>) {
        let faces = [[0u32, 1, 5, 4], [4, 5, 7, 6], [6, 7, 3, 2], [2, 3, 1, 0], [0, 4, 6, 2], [1, 3, 7, 5]];
        let grid = [[(1, 0), (2, 0), (2, 1), (1, 1)], [(1, 1), (2, 1), (2, 2), (1, 2)], [(1, 2), (2, 2), (2, 3), (1, 3)], [(1, 3), (2, 3), (2, 4), (1, 4)], [(0, 1), (1, 1), (1, 2), (0, 2)], [(3, 1), (3, 2), (2, 2), (2, 1)]];
        let pos: Vec<DVec3> = (0..8).map(|v| DVec3::new((v & 1) as f64 * 2.0 - 1.0, (v >> 1 & 1) as f64 * 2.0 - 1.0, (v >> 2 & 1) as f64 * 2.0 - 1.0)).collect();
        let idx: Vec<i64> = faces.iter().flatten().map(|&v| v as i64).collect();
        let m = Mesh::from_polygons(pos, &[4; 6], &idx, crate::mesh::BuildOptions::default()).unwrap();
        let mut keys: Vec<(i32, i32)> = Vec::new();
        let mut ids = Vec::new();
        for g in grid.iter().flatten() {
            let k = keys.iter().position(|x| x == g).unwrap_or_else(|| {
                keys.push(*g);
                keys.len() - 1
            });
            ids.push(k as u32);
        }
        let vals = keys.iter().flat_map(|&(i, j)| [i as f64 / 4.0, j as f64 / 4.0]).collect();
        (m, ids, vals)
    }

    #[test]
    fn plus_rules_pin_junctions_and_concave_values() {
        let (m, ids, vals) = cross_cube();
        let fv = FaceVarying::new(&m, &ids, &vals, 2, None).unwrap();
        assert_eq!(fv.mesh.n_vertices(), 14);
        let pinned = |interp| {
            let f = fv.clone().with_creases(&m, None, SubdivOptions::default()).unwrap().with_plus_corners(&m, interp).unwrap();
            f.creases.unwrap().vertex.iter().filter(|&&s| s >= INFINITE).count()
        };
        // plus1: the three-value vertices 0 and 1 (6 values); plus2 also the
        // two-value vertices 2 and 3, each with a one-face value (4 more),
        // and the top four, where a seam ends (darts: edge 0-4 is cut at 0 only)
        assert_eq!(pinned(Interpolation::CornersOnly), 0);
        assert_eq!(pinned(Interpolation::CornersPlus1), 6);
        assert_eq!(pinned(Interpolation::CornersPlus2), 14);
    }

    #[test]
    fn all_seams_make_every_face_its_own_island() {
        let (m, ids, vals) = cube_all_seams();
        let fv = FaceVarying::new(&m, &ids, &vals, 2, None).unwrap();
        assert_eq!((fv.mesh.n_vertices(), fv.mesh.n_faces() - fv.mesh.n_holes(), fv.mesh.n_holes()), (24, 6, 6));
        for interp in [Interpolation::Smooth, Interpolation::CornersOnly, Interpolation::Boundaries, Interpolation::All] {
            let lv = fv.level(catmull_clark_level, interp, SubdivOptions::default()).unwrap();
            lv.mesh.validate().unwrap();
            // an island of one quad: corners stay, except with Smooth (edge only: crease rule)
            let rows = lv.corner_rows().unwrap();
            let first = &lv.values[rows[0] as usize * 2..rows[0] as usize * 2 + 2];
            let moved = (first[0] - vals[0]).abs() + (first[1] - vals[1]).abs() > 1e-9;
            assert_eq!(moved, interp == Interpolation::Smooth, "{interp:?}");
        }
    }
}
