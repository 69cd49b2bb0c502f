//! TopMod's remeshing schemes that TopMod itself defines as compositions
//! (`src/MainWindowCallbacks.cc`, the comment "Implemented as …" in each
//! callback), written once here over the schemes they compose. Counts
//! follow from the parts': each function's docs give them.

use crate::error::Result;
use crate::mesh::Mesh;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::dual::dual;
use crate::schemes::face_parents::via_origins;

/// Root-3 (`subdivideRoot3`: dual + honeycomb + dual): V' = V + F,
/// E' = 3E, F' = 2E triangles (the √3 connectivity, honeycomb's points).
pub fn root3(m: &Mesh) -> Result<Mesh> {
    use crate::schemes::honeycomb as h;
    let d = dual(m)?;
    if crate::schemes::face_parents::recording() {
        // face parents through honeycomb's origins: the one-pass build below
        // records none (same mesh, keyed::hashes)
        return dual(&via_origins(&d, |r| h::honeycomb_level(&d, 0.5, None, r), || h::honeycomb(&d, 0.5, None))?);
    }
    super::root3_dual::dual_of_honeycomb(&d, 0.5)
}

/// Dual Loop (`subdivideDualLoop`: dual + Loop + dual). Loop fans the dual's
/// non-triangles first (the input's vertices of valence ≠ 3); with
/// V₃ vertices of valence 3 and S = Σ valence over the others:
/// F_t = V₃ + S, E_t = E + S, V_t = F + V − V₃ (the fanned dual), then
/// V' = 4F_t, E' = 2E_t + 3F_t, F' = V_t + E_t; every vertex 3-valent.
/// Built in one pass without the intermediate meshes (see
/// `topmod::dual_loop`), the composition's output bit for bit.
pub fn dual_loop(m: &Mesh) -> Result<Mesh> {
    super::dual_loop::dual_loop(m)
}

/// Cubic pentagonalization (`subdivideCubicPentagonal`: pentagonalization,
/// dual, dual): pentagonalization's counts, positions the centroids of
/// centroids.
pub fn cubic_pentagonalize(m: &Mesh, offset: f64) -> Result<Mesh> {
    super::cubic_pentagonal::cubic_pentagonalize(m, offset)
}

/// `dual(dual(p))` without the intermediate dual (issue 16: the two duals
/// were two thirds of cubic pentagonalization's time). The double dual has
/// p's connectivity: face f of it is p's face f and its vertex v is p's
/// vertex v, at the mean of the centroids around v (summed in v's rotation
/// from `v_out`, the order of the dual's face v). What differs is the
/// numbering: the outer dual walks p's faces in order, each from the corner
/// at which the inner dual first met its centroid (the first face of p met
/// walking p's vertices in order) and numbers edges by first crossing.
/// Both are reproduced here bit for bit (`keyed::hashes`); with holes or
/// point-spheres it is the two duals.
pub(super) fn dual_dual(p: &Mesh) -> Result<Mesh> {
    use crate::mesh::{NONE, POINT};
    use glam::DVec3;
    if p.n_holes() > 0 || p.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&dual(p)?);
    }
    let (nv, ne, nf, nh) = (p.n_vertices(), p.n_edges(), p.n_faces(), p.n_halfedges());
    crate::schemes::hosts::check_output_size("dual", nh, nf)?;
    crate::schemes::hosts::check_output_size("dual", nh, nv)?;
    let (next, vert, face) = p.halfedge_columns();
    let cen = crate::schemes::dual::centroids(p)?;
    // the dual's faces: positions, and the corner c0[f] of each centroid's
    // first appearance
    let mut pos = Vec::with_capacity(nv);
    let mut c0 = vec![NONE; nf];
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = p.v_out[v];
        let (mut h, mut sum, mut k) = (s, DVec3::ZERO, 0usize);
        loop {
            let f = face[h as usize] as usize;
            sum += cen[f];
            k += 1;
            if c0[f] == NONE {
                c0[f] = h;
            }
            h = p.he_prev[h as usize] ^ 1;
            if h == s {
                break;
            }
        }
        pos.push(sum / k as f64);
    }
    drop(cen);
    // keys: p's edges
    let mut walk = DualWalk::new(pos, nh, nf, ne);
    for (f, &s) in c0.iter().enumerate() {
        crate::cancel::poll(f)?;
        let (mut h, mut last) = (s, NONE);
        loop {
            let v = vert[h as usize];
            walk.put(f, v, (h >> 1) as usize, &mut last);
            h = next[h as usize];
            if h == s {
                break;
            }
        }
        walk.close(f, last);
    }
    if crate::schemes::face_parents::recording() {
        // the two duals' steps composed: faces and vertices keep their ids
        let v = crate::schemes::face_parents::VERT;
        crate::schemes::face_parents::record(Some(crate::schemes::face_parents::Step { in_v: nv, in_f: nf, face: (0..nf as u32).collect(), vertex: (0..nv as u32).map(|i| v | i).collect() }));
    }
    Mesh::from_columns(walk.finish()?)
}

/// Dual pentagonalization (`subdivideDualPentagonal`: dual +
/// pentagonalization + dual): V' = 2E, E' = 5E, F' = V + F + 2E; histogram:
/// the input's face sizes, one k-gon per valence-k vertex and 2E triangles.
pub fn dual_pentagonalize(m: &Mesh, offset: f64) -> Result<Mesh> {
    super::pentagonalize_dual::dual_of_pentagonalize(&dual(m)?, offset)
}

/// Dual pentagon preserving (`subdivideDualPentagonPreserving`: dual +
/// pentagon preserving + dual). With S the valence sum over the input's
/// vertices of valence ≥ 3: V' = V + S, E' = 2E + 2S, F' = F + E + S.
pub fn dual_pentagon_preserving(m: &Mesh, scale: f64) -> Result<Mesh> {
    super::pentagonal_dual::dual_of_pentagon_preserving(&dual(m)?, scale)
}

/// 12.6.4 (`subdivide1264`: dual + dual 12.6.4 + dual): V' = V + E + F,
/// E' = 6E, F' = 4E triangles.
pub fn remesh_12_6_4(m: &Mesh, scale: f64) -> Result<Mesh> {
    super::twelve_six_four_dual::dual_of_dual_12_6_4(&dual(m)?, scale)
}

/// Dual checkerboard (`subdivideDualCheckerBoard`: dual + checkerboard +
/// dual): V' = V + 4E, E' = 9E, F' = F + 4E; histogram: the input's face
/// sizes plus 4E quads (checkerboard's new vertices are 4-valent).
pub fn dual_checkerboard(m: &Mesh, thickness: f64) -> Result<Mesh> {
    super::checkerboard_dual::dual_of_checkerboard(&dual(m)?, thickness)
}

/// Dual hexagon preserving (`subdivideDualHexagonPreserving`: dual, root-4,
/// dual): V' = V + E, E' = 4E, F' = F + 2E; histogram: the input's face
/// sizes plus 2E triangles (root-4's inner points are 3-valent).
pub fn dual_hexagon_preserving(m: &Mesh, weight: f64, twist: f64) -> Result<Mesh> {
    super::root4_dual::dual_of_root4(&dual(m)?, weight, twist)
}

/// Doo-Sabin BC (`dooSabinSubdivideBC`: every edge split at its midpoint,
/// then Doo-Sabin): with the split mesh's H' = 4E, V' = 4E, E' = 8E,
/// F' = F + 2E + (V + E); histogram: an n-gon gives a 2n-gon, 2E quads, a
/// valence-k vertex a k-gon and each midpoint a two-gon.
pub fn doo_sabin_bc(m: &Mesh) -> Result<Mesh> {
    use crate::schemes::doo_sabin as ds;
    let s = super::linear::split_edges(m, 2)?;
    via_origins(&s, |r| ds::doo_sabin_level(&s, r), || ds::doo_sabin(&s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, hist_of};
    use std::collections::BTreeMap;

    fn valences(m: &Mesh) -> BTreeMap<usize, usize> {
        let mut h = m.valence_histogram();
        h.remove(&0);
        h
    }

    #[test]
    fn root3_counts() {
        check("root3", root3, |_, (v, e, f)| (v + f, 3 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(3, 2 * e)]));
    }

    #[test]
    fn dual_loop_counts() {
        let want = |m: &Mesh, (v, e, f): (usize, usize, usize)| {
            let vh = valences(m);
            let v3 = vh.get(&3).copied().unwrap_or(0);
            let s: usize = vh.iter().filter(|(&k, _)| k != 3).map(|(&k, &c)| k * c).sum();
            let (ft, et, vt) = (v3 + s, e + s, f + v - v3);
            (4 * ft, 2 * et + 3 * ft, vt + et)
        };
        super::super::tests::check_counts("dual_loop", dual_loop, want, |_, r| {
            // the dual of Loop's triangles: every vertex 3-valent
            assert!(valences(r).keys().all(|&k| k == 3));
        });
    }

    #[test]
    fn pentagonal_compositions() {
        check("cubic_pentagonalize", |m| cubic_pentagonalize(m, 0.0), |_, (v, e, f)| (v + 2 * e + f, 5 * e, 2 * e), |_, (_, e, _)| BTreeMap::from([(5, 2 * e)]));
        check("dual_pentagonalize", |m| dual_pentagonalize(m, 0.0), |_, (v, e, f)| (2 * e, 5 * e, v + f + 2 * e), |m, (_, e, _)| {
            let mut h = hist_of(m);
            for (k, c) in valences(m) {
                *h.entry(k).or_insert(0) += c;
            }
            *h.entry(3).or_insert(0) += 2 * e;
            h
        });
    }

    /// The one-pass cubic pentagonalization is the composition it fuses:
    /// the same mesh or the same error, on the corpus (non-convex faces,
    /// self-loops, two-gons, one-gons, genus 3, point-spheres) and on open
    /// meshes and bad offsets (which take the composition).
    #[test]
    fn cubic_pentagonalize_is_its_composition() {
        use crate::schemes::hosts::test_meshes::{one_gon_two_gon_cube, open_meshes};
        let mut ms = super::super::tests::meshes();
        ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
        ms.extend(open_meshes());
        for (name, m) in &ms {
            for off in [0.0, 0.3, 1.0, 1.5] {
                let composed = super::super::pentagonal::pentagonalize(m, off).and_then(|p| dual(&dual(&p)?));
                match (cubic_pentagonalize(m, off), composed) {
                    (Ok(a), Ok(b)) => assert!(a == b, "{name}, offset {off}: the fused build differs from the composition"),
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
                    (a, b) => panic!("{name}, offset {off}: fused {:?}, composition {:?}", a.err(), b.err()),
                }
            }
        }
    }

    /// The fused dual pentagonalization is the composition it fuses
    /// ([`check_fused`]: the same bits or error, traced and not), on the
    /// same inputs and offsets as [`cubic_pentagonalize_is_its_composition`].
    #[test]
    fn dual_pentagonalize_is_its_composition() {
        use crate::schemes::hosts::test_meshes::{check_fused, one_gon_two_gon_cube, open_meshes};
        let mut ms = super::super::tests::meshes();
        ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
        ms.extend(open_meshes());
        let closed = ms.iter().filter(|(_, m)| m.n_holes() == 0 && !m.has_point_spheres()).count();
        let mut fused_runs = 0;
        for (name, m) in &ms {
            for off in [0.0, 0.3, 1.0, 1.5] {
                let composed = |m: &Mesh| dual(&super::super::pentagonal::pentagonalize(&dual(m)?, off)?);
                fused_runs += check_fused(&format!("{name}, offset {off}"), m, &|m| dual_pentagonalize(m, off), &composed) as usize;
            }
        }
        // offset 1.5 is refused; the other three build every closed input
        assert_eq!(fused_runs, 3 * closed, "one pass on {fused_runs} of {closed} closed meshes × 3 offsets");
    }

    #[test]
    fn twelve_six_four_and_checkerboard() {
        check("remesh_12_6_4", |m| remesh_12_6_4(m, 0.7), |_, (v, e, f)| (v + e + f, 6 * e, 4 * e), |_, (_, e, _)| BTreeMap::from([(3, 4 * e)]));
        check("dual_checkerboard", |m| dual_checkerboard(m, 0.33), |_, (v, e, f)| (v + 4 * e, 9 * e, f + 4 * e), |m, (_, e, _)| {
            let mut h = hist_of(m);
            *h.entry(4).or_insert(0) += 4 * e;
            h
        });
    }

    #[test]
    fn hexagon_and_doo_sabin_bc() {
        check("dual_hexagon_preserving", |m| dual_hexagon_preserving(m, 0.0, 0.0), |_, (v, e, f)| (v + e, 4 * e, f + 2 * e), |m, (_, e, _)| {
            let mut h = hist_of(m);
            *h.entry(3).or_insert(0) += 2 * e;
            h
        });
        check("doo_sabin_bc", doo_sabin_bc, |_, (v, e, f)| (4 * e, 8 * e, f + 3 * e + v), |m, (_, e, _)| {
            let mut h = BTreeMap::new();
            for (n, c) in hist_of(m) {
                *h.entry(2 * n).or_insert(0) += c;
            }
            *h.entry(4).or_insert(0) += 2 * e;
            for (k, c) in valences(m) {
                *h.entry(k).or_insert(0) += c;
            }
            *h.entry(2).or_insert(0) += e;
            h
        });
    }

    #[test]
    fn dual_pentagon_preserving_runs() {
        // counts: pentagon_preserving's on the dual (checked there), dualised
        for (name, m) in super::super::tests::meshes() {
            let d = dual(&m).unwrap();
            let p = super::super::pentagonal::pentagon_preserving(&d, 0.75).unwrap();
            let r = dual_pentagon_preserving(&m, 0.75).unwrap();
            r.validate().unwrap();
            assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces()), (p.n_faces(), p.n_edges(), p.n_vertices()), "{name}");
            assert_eq!(r.genus(), m.genus(), "{name}");
        }
    }
}
