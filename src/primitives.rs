//! Built-in solids: the five Platonic solids (centred at the origin, faces
//! oriented outward), a quad torus, and a genus-g slab built with InsertEdge.

use crate::error::{MeshError, Result};
use crate::mesh::{BuildOptions, Corner, FaceId, Mesh, VertexId};
use glam::DVec3;

/// Builds from polygon lists, flipping any face whose normal points towards
/// the centre so every solid is outward-oriented whatever order it was typed in.
fn convex_solid(pos: Vec<DVec3>, faces: Vec<Vec<u32>>) -> Mesh {
    let centre = pos.iter().sum::<DVec3>() / pos.len() as f64;
    let mut sizes = Vec::new();
    let mut idx = Vec::new();
    for mut f in faces {
        let c = f.iter().map(|&v| pos[v as usize]).sum::<DVec3>() / f.len() as f64;
        let mut n = DVec3::ZERO;
        for i in 0..f.len() {
            n += pos[f[i] as usize].cross(pos[f[(i + 1) % f.len()] as usize]);
        }
        if n.dot(c - centre) < 0.0 {
            f.reverse();
        }
        sizes.push(f.len() as i64);
        idx.extend(f.iter().map(|&v| v as i64));
    }
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).expect("built-in solid is a valid manifold")
}

/// Regular tetrahedron with vertices at alternate corners of the cube [-1, 1]³.
pub fn tetrahedron() -> Mesh {
    let p = [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]].map(DVec3::from_array).to_vec();
    convex_solid(p, vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]])
}

/// The cube [-1, 1]³: 8 vertices, 12 edges, 6 quads.
pub fn cube() -> Mesh {
    let p: Vec<DVec3> = (0..8)
        .map(|i| DVec3::new(if i & 1 != 0 { 1. } else { -1. }, if i & 2 != 0 { 1. } else { -1. }, if i & 4 != 0 { 1. } else { -1. }))
        .collect();
    convex_solid(
        p,
        vec![vec![0, 2, 3, 1], vec![4, 5, 7, 6], vec![0, 1, 5, 4], vec![2, 6, 7, 3], vec![0, 4, 6, 2], vec![1, 3, 7, 5]],
    )
}

/// Octahedron with vertices (±1, 0, 0), (0, ±1, 0), (0, 0, ±1).
pub fn octahedron() -> Mesh {
    let p = [[1., 0., 0.], [-1., 0., 0.], [0., 1., 0.], [0., -1., 0.], [0., 0., 1.], [0., 0., -1.]].map(DVec3::from_array).to_vec();
    let mut faces = Vec::new();
    for &x in &[0u32, 1] {
        for &y in &[2u32, 3] {
            for &z in &[4u32, 5] {
                faces.push(vec![x, y, z]);
            }
        }
    }
    convex_solid(p, faces)
}

fn icosahedron_points() -> Vec<DVec3> {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p = Vec::new();
    for &a in &[-1.0, 1.0] {
        for &b in &[-phi, phi] {
            p.push(DVec3::new(0.0, a, b));
            p.push(DVec3::new(a, b, 0.0));
            p.push(DVec3::new(b, 0.0, a));
        }
    }
    p
}

/// The 20 triangles of the icosahedron: triples of mutually adjacent vertices.
fn icosahedron_faces(p: &[DVec3]) -> Vec<Vec<u32>> {
    let adj = |i: usize, j: usize| (p[i].distance(p[j]) - 2.0).abs() < 1e-9;
    let mut faces = Vec::new();
    for i in 0..12 {
        for j in i + 1..12 {
            for k in j + 1..12 {
                if adj(i, j) && adj(j, k) && adj(i, k) {
                    faces.push(vec![i as u32, j as u32, k as u32]);
                }
            }
        }
    }
    faces
}

/// Icosahedron with vertices (0, ±1, ±φ) and cyclic permutations (edge 2).
pub fn icosahedron() -> Mesh {
    let p = icosahedron_points();
    let f = icosahedron_faces(&p);
    convex_solid(p, f)
}

/// Dodecahedron, the dual of [`icosahedron`]: vertices at the icosahedron's
/// face centroids, scaled to circumradius √3 (the cube (±1, ±1, ±1) is inscribed).
pub fn dodecahedron() -> Mesh {
    let ip = icosahedron_points();
    let ifaces = icosahedron_faces(&ip);
    let cents: Vec<DVec3> = ifaces.iter().map(|f| f.iter().map(|&v| ip[v as usize]).sum::<DVec3>() / 3.0).collect();
    let r = cents[0].length();
    let pos: Vec<DVec3> = cents.iter().map(|c| *c * (3f64.sqrt() / r)).collect();
    let mut faces = Vec::new();
    for (v, axis) in ip.iter().enumerate() {
        let mut around: Vec<u32> = (0..ifaces.len() as u32).filter(|&f| ifaces[f as usize].contains(&(v as u32))).collect();
        let a = axis.normalize();
        let u = a.any_orthonormal_vector();
        let w = a.cross(u);
        around.sort_by(|&x, &y| {
            let ang = |f: u32| {
                let d = pos[f as usize];
                d.dot(w).atan2(d.dot(u))
            };
            ang(x).total_cmp(&ang(y))
        });
        faces.push(around);
    }
    convex_solid(pos, faces)
}

/// A quad torus around the z axis: `major` segments around the axis,
/// `minor` around the tube, radii `major_radius` > `minor_radius` > 0.
/// V = major·minor, E = 2V, F = V, genus 1.
pub fn torus(major: usize, minor: usize, major_radius: f64, minor_radius: f64) -> Result<Mesh> {
    if major < 3 || minor < 3 {
        return Err(MeshError::InvalidArgument(format!(
            "torus needs at least 3 segments each way (got major={major}, minor={minor})"
        )));
    }
    if !(major_radius > minor_radius && minor_radius > 0.0) || !major_radius.is_finite() {
        return Err(MeshError::InvalidArgument(format!(
            "torus radii must satisfy major_radius > minor_radius > 0 (got {}, {})",
            crate::error::num(major_radius),
            crate::error::num(minor_radius)
        )));
    }
    // V = F = major·minor, E = 2V: refuse before allocating what cannot fit
    let v = (major as u64).saturating_mul(minor as u64);
    let c = crate::budget::Counts::plain(v, v.saturating_mul(2), v);
    if c.e.saturating_mul(2) > crate::mesh::MAX_ELEMENTS as u64 {
        return Err(MeshError::InvalidArgument(format!(
            "torus: major·minor = {major}·{minor} gives {} half-edges, more than 31-bit ids allow (major·minor at most {})",
            4 * v as u128,
            crate::mesh::MAX_ELEMENTS / 4
        )));
    }
    crate::budget::check("torus", &format!("a {major}x{minor} torus"), crate::budget::build_bytes(&c))?;
    let tau = std::f64::consts::TAU;
    let mut pos = Vec::with_capacity(major * minor);
    for i in 0..major {
        let t = tau * i as f64 / major as f64;
        for j in 0..minor {
            let s = tau * j as f64 / minor as f64;
            let r = major_radius + minor_radius * s.cos();
            pos.push(DVec3::new(r * t.cos(), r * t.sin(), minor_radius * s.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % major) * minor + j % minor) as i64;
    let mut idx = Vec::with_capacity(4 * major * minor);
    for i in 0..major {
        for j in 0..minor {
            // (∂/∂θ × ∂/∂φ) points away from the tube's core: outward
            idx.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_polygons(pos, &vec![4; major * minor], &idx, BuildOptions::default())
}

/// A closed genus-`g` surface: a slab of (2g+1)×3 unit cells, thickness 1,
/// made as a genus-0 box of quads, then tunnelled through every second cell
/// of the middle row with InsertEdge (dissertation ch. II.5): the first edge
/// between a cell's top and bottom face merges them (a handle, genus +1),
/// three more split the merged face into the tunnel's four walls.
pub fn genus_surface(g: usize) -> Result<Mesh> {
    let nx = 2 * g + 1;
    let ny = 3;
    let (gx, gy) = (nx + 1, ny + 1);
    let mut pos = Vec::with_capacity(2 * gx * gy);
    for z in [0.5, -0.5] {
        for j in 0..gy {
            for i in 0..gx {
                pos.push(DVec3::new(i as f64 - nx as f64 / 2.0, j as f64 - ny as f64 / 2.0, z));
            }
        }
    }
    let top = |i: usize, j: usize| (j * gx + i) as i64;
    let bot = |i: usize, j: usize| (gx * gy + j * gx + i) as i64;
    let mut faces: Vec<[i64; 4]> = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            faces.push([top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1)]);
            faces.push([bot(i, j), bot(i, j + 1), bot(i + 1, j + 1), bot(i + 1, j)]);
        }
    }
    // the four sides, walking the rim counter-clockwise seen from above
    let mut rim = Vec::new();
    for i in 0..nx {
        rim.push((i, 0));
    }
    for j in 0..ny {
        rim.push((nx, j));
    }
    for i in (1..=nx).rev() {
        rim.push((i, ny));
    }
    for j in (1..=ny).rev() {
        rim.push((0, j));
    }
    for k in 0..rim.len() {
        let (a, b) = (rim[k], rim[(k + 1) % rim.len()]);
        faces.push([bot(a.0, a.1), bot(b.0, b.1), top(b.0, b.1), top(a.0, a.1)]);
    }
    let idx: Vec<i64> = faces.iter().flatten().copied().collect();
    let mut m = Mesh::from_polygons(pos, &vec![4; faces.len()], &idx, BuildOptions::default())?;
    for h in 0..g {
        let (i, j) = (2 * h + 1, 1);
        let cell = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
        let tv: Vec<i64> = cell.iter().map(|&(a, b)| top(a, b)).collect();
        let bv: Vec<i64> = cell.iter().map(|&(a, b)| bot(a, b)).collect();
        // the face around `at` containing all of `want`, and `at`'s corner in it
        let corner = |m: &Mesh, at: i64, want: &[i64]| -> Corner {
            let at = VertexId(at as u32);
            let h = m
                .vertex_halfedges(at)
                .find(|&h| {
                    let f: FaceId = m.face(h);
                    want.iter().all(|&w| m.face_vertices(f).any(|x| x.0 as i64 == w))
                })
                .expect("tunnel face exists");
            Corner::Halfedge(h)
        };
        for k in 0..4 {
            let (c1, c2) = if k == 0 {
                (corner(&m, tv[0], &tv), corner(&m, bv[0], &bv))
            } else {
                let want = [tv[k], bv[k], tv[(k + 1) % 4]];
                (corner(&m, tv[k], &want), corner(&m, bv[k], &want))
            };
            m.insert_edge(c1, c2)?;
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(m: &Mesh, v: usize, e: usize, f: usize, genus: i64) {
        m.validate().unwrap();
        assert_eq!((m.n_vertices(), m.n_edges(), m.n_faces(), m.genus()), (v, e, f, genus));
        assert!(m.signed_volume() > 0.0, "outward orientation");
    }

    #[test]
    fn platonic_counts() {
        check(&tetrahedron(), 4, 6, 4, 0);
        check(&cube(), 8, 12, 6, 0);
        check(&octahedron(), 6, 12, 8, 0);
        check(&dodecahedron(), 20, 30, 12, 0);
        check(&icosahedron(), 12, 30, 20, 0);
    }

    #[test]
    fn torus_counts() {
        check(&torus(8, 5, 2.0, 0.5).unwrap(), 40, 80, 40, 1);
        assert!(torus(2, 5, 2.0, 0.5).is_err());
        assert!(torus(8, 5, 0.5, 2.0).is_err());
    }

    #[test]
    fn genus_surfaces() {
        for g in 0..6 {
            let m = genus_surface(g).unwrap();
            m.validate().unwrap();
            assert_eq!(m.genus(), g as i64);
            assert_eq!(m.n_components(), 1);
            assert!(m.signed_volume() > 0.0);
            assert_eq!(m.face_size_histogram().keys().copied().collect::<Vec<_>>(), vec![4]);
        }
    }
}
