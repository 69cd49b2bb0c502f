//! The broad phase of [`super::crossing_pairs`]: a bounding volume
//! hierarchy over the triangles' boxes (median splits along the longest
//! axis, leaves of at most [`LEAF`] triangles) traversed against itself, so
//! only pairs of overlapping boxes reach the exact predicate, in time
//! O(n log n + pairs) whatever the density. The uniform grid it replaces
//! (at most 256 cells per axis, cells shaped by the whole bounding box)
//! put hundreds of triangles in a cell of a thin or dense surface (a
//! wireframe's tubes, a fine torus) and tested every pair in it: the
//! wireframe tools' crossing report took seconds (issue 16).

use glam::DVec3;

/// Triangles per leaf.
const LEAF: usize = 8;
/// Traversal depth below which node pairs are split across threads.
const PAR_DEPTH: u32 = 10;

type Box3 = (DVec3, DVec3);

#[derive(Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: `order[a..b]`; inner node: children `a` and `b`.
    a: u32,
    b: u32,
    leaf: bool,
    /// Holds a focused triangle.
    focus: bool,
}

pub(super) struct Bvh<'a> {
    boxes: &'a [Box3],
    focus: Option<&'a [bool]>,
    order: Vec<u32>,
    nodes: Vec<Node>,
}

#[inline]
fn overlap(a: &Box3, b: &Box3) -> bool {
    // touching boxes overlap (the grid tested them too)
    !(a.0.cmpgt(b.1).any() || b.0.cmpgt(a.1).any())
}

impl<'a> Bvh<'a> {
    /// The hierarchy over triangles `items` (indices into `boxes`).
    pub fn new(boxes: &'a [Box3], focus: Option<&'a [bool]>, mut items: Vec<u32>) -> Bvh<'a> {
        let mut t = Bvh { boxes, focus, order: Vec::new(), nodes: Vec::with_capacity(2 * items.len() / LEAF + 1) };
        if !items.is_empty() {
            let cen: Vec<DVec3> = boxes.iter().map(|b| (b.0 + b.1) * 0.5).collect();
            t.build(&mut items, 0, &cen);
        }
        t.order = items;
        t
    }

    fn focused(&self, i: u32) -> bool {
        self.focus.map_or(true, |f| f[i as usize])
    }

    /// Builds the node of `items` (which start at `first` in the final
    /// order) and returns its index.
    fn build(&mut self, items: &mut [u32], first: usize, cen: &[DVec3]) -> u32 {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let (mut clo, mut chi) = (lo, hi);
        let mut focus = false;
        for &i in items.iter() {
            let b = &self.boxes[i as usize];
            lo = lo.min(b.0);
            hi = hi.max(b.1);
            clo = clo.min(cen[i as usize]);
            chi = chi.max(cen[i as usize]);
            focus |= self.focus.map_or(true, |f| f[i as usize]);
        }
        let k = self.nodes.len() as u32;
        self.nodes.push(Node { lo, hi, a: first as u32, b: (first + items.len()) as u32, leaf: true, focus });
        if items.len() > LEAF {
            // split at the median centroid along the centroids' longest axis
            let ext = chi - clo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z { 0 } else if ext.y >= ext.z { 1 } else { 2 };
            let mid = items.len() / 2;
            items.select_nth_unstable_by(mid, |&x, &y| cen[x as usize][axis].total_cmp(&cen[y as usize][axis]));
            let (l, r) = items.split_at_mut(mid);
            let a = self.build(l, first, cen);
            let b = self.build(r, first + mid, cen);
            self.nodes[k as usize] = Node { lo, hi, a, b, leaf: false, focus };
        }
        k
    }

    /// Every pair `(i, j)`, `i < j`, of triangles with overlapping boxes
    /// and at least one focused, for which `test` holds; unsorted.
    pub fn pairs(&self, test: &(impl Fn(u32, u32) -> bool + Sync)) -> Vec<(u32, u32)> {
        if self.nodes.is_empty() {
            return Vec::new();
        }
        self.within(0, test, 0)
    }

    /// Pairs inside node `a`.
    fn within(&self, a: u32, test: &(impl Fn(u32, u32) -> bool + Sync), depth: u32) -> Vec<(u32, u32)> {
        let n = self.nodes[a as usize];
        if !n.focus || crate::cancel::requested() {
            return Vec::new(); // cancelled: incomplete, the caller checks
        }
        if n.leaf {
            let mut out = Vec::new();
            let items = &self.order[n.a as usize..n.b as usize];
            for (k, &i) in items.iter().enumerate() {
                for &j in &items[k + 1..] {
                    self.leaf_pair(i, j, test, &mut out);
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

    fn between_into(&self, a: u32, b: u32, test: &(impl Fn(u32, u32) -> bool + Sync), depth: u32, out: &mut Vec<(u32, u32)>) {
        let (na, nb) = (self.nodes[a as usize], self.nodes[b as usize]);
        if !(na.focus || nb.focus) || !overlap(&(na.lo, na.hi), &(nb.lo, nb.hi)) {
            return;
        }
        if na.leaf && nb.leaf {
            for &i in &self.order[na.a as usize..na.b as usize] {
                for &j in &self.order[nb.a as usize..nb.b as usize] {
                    self.leaf_pair(i, j, test, out);
                }
            }
            return;
        }
        if crate::cancel::requested() {
            return;
        }
        // descend the larger node (a leaf never)
        let split_a = !na.leaf && (nb.leaf || (na.hi - na.lo).max_element() >= (nb.hi - nb.lo).max_element());
        let (x, y, other) = if split_a { (na.a, na.b, b) } else { (nb.a, nb.b, a) };
        if depth < PAR_DEPTH {
            let (mut l, r) = rayon::join(|| self.between(x, other, test, depth + 1), || self.between(y, other, test, depth + 1));
            l.extend(r);
            out.extend(l);
        } else {
            self.between_into(x, other, test, depth + 1, out);
            self.between_into(y, other, test, depth + 1, out);
        }
    }

    #[inline]
    fn leaf_pair(&self, i: u32, j: u32, test: &(impl Fn(u32, u32) -> bool + Sync), out: &mut Vec<(u32, u32)>) {
        if (self.focused(i) || self.focused(j)) && overlap(&self.boxes[i as usize], &self.boxes[j as usize]) && test(i, j) {
            out.push((i.min(j), i.max(j)));
        }
    }
}
