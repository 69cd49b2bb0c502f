//! A/B of `io::ply::gather` (one pass over the records, every column at
//! once) against the column-by-column pass it replaced, on 1M records laid
//! out as topomesh's triangle PLY (`[u8 3][3 x i32][u8 3][3 x i32]`), both
//! in one process, alternating: `cargo run --release --example ab_gather`.
use rayon::prelude::*;
use std::time::Instant;

fn by_column(data: &[u8], start: usize, n: usize, record: usize, fields: &[(usize, usize)]) -> Vec<Vec<u8>> {
    const B: usize = 1 << 14;
    fields
        .iter()
        .map(|&(off, w)| {
            let mut col = vec![0u8; n * w];
            topomesh::mesh::populate(&mut col, n * w);
            col.par_chunks_mut(B * w).enumerate().for_each(|(b, dst)| {
                let src = &data[start + b * B * record + off..];
                for (i, d) in dst.chunks_exact_mut(w).enumerate() {
                    d.copy_from_slice(&src[i * record..i * record + w]);
                }
            });
            col
        })
        .collect()
}

fn main() {
    let n = 1_000_000;
    let mut data = vec![0u8; 26 * n];
    for r in 0..n {
        let rec = &mut data[26 * r..26 * r + 26];
        rec[0] = 3;
        rec[13] = 3;
        for k in 0..3 {
            rec[1 + 4 * k..5 + 4 * k].copy_from_slice(&((3 * r + k) as i32).to_le_bytes());
            rec[14 + 4 * k..18 + 4 * k].copy_from_slice(&((3 * r + k) as i32 ^ 1).to_le_bytes());
        }
    }
    let fields = [(0, 1), (1, 12), (13, 1), (14, 12)];
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _ in 0..15 {
        let t = Instant::now();
        let x = topomesh::io::ply::gather(&data, 0, n, 26, &fields).unwrap();
        a.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let y = by_column(&data, 0, n, 26, &fields);
        b.push(t.elapsed().as_secs_f64() * 1e3);
        assert_eq!(x, y);
    }
    a.sort_by(f64::total_cmp);
    b.sort_by(f64::total_cmp);
    println!("one pass: median {:.2} ms, min {:.2}; by column: median {:.2} ms, min {:.2}", a[7], a[0], b[7], b[0]);
}
