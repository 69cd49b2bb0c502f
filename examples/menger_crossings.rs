//! Crossing triangle pairs (the exact predicate of
//! `topomesh::geometry::crossing`) of generalized Menger iterations, with
//! output size, build time and peak memory:
//! `cargo run --release --example menger_crossings [CASE...]`, cases like
//! `cube:4` (every iteration 1..=4 is reported). Without cases: the table of
//! issue 17, with the thickness reduction's figures (faces reduced, the
//! smallest factor, rebuilds); `MENGER_REDUCE=0` turns the reduction off
//! (the construction before it).
use std::time::Instant;
use topomesh::geometry::{crossing::crossing_pairs, triangles_with_points};
use topomesh::{primitives, Mesh};

fn input(name: &str) -> Mesh {
    match name {
        "cube" => primitives::cube(),
        "tetrahedron" => primitives::tetrahedron(),
        "octahedron" => primitives::octahedron(),
        "icosahedron" => primitives::icosahedron(),
        "dodecahedron" => primitives::dodecahedron(),
        "torus" => primitives::torus(24, 12, 1.0, 0.4).unwrap(),
        "genus2" => primitives::genus_surface(2).unwrap(),
        _ => panic!("unknown input {name}"),
    }
}

/// Peak resident set size of this process so far (kB), from /proc.
fn peak_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()))
        .unwrap_or(0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let default = ["cube:4", "tetrahedron:4", "octahedron:3", "icosahedron:3", "dodecahedron:3", "torus:2", "genus2:2"];
    let cases: Vec<String> = if args.is_empty() { default.iter().map(|s| s.to_string()).collect() } else { args };
    let reduce = std::env::var("MENGER_REDUCE").map_or(true, |v| v != "0");
    let o = topomesh::schemes::menger::MengerOptions { reduce_thickness: reduce, ..Default::default() };
    for case in cases {
        let (name, n) = case.split_once(':').expect("CASE is name:iterations");
        let n: usize = n.parse().expect("iterations");
        let mut m = input(name);
        for k in 1..=n {
            let t = Instant::now();
            let next = topomesh::schemes::menger::menger_reported(&m, &o);
            let secs = t.elapsed().as_secs_f64();
            let report;
            m = match next {
                Ok((x, r)) => {
                    report = r;
                    x
                }
                Err(e) => {
                    println!("{name} {k}: error {e}");
                    break;
                }
            };
            let (tris, p) = triangles_with_points(&m);
            let pairs = crossing_pairs(&p, &tris, None, false).len();
            let meets = crossing_pairs(&p, &tris, None, true).len();
            let (nred, fmin) = report.reduced();
            println!(
                "{name} {k}: faces {} genus {} volume {:.6} crossings {pairs} (with contacts {meets}) reduced {nred}/{} faces min {fmin:.4} rounds {} build {secs:.3} s ({:.0} faces/s) peak {} kB",
                m.n_faces(),
                m.genus(),
                m.signed_volume(),
                report.face_factor.len(),
                report.rounds,
                m.n_faces() as f64 / secs,
                peak_kb()
            );
        }
    }
}
