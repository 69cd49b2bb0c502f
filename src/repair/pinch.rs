//! Splitting pinched vertices: one output vertex per umbrella (fan of
//! corners around a vertex joined through edges).

use crate::union_find::{root, union};
use super::{Faces, NONE};

/// The output vertex of every corner, the cluster each output vertex copies,
/// and how many extra copies were made.
///
/// With consistent orientation, the corner after `c` around its vertex is the
/// twin of the side entering `c` (`twin(prev(c))`), which starts at the same
/// vertex; a union-find over that relation gives the umbrellas. The umbrella
/// met first (in corner order) keeps the vertex; used clusters are numbered
/// in cluster order, extra copies after them in the order they are met.
/// Clusters no face uses get no output vertex.
pub(super) fn split(f: &Faces, twin: &[u32], n_clusters: usize) -> (Vec<u32>, Vec<u32>, usize) {
    let n = f.verts.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for c in 0..n {
        let t = twin[f.prev(c)];
        if t != NONE {
            union(&mut parent, c as u32, t);
        }
    }
    // roots: the cluster they keep (tag 0) or the index of their extra copy
    const EXTRA: u32 = 1 << 31;
    let mut primary = vec![false; n_clusters];
    let mut root_tag = vec![NONE; n];
    let mut extras: Vec<u32> = Vec::new();
    for c in 0..n {
        let r = root(&mut parent, c as u32) as usize;
        if root_tag[r] == NONE {
            let v = f.verts[c];
            root_tag[r] = if primary[v as usize] {
                extras.push(v);
                EXTRA | (extras.len() - 1) as u32
            } else {
                primary[v as usize] = true;
                v
            };
        }
    }
    let mut number = vec![NONE; n_clusters];
    let mut source: Vec<u32> = Vec::with_capacity(n_clusters + extras.len());
    for (v, &used) in primary.iter().enumerate() {
        if used {
            number[v] = source.len() as u32;
            source.push(v as u32);
        }
    }
    let base = source.len() as u32;
    source.extend_from_slice(&extras);
    let out = (0..n)
        .map(|c| {
            let tag = root_tag[root(&mut parent, c as u32) as usize];
            if tag & EXTRA != 0 { base + (tag & !EXTRA) } else { number[tag as usize] }
        })
        .collect();
    (out, source, extras.len())
}
