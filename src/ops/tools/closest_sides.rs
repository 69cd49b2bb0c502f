//! Greedy closest-pair matching for the closest-edge multi-face handle
//! (`multi_handle.rs`): every valid pair of items of different groups is a
//! candidate keyed by (distance, lower index, higher index); the candidates
//! are taken in increasing key order, each item used once. That is TopMod's
//! rule (`multiConnectFaces`: all pairs sorted by distance), which built and
//! sorted every pair: quadratic in the selected faces' sides (a 4,000-sided
//! prism's two caps took 0.9 s, 100,000 sides 392 s).
//!
//! Here the same matching is found without the pair list. Each item asks a
//! k-d tree over the items' points for its best available partner (the
//! smallest key of a valid pair with an unused item of another group); a
//! heap holds one such answer per item. The smallest answer on the heap is
//! the smallest available pair of all (an item's answers only grow as items
//! are used), so it is taken when both items are still free; when its
//! partner has gone, the item asks again for its next partner. Matches come
//! out in the order the sorted list gave them, so the bridges are inserted
//! in the same order and the output is the same mesh, ids included
//! (`tests::tree_equals_the_sorted_pairs`). Subtrees without free items, or
//! holding only the asking item's own group, are skipped, so sides of one
//! large face do not slow each other's searches. When no pair of an item
//! is valid its search still visits every item: the worst case stays
//! quadratic, as before, but typical selections (caps facing each other,
//! neighbouring faces) take n log n.

use crate::error::Result;
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A candidate pair's key: its distance, then the two items (lower first).
#[derive(Clone, Copy, Debug)]
struct Key {
    d: f64,
    lo: u32,
    hi: u32,
}

impl Key {
    fn cmp(&self, o: &Key) -> Ordering {
        self.d.total_cmp(&o.d).then(self.lo.cmp(&o.lo)).then(self.hi.cmp(&o.hi))
    }
}

/// A heap entry: the best available pair `key` of item `x` when it asked.
struct Entry {
    key: Key,
    x: u32,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    // reversed: `BinaryHeap` is a max-heap
    fn cmp(&self, o: &Self) -> Ordering {
        o.key.cmp(&self.key).then(o.x.cmp(&self.x))
    }
}

const LEAF: usize = 8;
const NONE: u32 = u32::MAX;

struct Node {
    lo: DVec3,
    hi: DVec3,
    start: u32,
    end: u32,
    /// children (NONE at a leaf)
    left: u32,
    right: u32,
    parent: u32,
    /// the one group of every item below, or NONE when mixed
    group: u32,
    /// items below not yet used
    live: u32,
}

/// A k-d tree over the items' points, median split on the longest axis.
struct Tree {
    nodes: Vec<Node>,
    order: Vec<u32>,
    leaf_of: Vec<u32>,
}

impl Tree {
    fn new(pts: &[DVec3], group: &[u32]) -> Tree {
        let mut order: Vec<u32> = (0..pts.len() as u32).collect();
        let mut nodes: Vec<Node> = Vec::with_capacity(2 * pts.len() / LEAF + 2);
        let mut leaf_of = vec![NONE; pts.len()];
        // (start, end, parent, whether it is the parent's right child)
        let mut stack = vec![(0usize, pts.len(), NONE, false)];
        while let Some((s, e, parent, right)) = stack.pop() {
            let id = nodes.len() as u32;
            let items = &mut order[s..e];
            let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            let g0 = group[items[0] as usize];
            let mut g = g0;
            for &i in items.iter() {
                lo = lo.min(pts[i as usize]);
                hi = hi.max(pts[i as usize]);
                if group[i as usize] != g0 {
                    g = NONE;
                }
            }
            nodes.push(Node { lo, hi, start: s as u32, end: e as u32, left: NONE, right: NONE, parent, group: g, live: (e - s) as u32 });
            if parent != NONE {
                let p = &mut nodes[parent as usize];
                if right {
                    p.right = id;
                } else {
                    p.left = id;
                }
            }
            if e - s <= LEAF {
                for &i in items.iter() {
                    leaf_of[i as usize] = id;
                }
                continue;
            }
            let ext = hi - lo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z { 0 } else if ext.y >= ext.z { 1 } else { 2 };
            let mid = (e - s) / 2;
            items.select_nth_unstable_by(mid, |&a, &b| pts[a as usize][axis].total_cmp(&pts[b as usize][axis]));
            stack.push((s + mid, e, id, true));
            stack.push((s, s + mid, id, false));
        }
        Tree { nodes, order, leaf_of }
    }

    /// Marks item `i` used: no search enters a subtree whose items are all used.
    fn take(&mut self, i: usize) {
        let mut n = self.leaf_of[i];
        while n != NONE {
            let node = &mut self.nodes[n as usize];
            node.live -= 1;
            n = node.parent;
        }
    }
}

fn box_distance(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    let gap = (lo - p).max(p - hi).max(DVec3::ZERO);
    gap.length()
}

/// The pairs (lower index first) that the greedy matching takes, in the
/// order it takes them: candidates are the pairs x < y of different
/// `group`s with `valid(x, y)`, keyed by (`dist(x, y)`, x, y); `pts[i]` is a
/// point whose distances approximate `dist` to within rounding (both
/// computed from the same coordinates). Equal to sorting every candidate and
/// taking each whose items are both free (`brute_pairs`).
pub(crate) fn greedy_pairs(
    pts: &[DVec3],
    group: &[u32],
    dist: impl Fn(usize, usize) -> f64,
    valid: impl Fn(usize, usize) -> bool,
) -> Result<Vec<(usize, usize)>> {
    let n = pts.len();
    let scale = pts.iter().fold(0f64, |s, p| s.max(p.abs().max_element()));
    // the tree's pruning compares distances of points with `dist`: only
    // sound while both are finite with rounding far below the gaps
    if !(scale <= 1e300) || n < 2 {
        return brute_pairs(n, group, dist, valid);
    }
    let mut tree = Tree::new(pts, group);
    let mut used = vec![false; n];
    // the smallest key > `after` of a valid pair of x with a free item
    let search = |tree: &Tree, used: &[bool], x: usize, after: Option<Key>| -> Option<Key> {
        let (gx, px) = (group[x], pts[x]);
        let mut best: Option<Key> = None;
        let mut stack: Vec<(u32, f64)> = vec![(0, 0.0)];
        while let Some((id, bd)) = stack.pop() {
            let node = &tree.nodes[id as usize];
            if let Some(b) = best {
                // rounding margin: `dist` and the points' distances differ by
                // a few ulps of the coordinates
                if bd > b.d + 1e-12 * (scale + b.d) {
                    continue;
                }
            }
            if node.left == NONE {
                for &y in &tree.order[node.start as usize..node.end as usize] {
                    let y = y as usize;
                    if used[y] || group[y] == gx {
                        continue;
                    }
                    let (lo, hi) = if x < y { (x, y) } else { (y, x) };
                    let k = Key { d: dist(lo, hi), lo: lo as u32, hi: hi as u32 };
                    if after.is_some_and(|a| k.cmp(&a) != Ordering::Greater) || best.is_some_and(|b| k.cmp(&b) != Ordering::Less) {
                        continue;
                    }
                    if valid(lo, hi) {
                        best = Some(k);
                    }
                }
                continue;
            }
            // nearer child last, so it is searched first
            let mut kids = [node.left, node.right].map(|c| {
                let c_node = &tree.nodes[c as usize];
                let skip = c_node.live == 0 || c_node.group == gx;
                (c, if skip { f64::INFINITY } else { box_distance(px, c_node.lo, c_node.hi) }, skip)
            });
            if kids[0].1 < kids[1].1 {
                kids.swap(0, 1);
            }
            for (c, d, skip) in kids {
                if !skip {
                    stack.push((c, d));
                }
            }
        }
        best
    };
    let mut heap = BinaryHeap::with_capacity(n);
    for x in 0..n {
        crate::cancel::poll(x)?;
        if let Some(key) = search(&tree, &used, x, None) {
            heap.push(Entry { key, x: x as u32 });
        }
    }
    let mut out = Vec::new();
    let mut asked = n;
    while let Some(Entry { key, x }) = heap.pop() {
        let x = x as usize;
        if used[x] {
            continue;
        }
        let y = if key.lo as usize == x { key.hi as usize } else { key.lo as usize };
        if used[y] {
            asked += 1;
            crate::cancel::poll(asked)?;
            if let Some(key) = search(&tree, &used, x, Some(key)) {
                heap.push(Entry { key, x: x as u32 });
            }
            continue;
        }
        used[x] = true;
        used[y] = true;
        tree.take(x);
        tree.take(y);
        out.push((key.lo as usize, key.hi as usize));
    }
    Ok(out)
}

/// TopMod's way: every candidate pair, sorted, taken when both items are
/// free (quadratic; the fallback for coordinates near overflow, and the
/// reference of the tests).
fn brute_pairs(n: usize, group: &[u32], dist: impl Fn(usize, usize) -> f64, valid: impl Fn(usize, usize) -> bool) -> Result<Vec<(usize, usize)>> {
    let mut cand: Vec<(f64, usize, usize)> = Vec::new();
    for x in 0..n {
        crate::cancel::poll(x)?;
        for y in x + 1..n {
            if group[x] != group[y] && valid(x, y) {
                cand.push((dist(x, y), x, y));
            }
        }
    }
    cand.sort_by(|u, v| u.0.total_cmp(&v.0));
    let mut used = vec![false; n];
    let mut out = Vec::new();
    for (_, x, y) in cand {
        if !used[x] && !used[y] {
            used[x] = true;
            used[y] = true;
            out.push((x, y));
        }
    }
    Ok(out)
}

#[cfg(test)]
pub(crate) fn brute_pairs_for_tests(n: usize, group: &[u32], dist: impl Fn(usize, usize) -> f64, valid: impl Fn(usize, usize) -> bool) -> Vec<(usize, usize)> {
    brute_pairs(n, group, dist, valid).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Xorshift;

    /// The tests' generator with a bound: uniform below `n`.
    fn below(rng: &mut Xorshift, n: u64) -> u64 {
        rng.next_u64() % n
    }

    #[test]
    fn tree_equals_the_sorted_pairs() {
        // clusters, lattices (many equal distances), few and many groups,
        // pairs refused by a hash of their indices or by direction
        let mut rng = Xorshift::new(0x9e3779b97f4a7c15);
        let mut taken = 0;
        for case in 0..600 {
            let n = 2 + below(&mut rng, if case % 10 == 0 { 400 } else { 60 }) as usize;
            let groups = 1 + below(&mut rng, 6) as u32;
            let lattice = case % 3 == 0;
            let pts: Vec<DVec3> = (0..n)
                .map(|_| {
                    if lattice {
                        DVec3::new(below(&mut rng, 4) as f64, below(&mut rng, 4) as f64, below(&mut rng, 2) as f64)
                    } else {
                        let c = below(&mut rng, 3) as f64 * 10.0;
                        DVec3::new(c + rng.unit(), rng.unit() * 0.1, c * rng.unit())
                    }
                })
                .collect();
            let group: Vec<u32> = (0..n).map(|_| below(&mut rng, groups as u64) as u32).collect();
            let refuse = below(&mut rng, 4);
            let dist = |x: usize, y: usize| (pts[x] - pts[y]).length();
            let valid = |x: usize, y: usize| match refuse {
                0 => true,
                1 => (x * 7 + y * 13) % 5 != 0,
                2 => (pts[x] - pts[y]).x.abs() >= (pts[x] - pts[y]).y.abs(),
                _ => (x + y) % 17 == 0,
            };
            let fast = greedy_pairs(&pts, &group, dist, valid).unwrap();
            let slow = brute_pairs_for_tests(n, &group, dist, valid);
            assert_eq!(fast, slow, "case {case}: n {n}, {groups} groups, refuse rule {refuse}, lattice {lattice}");
            taken += fast.len();
        }
        assert!(taken > 3000, "the cases match too few pairs to test anything ({taken})");
    }
}
