//! Merging coincident vertices: exact duplicates by sorting their bit
//! patterns, then vertices within the tolerance on a hash grid.

use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::hash::{Hash, Hasher};

use crate::mesh::build::first_index;

const NONE: u32 = u32::MAX;

/// The cluster of every input vertex, clusters numbered in the order of their
/// lowest member, and the number of clusters. A cluster's position is that of
/// its lowest member.
///
/// Vertices are visited in index order; each joins the lowest-numbered
/// earlier cluster whose position lies within `tol` (Euclidean), or starts a
/// new one. So every vertex is within `tol` of its cluster's position (no
/// chaining), and `tol == 0` merges exactly equal positions only (`-0.0 ==
/// 0.0`). Exact duplicates are merged first by a parallel sort, so the grid
/// only sees distinct points; cells of `4·tol` hold a bounded number of
/// cluster positions (they are more than `tol` apart), so the pass is linear.
pub(crate) fn weld(pos: &[DVec3], tol: f64) -> (Vec<u32>, usize) {
    let n = pos.len();
    // --- exact: sort (hash of the bits, index); equal points have equal
    // hashes, and a run of equal hashes is split by exact comparison
    let key = |p: DVec3| [(p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits()];
    let hash = |k: [u64; 3]| {
        let mut h = rustc_hash::FxHasher::default();
        k.hash(&mut h);
        h.finish()
    };
    let mut order: Vec<(u64, u32)> = pos.par_iter().enumerate().map(|(i, &p)| (hash(key(p)), i as u32)).collect();
    order.par_sort_unstable();
    let mut exact = vec![NONE; n];
    let mut i = 0;
    while i < n {
        let mut j = i + 1;
        while j < n && order[j].0 == order[i].0 {
            j += 1;
        }
        // within a run (index order), each point joins the first equal one
        for x in i..j {
            let v = order[x].1 as usize;
            if exact[v] != NONE {
                continue;
            }
            exact[v] = v as u32;
            for &(_, w) in &order[x + 1..j] {
                if exact[w as usize] == NONE && key(pos[w as usize]) == key(pos[v]) {
                    exact[w as usize] = v as u32;
                }
            }
        }
        i = j;
    }
    drop(order);

    // --- near: the distinct points, in index order, on a grid of 2·tol cells
    let max_abs = pos.iter().fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    // a tolerance below the float spacing of the coordinates is exact welding
    // (and would overflow the integer cell coordinates)
    let near = tol > 0.0 && max_abs / (4.0 * tol) < (1u64 << 60) as f64;
    let mut cluster = vec![NONE; n];
    let mut n_clusters = 0u32;
    if !near {
        for v in 0..n {
            let r = exact[v] as usize;
            if r == v {
                cluster[v] = n_clusters;
                n_clusters += 1;
            } else {
                cluster[v] = cluster[r];
            }
        }
        return (cluster, n_clusters as usize);
    }
    // cells of 4·tol: a probe box of ±tol meets 1.5³ ≈ 3.4 cells on average
    let cell = 4.0 * tol;
    let cell_of = |x: f64| (x / cell).floor() as i64;
    // cell -> last cluster started in it; `next_in_cell` chains the others
    let mut grid: FxHashMap<[i64; 3], u32> = FxHashMap::default();
    let mut next_in_cell: Vec<u32> = Vec::new();
    let mut cluster_vertex: Vec<u32> = Vec::new();
    for v in 0..n {
        let r = exact[v] as usize;
        if r != v {
            cluster[v] = cluster[r];
            continue;
        }
        let p = pos[v];
        let lo = [cell_of(p.x - tol), cell_of(p.y - tol), cell_of(p.z - tol)];
        let hi = [cell_of(p.x + tol), cell_of(p.y + tol), cell_of(p.z + tol)];
        let mut best = NONE;
        for cx in lo[0]..=hi[0] {
            for cy in lo[1]..=hi[1] {
                for cz in lo[2]..=hi[2] {
                    let mut c = grid.get(&[cx, cy, cz]).copied().unwrap_or(NONE);
                    while c != NONE {
                        if c < best && pos[cluster_vertex[c as usize] as usize].distance(p) <= tol {
                            best = c;
                        }
                        c = next_in_cell[c as usize];
                    }
                }
            }
        }
        if best == NONE {
            best = n_clusters;
            n_clusters += 1;
            cluster_vertex.push(v as u32);
            let k = [cell_of(p.x), cell_of(p.y), cell_of(p.z)];
            let head = grid.insert(k, best).unwrap_or(NONE);
            next_in_cell.push(head);
        }
        cluster[v] = best;
    }
    debug_assert!(first_index(&cluster, |&c| c == NONE).is_none());
    (cluster, n_clusters as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_merges_equal_points_only() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(-0.0, 0.0, 0.0), DVec3::new(1e-300, 0.0, 0.0), DVec3::X];
        let (c, n) = weld(&p, 0.0);
        assert_eq!(c, vec![0, 1, 0, 2, 1]);
        assert_eq!(n, 3);
    }

    #[test]
    fn tolerance_joins_the_lowest_cluster_within_reach_without_chaining() {
        let t = 1e-3;
        let p = [DVec3::ZERO, DVec3::new(0.9e-3, 0.0, 0.0), DVec3::new(1.8e-3, 0.0, 0.0), DVec3::new(0.0, 0.0, 0.5e-3)];
        let (c, n) = weld(&p, t);
        // 1 is within t of 0; 2 is 1.8t from 0 (its cluster position), so new
        assert_eq!(c, vec![0, 0, 1, 0]);
        assert_eq!(n, 2);
    }

    #[test]
    fn tolerance_below_float_spacing_is_exact() {
        let p = [DVec3::splat(1e6), DVec3::splat(1e6), DVec3::splat(2e6)];
        let (c, n) = weld(&p, 1e-300);
        assert_eq!((c, n), (vec![0, 0, 1], 2));
    }
}
