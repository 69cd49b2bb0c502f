//! Dual Loop on the 100k-quad torus, the composition (dual, Loop, dual)
//! against the one-pass build, alternating in one process (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example ab_dual_loop [N]`
//! prints the best and median of N calls each (ms, M output faces/s).
//! `TOPOMESH_HUGE_PAGES=1` advises blocks of 4–64 MiB to use huge pages, as
//! the Python extension's allocator then does (`common::Huge`; off by
//! default there and here). `AB_ONLY=1` times the one pass alone (for a
//! profiler).
mod common;

use topomesh::schemes::{dual::dual, loop_subdivision::loop_subdivision, topmod::compose};

#[global_allocator]
static GLOBAL: common::Huge = common::Huge;

fn main() {
    let (reps, t) = common::setup();
    let ops: [(&str, common::Op); 2] = [("composition", |m| dual(&loop_subdivision(&dual(m)?)?)), ("one pass", compose::dual_loop)];
    let (a, b) = (ops[0].1(&t).unwrap(), ops[1].1(&t).unwrap());
    assert!(a == b, "the builds differ");
    drop((a, b));
    let only = std::env::var("AB_ONLY").is_ok_and(|v| v == "1");
    common::alternate(&ops, &t, reps, only.then_some(0));
}
