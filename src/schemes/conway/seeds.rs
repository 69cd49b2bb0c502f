//! The seeds of Hart's notation: `T C O D I` (the Platonic solids of
//! `crate::primitives`) and the families `Pn` (prism), `An` (antiprism),
//! `Yn` (pyramid), built with unit circumradius of the n-gon and unit-ish
//! edges like polyhedronisme's `prism`, `antiprism` and `pyramid`.

use crate::error::{MeshError, Result};
use crate::mesh::{BuildOptions, Mesh};
use glam::DVec3;
use std::f64::consts::PI;

/// Largest n accepted for `Pn`, `An`, `Yn`.
pub const MAX_SIDES: usize = 1 << 20;

/// A seed of the notation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Seed {
    Tetrahedron,
    Cube,
    Octahedron,
    Dodecahedron,
    Icosahedron,
    Prism(usize),
    Antiprism(usize),
    Pyramid(usize),
}

impl Seed {
    /// `(V, E, F)` of the seed.
    pub fn counts(self) -> (usize, usize, usize) {
        match self {
            Seed::Tetrahedron => (4, 6, 4),
            Seed::Cube => (8, 12, 6),
            Seed::Octahedron => (6, 12, 8),
            Seed::Dodecahedron => (20, 30, 12),
            Seed::Icosahedron => (12, 30, 20),
            Seed::Prism(n) => (2 * n, 3 * n, n + 2),
            Seed::Antiprism(n) => (2 * n, 4 * n, 2 * n + 2),
            Seed::Pyramid(n) => (n + 1, 2 * n, n + 1),
        }
    }

    /// Builds the seed (checked against the memory budget first).
    pub fn build(self) -> Result<Mesh> {
        use crate::primitives as p;
        let (v, e, f) = self.counts();
        let c = crate::budget::Counts::plain(v as u64, e as u64, f as u64);
        crate::budget::check("conway", &format!("the seed {self:?}"), crate::budget::build_bytes(&c))?;
        match self {
            Seed::Tetrahedron => Ok(p::tetrahedron()),
            Seed::Cube => Ok(p::cube()),
            Seed::Octahedron => Ok(p::octahedron()),
            Seed::Dodecahedron => Ok(p::dodecahedron()),
            Seed::Icosahedron => Ok(p::icosahedron()),
            Seed::Prism(n) => prism(n),
            Seed::Antiprism(n) => antiprism(n),
            Seed::Pyramid(n) => pyramid(n),
        }
    }
}

fn check_sides(name: &str, n: usize) -> Result<()> {
    if !(3..=MAX_SIDES).contains(&n) {
        return Err(MeshError::InvalidArgument(format!("{name}: n = {n} is outside [3, {MAX_SIDES}]")));
    }
    Ok(())
}

/// Points of the regular n-gon of circumradius 1 at height z, turned by `phase` steps of π/n.
fn ring(n: usize, z: f64, phase: f64) -> impl Iterator<Item = DVec3> {
    (0..n).map(move |i| {
        let a = (2.0 * i as f64 + phase) * PI / n as f64;
        DVec3::new(a.cos(), a.sin(), z)
    })
}

fn build(pos: Vec<DVec3>, faces: Vec<Vec<u32>>) -> Result<Mesh> {
    let sizes: Vec<i64> = faces.iter().map(|f| f.len() as i64).collect();
    let idx: Vec<i64> = faces.iter().flatten().map(|&v| v as i64).collect();
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default())
}

/// Prism `Pn`: two n-gons at z = ±sin(π/n) (square sides), n quads.
/// V = 2n, E = 3n, F = n + 2.
pub fn prism(n: usize) -> Result<Mesh> {
    check_sides("prism", n)?;
    let h = (PI / n as f64).sin();
    let pos: Vec<DVec3> = ring(n, -h, 0.0).chain(ring(n, h, 0.0)).collect();
    let u = n as u32;
    let mut faces = vec![(0..u).rev().collect::<Vec<_>>(), (u..2 * u).collect()];
    for i in 0..u {
        let j = (i + 1) % u;
        faces.push(vec![i, j, u + j, u + i]);
    }
    build(pos, faces)
}

/// Antiprism `An`: two n-gons turned by π/n against each other, heights
/// chosen so every edge has the same length, 2n triangles between.
/// V = 2n, E = 4n, F = 2n + 2.
pub fn antiprism(n: usize) -> Result<Mesh> {
    check_sides("antiprism", n)?;
    let s = (PI / n as f64).sin();
    let t = (PI / (2 * n) as f64).sin();
    let h = (s * s - t * t).max(0.0).sqrt(); // half the height: (2s)² = (2t)² + (2h)²
    let pos: Vec<DVec3> = ring(n, -h, 0.0).chain(ring(n, h, 1.0)).collect();
    let u = n as u32;
    let mut faces = vec![(0..u).rev().collect::<Vec<_>>(), (u..2 * u).collect()];
    for i in 0..u {
        let j = (i + 1) % u;
        faces.push(vec![i, j, u + i]);
        faces.push(vec![j, u + j, u + i]);
    }
    build(pos, faces)
}

/// Pyramid `Yn`: an n-gon and n triangles meeting at an apex, with side
/// edges as long as the base edges where n < 6 (height 1 otherwise).
/// V = n + 1, E = 2n, F = n + 1.
pub fn pyramid(n: usize) -> Result<Mesh> {
    check_sides("pyramid", n)?;
    let s = 2.0 * (PI / n as f64).sin();
    let a = if s > 1.0 + 1e-9 { (s * s - 1.0).sqrt() } else { 1.0 };
    // base and apex around the centroid's height
    let mut pos: Vec<DVec3> = ring(n, -a / 4.0, 0.0).collect();
    pos.push(DVec3::new(0.0, 0.0, 0.75 * a));
    let u = n as u32;
    let mut faces = vec![(0..u).rev().collect::<Vec<_>>()];
    for i in 0..u {
        faces.push(vec![i, (i + 1) % u, u]);
    }
    build(pos, faces)
}
