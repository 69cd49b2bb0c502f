//! The broad phase of [`super::crossing_pairs`]: a bounding volume
//! hierarchy over the triangles' boxes (median splits along the longest
//! axis, leaves of at most [`LEAF`] triangles) traversed against itself, so
//! only pairs of overlapping boxes reach the exact predicate, in time
//! O(n log n + pairs) whatever the density. The uniform grid it replaces
//! (at most 256 cells per axis, cells shaped by the whole bounding box)
//! put hundreds of triangles in a cell of a thin or dense surface (a
//! wireframe's tubes, a fine torus) and tested every pair in it: the
//! wireframe tools' crossing report took seconds (issue 16).
//!
//! The tree is built over the triangles' records themselves, which the
//! median splits leave in leaf order: the leaf loops, where the scan spends
//! its time (a wireframe's tubes test about ten box pairs per triangle),
//! read them contiguously, and no centroid table or permutation is
//! allocated (fresh pages cost as much as the scan's arithmetic here).

use glam::DVec3;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// Triangles per leaf.
const LEAF: usize = 8;
/// Traversal depth below which node pairs are split across threads.
const PAR_DEPTH: u32 = 10;
/// Subtrees of at least this many triangles are built on two threads.
const PAR_BUILD: usize = 1 << 15;

/// A triangle: its bounding box, its index, whether it is focused.
#[derive(Clone, Copy)]
pub(super) struct Item {
    pub lo: DVec3,
    pub hi: DVec3,
    pub id: u32,
    pub focus: bool,
}

impl Item {
    /// Triangle `id` (corners `t` of `p`) with its bounding box.
    pub fn of(p: &[DVec3], t: [u32; 3], id: u32, focus: bool) -> Item {
        let q = t.map(|v| p[v as usize]);
        Item { lo: q[0].min(q[1]).min(q[2]), hi: q[0].max(q[1]).max(q[2]), id, focus }
    }
}

#[derive(Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: `items[a..b]`; inner node: children `a` and `b`.
    a: u32,
    b: u32,
    leaf: bool,
    /// Holds a focused triangle.
    focus: bool,
}

pub(super) struct Bvh {
    items: Vec<Item>,
    nodes: Vec<Node>,
}

/// Pairs found so far, by every traversal sharing it, and the count at
/// which they stop (`pairs_upto`).
pub(super) struct Budget {
    found: AtomicUsize,
    limit: usize,
}

impl Budget {
    pub fn new(limit: usize) -> Budget {
        Budget { found: AtomicUsize::new(0), limit }
    }

    /// `test`, counting its hits, and false once `limit` pairs are found.
    pub fn counted(&self, test: &(impl Fn(u32, u32) -> bool + Sync), i: u32, j: u32) -> bool {
        if self.found.load(Relaxed) >= self.limit {
            return false;
        }
        let hit = test(i, j);
        if hit {
            self.found.fetch_add(1, Relaxed);
        }
        hit
    }

    /// Whether `limit` pairs were found.
    pub fn spent(&self) -> bool {
        self.found.load(Relaxed) >= self.limit
    }
}

#[inline]
fn overlap(a: (DVec3, DVec3), b: (DVec3, DVec3)) -> bool {
    // touching boxes overlap (the grid tested them too)
    !(a.0.cmpgt(b.1).any() || b.0.cmpgt(a.1).any())
}

impl Bvh {
    /// The hierarchy over `items` (reordered into leaf order).
    pub fn new(mut items: Vec<Item>) -> Bvh {
        if items.is_empty() {
            return Bvh { items, nodes: Vec::new() };
        }
        let empty = Node { lo: DVec3::ZERO, hi: DVec3::ZERO, a: 0, b: 0, leaf: true, focus: false };
        let mut nodes = vec![empty; node_counts(items.len()).0];
        build(&mut nodes, 0, &mut items, 0);
        Bvh { items, nodes }
    }

    /// The box of every triangle, or None for an empty tree.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.nodes.first().map(|n| (n.lo, n.hi))
    }

    /// Every pair `(i, j)`, `i < j`, of triangles with overlapping boxes
    /// and at least one focused, for which `test` holds; unsorted.
    #[cfg(test)]
    pub fn pairs(&self, test: &(impl Fn(u32, u32) -> bool + Sync)) -> Vec<(u32, u32)> {
        self.pairs_upto(test, &Budget::new(usize::MAX))
    }

    /// [`Bvh::pairs`] until `budget`'s limit of pairs is found (a few more
    /// where threads find them at once; `budget.spent()` tells): a surface
    /// folded through itself everywhere has quadratically many crossing
    /// pairs (88 M for a wireframe of a prism's two 8,000-gons, 28 s), and a
    /// report needs only to say that there are that many.
    pub fn pairs_upto(&self, test: &(impl Fn(u32, u32) -> bool + Sync), budget: &Budget) -> Vec<(u32, u32)> {
        if self.nodes.is_empty() {
            return Vec::new();
        }
        let counted = |i: u32, j: u32| budget.counted(test, i, j);
        Walk { a: self, b: self, budget }.within(0, &counted, 0)
    }

    /// The pairs with one triangle in this tree and one in `other`, as
    /// [`Bvh::pairs_upto`] finds them within one tree.
    pub fn pairs_between_upto(&self, other: &Bvh, test: &(impl Fn(u32, u32) -> bool + Sync), budget: &Budget) -> Vec<(u32, u32)> {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return Vec::new();
        }
        let counted = |i: u32, j: u32| budget.counted(test, i, j);
        let mut out = Vec::new();
        Walk { a: self, b: other, budget }.between_into(0, 0, &counted, 0, &mut out);
        out
    }
}

/// A traversal of the pairs of one tree (`a` and `b` the same) or of two
/// (node ids of `between_into` index `a`'s nodes first, `b`'s second).
struct Walk<'a> {
    a: &'a Bvh,
    b: &'a Bvh,
    budget: &'a Budget,
}

impl Walk<'_> {
    /// Cancelled, or `limit` pairs found: the traversal returns.
    fn halted(&self) -> bool {
        crate::cancel::requested() || self.budget.spent()
    }

    /// Pairs inside node `a` (of tree `a`, which is `b`).
    fn within(&self, a: u32, test: &(impl Fn(u32, u32) -> bool + Sync), depth: u32) -> Vec<(u32, u32)> {
        let n = self.a.nodes[a as usize];
        if !n.focus || self.halted() {
            return Vec::new(); // cancelled: incomplete, the caller checks
        }
        if n.leaf {
            let mut out = Vec::new();
            let items = &self.a.items[n.a as usize..n.b as usize];
            for (k, x) in items.iter().enumerate() {
                for y in &items[k + 1..] {
                    leaf_pair(x, y, test, &mut out);
                }
            }
            return out;
        }
        if depth < PAR_DEPTH {
            let ((mut x, y), z) = rayon::join(|| rayon::join(|| self.within(n.a, test, depth + 1), || self.within(n.b, test, depth + 1)), || self.between(n.a, n.b, test, depth + 1));
            x.extend(y);
            x.extend(z);
            return x;
        }
        let mut out = self.within(n.a, test, depth + 1);
        out.extend(self.within(n.b, test, depth + 1));
        out.extend(self.between(n.a, n.b, test, depth + 1));
        out
    }

    /// Pairs with one triangle in node `a` and one in node `b`.
    fn between(&self, a: u32, b: u32, test: &(impl Fn(u32, u32) -> bool + Sync), depth: u32) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        self.between_into(a, b, test, depth, &mut out);
        out
    }

    /// Pairs with one triangle in node `a` of tree `a` and one in node `b`
    /// of tree `b`.
    fn between_into(&self, a: u32, b: u32, test: &(impl Fn(u32, u32) -> bool + Sync), depth: u32, out: &mut Vec<(u32, u32)>) {
        let (na, nb) = (self.a.nodes[a as usize], self.b.nodes[b as usize]);
        if !(na.focus || nb.focus) || !overlap((na.lo, na.hi), (nb.lo, nb.hi)) {
            return;
        }
        if na.leaf && nb.leaf {
            // only the boxes that reach into the other leaf's box can
            // overlap one of its boxes: most of a leaf's 8 × 8 pairs end here
            let near = |items: &[Item], n: &Node, o: &Node| {
                let (mut k, mut at) = (0, [0usize; LEAF]);
                for x in n.a as usize..n.b as usize {
                    at[k] = x;
                    k += overlap((items[x].lo, items[x].hi), (o.lo, o.hi)) as usize;
                }
                (k, at)
            };
            let ((ka, xa), (kb, yb)) = (near(&self.a.items, &na, &nb), near(&self.b.items, &nb, &na));
            for &x in &xa[..ka] {
                for &y in &yb[..kb] {
                    leaf_pair(&self.a.items[x], &self.b.items[y], test, out);
                }
            }
            return;
        }
        if self.halted() {
            return;
        }
        // descend the larger node (a leaf never)
        let split_a = !na.leaf && (nb.leaf || (na.hi - na.lo).max_element() >= (nb.hi - nb.lo).max_element());
        let ((x, xb), (y, yb)) = if split_a { ((na.a, b), (na.b, b)) } else { ((a, nb.a), (a, nb.b)) };
        if depth < PAR_DEPTH {
            let (mut l, r) = rayon::join(|| self.between(x, xb, test, depth + 1), || self.between(y, yb, test, depth + 1));
            l.extend(r);
            out.extend(l);
        } else {
            self.between_into(x, xb, test, depth + 1, out);
            self.between_into(y, yb, test, depth + 1, out);
        }
    }
}

/// The number of nodes of the hierarchy over `n` triangles and over
/// `n + 1` (median splits: a subtree's shape depends on its size only,
/// and the two halves of sizes `n` and `n + 1` have sizes within
/// `{⌊n/2⌋, ⌊n/2⌋ + 1}`), in O(log n).
fn node_counts(n: usize) -> (usize, usize) {
    if n < LEAF {
        return (1, 1);
    }
    let (x, y) = node_counts(n / 2);
    let c = |m: usize, (x, y): (usize, usize)| if m <= LEAF { 1 } else if m % 2 == 0 { 1 + 2 * if m / 2 == n / 2 { x } else { y } } else { 1 + x + y };
    (c(n, (x, y)), c(n + 1, (x, y)))
}

/// Builds the subtree of `items` (which start at `first` in the final
/// order) into `nodes`, its `node_counts` slots in preorder, the root at
/// index `base`: the order a sequential depth-first build pushes them in,
/// so the tree (and every traversal of it) does not depend on the threads.
/// Subtrees of [`PAR_BUILD`] triangles or more are built on two threads
/// (the median selections are a seventh of a per-face Menger iteration's
/// scan on one thread).
fn build(nodes: &mut [Node], base: u32, items: &mut [Item], first: usize) {
    debug_assert_eq!(nodes.len(), node_counts(items.len()).0);
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    // centroids doubled (lo + hi): the same order, one multiplication less
    let (mut clo, mut chi) = (lo, hi);
    let mut focus = false;
    for b in items.iter() {
        lo = lo.min(b.lo);
        hi = hi.max(b.hi);
        clo = clo.min(b.lo + b.hi);
        chi = chi.max(b.lo + b.hi);
        focus |= b.focus;
    }
    nodes[0] = Node { lo, hi, a: first as u32, b: (first + items.len()) as u32, leaf: true, focus };
    if items.len() > LEAF {
        // split at the median centroid along the centroids' longest axis
        let ext = chi - clo;
        let axis = if ext.x >= ext.y && ext.x >= ext.z { 0 } else if ext.y >= ext.z { 1 } else { 2 };
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |x, y| (x.lo[axis] + x.hi[axis]).total_cmp(&(y.lo[axis] + y.hi[axis])));
        let par = items.len() >= PAR_BUILD;
        let (l, r) = items.split_at_mut(mid);
        let cl = node_counts(mid).0;
        let (head, rest) = nodes.split_at_mut(1);
        let (ln, rn) = rest.split_at_mut(cl);
        let (a, b) = (base + 1, base + 1 + cl as u32);
        if par {
            rayon::join(|| build(ln, a, l, first), || build(rn, b, r, first + mid));
        } else {
            build(ln, a, l, first);
            build(rn, b, r, first + mid);
        }
        head[0] = Node { lo, hi, a, b, leaf: false, focus };
    }
}

#[inline]
fn leaf_pair(x: &Item, y: &Item, test: &(impl Fn(u32, u32) -> bool + Sync), out: &mut Vec<(u32, u32)>) {
    if (x.focus || y.focus) && overlap((x.lo, x.hi), (y.lo, y.hi)) && test(x.id, y.id) {
        out.push((x.id.min(y.id), x.id.max(y.id)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `node_counts` is the recursion it shortcuts, for every size up to
    /// 4,096 and some large ones.
    #[test]
    fn node_counts_match_the_recursion() {
        fn count(n: usize) -> usize {
            if n <= LEAF { 1 } else { 1 + count(n / 2) + count(n - n / 2) }
        }
        for n in (0..4096).chain([65_535, 65_536, 100_001, 1 << 20]) {
            assert_eq!(node_counts(n), (count(n), count(n + 1)), "{n}");
        }
    }

    /// The tree is the same whatever the threads: built on one thread and
    /// on two (subtrees above `PAR_BUILD` split across them), every node
    /// and the leaf order of the triangles are equal.
    #[test]
    fn build_does_not_depend_on_the_threads() {
        let mut rng = crate::test_rng::Xorshift::new(0x2545_f491_4f6c_dd1d);
        let mut rnd = || rng.unit();
        let items: Vec<Item> = (0..3 * PAR_BUILD as u32 + 17)
            .map(|id| {
                let c = DVec3::new(rnd(), rnd(), rnd() * 0.1);
                let e = DVec3::new(rnd(), rnd(), rnd()) * 0.01;
                Item { lo: c - e, hi: c + e, id, focus: id % 3 != 0 }
            })
            .collect();
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| Bvh::new(items.clone()))
        };
        let (a, b) = (on(1), on(2));
        let key = |n: &Node| (n.lo.to_array(), n.hi.to_array(), n.a, n.b, n.leaf, n.focus);
        assert_eq!(a.nodes.len(), node_counts(items.len()).0);
        assert!(a.nodes.iter().map(key).eq(b.nodes.iter().map(key)));
        assert!(a.items.iter().map(|x| x.id).eq(b.items.iter().map(|x| x.id)));
        // every leaf holds at most LEAF triangles, and the leaves cover them once
        let mut covered = vec![0u8; items.len()];
        for n in a.nodes.iter().filter(|n| n.leaf) {
            assert!(n.b - n.a <= LEAF as u32 && n.b > n.a);
            (n.a..n.b).for_each(|i| covered[i as usize] += 1);
        }
        assert!(covered.iter().all(|&c| c == 1));
    }
}
