//! Truncate (`t = dkd`) on the 100k-quad torus, the composition (the
//! first dual, then the fused `dual(kis(·))`, as `conway "zd"` runs it)
//! against the one-pass build, alternating in one process (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example ab_truncate [N]`
//! prints the best and median of N calls each (ms, M output faces/s) and
//! the FNV hash of both outputs (`prof_keyed`'s), with zip (`dk`, the
//! same output size) for reference. `TOPOMESH_HUGE_PAGES=1` advises huge
//! pages as the extension then does (`common::Huge`).
mod common;

use topomesh::schemes::conway::conway;

#[global_allocator]
static GLOBAL: common::Huge = common::Huge;

fn main() {
    let (reps, t) = common::setup();
    // zip (`dk`, the same output size, already one pass) for reference
    let ops: [(&str, common::Op); 3] = [("composition", |m| conway("zd", Some(m))), ("one pass", |m| conway("t", Some(m))), ("zip", |m| conway("z", Some(m)))];
    let (a, b) = (ops[0].1(&t).unwrap(), ops[1].1(&t).unwrap());
    let (ha, hb) = (common::hash(&a), common::hash(&b));
    println!("hash composition {ha:016x}, one pass {hb:016x}");
    assert!(ha == hb && a == b, "the builds differ");
    drop((a, b));
    common::alternate(&ops, &t, reps, None);
}
