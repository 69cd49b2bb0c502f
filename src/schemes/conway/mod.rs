//! Conway's polyhedron operators in George Hart's notation, on any closed
//! manifold mesh: any face size, non-convex faces, self-loops, two-gons,
//! point-spheres, any genus and several components. Meshes with boundary
//! loops (hole faces) are refused: the operators have no boundary rules.
//!
//! Sources: G. W. Hart, "Conway Notation for Polyhedra"
//! (<http://www.georgehart.com/virtual-polyhedra/conway_notation.html>) for
//! the notation, the seeds and the relations (`t = dkd`, `j = da`,
//! `e = aa`, `o = de`, `s = dg`, `b = ta`, `m = kj`, `n = kd`, `z = dk`,
//! `tN`, `kN`); A. Levskaya's polyhedronisme
//! (<https://github.com/levskaya/polyhedronisme>, `topo_operators.js`,
//! `polyhedronisme.js`: its flag constructions, parser and seeds) for the
//! primitive operators' topology and positions (face centroids, edge points
//! at 1/3, inset 0.5, kis apex 0.1 along the normal), and the extended
//! operators `c u w v p q l` as Wikipedia's "Conway polyhedron notation"
//! lists them. Deviations from polyhedronisme are stated where they occur:
//! nothing is projected to the unit sphere (inputs need not surround the
//! origin), chamfer insets instead of pushing outwards, `u` is Conway's
//! subdivide (`dcd`) and not polyhedronisme's triangle-only `trisub`, and
//! `n` is needle (`kd`), not polyhedronisme's inset. [`canonical`] gives
//! Hart's canonical shape.
//!
//! The primitives are built in one pass from the half-edge columns
//! ([`build::Out`]: sides paired by edge id, never by vertex pairs), so
//! orientation is the input's: the chiral operators `g s w p` (and `v`)
//! turn the way the face order says, and the result of a mirror image is
//! the mirror image of the result on every genus. `d` is
//! [`crate::schemes::dual`] (face centroids; Hart's `d` in topology:
//! V' = F, E' = E, F' = V, the face of vertex v has its valence).
//! Compositions are written once, in [`Op::apply`].
//!
//! Counts (χ = V − E + F, genus and components are kept by every operator;
//! S the faces of size N, Σ their corners; for `tN`, `nN` the vertices of
//! valence N and their valences):
//!
//! | op | name | is | V' | E' | F' | faces |
//! |---|---|---|---|---|---|---|
//! | d | dual | | F | E | V | V of size valence |
//! | a | ambo | | E | 2E | F + V | F of size n, V of size valence |
//! | t, tN | truncate | dkd | 2E | 3E | F + V | F of size 2n, V of size valence |
//! | k, kN | kis | | V + F | 3E | 2E | 2E triangles |
//! | j | join | da | V + F | 2E | E | E quads |
//! | e | expand | aa | 2E | 4E | F + V + E | F of n, V of valence, E quads |
//! | o | ortho | de | V + F + E | 4E | 2E | 2E quads |
//! | g | gyro | | V + F + 2E | 5E | 2E | 2E pentagons |
//! | s | snub | dg | 2E | 5E | F + V + 2E | F of n, V of valence, 2E triangles |
//! | b | bevel | ta | 4E | 6E | F + V + E | F of 2n, V of 2·valence, E quads |
//! | m | meta | kj | V + F + E | 6E | 4E | 4E triangles |
//! | n, nN | needle | kd | V + F | 3E | 2E | 2E triangles |
//! | z, zN | zip | dk | 2E | 3E | F + V | F of n, V of 2·valence |
//! | c | chamfer | | V + 2E | 4E | F + E | F of n, E hexagons |
//! | u | subdivide | dcd | V + E | 4E | F + 2E | F of n, 2E triangles |
//! | w | whirl | | V + 4E | 7E | F + 2E | F of n, 2E hexagons |
//! | v | volute | dwd | V + 2E | 7E | F + 4E | F of n, 4E triangles |
//! | p | propellor | | V + 2E | 5E | F + 2E | F of n, 2E quads |
//! | q | quinto | | V + 3E | 6E | F + 2E | F of n, 2E pentagons |
//! | l, lN | loft | | V + 2E | 5E | F + 2E | F of n, 2E quads |
//! | r | reflect | | V | E | F | the same, mirrored |
//!
//! With a number N, `k`, `l`, `z` act on the N-sided faces only and `t`,
//! `n` on the N-valent vertices only; faces (vertices) of other sizes stay.

mod ambo;
mod bevel;
pub(crate) mod build;
pub mod canonical;
mod chiral;
mod dual_ambo;
mod dual_chiral;
mod dual_kis;
mod inset;
mod kis_of;
pub(crate) mod kis;
mod ortho;
pub mod seeds;
#[cfg(test)]
mod tests;
mod truncate;

pub use ambo::{ambo, quinto, subdivide};
pub use chiral::{gyro, propellor, whirl};
pub use inset::{chamfer, loft};
pub use kis::kis;
pub use seeds::Seed;

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::dual::dual;
use crate::schemes::hosts::with_point_spheres;

/// One operator of the notation, with its number where it takes one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Dual,
    Ambo,
    Truncate(Option<usize>),
    Kis(Option<usize>),
    Join,
    Expand,
    Ortho,
    Gyro,
    Snub,
    Bevel,
    Meta,
    Needle(Option<usize>),
    Zip(Option<usize>),
    Chamfer,
    Subdivide,
    Whirl,
    Volute,
    Propellor,
    Quinto,
    Loft(Option<usize>),
    Reflect,
}

/// A row of the operator table.
#[derive(Clone, Copy, Debug)]
pub struct OpInfo {
    /// The letter of the notation.
    pub letter: char,
    /// Hart's name.
    pub name: &'static str,
    /// The `Mesh` method in Python.
    pub method: &'static str,
    /// Its definition by other operators (empty for a primitive).
    pub definition: &'static str,
    /// Takes a number N (face size or vertex valence).
    pub takes_n: bool,
    /// `V', E', F'` from the input's V, E, F.
    pub counts: [&'static str; 3],
}

macro_rules! row {
    ($l:literal, $n:literal, $m:literal, $d:literal, $t:literal, $v:literal, $e:literal, $f:literal) => {
        OpInfo { letter: $l, name: $n, method: $m, definition: $d, takes_n: $t, counts: [$v, $e, $f] }
    };
}

/// Every operator, in the order of the module docs' table.
pub const OPERATORS: &[OpInfo] = &[
    row!('d', "dual", "dual", "", false, "F", "E", "V"),
    row!('a', "ambo", "ambo", "", false, "E", "2E", "F + V"),
    row!('t', "truncate", "truncate", "dkd", true, "2E", "3E", "F + V"),
    row!('k', "kis", "kis", "", true, "V + F", "3E", "2E"),
    row!('j', "join", "join", "da", false, "V + F", "2E", "E"),
    row!('e', "expand", "expand", "aa", false, "2E", "4E", "F + V + E"),
    row!('o', "ortho", "ortho", "de", false, "V + F + E", "4E", "2E"),
    row!('g', "gyro", "gyro", "", false, "V + F + 2E", "5E", "2E"),
    row!('s', "snub", "snub", "dg", false, "2E", "5E", "F + V + 2E"),
    row!('b', "bevel", "bevel", "ta", false, "4E", "6E", "F + V + E"),
    row!('m', "meta", "meta", "kj", false, "V + F + E", "6E", "4E"),
    row!('n', "needle", "needle", "kd", true, "V + F", "3E", "2E"),
    row!('z', "zip", "zip", "dk", true, "2E", "3E", "F + V"),
    row!('c', "chamfer", "chamfer", "", false, "V + 2E", "4E", "F + E"),
    row!('u', "subdivide", "conway_subdivide", "dcd", false, "V + E", "4E", "F + 2E"),
    row!('w', "whirl", "whirl", "", false, "V + 4E", "7E", "F + 2E"),
    row!('v', "volute", "volute", "dwd", false, "V + 2E", "7E", "F + 4E"),
    row!('p', "propellor", "propellor", "", false, "V + 2E", "5E", "F + 2E"),
    row!('q', "quinto", "quinto", "", false, "V + 3E", "6E", "F + 2E"),
    row!('l', "loft", "loft", "", true, "V + 2E", "5E", "F + 2E"),
    row!('r', "reflect", "reflect", "", false, "V", "E", "F"),
];

const SEED_LETTERS: &str = "T C O D I P<n> A<n> Y<n>";

impl Op {
    /// The operator of `letter` with its number, if `letter` is one.
    fn from_letter(letter: char, n: Option<usize>) -> Option<Op> {
        use Op::*;
        Some(match letter {
            'd' => Dual,
            'a' => Ambo,
            't' => Truncate(n),
            'k' => Kis(n),
            'j' => Join,
            'e' => Expand,
            'o' => Ortho,
            'g' => Gyro,
            's' => Snub,
            'b' => Bevel,
            'm' => Meta,
            'n' => Needle(n),
            'z' => Zip(n),
            'c' => Chamfer,
            'u' => Subdivide,
            'w' => Whirl,
            'v' => Volute,
            'p' => Propellor,
            'q' => Quinto,
            'l' => Loft(n),
            'r' => Reflect,
            _ => return None,
        })
    }

    /// Applies the operator (compositions as in the module docs' table).
    pub fn apply(self, m: &Mesh) -> Result<Mesh> {
        use Op::*;
        match self {
            Dual => dual(m),
            Ambo => ambo(m),
            Truncate(None) => truncate::truncate(m),
            Truncate(n) => dual(&kis(&dual(m)?, n)?),
            Kis(n) => kis(m, n),
            Join => dual_ambo::join(m),
            Expand => ambo::expand(m),
            Ortho => ortho::ortho(m),
            Gyro => gyro(m),
            Snub => dual_chiral::snub(m),
            Bevel => bevel::bevel(m),
            Meta => kis_of::meta(m),
            Needle(None) => kis_of::needle(m),
            Needle(n) => kis(&dual(m)?, n),
            Zip(None) => dual_kis::dual_kis(m),
            Zip(n) => dual(&kis(m, n)?),
            Chamfer => chamfer(m),
            Subdivide => subdivide(m),
            Whirl => whirl(m),
            Volute => dual_chiral::dual_whirl(&dual(m)?),
            Propellor => propellor(m),
            Quinto => quinto(m),
            Loft(n) => loft(m, n),
            Reflect => reflect(m),
        }
    }

    /// Upper bounds of `(V', E', F')` from `(V, E, F)` (exact without a
    /// number; with one, what the operator gives on all faces).
    pub fn predict(self, (v, e, f): (u64, u64, u64)) -> (u64, u64, u64) {
        use Op::*;
        let (a, m, s) = (|x: u64, y: u64| x.saturating_add(y), |k: u64, x: u64| k.saturating_mul(x), a3);
        fn a3(x: u64, y: u64, z: u64) -> u64 {
            x.saturating_add(y).saturating_add(z)
        }
        match self {
            Dual => (f, e, v),
            Ambo => (e, m(2, e), a(f, v)),
            Truncate(_) | Zip(_) => (m(2, e), m(3, e), a(f, v)),
            Kis(_) | Needle(_) => (a(v, f), m(3, e), m(2, e)),
            Join => (a(v, f), m(2, e), e),
            Expand => (m(2, e), m(4, e), s(f, v, e)),
            Ortho => (s(v, f, e), m(4, e), m(2, e)),
            Gyro => (s(v, f, m(2, e)), m(5, e), m(2, e)),
            Snub => (m(2, e), m(5, e), s(f, v, m(2, e))),
            Bevel => (m(4, e), m(6, e), s(f, v, e)),
            Meta => (s(v, f, e), m(6, e), m(4, e)),
            Chamfer => (a(v, m(2, e)), m(4, e), a(f, e)),
            Subdivide => (a(v, e), m(4, e), a(f, m(2, e))),
            Whirl => (a(v, m(4, e)), m(7, e), a(f, m(2, e))),
            Volute => (a(v, m(2, e)), m(7, e), a(f, m(4, e))),
            Propellor | Loft(_) => (a(v, m(2, e)), m(5, e), a(f, m(2, e))),
            Quinto => (a(v, m(3, e)), m(6, e), a(f, m(2, e))),
            Reflect => (v, e, f),
        }
    }
}

/// A parsed notation: the operators in the order they apply (the
/// rightmost letter first) and the seed, if the string names one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notation {
    pub ops: Vec<Op>,
    pub seed: Option<Seed>,
}

fn parse_err(s: &str, pos: usize, what: String) -> MeshError {
    MeshError::InvalidArgument(format!("conway: at position {pos} of {s:?}: {what}"))
}

/// Parses Hart's notation, e.g. `"dtkC"`, `"t5dD"`, `"gP5"`, or operators
/// alone (`"tk"`) to apply to a given mesh. A letter may be followed by a
/// number (`t5`, `k3`, `P7`); the seed, if any, is the rightmost letter.
/// Errors name the position (0-based, in characters) and the character.
pub fn parse(s: &str) -> Result<Notation> {
    let chars: Vec<char> = s.chars().collect();
    let mut tokens: Vec<(usize, char, Option<usize>)> = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let (at, c) = (i, chars[i]);
        if !c.is_ascii_alphabetic() {
            let what = if c.is_ascii_digit() { format!("number {c:?} without a letter before it") } else { format!("unexpected character {c:?}") };
            return Err(parse_err(s, at, what));
        }
        i += 1;
        let start = i;
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        let n = if i > start {
            let digits: String = chars[start..i].iter().collect();
            match digits.parse::<usize>() {
                Ok(n) if (1..=seeds::MAX_SIDES).contains(&n) => Some(n),
                _ => return Err(parse_err(s, start, format!("number {digits} after {c:?} is outside [1, {}]", seeds::MAX_SIDES))),
            }
        } else {
            None
        };
        tokens.push((at, c, n));
    }
    let mut seed = None;
    let mut ops = Vec::with_capacity(tokens.len());
    let last = tokens.len().wrapping_sub(1);
    for (k, &(at, c, n)) in tokens.iter().enumerate() {
        let family = |f: fn(usize) -> Seed| -> Result<Seed> {
            match n {
                Some(n) if n >= 3 => Ok(f(n)),
                Some(n) => Err(parse_err(s, at, format!("seed {c:?} needs at least 3 sides, got {n}"))),
                None => Err(parse_err(s, at, format!("seed {c:?} needs its number of sides, e.g. {c}5"))),
            }
        };
        let plain = |sd: Seed| -> Result<Seed> {
            match n {
                None => Ok(sd),
                Some(_) => Err(parse_err(s, at, format!("seed {c:?} takes no number"))),
            }
        };
        let sd = match c {
            'T' => Some(plain(Seed::Tetrahedron)?),
            'C' => Some(plain(Seed::Cube)?),
            'O' => Some(plain(Seed::Octahedron)?),
            'D' => Some(plain(Seed::Dodecahedron)?),
            'I' => Some(plain(Seed::Icosahedron)?),
            'P' => Some(family(Seed::Prism)?),
            'A' => Some(family(Seed::Antiprism)?),
            'Y' => Some(family(Seed::Pyramid)?),
            _ => None,
        };
        if let Some(sd) = sd {
            if k != last {
                return Err(parse_err(s, at, format!("seed {c:?} must be the rightmost letter")));
            }
            seed = Some(sd);
            continue;
        }
        let Some(op) = Op::from_letter(c, n) else {
            return Err(parse_err(s, at, format!("unknown letter {c:?} (operators: {}; seeds: {SEED_LETTERS})", OPERATORS.iter().map(|o| o.letter).collect::<String>())));
        };
        if n.is_some() && !OPERATORS.iter().any(|o| o.letter == c && o.takes_n) {
            return Err(parse_err(s, at, format!("operator {c:?} takes no number (only t, k, n, z, l do)")));
        }
        ops.push(op);
    }
    ops.reverse();
    Ok(Notation { ops, seed })
}

/// Runs a notation on `seed` (the string's seed when `seed` is `None`).
///
/// The whole chain is checked against the memory budget and the 31-bit id
/// limit up front, from the operators' count formulas, before anything is
/// built. Errors: no seed or two seeds, the operators' own errors (holes).
pub fn conway(notation: &str, seed: Option<&Mesh>) -> Result<Mesh> {
    let nt = parse(notation)?;
    let built;
    let start = match (nt.seed, seed) {
        (Some(_), Some(_)) => {
            return Err(MeshError::InvalidArgument(format!("conway: {notation:?} names a seed and a seed mesh was given too; drop one")));
        }
        (None, None) => {
            return Err(MeshError::InvalidArgument(format!("conway: {notation:?} has no seed; end it with one of {SEED_LETTERS} or give a seed mesh")));
        }
        (Some(sd), None) => {
            built = sd.build()?;
            &built
        }
        (None, Some(m)) => m,
    };
    apply_all(&format!("conway {notation:?}"), start, &nt.ops)
}

/// Applies `ops` in order to `m` (a copy of `m` for none), after checking
/// the whole chain against the memory budget and the id limit; `name`
/// names the call in errors.
pub fn apply_all(name: &str, m: &Mesh, ops: &[Op]) -> Result<Mesh> {
    // every operator refuses holes (no boundary rule): named here after the
    // call ("tk", "truncate"), not after the step inside it that refused
    if !ops.is_empty() {
        crate::schemes::hosts::refuse_holes(name, m)?;
    }
    check_chain(name, m, ops)?;
    let mut cur: Option<Mesh> = None;
    for op in ops {
        crate::cancel::check()?;
        cur = Some(op.apply(cur.as_ref().unwrap_or(m))?);
    }
    Ok(cur.unwrap_or_else(|| m.clone()))
}

/// Refuses a chain whose predicted largest step exceeds the budget or the id limit.
fn check_chain(name: &str, m: &Mesh, ops: &[Op]) -> Result<()> {
    use crate::budget::{check, level_bytes, Counts};
    let mut c = (m.n_vertices() as u64, m.n_edges() as u64, m.n_faces() as u64);
    let mut worst = 0u64;
    for op in ops {
        let n = op.predict(c);
        let max = crate::mesh::MAX_ELEMENTS as u64;
        if n.0 > max || n.1.saturating_mul(2) > max || n.2 > max {
            return Err(MeshError::Memory(format!(
                "{name}: a step would have about {} vertices, {} edges and {} faces, more than 31-bit ids allow",
                n.0, n.1, n.2
            )));
        }
        worst = worst.max(level_bytes(&Counts::plain(c.0, c.1, c.2), &Counts::plain(n.0, n.1, n.2)));
        c = n;
    }
    check(name, "its largest step", worst)
}

/// Reflect (`r`, polyhedronisme `reflect`): every position through the
/// origin and every face reversed, so the result is the mirror image with
/// outward faces. V' = V, E' = E, F' = F, face sizes unchanged.
pub fn reflect(m: &Mesh) -> Result<Mesh> {
    let mut r = with_point_spheres("reflect", m, |m| {
        let c = build::Ctx::new(m)?;
        let mut out = build::Out::new(m.positions().to_vec(), c.ne, c.nf, c.nh).of(&c);
        out.keeps_vertices(c.nv);
        for f in 0..c.nf {
            out.from_face(f);
            let hs = c.fl.corners(f);
            // side head(h) -> tail(h) along the edge of h, in reverse order
            out.face(hs.iter().rev().map(|&h| (c.head(h as usize), h >> 1)));
        }
        out.finish("reflect")
    })?;
    for p in r.positions_mut() {
        *p = -*p;
    }
    Ok(r)
}
