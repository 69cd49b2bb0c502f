//! Per-neighbourhood recipes of the sponge builder (issue 19: the
//! sponge in output time, at least 5× a NumPy voxel construction).
//!
//! Everything the builder does for one kept cell besides its position
//! arithmetic depends on its 27-bit neighbourhood `nb` alone: its exposed
//! faces, the edges and vertices it owns, which neighbour owns each edge
//! and corner of its faces (and at which bit of that owner's masks), and
//! which corner gives a vertex its `v_out`. Working that out per cell (bit
//! loops over the stencils, a search for each owner) happened in the two
//! per-cell loops that took 54 % of a level-3 build's samples under `perf`
//! (most of the rest: the kernel's page faults); a [`Recipe`] holds the
//! answers for one `nb`, and the 321 neighbourhoods that occur at levels
//! 0–5 ([`PATTERNS`], checked against a scan of every level in the tests)
//! get theirs once per process. A neighbourhood outside that list (none can occur: the scan
//! finds no new one past level 4) would get its recipe built on the spot,
//! so the output never depends on the list.

use super::tables::Stencils;
use std::sync::OnceLock;

/// One corner of an exposed face: indices into the recipe's used edges
/// and vertices, the half-edge's direction bit, and whether this corner's
/// half-edge becomes its vertex's `v_out`.
#[derive(Clone, Copy, Default)]
pub(super) struct Corner {
    pub(super) edge: u8,
    pub(super) neg: u8,
    pub(super) vert: u8,
    pub(super) v_out: bool,
}

/// The builder's work for one neighbourhood (module docs).
#[derive(Clone)]
pub(super) struct Recipe {
    /// Exposed faces (bit `d`), owned edges (bit `le`), owned corners (bit `i`).
    pub(super) fmask: u8,
    pub(super) emask: u16,
    pub(super) vmask: u8,
    /// Every owned vertex's cells meet in one disk.
    pub(super) ok: bool,
    /// Owner cells: slot 0 is this cell, slot `s ≥ 1` the neighbour at
    /// `nb` bit `owners[s - 1]`.
    pub(super) n_owners: u8,
    pub(super) owners: [u8; MAX_OWNERS],
    /// Cell edges of the exposed faces: owner slot, and the owner's
    /// `emask` bits below this edge's (its rank among the owner's edges).
    pub(super) n_edges: u8,
    pub(super) edge_slot: [u8; 12],
    pub(super) edge_below: [u16; 12],
    /// Cell corners of the exposed faces, likewise with `vmask`.
    pub(super) n_verts: u8,
    pub(super) vert_slot: [u8; 8],
    pub(super) vert_below: [u8; 8],
    /// The exposed faces in direction order, each from its first corner.
    pub(super) n_faces: u8,
    pub(super) faces: [[Corner; 4]; 6],
}

impl Recipe {
    /// The recipe of neighbourhood `nb`: the per-cell rules of the builder
    /// (module docs of `menger_sponge`), worked out once.
    pub(super) fn build(st: &Stencils, nb: u32) -> Recipe {
        let mut r = Recipe {
            fmask: 0,
            emask: 0,
            vmask: 0,
            ok: true,
            n_owners: 0,
            owners: [0; MAX_OWNERS],
            n_edges: 0,
            edge_slot: [0; 12],
            edge_below: [0; 12],
            n_verts: 0,
            vert_slot: [0; 8],
            vert_below: [0; 8],
            n_faces: 0,
            faces: [[Corner::default(); 4]; 6],
        };
        for d in 0..6 {
            if nb & (1 << st.face[d]) == 0 {
                r.fmask |= 1 << d;
            }
        }
        // owned: no earlier cell around it is kept; boundary: not all are
        for le in 0..12 {
            if nb & st.edge_before[le] == 0 && nb & st.edge_all[le] != st.edge_all[le] {
                r.emask |= 1 << le;
            }
        }
        for i in 0..8 {
            if nb & st.vert_before[i] == 0 && nb & st.vert_all[i] != st.vert_all[i] {
                r.vmask |= 1 << i;
                r.ok &= st.manifold[st.vert_pattern(nb, i) as usize];
            }
        }
        // the owner slot of the neighbour at `nb` bit `bit` (this cell: None)
        fn slot_of(r: &mut Recipe, bit: Option<u32>) -> u8 {
            let Some(b) = bit else { return 0 };
            if let Some(s) = r.owners[..r.n_owners as usize].iter().position(|&o| o as u32 == b) {
                return s as u8 + 1;
            }
            r.owners[r.n_owners as usize] = b as u8;
            r.n_owners += 1;
            r.n_owners
        }
        // per cell edge / corner: its index among the used ones
        let (mut edge_ix, mut vert_ix) = ([u8::MAX; 12], [u8::MAX; 8]);
        for d in 0..6 {
            if r.fmask & (1 << d) == 0 {
                continue;
            }
            let mut face = [Corner::default(); 4];
            for (e, q) in st.quads[d].iter().enumerate() {
                let le = q.edge as usize;
                if edge_ix[le] == u8::MAX {
                    // the first kept cell around the edge owns it (this one if none before)
                    let cells = &st.edge_cells[le];
                    let k = (0..le & 3).find(|&k| nb & (1 << cells[k]) != 0).unwrap_or(le & 3);
                    let s = slot_of(&mut r, (k != le & 3).then_some(cells[k]));
                    let j = r.n_edges as usize;
                    // the edge is the owner's edge 4·axis + k
                    (r.edge_slot[j], r.edge_below[j]) = (s, (1u16 << ((le & !3) + k)) - 1);
                    edge_ix[le] = j as u8;
                    r.n_edges += 1;
                }
                let i = q.corner as usize;
                if vert_ix[i] == u8::MAX {
                    let cells = &st.vert_cells[i];
                    let k = (0..i).find(|&k| nb & (1 << cells[k]) != 0).unwrap_or(i);
                    let s = slot_of(&mut r, (k != i).then_some(cells[k]));
                    let j = r.n_verts as usize;
                    (r.vert_slot[j], r.vert_below[j]) = (s, (1u8 << k).wrapping_sub(1));
                    vert_ix[i] = j as u8;
                    r.n_verts += 1;
                }
                face[e] = Corner { edge: edge_ix[le], neg: q.neg, vert: vert_ix[i], v_out: st.first_dir(nb, i) == q.dir };
            }
            r.faces[r.n_faces as usize] = face;
            r.n_faces += 1;
        }
        r
    }
}

/// The recipes of [`PATTERNS`], found by `nb` through an open-addressed
/// table (a multiplicative hash; at most a few probes, all in cache).
pub(super) struct Recipes {
    keys: Vec<u32>,
    index: Vec<u16>,
    recipes: Vec<Recipe>,
}

impl Recipes {
    /// The recipe of index `i` (from [`Recipes::find`]).
    #[inline]
    pub(super) fn get(&self, i: u16) -> &Recipe {
        &self.recipes[i as usize]
    }
}

/// The index standing for "no recipe in the table" (built on the spot).
pub(super) const MISS: u16 = u16::MAX;

/// Most owner cells besides the cell itself in any recipe (at most the 26
/// neighbours; `recipes_match_the_per_cell_rules` checks the bound).
pub(super) const MAX_OWNERS: usize = 26;

/// An empty slot (no neighbourhood has bits above 26).
const EMPTY: u32 = u32::MAX;
const BITS: u32 = 10;

impl Recipes {
    /// The process's table, built on first use (about 0.1 ms).
    pub(super) fn table() -> &'static Recipes {
        static TABLE: OnceLock<Recipes> = OnceLock::new();
        TABLE.get_or_init(|| {
            let st = Stencils::get();
            let mut t = Recipes { keys: vec![EMPTY; 1 << BITS], index: vec![0; 1 << BITS], recipes: Vec::with_capacity(PATTERNS.len()) };
            for &nb in PATTERNS {
                let mut h = Self::hash(nb);
                while t.keys[h] != EMPTY {
                    h = (h + 1) & ((1 << BITS) - 1);
                }
                t.keys[h] = nb;
                t.index[h] = t.recipes.len() as u16;
                t.recipes.push(Recipe::build(st, nb));
            }
            t
        })
    }

    /// A table without recipes: every lookup misses (for the tests of the
    /// builder's on-the-spot path).
    #[cfg(test)]
    pub(super) fn empty() -> Recipes {
        Recipes { keys: vec![EMPTY; 1 << BITS], index: vec![0; 1 << BITS], recipes: Vec::new() }
    }

    #[inline]
    fn hash(nb: u32) -> usize {
        (nb.wrapping_mul(0x9E37_79B9) >> (32 - BITS)) as usize
    }

    /// The recipe of `nb` and its index, if `nb` is one of [`PATTERNS`].
    #[inline]
    pub(super) fn find(&self, nb: u32) -> Option<(&Recipe, u16)> {
        let mut h = Self::hash(nb);
        loop {
            let k = self.keys[h];
            if k == nb {
                let i = self.index[h];
                return Some((&self.recipes[i as usize], i));
            }
            if k == EMPTY {
                return None;
            }
            h = (h + 1) & ((1 << BITS) - 1);
        }
    }
}

/// Every neighbourhood of a kept cell at levels 0–5 (bit `9i + 3j + k` for
/// the offset `(i − 1, j − 1, k − 1)`), sorted; `patterns_are_complete`
/// rebuilds the list from a scan of every level.
pub(super) static PATTERNS: &[u32] = &[
    0x0002000, 0x0003410, 0x0006410, 0x0007618, 0x0007a28, 0x0007c30, 0x000f658, 0x0013010,
    0x0013612, 0x0013e16, 0x0016010, 0x0016c12, 0x0016e13, 0x001a682, 0x001b490, 0x001f018,
    0x001f219, 0x001fc1a, 0x001fcb0, 0x001fe1b, 0x0027d30, 0x002f028, 0x002fe2d, 0x0032c82,
    0x0036490, 0x0037030, 0x0037632, 0x0037698, 0x0037834, 0x0037e36, 0x003b590, 0x003bec3,
    0x003e4d0, 0x003ef86, 0x003f6d8, 0x003fb68, 0x003fdb0, 0x00d3612, 0x00d3e16, 0x0196c12,
    0x0196e13, 0x01dfe1b, 0x01efe2d, 0x01f7e36, 0x0247618, 0x024f658, 0x0403400, 0x040341a,
    0x040343e, 0x04034da, 0x04034fe, 0x0406400, 0x0406432, 0x040643b, 0x04065b2, 0x04065bb,
    0x0413000, 0x0413098, 0x041309b, 0x04131b8, 0x04131bb, 0x0416000, 0x04160b0, 0x04160b6,
    0x04160f8, 0x04160fe, 0x0493600, 0x0493603, 0x0493698, 0x049369b, 0x04937bf, 0x0496c00,
    0x0496c06, 0x0496cb0, 0x0496cb6, 0x0496cff, 0x04d6e00, 0x04d6e06, 0x04d6eb7, 0x0593e00,
    0x0593e03, 0x0593e9f, 0x0607600, 0x0607609, 0x0607632, 0x060763b, 0x06077fb, 0x061f000,
    0x061f048, 0x061f0b0, 0x061f0f8, 0x061f0ff, 0x065f200, 0x065f248, 0x065f2f9, 0x068201a,
    0x0683410, 0x0687c30, 0x069b490, 0x069fc00, 0x069fcb0, 0x069fcfe, 0x06dfe00, 0x06dfe07,
    0x06dfe49, 0x06dfeb6, 0x06dfef8, 0x06dfeff, 0x0907c30, 0x0927d30, 0x0a07a00, 0x0a07a3d,
    0x0a07bfd, 0x0a2f000, 0x0a2f178, 0x0a2f17f, 0x0b6fe00, 0x0b6fe07, 0x0b6ff78, 0x0b6ff7f,
    0x0c07c00, 0x0c07c1a, 0x0c07c24, 0x0c07c3e, 0x0c07dfe, 0x0c37000, 0x0c37098, 0x0c37120,
    0x0c371b8, 0x0c371bf, 0x0c82032, 0x0c86410, 0x0c87618, 0x0cb6490, 0x0cb7600, 0x0cb7698,
    0x0cb77bb, 0x0d37800, 0x0d37920, 0x0d379bc, 0x0db7e00, 0x0db7e07, 0x0db7e9b, 0x0db7f24,
    0x0db7fb8, 0x0db7fbf, 0x0ec303b, 0x0ec6410, 0x0ec7618, 0x0eff6d8, 0x0f47a28, 0x0f7fb68,
    0x0f83410, 0x0f8603e, 0x0f87c30, 0x0fbfdb0, 0x121f018, 0x121f219, 0x125fe1b, 0x127bec3,
    0x127f6d8, 0x160f600, 0x160f609, 0x160f67b, 0x1ecb07b, 0x1ecf658, 0x209a600, 0x209a6d3,
    0x209a7f7, 0x20b2c00, 0x20b2d96, 0x20b2ddf, 0x241b400, 0x241b41a, 0x241b4c0, 0x241b4da,
    0x241b5fe, 0x2436400, 0x2436432, 0x2436580, 0x24365b2, 0x24365fb, 0x2602098, 0x2613010,
    0x2613612, 0x2637030, 0x2637600, 0x2637632, 0x26377bb, 0x26c249b, 0x26d3010, 0x26d3612,
    0x26f7e36, 0x27c2c9f, 0x27d3e16, 0x2c020b0, 0x2c16010, 0x2c16c12, 0x2c1f018, 0x2c1fc00,
    0x2c1fc1a, 0x2c1fcfe, 0x2d824b6, 0x2d96010, 0x2d96c12, 0x2d9fe1b, 0x2dc26b7, 0x2dd6e13,
    0x301b490, 0x303b590, 0x30fbe00, 0x30fbe49, 0x30fbf96, 0x30fbfdf, 0x343e400, 0x343e580,
    0x343e5f2, 0x34da682, 0x34fef86, 0x363f600, 0x363f63b, 0x363f649, 0x363f7b2, 0x363f7c0,
    0x363f7fb, 0x3683410, 0x36920da, 0x369b490, 0x36bfdb0, 0x3e030f8, 0x3e16010, 0x3e1f018,
    0x3e1fe1b, 0x3e432f9, 0x3e5f219, 0x3f83410, 0x3f834fe, 0x3f96010, 0x3f960fe, 0x3f9fc1a,
    0x3f9fcb0, 0x3fc36ff, 0x3fd6c12, 0x3fdf018, 0x3fdfe1b, 0x4837030, 0x4837834, 0x4937e36,
    0x493ef86, 0x493fdb0, 0x4c27c00, 0x4c27c24, 0x4c27d3e, 0x4fa613e, 0x4fa7d30, 0x5a3fa00,
    0x5a3fa3d, 0x5a3fbc0, 0x5a3fbfd, 0x5e2f028, 0x5e2fe2d, 0x5fef028, 0x5fefe2d, 0x6036490,
    0x603e4d0, 0x61bee00, 0x61beed3, 0x61bef24, 0x61beff7, 0x643b400, 0x643b4c0, 0x643b5da,
    0x65b2c82, 0x65bbec3, 0x6c3fc00, 0x6c3fc3e, 0x6c3fcda, 0x6c3fd24, 0x6c3fdc0, 0x6c3fdfe,
    0x6c86410, 0x6c921b2, 0x6cb6490, 0x6cbf6d8, 0x6e061b8, 0x6e13010, 0x6e37030, 0x6e37e36,
    0x6ec6410, 0x6ec65bb, 0x6ed3010, 0x6ed31bb, 0x6ef7632, 0x6ef7698, 0x6f069bc, 0x6f37834,
    0x6fc6dbf, 0x6fd3612, 0x6ff7030, 0x6ff7e36, 0x703f6d8, 0x703fb68, 0x703fdb0, 0x76b21da,
    0x76bb590, 0x77f2c82, 0x77fbec3, 0x7c9a1f2, 0x7cbe4d0, 0x7dda682, 0x7dfef86, 0x7ec7618,
    0x7edb1fb, 0x7ef6490, 0x7eff6d8, 0x7f47a28, 0x7f7fb68, 0x7f87c30, 0x7f9b490, 0x7fb61fe,
    0x7fbfdb0,
];

#[cfg(test)]
mod tests {
    use super::super::tables::Cells;
    use super::*;

    /// Every neighbourhood of a kept cell at levels 0–5, from a scan of
    /// the cells (the builder's own `neighbourhood`).
    fn scan() -> Vec<u32> {
        let mut seen = std::collections::BTreeSet::new();
        for level in 0..=super::super::MAX_LEVEL {
            let g = Cells::new(level);
            for x in 0..g.n {
                g.for_slab(x, |row, _, _, z, _| {
                    seen.insert(g.neighbourhood(row, z));
                });
            }
        }
        seen.into_iter().collect()
    }

    /// The list is exactly the neighbourhoods that occur, so every cell
    /// up to the highest level finds its recipe in the table.
    #[test]
    fn patterns_are_complete() {
        let found = scan();
        assert_eq!(found.len(), 321);
        assert_eq!(PATTERNS, &found[..]);
        let t = Recipes::table();
        for &nb in PATTERNS {
            let (r, i) = t.find(nb).unwrap();
            assert!(std::ptr::eq(r, t.get(i)));
        }
        // neighbourhoods not in the list are not found (they are built on the spot)
        assert!(t.find(0).is_none() && t.find((1 << 27) - 1).is_none());
    }

    /// Each recipe gives the per-cell rules' answers (the builder before
    /// recipes): masks, owners of every edge and corner of the exposed
    /// faces (slot → offset) and the `v_out` corners; owner slots fit
    /// [`MAX_OWNERS`].
    #[test]
    fn recipes_match_the_per_cell_rules() {
        let st = Stencils::new();
        let mut most = 0;
        for &nb in PATTERNS {
            let r = Recipe::build(&st, nb);
            most = most.max(r.n_owners as usize);
            assert_eq!(r.n_faces as u32, r.fmask.count_ones());
            let mut j = 0;
            for d in 0..6 {
                if nb & (1 << st.face[d]) != 0 {
                    assert_eq!(r.fmask & (1 << d), 0);
                    continue;
                }
                for (e, q) in st.quads[d].iter().enumerate() {
                    let c = r.faces[j][e];
                    // the owner: the first kept cell around the edge
                    let le = q.edge as usize;
                    let k = (0..4).find(|&k| nb & (1 << st.edge_cells[le][k]) != 0).unwrap();
                    let s = r.edge_slot[c.edge as usize] as usize;
                    let bit = if s == 0 { 13 } else { r.owners[s - 1] as u32 };
                    assert_eq!(bit, st.edge_cells[le][k], "nb {nb:#x} face {d} corner {e}");
                    assert_eq!(r.edge_below[c.edge as usize], (1u16 << (4 * (le / 4) + k)) - 1);
                    assert_eq!(c.neg, q.neg);
                    let i = q.corner as usize;
                    let kv = (0..8).find(|&k| nb & (1 << st.vert_cells[i][k]) != 0).unwrap();
                    let s = r.vert_slot[c.vert as usize] as usize;
                    let bit = if s == 0 { 13 } else { r.owners[s - 1] as u32 };
                    assert_eq!(bit, st.vert_cells[i][kv]);
                    assert_eq!(r.vert_below[c.vert as usize] as u32, (1u32 << kv) - 1);
                    assert_eq!(c.v_out, st.first_dir(nb, i) == q.dir);
                }
                j += 1;
            }
        }
        assert!(most <= MAX_OWNERS, "{most} owners");
    }
}
