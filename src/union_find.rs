//! Union-find over `u32` labels, shared by the component queries, the
//! repair's umbrella split and the Menger builder's corner groups. The
//! smaller root always stays the root, so labels come out deterministic.

/// The root of `x`'s set (with path halving).
#[inline]
pub(crate) fn root(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let g = p[p[x as usize] as usize];
        p[x as usize] = g;
        x = g;
    }
    x
}

/// Joins the sets of `a` and `b`; the smaller root stays the root.
#[inline]
pub(crate) fn union(p: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (root(p, a), root(p, b));
    if ra != rb {
        p[ra.max(rb) as usize] = ra.min(rb);
    }
}
