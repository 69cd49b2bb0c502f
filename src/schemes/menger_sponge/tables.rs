//! Neighbourhood tables and the compact numbering of kept cells used by
//! the sponge builder (module docs of `menger_sponge`, "Construction").

/// Flag of a coordinate outside `0..n` in the padded digit masks: it makes
/// every cell there count as removed.
pub(super) const OUT: u32 = 1 << 31;

/// Bit of the cell at offset `d` ∈ {−1, 0, 1}³ in a 27-bit neighbourhood mask.
pub(super) fn nb_bit(d: [i32; 3]) -> u32 {
    ((d[0] + 1) * 9 + (d[1] + 1) * 3 + (d[2] + 1)) as u32
}

/// Offset of corner `i` of a cell (bit `a` of `i` = coordinate `a`).
pub(super) fn corner_off(i: usize) -> [i32; 3] {
    [(i & 1) as i32, ((i >> 1) & 1) as i32, ((i >> 2) & 1) as i32]
}

pub(super) fn add(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(super) fn sub(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn unit(a: usize) -> [i32; 3] {
    let mut e = [0; 3];
    e[a] = 1;
    e
}

/// Cells around the grid edge along axis `a` from `base`: the cell `k` is
/// `base − (k & 1)·e_u − (k >> 1)·e_v`, with `u, v` the next two axes.
pub(super) fn edge_cells(base: [i32; 3], a: usize) -> [[i32; 3]; 4] {
    let (eu, ev) = (unit((a + 1) % 3), unit((a + 2) % 3));
    [base, sub(base, eu), sub(base, ev), sub(sub(base, eu), ev)]
}

/// The 4 corners of the face of the cell at the origin facing direction `d`
/// (axis `d / 2`, negative for even `d`), counter-clockwise seen from outside.
pub(super) fn quad(d: usize) -> [[i32; 3]; 4] {
    let a = d / 2;
    let (eu, ev) = (unit((a + 1) % 3), unit((a + 2) % 3));
    let p = if d % 2 == 1 { unit(a) } else { [0; 3] };
    if d % 2 == 1 {
        [p, add(p, eu), add(add(p, eu), ev), add(p, ev)]
    } else {
        [p, add(p, ev), add(add(p, eu), ev), add(p, eu)]
    }
}

/// A face corner in cell terms: its tail corner, the cell edge it runs
/// along, whether it runs towards decreasing coordinate, and its direction
/// (`2·axis + positive`).
#[derive(Clone, Copy, Default)]
pub(super) struct QuadCorner {
    pub(super) corner: u8,
    pub(super) edge: u8,
    pub(super) neg: u8,
    pub(super) dir: u8,
}

/// Neighbourhood masks, fixed for all levels.
pub(super) struct Stencils {
    /// Neighbour across face direction `d`.
    pub(super) face: [u32; 6],
    /// The 8 cells around corner `i`: cell `k` is `corner − corner_off(k)`.
    pub(super) vert_cells: [[u32; 8]; 8],
    /// The 4 cells around cell edge `le = 4·axis + su + 2·sv` (base
    /// `su·e_u + sv·e_v`), in [`edge_cells`] order.
    pub(super) edge_cells: [[u32; 4]; 12],
    /// Masks of all cells around corner `i` / edge `le`, and of those before
    /// this cell (the earlier ones own it when kept).
    pub(super) vert_all: [u32; 8],
    pub(super) vert_before: [u32; 8],
    pub(super) edge_all: [u32; 12],
    pub(super) edge_before: [u32; 12],
    /// The cells around the grid edge leaving corner `i` in direction `D`.
    pub(super) dir_cells: [[u32; 6]; 8],
    pub(super) quads: [[QuadCorner; 4]; 6],
    /// Patterns of kept cells around a vertex (bit `k` = cell `k`) whose
    /// boundary squares form one cycle around it.
    pub(super) manifold: [bool; 256],
}

impl Stencils {
    /// The process's stencils, built on first use.
    pub(super) fn get() -> &'static Stencils {
        static ST: std::sync::OnceLock<Stencils> = std::sync::OnceLock::new();
        ST.get_or_init(Stencils::new)
    }

    pub(super) fn new() -> Stencils {
        let mut st = Stencils {
            face: [0; 6],
            vert_cells: [[0; 8]; 8],
            edge_cells: [[0; 4]; 12],
            vert_all: [0; 8],
            vert_before: [0; 8],
            edge_all: [0; 12],
            edge_before: [0; 12],
            dir_cells: [[0; 6]; 8],
            quads: [[QuadCorner::default(); 4]; 6],
            manifold: manifold_patterns(),
        };
        for d in 0..6 {
            let mut v = [0; 3];
            v[d / 2] = if d % 2 == 1 { 1 } else { -1 };
            st.face[d] = nb_bit(v);
        }
        for i in 0..8 {
            for k in 0..8 {
                st.vert_cells[i][k] = nb_bit(sub(corner_off(i), corner_off(k)));
                st.vert_all[i] |= 1 << st.vert_cells[i][k];
                if k < i {
                    st.vert_before[i] |= 1 << st.vert_cells[i][k];
                }
            }
            for dd in 0..6 {
                let a = dd / 2;
                let base = if dd % 2 == 1 { corner_off(i) } else { sub(corner_off(i), unit(a)) };
                let mut m = 0;
                for c in edge_cells(base, a) {
                    m |= 1 << nb_bit(c);
                }
                st.dir_cells[i][dd] = m;
            }
        }
        for le in 0..12 {
            let a = le / 4;
            let base = add(if le & 1 == 1 { unit((a + 1) % 3) } else { [0; 3] }, if le & 2 == 2 { unit((a + 2) % 3) } else { [0; 3] });
            let cells = edge_cells(base, a);
            for k in 0..4 {
                st.edge_cells[le][k] = nb_bit(cells[k]);
                st.edge_all[le] |= 1 << st.edge_cells[le][k];
                if k < le & 3 {
                    st.edge_before[le] |= 1 << st.edge_cells[le][k];
                }
            }
            debug_assert_eq!(cells[le & 3], [0; 3]);
        }
        for d in 0..6 {
            let q = quad(d);
            for e in 0..4 {
                let (p0, p1) = (q[e], q[(e + 1) % 4]);
                let a = (0..3).find(|&i| p0[i] != p1[i]).unwrap();
                let neg = p1[a] < p0[a];
                let base = if neg { p1 } else { p0 };
                let (u, v) = ((a + 1) % 3, (a + 2) % 3);
                st.quads[d][e] = QuadCorner {
                    corner: (p0[0] + 2 * p0[1] + 4 * p0[2]) as u8,
                    edge: (4 * a as i32 + base[u] + 2 * base[v]) as u8,
                    neg: neg as u8,
                    dir: (2 * a + !neg as usize) as u8,
                };
            }
        }
        st
    }

    /// Bit `k` set when cell `k` around corner `i` is kept.
    #[inline]
    pub(super) fn vert_pattern(&self, nb: u32, i: usize) -> u32 {
        let mut p = 0;
        for (k, &b) in self.vert_cells[i].iter().enumerate() {
            p |= ((nb >> b) & 1) << k;
        }
        p
    }

    /// The first direction at corner `i` along a boundary edge (kept and
    /// removed cells around it), whose outgoing half-edge becomes `v_out`.
    #[inline]
    pub(super) fn first_dir(&self, nb: u32, i: usize) -> u8 {
        for (dd, &m) in self.dir_cells[i].iter().enumerate() {
            let t = nb & m;
            if t != 0 && t != m {
                return dd as u8;
            }
        }
        u8::MAX
    }
}

/// For every pattern of kept cells around a grid point, whether the squares
/// between kept and removed cells form one cycle around the point (a disk).
pub(super) fn manifold_patterns() -> [bool; 256] {
    let mut out = [false; 256];
    for (p, slot) in out.iter_mut().enumerate().take(255).skip(1) {
        // the link: nodes are the 6 edge directions, each square joins two
        let mut deg = [0u8; 6];
        let mut root: [usize; 6] = [0, 1, 2, 3, 4, 5];
        fn find(r: &[usize; 6], mut x: usize) -> usize {
            while r[x] != x {
                x = r[x];
            }
            x
        }
        for k in 0..8 {
            for a in 0..3 {
                let k2 = k ^ (1 << a);
                if k2 < k || (p >> k) & 1 == (p >> k2) & 1 {
                    continue;
                }
                // cell k lies on the negative side of axis b iff its offset bit b is 1
                let dirs = [(a + 1) % 3, (a + 2) % 3].map(|b| 2 * b + ((k >> b) & 1 == 0) as usize);
                deg[dirs[0]] += 1;
                deg[dirs[1]] += 1;
                let (r0, r1) = (find(&root, dirs[0]), find(&root, dirs[1]));
                root[r0] = r1;
            }
        }
        let used: Vec<usize> = (0..6).filter(|&d| deg[d] > 0).collect();
        let one = used.iter().all(|&d| find(&root, d) == find(&root, used[0]));
        *slot = deg.iter().all(|&d| d == 0 || d == 2) && one;
    }
    out
}

/// The digit-1 masks of the coordinates and the compact numbering of the
/// kept cells (module docs, "Construction").
pub(super) struct Cells {
    pub(super) n: usize,
    /// `ones` of coordinate `t` at index `t + 1`, [`OUT`] at both ends.
    pub(super) ones: Vec<u32>,
    /// First kept cell of row `(x, y)` at `x·n + y`; `n²` + 1 entries.
    pub(super) row_start: Vec<u32>,
    /// `z_rank[m·n + z]`: kept cells before `z` in a row of mask `m`.
    pub(super) z_rank: Vec<u32>,
    /// The kept `z` of a row of mask `m`.
    pub(super) z_list: Vec<Vec<u32>>,
    /// `window[m·n + z]`: bit `k` set when `z + k − 1` is kept in a row of
    /// mask `m`; one more row of zeros for empty rows.
    pub(super) window: Vec<u8>,
}

/// The rows around one row of cells (see [`Cells::row`]).
pub(super) struct Row {
    pub(super) start: [u32; 9],
    pub(super) off: [usize; 9],
}

impl Cells {
    pub(super) fn new(level: u32) -> Cells {
        let n = 3usize.pow(level);
        let mut ones = vec![OUT; n + 2];
        for t in 0..n {
            let (mut r, mut m, mut k) = (t, 0u32, 0);
            while r > 0 {
                if r % 3 == 1 {
                    m |= 1 << k;
                }
                r /= 3;
                k += 1;
            }
            ones[t + 1] = m;
        }
        let masks = 1usize << level;
        let mut z_rank = vec![0u32; (masks + 1) * n];
        let mut window = vec![0u8; (masks + 1) * n];
        let mut z_list = vec![Vec::new(); masks];
        for m in 0..masks {
            for z in 0..n {
                z_rank[m * n + z] = z_list[m].len() as u32;
                if ones[z + 1] & m as u32 == 0 {
                    z_list[m].push(z as u32);
                }
                for k in 0..3 {
                    if ones[z + k] & (m as u32 | OUT) == 0 {
                        window[m * n + z] |= 1 << k;
                    }
                }
            }
        }
        let mut row_start = Vec::with_capacity(n * n + 1);
        let mut k = 0u32;
        for x in 0..n {
            for y in 0..n {
                row_start.push(k);
                let (a, b) = (ones[x + 1], ones[y + 1]);
                if a & b == 0 {
                    k += z_list[(a | b) as usize].len() as u32;
                }
            }
        }
        row_start.push(k);
        Cells { n, ones, row_start, z_rank, z_list, window }
    }

    /// The 9 rows around row `(x, y)` (`i·3 + j` for `x + i − 1, y + j − 1`):
    /// their first cell and their `z_rank` / `window` row offsets (the empty
    /// row `2ⁿ` where a row is outside or empty).
    #[inline]
    pub(super) fn row(&self, x: usize, y: usize) -> Row {
        let (n, o) = (self.n, &self.ones);
        let empty = self.z_list.len() * n;
        let mut r = Row { start: [0; 9], off: [empty; 9] };
        for i in 0..3 {
            for j in 0..3 {
                let (a, b) = (o[x + i], o[y + j]);
                if (a | b) & OUT == 0 && a & b == 0 {
                    r.start[i * 3 + j] = self.row_start[(x + i - 1) * n + y + j - 1];
                    r.off[i * 3 + j] = (a | b) as usize * n;
                }
            }
        }
        r
    }

    /// Which of the 27 cells around cell `z` of the row are kept (bit
    /// `9i + 3j + k` for the offset `(i − 1, j − 1, k − 1)`).
    #[inline]
    pub(super) fn neighbourhood(&self, r: &Row, z: usize) -> u32 {
        let mut nb = 0u32;
        for (t, &off) in r.off.iter().enumerate() {
            nb |= (self.window[off + z] as u32) << (3 * t);
        }
        nb
    }

    /// Compact index of the kept cell at bit `b` of cell `z`'s neighbourhood
    /// mask (offset `(b / 9 − 1, b / 3 % 3 − 1, b % 3 − 1)` from it).
    #[inline]
    pub(super) fn index_bit(&self, r: &Row, z: usize, b: usize) -> usize {
        let t = b / 3;
        (r.start[t] + self.z_rank[r.off[t] + z + b % 3 - 1]) as usize
    }

    /// Calls `f(row, z, index)` for the kept cells of slab `x` in order.
    #[inline]
    pub(super) fn for_slab(&self, x: usize, mut f: impl FnMut(&Row, usize, usize, usize, usize)) {
        let n = self.n;
        let a = self.ones[x + 1];
        let mut ci = self.row_start[x * n] as usize;
        for y in 0..n {
            let b = self.ones[y + 1];
            if a & b != 0 {
                continue;
            }
            let r = self.row(x, y);
            for &z in &self.z_list[(a | b) as usize] {
                f(&r, x, y, z as usize, ci);
                ci += 1;
            }
        }
    }

    /// The cell range of slab `x`.
    pub(super) fn slab(&self, x: usize) -> std::ops::Range<usize> {
        self.row_start[x * self.n] as usize..self.row_start[(x + 1) * self.n] as usize
    }
}

/// Splits `s` into the consecutive pieces of lengths `lens`.
pub(super) fn split_lens<T>(mut s: &mut [T], lens: impl Iterator<Item = usize>) -> Vec<&mut [T]> {
    let mut out = Vec::new();
    for l in lens {
        let (a, b) = std::mem::take(&mut s).split_at_mut(l);
        out.push(a);
        s = b;
    }
    out
}

