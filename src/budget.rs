//! The memory budget: calls predict the peak bytes of each level from its
//! count formulas and refuse with [`MeshError::Memory`] before allocating
//! what the machine cannot hold, instead of dying in the allocator's abort.
//!
//! The budget is process-wide: set by [`set`] (Python
//! `topomesh.set_memory_budget`), else by the environment variable
//! `TOPOMESH_MEMORY_BUDGET` (bytes, optionally with a `K`/`M`/`G`/`T` suffix,
//! powers of 1024), else from the machine, recomputed at each check:
//! `MemAvailable` of `/proc/meminfo`, lowered to the room left under the
//! soft address-space limit (`RLIMIT_AS`) when one is set. Where `/proc` is
//! missing the machine imposes no budget and only the allocation probe
//! ([`probe`]) guards.
//!
//! Predictions use generous per-element costs: the stored mesh (docs/internals.md,
//! "Memory": 16 B per half-edge, 28 per vertex, 5 per face) plus the
//! builder's temporaries, calibrated against measured peak RSS (see
//! [`LEVEL_FACTOR`]). All arithmetic saturates, so a prediction never wraps.

use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, POINT};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

static USER_SET: AtomicBool = AtomicBool::new(false);
static USER_BYTES: AtomicU64 = AtomicU64::new(0);

/// The environment variable read when no budget was set by [`set`].
pub const ENV_VAR: &str = "TOPOMESH_MEMORY_BUDGET";

/// Sets the budget in bytes, or `None` to go back to the environment
/// variable / machine default.
pub fn set(bytes: Option<u64>) {
    match bytes {
        Some(b) => {
            USER_BYTES.store(b, Ordering::Relaxed);
            USER_SET.store(true, Ordering::Relaxed);
        }
        None => USER_SET.store(false, Ordering::Relaxed),
    }
}

/// The budget in force, in bytes (`u64::MAX` when nothing limits it).
///
/// Fails when `TOPOMESH_MEMORY_BUDGET` is set but not a size.
pub fn get() -> Result<u64> {
    if USER_SET.load(Ordering::Relaxed) {
        return Ok(USER_BYTES.load(Ordering::Relaxed));
    }
    if let Ok(s) = std::env::var(ENV_VAR) {
        return parse_size(&s).ok_or_else(|| {
            MeshError::InvalidArgument(format!(
                "{ENV_VAR}={s:?} is not a size in bytes (an integer >= 0, optionally followed by K, M, G or T)"
            ))
        });
    }
    Ok(machine())
}

/// `"123"`, `"8G"`, `"1.5T"`, `"512 MiB"` → bytes (suffixes are powers of 1024).
pub fn parse_size(s: &str) -> Option<u64> {
    let t = s.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let x: f64 = num.parse().ok()?;
    let unit = unit.trim().to_ascii_uppercase();
    let unit = unit.trim_end_matches("IB").trim_end_matches('B');
    let mult = match unit {
        "" => 1u64,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        "T" => 1 << 40,
        _ => return None,
    };
    let b = x * mult as f64;
    (b.is_finite() && b >= 0.0).then(|| if b >= u64::MAX as f64 { u64::MAX } else { b as u64 })
}

/// What the machine can give now: `MemAvailable`, and no more than the room
/// left under the soft `RLIMIT_AS` (read from `/proc/self/limits`, minus the
/// current `VmSize`). `u64::MAX` where neither is known.
pub fn machine() -> u64 {
    let avail = proc_field("/proc/meminfo", "MemAvailable:").unwrap_or(u64::MAX);
    let room = address_space_limit()
        .map(|lim| lim.saturating_sub(proc_field("/proc/self/status", "VmSize:").unwrap_or(0)))
        .unwrap_or(u64::MAX);
    avail.min(room)
}

/// A `kB` field of a `/proc` file, in bytes.
fn proc_field(path: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(path).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kb: u64 = line[key.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kb.saturating_mul(1024))
}

/// The soft address-space limit in bytes, `None` when unlimited or unknown.
fn address_space_limit() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..].split_whitespace().next()?.parse().ok()
}

/// Bytes as `"41.2 GB"` (decimal units, as the messages compare magnitudes).
pub fn human(b: u64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut x = b as f64;
    let mut k = 0;
    while x >= 1000.0 && k + 1 < units.len() {
        x /= 1000.0;
        k += 1;
    }
    if k == 0 {
        format!("{b} B")
    } else {
        format!("{x:.1} {}", units[k])
    }
}

/// Refuses `bytes` for `call` (`what` says which level, e.g. `"level 12 of
/// 15"`) when it exceeds the budget, then probes the allocation ([`probe`]).
pub fn check(call: &str, what: &str, bytes: u64) -> Result<()> {
    // the machine surely has this much: skip reading /proc for small levels
    if bytes < SMALL && !USER_SET.load(Ordering::Relaxed) && std::env::var_os(ENV_VAR).is_none() {
        return Ok(());
    }
    let budget = get()?;
    if bytes > budget {
        return Err(MeshError::Memory(format!(
            "{call}: {what} needs about {}, more than the memory budget of {} (topomesh.set_memory_budget or {ENV_VAR} sets it)",
            human(bytes),
            human(budget)
        )));
    }
    probe(call, what, bytes)
}

/// Levels below this are checked only against a budget the user set.
const SMALL: u64 = 16 << 20;

/// Faces of more corners than this count in [`check_stencils`].
const DENSE_FACE: usize = 64;

/// Bytes per stencil term, with the rows' construction: an open
/// `conway("P8000")` with one corner attribute (the transfer reads the
/// stencils) peaked at 1.2 GB through Doo-Sabin and 1.9 GB through
/// honeycomb, for 64 M terms over its 8,000-gon.
const STENCIL_TERM_BYTES: u64 = 32;

/// Stencil terms per (row, column) pair of an n-gon for the schemes whose
/// rows over a face are dense (each output point born in or beside the
/// face weighs all its corners), counted on `conway("P1000")` with and
/// without one cap: Catmull-Clark 2 (edge and vertex points hold the face
/// point), Loop 3 (through its centroid fan), Doo-Sabin and honeycomb 1;
/// the others' rows over a face are linear in its size.
pub fn dense_terms(scheme: &str) -> u64 {
    match scheme {
        "catmull_clark" => 2,
        "loop" => 3,
        "doo_sabin" | "honeycomb" => 1,
        _ => 0,
    }
}

/// Refuses a level's stencils (the subdivision matrix, and what vertex and
/// corner data read through it) when the dense rows over the input's
/// large faces would not fit: [`dense_terms`] × Σ n² over the real faces of
/// more than [`DENSE_FACE`] corners, at [`STENCIL_TERM_BYTES`] (a
/// 32,000-gon's Doo-Sabin rows alone are about 33 GB). Ordinary faces are
/// not counted: their rows are within the level's own prediction.
pub fn check_stencils(call: &str, m: &Mesh) -> Result<()> {
    let per = dense_terms(call);
    if per == 0 {
        return Ok(());
    }
    let (mut pairs, mut largest) = (0u64, (0usize, 0usize));
    for f in m.faces() {
        if m.is_hole(f) || m.f_start[f.idx()] & POINT != 0 {
            continue;
        }
        let n = m.face_degree(f);
        if n > DENSE_FACE {
            pairs = pairs.saturating_add((n as u64).saturating_mul(n as u64));
            if n > largest.1 {
                largest = (f.idx(), n);
            }
        }
    }
    if pairs == 0 {
        return Ok(());
    }
    let terms = pairs.saturating_mul(per);
    let what = format!(
        "its stencils (the subdivision matrix, which vertex and corner data on open or creased meshes go through), about {terms} terms over face {} of {} corners and the other faces of more than {DENSE_FACE}",
        largest.0, largest.1
    );
    check(call, &what, terms.saturating_mul(STENCIL_TERM_BYTES))
}

/// Below this a probe is not worth a system call.
const PROBE_MIN: u64 = 64 << 20;

/// Reserves `bytes` fallibly and gives them back at once: the pages are never
/// touched, so on Linux this costs one `mmap`/`munmap`, and an address-space
/// limit or an overcommit refusal becomes a [`MeshError::Memory`] here
/// instead of an abort in the middle of the level.
pub fn probe(call: &str, what: &str, bytes: u64) -> Result<()> {
    if bytes < PROBE_MIN {
        return Ok(());
    }
    let fail = || {
        MeshError::Memory(format!(
            "{call}: {what} needs about {}, and the system refused to reserve it (address-space limit or no memory left)",
            human(bytes)
        ))
    };
    let n = usize::try_from(bytes).map_err(|_| fail())?;
    let mut v: Vec<u8> = Vec::new();
    v.try_reserve_exact(n).map_err(|_| fail())?;
    drop(v);
    Ok(())
}

/// Element counts of a mesh, the input of the size predictors. `f3`
/// (triangles), `loops` (self-loops) and `cones` (Sierpinski cones) refine
/// some formulas; a predictor that cannot know one sets it to the value that
/// makes later predictions an upper bound.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub v: u64,
    pub e: u64,
    pub f: u64,
    /// Faces that are triangles (lower bound).
    pub f3: u64,
    /// Self-loops (upper bound).
    pub loops: u64,
    /// Sierpinski cones (upper bound; see `schemes::sierpinski`).
    pub cones: u64,
    /// Hole faces (boundary loops), counted in `f` (exact: every scheme
    /// that accepts an open mesh keeps its holes).
    pub holes: u64,
    /// Corners of the hole faces: the boundary edges (upper bound).
    pub boundary: u64,
}

impl Counts {
    /// Counts of `m`, in one pass over faces and edges.
    pub fn of(m: &Mesh) -> Counts {
        let next = &m.he_next;
        let f3 = m
            .f_start
            .iter()
            .filter(|&&s| {
                if s & POINT != 0 {
                    return false;
                }
                let a = next[s as usize];
                let b = next[a as usize];
                a != s && b != s && next[b as usize] == s
            })
            .count() as u64;
        let loops = m.n_self_loops() as u64;
        let (holes, boundary) = if m.n_holes() == 0 {
            (0, 0)
        } else {
            let b = (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count();
            (m.n_holes() as u64, b as u64)
        };
        Counts { holes, boundary, ..Counts::closed(m.n_vertices() as u64, m.n_edges() as u64, m.n_faces() as u64, f3, loops) }
    }

    /// Counts of a closed mesh of `v` vertices, `e` edges (`loops` of them
    /// self-loops) and `f` faces (`f3` triangles): what [`Counts::of`] gives
    /// for it, for a fused build whose intermediate mesh is never built.
    pub fn closed(v: u64, e: u64, f: u64, f3: u64, loops: u64) -> Counts {
        // one cone per vertex without self-loops; at most one per non-loop half-edge
        let cones = if loops == 0 { v } else { 2 * (e - loops) };
        Counts { v, e, f, f3, loops, cones, holes: 0, boundary: 0 }
    }

    /// Counts of a mesh of `v` vertices, `e` edges and `f` faces, nothing
    /// else known: no triangles and no self-loops, one cone per half-edge
    /// (the values that keep later predictions upper bounds).
    pub fn plain(v: u64, e: u64, f: u64) -> Counts {
        Counts { v, e, f, f3: 0, loops: 0, cones: e.saturating_mul(2), holes: 0, boundary: 0 }
    }
}

/// Bytes of a stored mesh (docs/internals.md, "Memory").
pub fn mesh_bytes(c: &Counts) -> u64 {
    c.e.saturating_mul(32).saturating_add(c.v.saturating_mul(28)).saturating_add(c.f.saturating_mul(5))
}

/// Peak bytes of building one level's output over its input mesh's bytes: the
/// output columns, the points buffer, corner-vertex and twin arrays, the
/// half-edge numbering and the face layout of the input. Measured growth of
/// peak RSS during one level (release build, 2 threads), over the output
/// mesh's own bytes: dual 0.87, sqrt3 1.18, simplest 1.26, vertex_truncation
/// 1.29, catmull_clark and midpoint 1.34, doo_sabin 1.56, honeycomb 1.59,
/// sierpinski 1.76, loop on quads (fanned first) 1.93, torus 2.31, menger
/// 2.92 (on 1–5 M-element outputs); 4 keeps every prediction above them.
/// (Menger's thickness reduction needs more and is checked on its own:
/// `schemes::menger`, `REDUCTION_PEAK`.)
pub const LEVEL_FACTOR: u64 = 4;

/// Predicted peak of one level: its input stays alive while the output and
/// the builder's temporaries are allocated.
pub fn level_bytes(input: &Counts, output: &Counts) -> u64 {
    mesh_bytes(input).saturating_add(mesh_bytes(output).saturating_mul(LEVEL_FACTOR))
}

/// Predicted peak of building a fresh mesh with these counts (primitives,
/// `from_polygons`): the mesh, its polygon input and the builder's arrays.
pub fn build_bytes(c: &Counts) -> u64 {
    mesh_bytes(c).saturating_mul(LEVEL_FACTOR + 1)
}

/// A scheme's count formulas for one level: `(lower, upper)` bounds of the
/// output counts (equal where the formulas are exact).
pub type Predictor = fn(&Counts) -> (Counts, Counts);

/// Checks every level of `levels` steps of `call` up front, from `start`,
/// with the lower-bound chain (so what it refuses could certainly not run).
pub fn check_levels(call: &str, start: &Counts, levels: u64, step: Predictor) -> Result<()> {
    let budget = get()?;
    let (mut before, mut lo) = (None, *start);
    let mut work = 0u64;
    for k in 1..=levels {
        let next = step(&lo).0;
        // counts that stay, or come back after two levels (dual), repeat
        // from here on: the levels left cost what these two cost, each
        if before == Some(next) || next == lo {
            let each = level_work(&lo).max(level_work(&next));
            return check_work(call, start, levels, work.saturating_add((levels - k + 1).saturating_mul(each)), k - 1, each);
        }
        work = work.saturating_add(level_work(&next));
        check_work(call, start, levels, work, k - 1, level_work(&next))?;
        check_ids(call, k, levels, &next)?;
        let need = level_bytes(&lo, &next);
        if need > budget {
            return Err(MeshError::Memory(format!(
                "{call}: level {k} of {levels} needs about {}, more than the memory budget of {} (topomesh.set_memory_budget or {ENV_VAR} sets it)",
                human(need),
                human(budget)
            )));
        }
        before = Some(lo);
        lo = next;
    }
    Ok(())
}

/// The most work one call of a multi-level scheme may be asked for, in
/// `level_work` units: about two minutes at this machine's 10–20 ns per
/// output half-edge. Only levels whose counts do not grow reach it (a
/// growing scheme meets the memory budget first): a dual asked for 10¹²
/// iterations would otherwise run for days, with no error to tell the typo.
pub const WORK_LIMIT: u64 = 10_000_000_000;

/// Work of one level with output `c`: its half-edges, plus a level's fixed
/// cost (allocation, set-up, a progress poll), counted as 4,096.
fn level_work(c: &Counts) -> u64 {
    c.e.saturating_mul(2).saturating_add(4096)
}

/// Refuses a call whose levels add up to more than [`WORK_LIMIT`]; `done`
/// levels cost `work` so far, each further one about `each`.
fn check_work(call: &str, start: &Counts, levels: u64, work: u64, done: u64, each: u64) -> Result<()> {
    if work <= WORK_LIMIT {
        return Ok(());
    }
    let most = done.max(WORK_LIMIT / each.max(1));
    Err(MeshError::InvalidArgument(format!(
        "{call}: iterations = {levels} on this mesh ({} faces) is about {work:.1e} output half-edges of work, more than one call runs ({WORK_LIMIT:.0e}, minutes); at most about {most} iterations here",
        start.f,
        work = work as f64,
        WORK_LIMIT = WORK_LIMIT as f64
    )))
}

/// Checks one level `k` of `levels` of `call` from the real counts of its
/// input, with the upper bound, and probes the allocation.
pub fn check_level(call: &str, k: u64, levels: u64, input: &Counts, step: Predictor) -> Result<()> {
    let out = step(input).1;
    check_ids(call, k, levels, &out)?;
    check(call, &format!("level {k} of {levels}"), level_bytes(input, &out))
}

/// The 31-bit id limit (docs/internals.md), checked on predicted counts.
fn check_ids(call: &str, k: u64, levels: u64, c: &Counts) -> Result<()> {
    let max = crate::mesh::MAX_ELEMENTS as u64;
    if c.e.saturating_mul(2) > max || c.v > max || c.f > max {
        return Err(MeshError::Memory(format!(
            "{call}: level {k} of {levels} would have about {} vertices, {} edges and {} faces, more than 31-bit ids allow ({max} of each, half as many edges)",
            c.v, c.e, c.f
        )));
    }
    Ok(())
}

/// Count formulas of the schemes (each scheme's module docs), as
/// [`Predictor`]s. Saturating throughout.
pub mod predict {
    use super::Counts;

    fn add(a: u64, b: u64) -> u64 {
        a.saturating_add(b)
    }
    fn mul(a: u64, b: u64) -> u64 {
        a.saturating_mul(b)
    }
    fn exact(c: Counts) -> (Counts, Counts) {
        (c, c)
    }

    /// A closed-mesh prediction made valid for an input with holes (h hole
    /// faces, b boundary edges). The holes stay holes, unrefined, so the
    /// closed formulas overcount by at most what refining them would make:
    /// a hole of n sides refined as a face (Loop fans it first) gives at
    /// most n + 1 vertices, 5n edges and 4n faces. The boundary rules add at
    /// most 2b vertices and edges (the dual: F_r + b + V_b vertices,
    /// E + 2b edges; Doo-Sabin's, √3's and simplest's boundary points at
    /// most b) and the h holes as faces (the dual's F' = V + h). Output
    /// boundaries have at most 3b edges (√3's even levels trisect them, the
    /// others at most halve), and as many holes. Bounds, not exact counts:
    /// the lower one only makes the up-front refusal (`check_levels`)
    /// refuse less. Closed inputs (h = b = 0) get the closed formulas.
    fn open(c: &Counts, (lo, hi): (Counts, Counts)) -> (Counts, Counts) {
        if c.holes == 0 && c.boundary == 0 {
            return (lo, hi);
        }
        let (h, b) = (c.holes, c.boundary);
        let sub = |x: u64, y: u64| x.saturating_sub(y);
        let bb = mul(3, b);
        let lo = Counts { v: sub(lo.v, add(b, h)), e: sub(lo.e, mul(5, b)), f: sub(lo.f, mul(4, b)), f3: sub(lo.f3, mul(4, b)), holes: h, boundary: bb, ..lo };
        let hi = Counts { v: add(hi.v, mul(2, b)), e: add(hi.e, mul(2, b)), f: add(hi.f, h), holes: h, boundary: bb, ..hi };
        (lo, hi)
    }

    /// V' = V + E + F, E' = 4E, F' = 2E (quads).
    pub fn catmull_clark(c: &Counts) -> (Counts, Counts) {
        open(c, exact(Counts::plain(add(add(c.v, c.e), c.f), mul(4, c.e), mul(2, c.e)).no_loops()))
    }
    /// V' = 2E, E' = 4E, F' = F + E + V.
    pub fn doo_sabin(c: &Counts) -> (Counts, Counts) {
        open(c, exact(Counts::plain(mul(2, c.e), mul(4, c.e), add(add(c.f, c.e), c.v)).no_loops()))
    }
    /// n-gons fanned into n triangles first (T = 2E − 2F₃ triangles,
    /// E_t = 3E − 3F₃, V_t = V + F − F₃), then V' = V_t + E_t, E' = 2E_t + 3T, F' = 4T.
    pub fn loop_subdivision(c: &Counts) -> (Counts, Counts) {
        let f3 = c.f3.min(c.f);
        let t = mul(2, c.e).saturating_sub(mul(2, f3));
        let et = mul(3, c.e).saturating_sub(mul(3, f3));
        let vt = add(c.v, c.f - f3);
        let out = Counts { f3: mul(4, t), ..Counts::plain(add(vt, et), add(mul(2, et), mul(3, t)), mul(4, t)) };
        open(c, exact(out.no_loops()))
    }
    /// V' = V + F, E' = 3E, F' = 2E (triangles).
    pub fn sqrt3(c: &Counts) -> (Counts, Counts) {
        let f = mul(2, c.e);
        open(c, exact(Counts { f3: f, ..Counts::plain(add(c.v, c.f), mul(3, c.e), f) }.no_loops()))
    }
    /// V' = E, E' = 2E, F' = F + V.
    pub fn simplest(c: &Counts) -> (Counts, Counts) {
        open(c, exact(Counts::plain(c.e, mul(2, c.e), add(c.f, c.v)).no_loops()))
    }
    /// Triangles 1 → 4, n-gons into n quads: V' = V + E + (F − F₃),
    /// F' = 2E + F₃, E' = 4E.
    pub fn midpoint(c: &Counts) -> (Counts, Counts) {
        let f3 = c.f3.min(c.f);
        let out = Counts { f3: mul(4, f3), ..Counts::plain(add(add(c.v, c.e), c.f - f3), mul(4, c.e), add(mul(2, c.e), f3)) };
        open(c, exact(out.no_loops()))
    }
    /// V' = F, E' = E, F' = V.
    pub fn dual(c: &Counts) -> (Counts, Counts) {
        open(c, exact(Counts::plain(c.f, c.e, c.v)))
    }
    /// Honeycomb and vertex truncation: V' = 2E, E' = 3E, F' = F + V (the
    /// rectifying ratio 0.5 gives fewer).
    pub fn truncation(c: &Counts) -> (Counts, Counts) {
        open(c, exact(Counts::plain(mul(2, c.e), mul(3, c.e), add(c.f, c.v)).no_loops()))
    }
    /// Sierpinski (schemes::sierpinski, "Count formulas"), with D = 0 and
    /// every face having a non-loop side: V' = V + N, E' = E + 4N,
    /// F' = 2N + K + F₀ (F₀ ≤ F), L' = L + N, K' = K + 2N.
    pub fn sierpinski(c: &Counts) -> (Counts, Counts) {
        let n = c.e.saturating_sub(c.loops);
        let lo = Counts {
            v: add(c.v, n),
            e: add(c.e, mul(4, n)),
            f: add(mul(2, n), c.cones.min(c.v)),
            f3: 0,
            loops: add(c.loops, n),
            cones: add(c.cones, mul(2, n)),
            ..Counts::default()
        };
        let hi = Counts { f: add(add(mul(2, n), c.cones), c.f), ..lo };
        (lo, hi)
    }
    /// Generalized Menger (schemes::menger, "Counts"): V' = V + 4E + G + 2E_m
    /// with G ≤ 2E, E_m ≤ E; F' = 6E + S + 2E_m + W + splits; at least the
    /// 6E quads (24E corners, so E' ≥ 12E); at most 44E corners (strip or
    /// miter quads per edge, vertex faces with 2E corners, cones of up to
    /// 4E triangles from one apex per vertex, splits).
    pub fn menger(c: &Counts) -> (Counts, Counts) {
        let lo = Counts::plain(add(c.v, mul(4, c.e)), mul(12, c.e), mul(6, c.e)).no_loops();
        // (per-face corners, `Offset::PerFace`: a cone apex per vertex and
        // up to 4E cone triangles, 44E corners)
        let hi = Counts::plain(add(mul(2, c.v), mul(8, c.e)), mul(22, c.e), add(mul(12, c.e), c.v)).no_loops();
        (lo, hi)
    }

    impl Counts {
        /// The output of a scheme that makes no self-loops: one cone per vertex.
        fn no_loops(self) -> Counts {
            Counts { loops: 0, cones: self.v, ..self }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;
    use crate::schemes;

    #[test]
    fn sizes_parse() {
        assert_eq!(parse_size("123"), Some(123));
        assert_eq!(parse_size("8G"), Some(8 << 30));
        assert_eq!(parse_size("512 MiB"), Some(512 << 20));
        assert_eq!(parse_size("1.5k"), Some(1536));
        assert_eq!(parse_size("lots"), None);
        assert_eq!(parse_size("-1"), None);
    }

    #[test]
    fn predictors_match_the_schemes() {
        type S = fn(&Mesh) -> Result<Mesh>;
        let cases: [(&str, S, Predictor); 8] = [
            ("catmull_clark", schemes::catmull_clark::catmull_clark, predict::catmull_clark),
            ("doo_sabin", schemes::doo_sabin::doo_sabin, predict::doo_sabin),
            ("loop", schemes::loop_subdivision::loop_subdivision, predict::loop_subdivision),
            ("sqrt3", schemes::sqrt3::sqrt3, predict::sqrt3),
            ("simplest", schemes::simplest::simplest, predict::simplest),
            ("midpoint", schemes::midpoint::midpoint, predict::midpoint),
            ("dual", schemes::dual::dual, predict::dual),
            ("sierpinski", schemes::sierpinski::sierpinski, predict::sierpinski),
        ];
        let inputs = [primitives::cube(), primitives::tetrahedron(), primitives::dodecahedron(), primitives::torus(5, 4, 2.0, 0.5).unwrap()];
        for (name, scheme, step) in cases {
            for m0 in &inputs {
                // two levels: the second starts from a scheme's output
                let mut m = m0.clone();
                for _ in 0..2 {
                    let (lo, hi) = step(&Counts::of(&m));
                    let r = scheme(&m).unwrap();
                    let got = Counts::of(&r);
                    for (a, l, h, what) in [(got.v, lo.v, hi.v, "V"), (got.e, lo.e, hi.e, "E"), (got.f, lo.f, hi.f, "F")] {
                        assert!(l <= a && a <= h, "{name}: {what} = {a} outside predicted [{l}, {h}]");
                    }
                    m = r;
                }
            }
        }
    }

    /// The predictors bound the real counts on open meshes too (hole faces
    /// counted as faces, as `Counts::of` does), two levels deep: a disk, an
    /// annulus, a box and an icosahedron with holes, and a genus-2 surface
    /// with three holes.
    #[test]
    fn predictors_bound_open_meshes() {
        use crate::mesh::BuildOptions;
        use crate::schemes::hosts::test_meshes::open_meshes;
        use crate::schemes::level::{Level, Request};
        let g = primitives::genus_surface(2).unwrap().to_polygons();
        let nf = g.sizes.len();
        let drop = [0, nf / 3, 2 * nf / 3];
        let (mut sizes, mut idx, mut k) = (Vec::new(), Vec::new(), 0usize);
        for (f, &n) in g.sizes.iter().enumerate() {
            if !drop.contains(&f) {
                sizes.push(n as i64);
                idx.extend(g.indices[k..k + n as usize].iter().map(|&v| v as i64));
            }
            k += n as usize;
        }
        let opts = BuildOptions { close_boundaries: true, ..Default::default() };
        let genus2 = Mesh::from_polygons(primitives::genus_surface(2).unwrap().positions().to_vec(), &sizes, &idx, opts).unwrap();
        assert_eq!(genus2.n_holes(), 3);
        let mut meshes = open_meshes();
        meshes.push(("genus2_three_holes", genus2));
        type L = fn(&Mesh, &Request) -> Result<Level>;
        fn honeycomb(m: &Mesh, r: &Request) -> Result<Level> {
            schemes::honeycomb::honeycomb_level(m, 0.5, None, r)
        }
        fn truncation(m: &Mesh, r: &Request) -> Result<Level> {
            schemes::vertex_truncation::vertex_truncation_level(m, schemes::vertex_truncation::Truncation::Polyhedral { ratio: 0.3 }, r)
        }
        let cases: [(&str, L, Predictor); 9] = [
            ("catmull_clark", schemes::catmull_clark::catmull_clark_level, predict::catmull_clark),
            ("doo_sabin", schemes::doo_sabin::doo_sabin_level, predict::doo_sabin),
            ("loop", schemes::loop_subdivision::loop_level, predict::loop_subdivision),
            ("sqrt3", schemes::sqrt3::sqrt3_level, predict::sqrt3),
            ("simplest", schemes::simplest::simplest_level, predict::simplest),
            ("midpoint", schemes::midpoint::midpoint_level, predict::midpoint),
            ("dual", schemes::dual::dual_level, predict::dual),
            ("honeycomb", honeycomb, predict::truncation),
            ("vertex_truncation", truncation, predict::truncation),
        ];
        for (name, level, step) in cases {
            for (mname, m0) in &meshes {
                let mut m = m0.clone();
                // the lower bounds chained from the input, as check_levels does
                let mut chain = Counts::of(&m);
                for k in 0..2 {
                    let c = Counts::of(&m);
                    let (lo, hi) = step(&c);
                    chain = step(&chain).0;
                    let r = level(&m, &Request { level: k, ..Request::plain() }).unwrap().mesh;
                    assert!(r.n_holes() > 0, "{name} {mname}: stays open");
                    let got = Counts::of(&r);
                    for (a, l, h, cl, what) in [(got.v, lo.v, hi.v, chain.v, "V"), (got.e, lo.e, hi.e, chain.e, "E"), (got.f, lo.f, hi.f, chain.f, "F")] {
                        assert!(l <= a && a <= h, "{name} on {mname}, level {k}: {what} = {a} outside predicted [{l}, {h}]");
                        assert!(cl <= a, "{name} on {mname}, level {k}: {what} = {a} below the chained lower bound {cl}");
                    }
                    assert!(got.boundary <= hi.boundary && got.holes == hi.holes, "{name} on {mname}: boundary {} > {}", got.boundary, hi.boundary);
                    m = r;
                }
            }
        }
    }

    #[test]
    fn menger_bounds_hold() {
        let o = schemes::menger::MengerOptions { thickness: 1.0 / 3.0, relative: true, collapse_angle: 90.0, offset: schemes::menger::Offset::Merged, ..Default::default() };
        let pf = schemes::menger::MengerOptions { offset: schemes::menger::Offset::PerFace, ..o };
        let oct2 = schemes::menger::menger(&primitives::octahedron(), &pf).unwrap();
        for m in [primitives::cube(), primitives::tetrahedron(), primitives::dodecahedron(), oct2] {
            let (lo, hi) = predict::menger(&Counts::of(&m));
            for opt in [&o, &pf] {
                let got = Counts::of(&schemes::menger::menger(&m, opt).unwrap());
                for (a, l, h) in [(got.v, lo.v, hi.v), (got.e, lo.e, hi.e), (got.f, lo.f, hi.f)] {
                    assert!(l <= a && a <= h, "menger: {a} outside [{l}, {h}]");
                }
            }
        }
    }

    #[test]
    fn refusals_name_the_level_and_bytes() {
        let c = Counts::of(&primitives::cube());
        let e = check_levels("catmull_clark", &c, 15, predict::catmull_clark).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, MeshError::Memory(_)));
        assert!(msg.starts_with("catmull_clark: level ") && msg.contains(" of 15 "), "{msg}");
        assert!(check_levels("catmull_clark", &c, 3, predict::catmull_clark).is_ok());
        assert!(probe("t", "x", u64::MAX).is_err());
        assert!(probe("t", "x", 100 << 20).is_ok());
    }

    /// Levels whose counts repeat (dual) never meet the memory budget: a
    /// typo of 10¹² iterations is refused by the work limit, at once, and
    /// the refusal names the iterations and how many would run.
    #[test]
    fn repeating_levels_meet_the_work_limit() {
        let c = Counts::of(&primitives::cube());
        let t = std::time::Instant::now();
        let e = check_levels("dual", &c, 1_000_000_000_000, predict::dual).unwrap_err();
        assert!(t.elapsed().as_secs_f64() < 1.0, "the check itself must not iterate the levels");
        let msg = e.to_string();
        assert!(matches!(e, MeshError::InvalidArgument(_)), "{msg}");
        assert!(msg.starts_with("dual: iterations = 1000000000000 on this mesh (6 faces)") && msg.contains("at most about"), "{msg}");
        // the bound it states is allowed, ten times more is not
        let most: u64 = msg.rsplit("at most about ").next().unwrap().split(' ').next().unwrap().parse().unwrap();
        assert!(check_levels("dual", &c, most, predict::dual).is_ok(), "{msg}");
        assert!(check_levels("dual", &c, 10 * most, predict::dual).is_err());
        // ordinary requests pass
        assert!(check_levels("dual", &c, 1000, predict::dual).is_ok());
    }
}
