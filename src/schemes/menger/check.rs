//! The crossing check of step 3 (module docs of [`super`], "Crossing
//! check"): build, test each input vertex's triangles with the exact
//! predicate of [`crate::geometry::crossing`], rebuild crossing vertices
//! fully collapsed, for a few rounds.

use super::remesh::{build_polygons, Built};
use super::MengerOptions;
use crate::error::Result;
use crate::geometry::crossing::local_crossings;
use crate::geometry::triangles_with_points;
use crate::mesh::{BuildOptions, Mesh};

/// Rounds of the crossing check (module docs): a vertex found crossing is
/// rebuilt fully collapsed; a second round catches vertices whose
/// neighbourhood changed.
const CROSSING_ROUNDS: usize = 3;

/// The polygons and the mesh of one iteration (module docs): built with the
/// rules of VII.3–VII.5, then every input vertex whose local result crosses
/// itself is rebuilt fully collapsed, for up to [`CROSSING_ROUNDS`] rounds.
/// Also returns how many input vertices still cross at the end.
pub(super) fn build_valid(m: &Mesh, o: &MengerOptions) -> Result<((Built, Mesh), usize)> {
    let mut full = vec![false; m.n_vertices()];
    // after the first round only vertices next to a change are checked again
    let mut recheck = vec![false; m.n_vertices()];
    // whether each vertex crossed when it was last checked
    let mut crossing = vec![false; m.n_vertices()];
    let mut round = 0;
    loop {
        // (the previous round's build is dropped before this one is made)
        let cur = build_once(m, o, &full)?;
        let (tris, tri_pos) = triangles_with_points(&cur.1);
        let only = (round > 0).then_some(&recheck[..]);
        let mut lc = local_crossings(&tri_pos, &tris, &cur.0.owner, cur.0.first_inner, only);
        drop((tris, tri_pos));
        crate::cancel::check()?;
        for (v, c) in crossing.iter_mut().enumerate() {
            if only.map_or(true, |r| r[v]) {
                *c = false;
            }
        }
        for &v in &lc {
            crossing[v as usize] = true;
        }
        if round == CROSSING_ROUNDS {
            return Ok((cur, crossing.iter().filter(|&&c| c).count()));
        }
        // a vertex face with no planar split would be coned from a new
        // vertex, a saddle-like point the next iteration cannot offset:
        // such vertices are fully collapsed too (no vertex face)
        lc.extend(cur.0.coned.iter().copied());
        let mut changed = false;
        recheck.iter_mut().for_each(|x| *x = false);
        for v in lc {
            if !full[v as usize] {
                full[v as usize] = true;
                changed = true;
                // its neighbours' structures share its pipes and strips
                recheck[v as usize] = true;
                for h in m.vertex_halfedges(crate::mesh::VertexId(v)) {
                    recheck[m.head(h).idx()] = true;
                }
            }
        }
        if !changed {
            return Ok((cur, crossing.iter().filter(|&&c| c).count()));
        }
        round += 1;
    }
}

/// One build with the given fully collapsed vertices: with the `4D` miter
/// bound and the near weld, or, when that does not give a manifold, with a
/// `2D` miter bound and coincident points welded only.
pub(super) fn build_once(m: &Mesh, o: &MengerOptions, full: &[bool]) -> Result<(Built, Mesh)> {
    let b = build_polygons(m, o, true, full)?;
    match Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default()) {
        Ok(mesh) => Ok((b, mesh)),
        Err(_) => {
            let b = build_polygons(m, o, false, full)?;
            let mesh = Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default())?;
            Ok((b, mesh))
        }
    }
}
