//! TopMod's extrusions (`topmodx/src/MainWindow.cc: performExtrusion`, the
//! operations in `include/dlflaux/DLFLExtrude.cc`), on a selection of faces,
//! read from TopMod's source, the only description of them.
//!
//! Each selected n-gon is replaced by a stack of `segments` rings of n new
//! points and a cap. Every step takes the current top polygon `p₀ … p_{n−1}`
//! with unit (Newell) normal N and centroid c:
//!
//! | kind | TopMod function | new ring | band per step |
//! |---|---|---|---|
//! | `Cubical` | `extrudeFace(d, num, rot, sf)` | p scaled by `scale` about c, rotated by `twist` degrees about N, moved by `length`·N | n quads |
//! | `DooSabin` | `extrudeFaceDS(d, num, twist, sf)` | Doo-Sabin's mask over `(1 − twist) p_j + twist p_{j+1} + length·N`, scaled by `scale` | n quads |
//! | `Octahedral` | `extrudeDualFace(d, num, rot, sf)` | the edge midpoints `(p_j + p_{j+1})/2 + length·N`, scaled, rotated by `twist` degrees | 2n triangles (`dualConnectFaces`) |
//! | `Stellate` | `stellateFace(d)` | — (cap: the fan to c + length·N) | — |
//! | `DoubleStellate` | `doubleStellateFace(d)` | — (cap: the fan, each triangle fanned again, the first centre moved by length·N) | — |
//! | `Dome` | `extrudeFaceDome(length, rot, sf)` | five Doo-Sabin steps (lengths 0.3, 0.18, 0.1, 0.05, 0.025 × `length`, scales 1.7, 1.6, 1.4, 1.2, 1.1 × `scale`, twist `twist`/5), then the fan at 0.01 × `length` | n quads each |
//! | `Dodecahedral` | `extrudeFaceDodeca(angle, num, l1, l2, l3)` | three rings ([`super::extrude_platonic`]) | 2n pentagons |
//! | `Icosahedral` | `extrudeFaceIcosa(angle, num, l1, l2, l3)` | three rings ([`super::extrude_platonic`]) | 6n triangles |
//!
//! The top ring keeps the face (its last ring is the new face), except for
//! the fans. Per selected n-gon, with s = `segments`:
//!
//! ```text
//! Cubical, DooSabin:  V += s·n,     E += 2s·n,  F += s·n
//! Octahedral:         V += s·n,     E += 3s·n,  F += 2s·n
//! Dodecahedral:       V += 3s·n,    E += 5s·n,  F += 2s·n
//! Icosahedral:        V += 3s·n,    E += 9s·n,  F += 6s·n
//! Stellate:           V += 1,       E += n,     F += n − 1   (n triangles)
//! DoubleStellate:     V += n + 1,   E += 4n,    F += 3n − 1  (3n triangles)
//! Dome:               V += 5n + 1,  E += 11n,   F += 6n − 1  (5n quads, n triangles)
//! ```
//!
//! The genus is unchanged; unselected faces keep their size. Vertex layout:
//! the input's vertices, then for each selected face (in selection order,
//! repeats ignored) its rings' points in corner order, then its fan centres.

use crate::schemes::keyed::{In, Out};
use super::corner_cutting::cut_face;
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::{DQuat, DVec3};

/// The extrusions of TopMod's menu. See the module docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Cubical,
    DooSabin,
    Octahedral,
    Stellate,
    DoubleStellate,
    Dome,
    Dodecahedral,
    Icosahedral,
}

impl Kind {
    /// Python names: `"cubical"`, `"doo_sabin"`, `"octahedral"`, `"stellate"`,
    /// `"double_stellate"`, `"dome"`.
    pub fn parse(s: &str) -> Option<Kind> {
        Self::ALL.into_iter().find(|k| k.name() == s)
    }
    const ALL: [Kind; 8] = [Kind::Cubical, Kind::DooSabin, Kind::Octahedral, Kind::Stellate, Kind::DoubleStellate, Kind::Dome, Kind::Dodecahedral, Kind::Icosahedral];
    /// The Python name (error messages say `kind 'cubical'`, as the user wrote it).
    pub fn name(self) -> &'static str {
        match self {
            Kind::Cubical => "cubical",
            Kind::DooSabin => "doo_sabin",
            Kind::Octahedral => "octahedral",
            Kind::Stellate => "stellate",
            Kind::DoubleStellate => "double_stellate",
            Kind::Dome => "dome",
            Kind::Dodecahedral => "dodecahedral",
            Kind::Icosahedral => "icosahedral",
        }
    }
    pub const NAMES: &'static str = "'cubical', 'doo_sabin', 'octahedral', 'stellate', 'double_stellate', 'dome', 'dodecahedral', 'icosahedral'";
    /// TopMod's default length (`sExtrudeDist` = 2, `sDomeExtrudeLengthFactor` = 1;
    /// 0 for the kinds that take `lengths` instead).
    pub fn default_length(self) -> f64 {
        match self {
            Kind::Dome => 1.0,
            Kind::Dodecahedral | Kind::Icosahedral => 0.0,
            _ => 2.0,
        }
    }
    /// TopMod's default angle and lengths (`sExtrudeAngle`, `sExtrudeLength1..3`
    /// and their `_iCosA` versions), for the kinds that take them.
    pub fn default_platonic(self) -> Option<(f64, [f64; 3])> {
        match self {
            Kind::Dodecahedral => Some((40.0, [0.5, 1.0, 1.0])),
            Kind::Icosahedral => Some((50.0, [0.5, 0.7, 0.8])),
            _ => None,
        }
    }
    /// (V, E, F) added per selected n-gon (see the module docs).
    pub fn added(self, n: usize, s: usize) -> (usize, usize, usize, isize) {
        match self {
            Kind::Cubical | Kind::DooSabin => (s * n, 2 * s * n, s * n, 0),
            Kind::Octahedral => (s * n, 3 * s * n, 2 * s * n, 0),
            Kind::Stellate => (1, n, n, -1),
            Kind::DoubleStellate => (n + 1, 4 * n, 3 * n, -1),
            Kind::Dome => (5 * n + 1, 11 * n, 6 * n, -1),
            Kind::Dodecahedral => (3 * s * n, 5 * s * n, 2 * s * n, 0),
            Kind::Icosahedral => (3 * s * n, 9 * s * n, 6 * s * n, 0),
        }
    }
}

/// Parameters of [`extrude`].
#[derive(Clone, Copy, Debug)]
pub struct Extrusion {
    pub kind: Kind,
    /// Distance along the normal per step (finite, >= 0).
    pub length: f64,
    /// Scale of each new ring about its centroid, in (0, 10].
    pub scale: f64,
    /// Degrees of rotation per step (Cubical, Octahedral, in [0, 360]),
    /// the Doo-Sabin twist (DooSabin, in [0, 1]) or TopMod's dome rotation
    /// factor (Dome, in [0, 5]); Stellate kinds take none (0).
    pub twist: f64,
    /// Steps (>= 1); only Cubical, DooSabin, Octahedral, Dodecahedral and
    /// Icosahedral take more than one.
    pub segments: usize,
    /// TopMod's angle in degrees, [0, 180] (Dodecahedral, Icosahedral only;
    /// `None` is TopMod's default).
    pub angle: Option<f64>,
    /// TopMod's lengths 1–3, each in [0, 100], relative to the face's mean
    /// side (Dodecahedral, Icosahedral only; `None` is TopMod's default).
    pub lengths: Option<[f64; 3]>,
}

impl Extrusion {
    /// Checks the ranges of the module docs; errors name the parameter.
    pub fn check(&self) -> Result<()> {
        let bad = |what: &str, x: String, range: &str| Err(MeshError::InvalidArgument(format!("extrude: {what} = {x} must be {range} for kind '{}'", self.kind.name())));
        if !(self.length.is_finite() && self.length >= 0.0) {
            return bad("length", crate::error::num(self.length), "finite and >= 0");
        }
        if !(self.scale.is_finite() && self.scale > 0.0 && self.scale <= 10.0) {
            return bad("scale", crate::error::num(self.scale), "in (0, 10]");
        }
        let (lo, hi) = match self.kind {
            Kind::Cubical | Kind::Octahedral => (0.0, 360.0),
            Kind::DooSabin => (0.0, 1.0),
            Kind::Dome => (0.0, 5.0),
            Kind::Stellate | Kind::DoubleStellate | Kind::Dodecahedral | Kind::Icosahedral => (0.0, 0.0),
        };
        let platonic = self.kind.default_platonic().is_some();
        if platonic {
            // TopMod's dodecahedral and icosahedral extrusions take an angle and three lengths instead
            if self.length != 0.0 {
                return bad("length", crate::error::num(self.length), "left unset (this kind takes lengths)");
            }
            if self.scale != 1.0 {
                return bad("scale", crate::error::num(self.scale), "1 (this kind takes lengths)");
            }
            if let Some(a) = self.angle {
                if !(a.is_finite() && (0.0..=180.0).contains(&a)) {
                    return bad("angle", crate::error::num(a), "in [0, 180]");
                }
            }
            if let Some(l) = self.lengths {
                if let Some(x) = l.iter().find(|x| !(x.is_finite() && (0.0..=100.0).contains(*x))) {
                    return bad("lengths", crate::error::num(*x), "each in [0, 100]");
                }
            }
        } else if self.angle.is_some() || self.lengths.is_some() {
            return bad(if self.angle.is_some() { "angle" } else { "lengths" }, "given".into(), "unset (only 'dodecahedral' and 'icosahedral' take it)");
        }
        if !(self.twist.is_finite() && self.twist >= lo && self.twist <= hi) {
            return bad("twist", crate::error::num(self.twist), &format!("in [{lo}, {hi}]"));
        }
        let multi = matches!(self.kind, Kind::Cubical | Kind::DooSabin | Kind::Octahedral) || platonic;
        if self.segments == 0 || (!multi && self.segments != 1) {
            return bad("segments", self.segments.to_string(), if multi { ">= 1" } else { "1" });
        }
        Ok(())
    }
}

fn centroid(p: &[DVec3]) -> DVec3 {
    p.iter().sum::<DVec3>() / p.len() as f64
}

fn normal(p: &[DVec3]) -> DVec3 {
    let n = p.len();
    (0..n).map(|j| p[j].cross(p[(j + 1) % n])).sum::<DVec3>().normalize_or_zero()
}

fn scaled(p: &mut [DVec3], s: f64) {
    if s != 1.0 {
        let c = centroid(p);
        for q in p.iter_mut() {
            *q = c + s * (*q - c);
        }
    }
}

fn rotated(p: &mut [DVec3], axis: DVec3, degrees: f64) {
    if degrees != 0.0 && axis != DVec3::ZERO {
        let c = centroid(p);
        let r = DQuat::from_axis_angle(axis, degrees.to_radians());
        for q in p.iter_mut() {
            *q = c + r * (*q - c);
        }
    }
}

/// One step's band: quads or `dualConnectFaces` triangles.
#[derive(Clone, Copy, PartialEq)]
enum Band {
    Quads,
    Triangles,
    Dodeca,
    Icosa,
}

/// The next ring of `p` for one step.
fn step_ring(kind: Kind, p: &[DVec3], length: f64, scale: f64, twist: f64) -> Vec<DVec3> {
    let n = p.len();
    let nrm = normal(p);
    let mut q: Vec<DVec3> = match kind {
        Kind::Cubical => p.to_vec(),
        Kind::Octahedral => (0..n).map(|j| (p[j] + p[(j + 1) % n]) * 0.5).collect(),
        _ => {
            let tw: Vec<DVec3> = (0..n).map(|j| p[j].lerp(p[(j + 1) % n], twist) + length * nrm).collect();
            let mut out = Vec::with_capacity(n);
            cut_face(&tw, 0.25 + 5.0 / (4.0 * n as f64), &mut out);
            scaled(&mut out, scale);
            return out;
        }
    };
    if kind == Kind::Octahedral {
        for x in q.iter_mut() {
            *x += length * nrm;
        }
        scaled(&mut q, scale);
        rotated(&mut q, nrm, twist);
    } else {
        scaled(&mut q, scale);
        rotated(&mut q, nrm, twist);
        for x in q.iter_mut() {
            *x += length * nrm;
        }
    }
    q
}

/// Extrudes the faces `faces` of `m` (indices, repeats ignored). See the
/// module docs. Open meshes are refused (TopMod's extrusions of a face
/// beside a hole are not defined here).
pub fn extrude(m: &Mesh, faces: &[usize], ex: &Extrusion) -> Result<Mesh> {
    ex.check()?;
    let sel = super::linear::selection("extrude", m, faces)?;
    with_point_spheres("extrude", m, |m| extrude_step(m, &sel, ex))
}

/// Every step's (kind, length, scale, twist, band), then the cap: a fan
/// with its centre's offset, doubled or not.
type Steps = Vec<(Kind, f64, f64, f64, Band)>;

fn extrude_step(m: &Mesh, faces: &[usize], ex: &Extrusion) -> Result<Mesh> {
    let (steps, cap): (Steps, Option<(f64, bool)>) = match ex.kind {
        Kind::Cubical | Kind::DooSabin => (vec![(ex.kind, ex.length, ex.scale, ex.twist, Band::Quads); ex.segments], None),
        Kind::Octahedral => (vec![(ex.kind, ex.length, ex.scale, ex.twist, Band::Triangles); ex.segments], None),
        Kind::Dodecahedral | Kind::Icosahedral => {
            let band = if ex.kind == Kind::Dodecahedral { Band::Dodeca } else { Band::Icosa };
            // the angle rides in the step's twist, the lengths go to `rings` apart
            let a = ex.kind.default_platonic().expect("platonic kind").0;
            (vec![(ex.kind, 0.0, 1.0, ex.angle.unwrap_or(a), band); ex.segments], None)
        }
        Kind::Stellate => (vec![], Some((ex.length, false))),
        Kind::DoubleStellate => (vec![], Some((ex.length, true))),
        Kind::Dome => {
            let s = [(0.3, 1.7), (0.18, 1.6), (0.1, 1.4), (0.05, 1.2), (0.025, 1.1)];
            (s.iter().map(|&(l, k)| (Kind::DooSabin, l * ex.length, k * ex.scale, ex.twist / 5.0, Band::Quads)).collect(), Some((0.01 * ex.length, false)))
        }
    };
    let lengths = ex.lengths.or(ex.kind.default_platonic().map(|p| p.1)).unwrap_or([0.0; 3]);
    rings(m, faces, &steps, cap, lengths)
}

/// TopMod's dome remeshing (`domeSubdivide(obj, length, sf)` in
/// `DLFLSubdiv.cc`): every edge cut in four (`subdivideAllEdges(obj, 4)`),
/// then seven Doo-Sabin extrusions of every face with lengths 0, 0.3, 0.18,
/// 0.1, 0.05, 0.025, 0.01 × `length` and scales 1.6, 1.7, 1.6, 1.4, 1.2,
/// 1.1, 0.01 × `scale`. V' = V + 59E, E' = 116E, F' = F + 56E; histogram:
/// an n-gon gives a 4n-gon (its top) and 56E quads. `length` in [0, 2],
/// `scale` in (0, 2] (TopMod's ranges; defaults 1).
pub fn dome(m: &Mesh, length: f64, scale: f64) -> Result<Mesh> {
    if !(length.is_finite() && (0.0..=2.0).contains(&length)) {
        return Err(MeshError::InvalidArgument(format!("dome: length = {} must be in [0, 2]", crate::error::num(length))));
    }
    if !(scale.is_finite() && scale > 0.0 && scale <= 2.0) {
        return Err(MeshError::InvalidArgument(format!("dome: scale = {} must be in (0, 2]", crate::error::num(scale))));
    }
    let split = super::linear::split_edges(m, 4)?;
    let s = [(0.0, 1.6), (0.3, 1.7), (0.18, 1.6), (0.1, 1.4), (0.05, 1.2), (0.025, 1.1), (0.01, 0.01)];
    let steps: Steps = s.iter().map(|&(l, k)| (Kind::DooSabin, l * length, k * scale, 0.0, Band::Quads)).collect();
    with_point_spheres("dome", &split, |m| {
        let all: Vec<usize> = (0..m.n_faces()).collect();
        rings(m, &all, &steps, None, [0.0; 3])
    })
}

/// `lengths`: the three lengths of the Dodeca and Icosa bands (their angle
/// rides in the step's twist).
fn rings(m: &Mesh, faces: &[usize], steps: &Steps, cap: Option<(f64, bool)>, lengths: [f64; 3]) -> Result<Mesh> {
    let i = In::new(m)?;
    let mut selected = vec![false; i.nf];
    let mut order = Vec::new();
    for &f in faces {
        if !selected[f] {
            selected[f] = true;
            order.push(f);
        }
    }
    let (mut dv, mut de) = (0usize, 0usize);
    for &f in &order {
        let n = i.fl.degree(f);
        for &(_, _, _, _, band) in steps {
            let (a, b) = match band {
                Band::Quads => (n, 2 * n),
                Band::Triangles => (n, 3 * n),
                Band::Dodeca => (3 * n, 5 * n),
                Band::Icosa => (3 * n, 9 * n),
            };
            dv += a;
            de += b;
        }
        match cap {
            Some((_, false)) => (dv, de) = (dv + 1, de + n),
            Some((_, true)) => (dv, de) = (dv + n + 1, de + 4 * n),
            None => {}
        }
    }
    let n_keys = i.ne + de;
    let mut o = Out::new(i.positions(dv), n_keys, i.nf, 2 * (i.ne + de)).of(&i);
    o.keeps_vertices(i.nv);
    let mut next_key = i.ne as u32;
    let mut alloc = |k: usize| {
        let b = next_key;
        next_key += k as u32;
        b
    };
    for f in 0..i.nf {
        if selected[f] {
            continue;
        }
        o.from_face(f);
        for &h in i.fl.corners(f) {
            o.c(i.vert[h as usize], h >> 1);
        }
        o.end();
    }
    for &f in &order {
        // every face of the extrusion (rings, bands, cap) descends from f
        o.from_face(f);
        let hs = i.fl.corners(f);
        let n = hs.len();
        let mut ring: Vec<u32> = hs.iter().map(|&h| i.vert[h as usize]).collect();
        let mut rkey: Vec<u32> = hs.iter().map(|&h| h >> 1).collect();
        let mut pts: Vec<DVec3> = hs.iter().map(|&h| i.p(h as usize)).collect();
        for &(kind, length, scale, twist, band) in steps {
            if matches!(band, Band::Dodeca | Band::Icosa) {
                let dodeca = band == Band::Dodeca;
                let rs = if dodeca { super::extrude_platonic::dodeca_rings(&pts, twist, lengths) } else { super::extrude_platonic::icosa_rings(&pts, twist, lengths) };
                let base = o.pos.len() as u32;
                for r in &rs {
                    o.pos.extend_from_slice(r);
                }
                let b = [base, base + n as u32, base + 2 * n as u32];
                let k = alloc(if dodeca { 5 * n } else { 9 * n });
                rkey = if dodeca { super::extrude_platonic::dodeca_band(&mut o, &ring, &rkey, b, k) } else { super::extrude_platonic::icosa_band(&mut o, &ring, &rkey, b, k) };
                ring = (0..n as u32).map(|j| b[2] + j).collect();
                pts = rs[2].clone();
                continue;
            }
            let q = step_ring(kind, &pts, length, scale, twist);
            let base = o.pos.len() as u32;
            o.pos.extend_from_slice(&q);
            let top: Vec<u32> = (0..n as u32).map(|j| base + j).collect();
            let tkey = alloc(n);
            let side = alloc(if band == Band::Quads { n } else { 2 * n });
            for j in 0..n {
                let k = (j + 1) % n;
                let (tk, sj, sk) = (tkey + j as u32, side + j as u32, side + k as u32);
                if band == Band::Quads {
                    // verticals: side + j joins ring[j] and top[j]
                    o.c(ring[j], rkey[j]);
                    o.c(ring[k], sk);
                    o.c(top[k], tk);
                    o.c(top[j], sj);
                    o.end();
                } else {
                    // X_j = side + j joins ring[k] and top[j]; Y_j = side + n + j joins top[j] and ring[j]
                    let (x, yj, yk) = (sj, side + (n + j) as u32, side + (n + k) as u32);
                    o.c(ring[j], rkey[j]);
                    o.c(ring[k], x);
                    o.c(top[j], yj);
                    o.end();
                    o.c(top[j], x);
                    o.c(ring[k], yk);
                    o.c(top[k], tk);
                    o.end();
                }
            }
            ring = top;
            rkey = (0..n as u32).map(|j| tkey + j).collect();
            pts = q;
        }
        match cap {
            None => {
                for j in 0..n {
                    o.c(ring[j], rkey[j]);
                }
                o.end();
            }
            Some((d, double)) => {
                let c0 = centroid(&pts);
                let nrm = normal(&pts);
                let c = o.pos.len() as u32;
                o.pos.push(if double { c0 } else { c0 + d * nrm });
                let spoke = alloc(n);
                if !double {
                    for j in 0..n {
                        let k = (j + 1) % n;
                        o.c(ring[j], rkey[j]);
                        o.c(ring[k], spoke + k as u32);
                        o.c(c, spoke + j as u32);
                        o.end();
                    }
                } else {
                    let inner = alloc(3 * n);
                    for j in 0..n {
                        let k = (j + 1) % n;
                        let t = o.pos.len() as u32;
                        o.pos.push((pts[j] + pts[k] + c0) / 3.0);
                        let a = |x: usize| inner + (3 * j + x) as u32;
                        o.c(ring[j], rkey[j]);
                        o.c(ring[k], a(1));
                        o.c(t, a(0));
                        o.end();
                        o.c(ring[k], spoke + k as u32);
                        o.c(c, a(2));
                        o.c(t, a(1));
                        o.end();
                        o.c(c, spoke + j as u32);
                        o.c(ring[j], a(0));
                        o.c(t, a(2));
                        o.end();
                    }
                    // TopMod moves the first centre after both fans (the second
                    // round's centres stay where the flat fan put them)
                    o.pos[c as usize] += d * nrm;
                }
            }
        }
    }
    o.finish("extrude")
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::meshes;
    use crate::schemes::hosts::test_meshes::n_point_spheres;

    const KINDS: [Kind; 8] = [Kind::Cubical, Kind::DooSabin, Kind::Octahedral, Kind::Stellate, Kind::DoubleStellate, Kind::Dome, Kind::Dodecahedral, Kind::Icosahedral];

    fn ex(kind: Kind, segments: usize) -> Extrusion {
        let twist = match kind {
            Kind::Cubical | Kind::Octahedral => 15.0,
            Kind::DooSabin => 0.2,
            Kind::Dome => 1.0,
            _ => 0.0,
        };
        let platonic = kind.default_platonic().is_some();
        Extrusion { kind, length: if platonic { 0.0 } else { 0.5 }, scale: if platonic { 1.0 } else { 0.8 }, twist, segments, angle: None, lengths: None }
    }

    #[test]
    fn counts_on_corpus() {
        for (name, m) in meshes() {
            let ps = n_point_spheres(&m);
            let real: Vec<usize> = (0..m.n_faces()).filter(|&f| m.face_halfedge(crate::FaceId(f as u32)).is_some()).collect();
            // every real face, and a selection of about a third (with a repeat)
            let some: Vec<usize> = real.iter().copied().step_by(3).chain(real.first().copied()).collect();
            for sel in [real.clone(), some] {
                for kind in KINDS {
                    let segs: &[usize] = if matches!(kind, Kind::Cubical | Kind::DooSabin | Kind::Octahedral | Kind::Dodecahedral | Kind::Icosahedral) { &[1, 3] } else { &[1] };
                    for &s in segs {
                        let r = extrude(&m, &sel, &ex(kind, s)).unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
                        r.validate().unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
                        let (mut v, mut e, mut f) = (m.n_vertices() - ps, m.n_edges(), (m.n_faces() - ps) as isize);
                        let uniq: std::collections::BTreeSet<usize> = sel.iter().copied().collect();
                        for &x in &uniq {
                            let (a, b, c, d) = kind.added(m.face_degree(crate::FaceId(x as u32)), s);
                            v += a;
                            e += b;
                            f += c as isize + d;
                        }
                        assert_eq!((r.n_vertices() - ps, r.n_edges(), (r.n_faces() - ps) as isize), (v, e, f), "{name} {kind:?} {s}");
                        assert_eq!(r.genus(), m.genus(), "{name} {kind:?}");
                        assert_eq!(n_point_spheres(&r), ps, "{name} {kind:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn dome_counts() {
        super::super::tests::check("dome", |m| dome(m, 1.0, 1.0), |_, (v, e, f)| (v + 59 * e, 116 * e, f + 56 * e), |m, (_, e, _)| {
            let mut h = std::collections::BTreeMap::new();
            for (n, c) in super::super::tests::hist_of(m) {
                *h.entry(4 * n).or_insert(0) += c;
            }
            *h.entry(4).or_insert(0) += 56 * e;
            h
        });
        assert!(dome(&crate::primitives::cube(), 3.0, 1.0).is_err());
    }

    #[test]
    fn cube_extrusions() {
        let c = crate::primitives::cube();
        let v0 = c.signed_volume();
        // a cubical extrusion of one face by 1 with scale 1 adds a unit... box of the face's area × length
        let area = c.face_newell(crate::FaceId(0)).length() / 2.0;
        let r = extrude(&c, &[0], &Extrusion { kind: Kind::Cubical, length: 1.0, scale: 1.0, twist: 0.0, segments: 1, angle: None, lengths: None }).unwrap();
        assert!((r.signed_volume() - v0 - area).abs() < 1e-9);
        let r2 = extrude(&c, &[0], &Extrusion { kind: Kind::Cubical, length: 0.5, scale: 1.0, twist: 0.0, segments: 2, angle: None, lengths: None }).unwrap();
        assert!((r2.signed_volume() - v0 - area).abs() < 1e-9);
        // a stellate extrusion adds a pyramid
        let s = extrude(&c, &[0], &Extrusion { kind: Kind::Stellate, length: 1.0, scale: 1.0, twist: 0.0, segments: 1, angle: None, lengths: None }).unwrap();
        assert!((s.signed_volume() - v0 - area / 3.0).abs() < 1e-9);
        let bad = |e: Extrusion| extrude(&c, &[0], &e).unwrap_err().to_string();
        assert!(bad(Extrusion { kind: Kind::Stellate, length: 1.0, scale: 1.0, twist: 0.0, segments: 2, angle: None, lengths: None }).contains("segments"));
        assert!(bad(Extrusion { kind: Kind::DooSabin, length: 1.0, scale: 1.0, twist: 2.0, segments: 1, angle: None, lengths: None }).contains("twist"));
        assert!(bad(Extrusion { kind: Kind::Cubical, length: 1.0, scale: 0.0, twist: 0.0, segments: 1, angle: None, lengths: None }).contains("scale"));
        assert!(extrude(&c, &[6], &ex(Kind::Cubical, 1)).unwrap_err().to_string().contains("face 6"));
    }

    #[test]
    fn platonic_extrusions_shape() {
        use super::super::tests::hist_of;
        // one face of the dodecahedron (a pentagon), one of the icosahedron (a triangle)
        for (m, kind, added) in [(crate::primitives::dodecahedron(), Kind::Dodecahedral, (5, 10)), (crate::primitives::icosahedron(), Kind::Icosahedral, (3, 18))] {
            let f = crate::FaceId(0);
            let (nrm, c) = (m.face_newell(f).normalize(), m.face_centroids()[0]);
            let r = extrude(&m, &[0], &ex(kind, 1)).unwrap();
            r.validate().unwrap();
            let mut want = hist_of(&m);
            *want.entry(added.0).or_insert(0) += added.1;
            assert_eq!(hist_of(&r), want, "{kind:?}");
            // every new point lies above the extruded face
            assert!(r.positions()[m.n_vertices()..].iter().all(|p| nrm.dot(*p - c) > 1e-6), "{kind:?}");
            assert!(r.signed_volume() > m.signed_volume());
            // the angle and lengths are the extrusion's own: other kinds refuse them, and ranges are named
            let e = |a: Option<f64>, l: Option<[f64; 3]>| extrude(&m, &[0], &Extrusion { angle: a, lengths: l, ..ex(kind, 1) });
            assert!(e(Some(200.0), None).unwrap_err().to_string().contains("angle"));
            assert!(e(None, Some([1.0, -1.0, 1.0])).unwrap_err().to_string().contains("lengths"));
            assert!(e(Some(60.0), Some([0.3, 0.4, 0.5])).is_ok());
            assert!(extrude(&m, &[0], &Extrusion { angle: Some(10.0), ..ex(Kind::Cubical, 1) }).unwrap_err().to_string().contains("angle"));
            assert!(extrude(&m, &[0], &Extrusion { length: 1.0, ..ex(kind, 1) }).unwrap_err().to_string().contains("length"));
        }
    }
}
