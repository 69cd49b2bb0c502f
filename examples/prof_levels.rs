//! One warm subdivision step at a chosen level on the 81,920-triangle
//! icosphere (issue 19; `TOPOMESH_PROF_INPUT=torus`: the 100k-quad torus),
//! for profilers and A/B runs, one thread:
//! `RAYON_NUM_THREADS=1 cargo run --release --example prof_levels -- catmull_clark|loop|midpoint|doo_sabin|sqrt3|honeycomb|vertex_truncation 3 [REPS]`.
//! Level L times one step on the output of L − 1 steps; `iter` as a 4th
//! argument times `L` steps from the sphere instead (what `iterations=L` does),
//! `counts` the budget's `Counts::of` on the level's input. Prints the median
//! wall time per call and per output face (`TOPOMESH_PROF_ALL=1`: every
//! call's time in order; `TOPOMESH_PROF_SPAWN=1`: each call on a fresh
//! thread, as the extension runs its work). Deterministic counts for A/B runs:
//! `valgrind --tool=cachegrind --cache-sim=yes --LL=33554432,16,64` on it.
use std::time::Instant;
use topomesh::schemes::{catmull_clark::catmull_clark, loop_subdivision::loop_subdivision};
use topomesh::{primitives, Mesh};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let scheme = a.get(1).map_or("catmull_clark", |s| s.as_str());
    let level: usize = a.get(2).map_or(3, |s| s.parse().unwrap());
    let reps: usize = a.get(3).map_or(5, |s| s.parse().unwrap());
    let iter = a.get(4).is_some_and(|s| s == "iter");
    let counts = a.get(4).is_some_and(|s| s == "counts");
    let step: fn(&Mesh) -> topomesh::Result<Mesh> = match scheme {
        "loop" => loop_subdivision,
        "midpoint" => topomesh::schemes::midpoint::midpoint,
        "honeycomb" => |m| topomesh::schemes::honeycomb::honeycomb(m, 0.5, None),
        "doo_sabin" => topomesh::schemes::doo_sabin::doo_sabin,
        "sqrt3" => topomesh::schemes::sqrt3::sqrt3,
        "vertex_truncation" => |m| topomesh::schemes::vertex_truncation::vertex_truncation(m, topomesh::schemes::vertex_truncation::Truncation::Chaikin),
        _ => catmull_clark,
    };
    // TOPOMESH_PROF_INPUT=torus: the 400×250 torus (100k quads) instead
    let mut sphere = primitives::icosahedron();
    if std::env::var("TOPOMESH_PROF_INPUT").is_ok_and(|s| s == "torus") {
        sphere = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    } else {
        for _ in 0..6 {
            sphere = loop_subdivision(&sphere).unwrap();
        }
    }
    let mut input = sphere.clone();
    if !iter {
        for _ in 1..level {
            input = step(&input).unwrap();
        }
    }
    if counts {
        // the budget's per-level count of the input (python iterate_with)
        let mut t = Vec::new();
        for _ in 0..reps {
            let t0 = Instant::now();
            std::hint::black_box(topomesh::budget::Counts::of(&input));
            t.push(t0.elapsed().as_secs_f64() * 1e3);
        }
        t.sort_by(f64::total_cmp);
        println!("Counts::of on {} faces: median {:.2} ms", input.n_faces(), t[t.len() / 2]);
        return;
    }
    let run = |m: &Mesh| -> Mesh {
        if !iter {
            return step(m).unwrap();
        }
        let mut cur = step(m).unwrap();
        for _ in 1..level {
            cur = step(&cur).unwrap();
        }
        cur
    };
    let mut t = Vec::new();
    let mut nf = 0;
    for _ in 0..reps {
        let t0 = Instant::now();
        // TOPOMESH_PROF_SPAWN=1: on a fresh non-pool thread, as the extension runs its work
        let r = if std::env::var("TOPOMESH_PROF_SPAWN").is_ok() { std::thread::scope(|s| s.spawn(|| run(&input)).join().unwrap()) } else { run(&input) };
        t.push(t0.elapsed().as_secs_f64() * 1e3);
        nf = r.n_faces();
    }
    if std::env::var("TOPOMESH_PROF_ALL").is_ok() {
        // every call in order: does a warm call cost what the first did?
        println!("{}", t.iter().map(|x| format!("{x:.0}")).collect::<Vec<_>>().join(" "));
    }
    t.sort_by(f64::total_cmp);
    let med = t[t.len() / 2];
    println!("{scheme} {} L{level}: {nf} faces, median {med:.1} ms, min {:.1} ms, {:.1} ns/face", if iter { "iter" } else { "step" }, t[0], med / nf as f64 * 1e6);
}
