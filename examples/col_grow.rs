//! Column modelling's crossing pairs before and after moving the crossing
//! joints' rings out (`Mesh::wireframe_columns_checked`, issue 16,
//! `ops/tools/column_repair.rs`), over the docs' survey inputs:
//! `cargo run --release --example col_grow` (`ALL=1`: every case).
use topomesh::{primitives, Mesh};

fn shortest(m: &Mesh) -> f64 {
    let (p, v) = (m.positions(), m.halfedge_columns().1);
    (0..m.n_edges()).map(|e| (p[v[2 * e] as usize] - p[v[2 * e + 1] as usize]).length()).fold(f64::INFINITY, f64::min)
}

fn main() {
    use topomesh::schemes::{catmull_clark::catmull_clark, honeycomb::honeycomb, loop_subdivision::loop_subdivision};
    let all = std::env::var("ALL").is_ok();
    let g2 = primitives::genus_surface(2).unwrap();
    let survey: Vec<(&str, Mesh)> = vec![
        ("tetrahedron", primitives::tetrahedron()),
        ("cube", primitives::cube()),
        ("octahedron", primitives::octahedron()),
        ("icosahedron", primitives::icosahedron()),
        ("dodecahedron", primitives::dodecahedron()),
        ("torus(24,12)", primitives::torus(24, 12, 1.0, 0.4).unwrap()),
        ("torus(6,4)", primitives::torus(6, 4, 1.0, 0.4).unwrap()),
        ("genus 2", g2.clone()),
        ("genus 3", primitives::genus_surface(3).unwrap()),
        ("cube CC 2", catmull_clark(&catmull_clark(&primitives::cube()).unwrap()).unwrap()),
        ("icosahedron Loop", loop_subdivision(&primitives::icosahedron()).unwrap()),
        ("honeycomb", honeycomb(&primitives::icosahedron(), 0.5, None).unwrap()),
    ];
    let more: Vec<(&str, Mesh)> = vec![
        ("genus 4", primitives::genus_surface(4).unwrap()),
        ("torus(12,6)", primitives::torus(12, 6, 1.0, 0.4).unwrap()),
        ("torus(8,3)", primitives::torus(8, 3, 1.0, 0.5).unwrap()),
        ("genus 2 CC", catmull_clark(&g2).unwrap()),
    ];
    // jittered tori and genus surfaces: every vertex moved by a tenth of the
    // shortest edge (a fixed xorshift stream)
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut jittered: Vec<(&str, Mesh)> = Vec::new();
    for (name, m) in [("torus(10,5)", primitives::torus(10, 5, 1.0, 0.4).unwrap()), ("torus(7,4)", primitives::torus(7, 4, 1.0, 0.5).unwrap()), ("genus 2", g2.clone()), ("genus 3", primitives::genus_surface(3).unwrap())] {
        for _ in 0..3 {
            let s = shortest(&m);
            let mut j = m.clone();
            for p in j.positions_mut() {
                *p += glam::DVec3::new(rnd(), rnd(), rnd()) * 0.2 * s;
            }
            jittered.push((name, j));
        }
    }
    for (label, cases, ths) in [("survey", &survey, &[0.05, 0.2][..]), ("more", &more, &[0.05, 0.1, 0.2, 0.3][..]), ("jittered", &jittered, &[0.05, 0.2][..])] {
        let (mut before, mut after, mut moved, mut runs) = (0, 0, 0, 0);
        for (name, m) in cases {
            let s = shortest(m);
            for n in [3usize, 4, 5, 6, 8] {
                for &th in ths {
                    let Ok(c) = m.wireframe_columns_checked(th * s, n) else { continue };
                    runs += 1;
                    before += c.crossing_pairs_before;
                    after += c.crossing_pairs;
                    moved += c.moved_vertices;
                    if all || c.crossing_pairs_before > 0 {
                        println!("{name:16} n={n} t={th}: {} -> {} pairs, {} vertices moved", c.crossing_pairs_before, c.crossing_pairs, c.moved_vertices);
                    }
                }
            }
        }
        println!("{label}: {runs} runs, {before} -> {after} crossing pairs, {moved} vertices moved");
    }
}
