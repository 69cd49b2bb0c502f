//! Binary little-endian PLY records of variable length, split in one pass.
//!
//! A PLY face element whose faces have several sizes has records of several
//! lengths: where a record starts depends on every list count before it, so
//! NumPy cannot lay the records out without a sequential walk, and plyfile
//! decodes them one face at a time (~20 s for 1M faces). This walk finds each
//! record's properties and copies every property's raw bytes into one
//! column, which the Python side (`topomesh._ply`) views with its dtype.
//! Headers and the uniform case (one record length, one `np.frombuffer`)
//! stay in Python. [`join_records`] is the inverse, used for every write:
//! it lays the records out from the columns in parallel blocks (NumPy's
//! packed structured arrays took ~0.15 s for 1M triangles, its byte scatter
//! for interleaved sizes 1.5–3 s).

use crate::error::{MeshError, Result};

/// One property of an element: a scalar of `value_size` bytes, or a list
/// whose count is an integer of `count.0` bytes (signed when `count.1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Property {
    pub count: Option<(u8, bool)>,
    pub value_size: u8,
}

/// The raw little-endian value bytes of each property, in record order, and
/// for list properties the count of each record (empty for scalars).
#[derive(Debug, Default)]
pub struct Columns {
    pub values: Vec<Vec<u8>>,
    pub counts: Vec<Vec<i64>>,
    /// Byte offset just after the last record.
    pub end: usize,
}

fn read_count(data: &[u8], pos: usize, (size, signed): (u8, bool)) -> Option<i64> {
    let b = data.get(pos..pos + size as usize)?;
    Some(match (size, signed) {
        (1, false) => b[0] as i64,
        (1, true) => b[0] as i8 as i64,
        (2, false) => u16::from_le_bytes([b[0], b[1]]) as i64,
        (2, true) => i16::from_le_bytes([b[0], b[1]]) as i64,
        (4, false) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as i64,
        (4, true) => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as i64,
        _ => return None,
    })
}

/// Walks the `n` records from `start`: `count(record, property, offset,
/// count type)` gives each list's length, `visit(property, value bytes)`
/// sees each property's values. Returns the offset after the last record.
fn walk(
    data: &[u8],
    start: usize,
    n: usize,
    props: &[Property],
    bad: &impl Fn(String) -> MeshError,
    mut count: impl FnMut(usize, usize, usize, (u8, bool)) -> Result<i64>,
    mut visit: impl FnMut(usize, &[u8]),
) -> Result<usize> {
    let mut pos = start;
    for r in 0..n {
        for (j, p) in props.iter().enumerate() {
            let len = match p.count {
                None => p.value_size as usize,
                Some(c) => {
                    let k = count(r, j, pos, c)?;
                    pos += c.0 as usize;
                    k as usize * p.value_size as usize
                }
            };
            let v = data.get(pos..pos + len).ok_or_else(|| bad(format!("record {r} is cut off by the end of the file")))?;
            visit(j, v);
            pos += len;
        }
    }
    Ok(pos)
}

/// Splits the `n` records of an element starting at byte `start` of `data`
/// into one column per property. Two passes (counts and sizes first, then
/// the copies into exactly sized columns), so a file that lies about its
/// counts is refused before anything large is allocated.
pub fn split_records(data: &[u8], start: usize, n: usize, props: &[Property], element: &str) -> Result<Columns> {
    let bad = |msg: String| MeshError::InvalidArgument(format!("PLY {element} element: {msg}"));
    for (j, p) in props.iter().enumerate() {
        let count_ok = p.count.is_none_or(|(s, _)| matches!(s, 1 | 2 | 4));
        if !count_ok || !matches!(p.value_size, 1 | 2 | 4 | 8) {
            return Err(bad(format!("property {j} has an unsupported type size")));
        }
    }
    // a record takes at least one byte per scalar and per list count, so `n`
    // records need at least that many bytes (no allocation beyond the file)
    let min_record: usize = props.iter().map(|p| p.count.map_or(p.value_size, |c| c.0) as usize).sum();
    if min_record > 0 && n > (data.len().saturating_sub(start)) / min_record {
        return Err(bad(format!("{n} records cannot fit in the {} bytes after the header", data.len().saturating_sub(start))));
    }
    let mut counts: Vec<Vec<i64>> = props.iter().map(|p| if p.count.is_some() { Vec::with_capacity(n) } else { Vec::new() }).collect();
    let mut totals = vec![0usize; props.len()];
    let end = walk(data, start, n, props, &bad, |r, j, pos, c| {
        let k = read_count(data, pos, c).ok_or_else(|| bad(format!("record {r} is cut off by the end of the file")))?;
        if k < 0 {
            return Err(bad(format!("record {r} has a negative list length ({k})")));
        }
        counts[j].push(k);
        Ok(k)
    }, |j, v| totals[j] += v.len())?;
    let mut values: Vec<Vec<u8>> = totals.iter().map(|&t| Vec::with_capacity(t)).collect();
    let counts_of = &counts;
    walk(data, start, n, props, &bad, |r, j, _, _| Ok(counts_of[j][r]), |j, v| values[j].extend_from_slice(v))?;
    Ok(Columns { values, counts, end })
}

/// One column of records to write: a scalar of `value_size` bytes per
/// record, or (`count` = 1 or 4, the bytes of its unsigned count) a list
/// whose record `r` holds `per * sizes[r]` values of `value_size` bytes.
/// `data` is the column's little-endian value bytes, records in order,
/// `source_size` bytes per value: `value_size`, or 8 for 4-byte values
/// narrowed from int64 (each must fit an int32; the writer then needs no
/// converted copy of the mesh's index arrays).
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    pub count: u8,
    pub per: u32,
    pub value_size: u8,
    pub source_size: u8,
    pub data: &'a [u8],
}

/// Records per parallel block of [`join_records`].
const BLOCK: usize = 1 << 14;

/// Copies `src` to the start of `dst`; the common small lengths (lists of
/// 3 or 4 indices, scalars) with constant sizes, which compile to plain
/// moves instead of a `memcpy` call per record.
#[inline(always)]
fn put(dst: &mut [u8], src: &[u8]) {
    match src.len() {
        1 => dst[0] = src[0],
        2 => dst[..2].copy_from_slice(&src[..2]),
        4 => dst[..4].copy_from_slice(&src[..4]),
        8 => dst[..8].copy_from_slice(&src[..8]),
        12 => dst[..12].copy_from_slice(&src[..12]),
        16 => dst[..16].copy_from_slice(&src[..16]),
        24 => dst[..24].copy_from_slice(&src[..24]),
        n => dst[..n].copy_from_slice(src),
    }
}

/// Writes the `N` int64 values of `src` as int32 at the start of `dst`;
/// whether one did not fit. `N` constant: the common triangles and quads
/// unrolled.
#[inline(always)]
fn narrow<const N: usize>(dst: &mut [u8], src: &[u8]) -> bool {
    let (dst, src) = (&mut dst[..4 * N], &src[..8 * N]);
    let mut wide = false;
    for i in 0..N {
        let v = i64::from_le_bytes(src[8 * i..8 * i + 8].try_into().unwrap());
        wide |= v as i32 as i64 != v;
        dst[4 * i..4 * i + 4].copy_from_slice(&(v as i32).to_le_bytes());
    }
    wide
}

/// [`narrow`] for any count (`src.len() / 8` values).
fn narrow_n(dst: &mut [u8], src: &[u8]) -> bool {
    let mut wide = false;
    for (d, v) in dst.chunks_exact_mut(4).zip(src.chunks_exact(8)) {
        let v = i64::from_le_bytes(v.try_into().unwrap());
        wide |= v as i32 as i64 != v;
        d.copy_from_slice(&(v as i32).to_le_bytes());
    }
    wide
}

/// The records of `sizes.len()` faces (`sizes[r]` corners each) laid out
/// property after property, as a PLY binary little-endian element body.
pub fn join_records(sizes: &[i64], fields: &[Field]) -> Result<Vec<u8>> {
    check_layout(sizes, fields)?;
    let mut out = Vec::new();
    join_into(sizes, fields, &mut out)?;
    Ok(out)
}

/// Checks `fields` against `sizes` (see [`Field`]); the corner count.
fn check_layout(sizes: &[i64], fields: &[Field]) -> Result<usize> {
    let bad = |msg: String| MeshError::InvalidArgument(format!("PLY record layout: {msg}"));
    if let Some(r) = sizes.iter().position(|&k| k < 0) {
        return Err(bad(format!("face {r} has a negative size ({})", sizes[r])));
    }
    let corners: usize = sizes.iter().map(|&k| k as usize).sum();
    let top = sizes.iter().copied().max().unwrap_or(0) as u64;
    for (j, f) in fields.iter().enumerate() {
        if f.source_size != f.value_size && (f.source_size, f.value_size) != (8, 4) {
            return Err(bad(format!("property {j}: {}-byte values from {}-byte sources", f.value_size, f.source_size)));
        }
        let units = if f.count == 0 { sizes.len() } else { corners * f.per as usize };
        if f.data.len() != units * f.source_size as usize {
            return Err(bad(format!("property {j} has {} bytes, expected {}", f.data.len(), units * f.source_size as usize)));
        }
        let limit = match f.count { 0 => u64::MAX, 1 => 255, 4 => u32::MAX as u64, c => return Err(bad(format!("property {j}: count of {c} bytes"))) };
        if top * f.per as u64 > limit {
            return Err(bad(format!("property {j}: a list of {} values does not fit its {}-byte count", top * f.per as u64, f.count)));
        }
    }
    Ok(corners)
}

/// [`join_records`] into `out`, whose allocation is reused when it is
/// large enough; `fields` already passed [`check_layout`] with `sizes`.
fn join_into(sizes: &[i64], fields: &[Field], out: &mut Vec<u8>) -> Result<()> {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    let bad = |msg: String| MeshError::InvalidArgument(format!("PLY record layout: {msg}"));
    let len = |k: usize| -> usize {
        fields.iter().map(|f| if f.count == 0 { f.value_size as usize } else { f.count as usize + k * f.per as usize * f.value_size as usize }).sum()
    };
    // per block: its first corner and its first byte
    let blocks: Vec<(usize, usize)> = sizes.par_chunks(BLOCK).map(|b| (b.iter().map(|&k| k as usize).sum(), b.iter().map(|&k| len(k as usize)).sum())).collect();
    let total: usize = blocks.iter().map(|b| b.1).sum();
    if out.capacity() < total {
        *out = vec![0u8; total];
        crate::mesh::populate(out, total);
    } else {
        out.clear();
        out.resize(total, 0);
    }
    let mut parts = Vec::with_capacity(blocks.len());
    let (mut rest, mut corner) = (&mut out[..], 0usize);
    for (i, &(nc, nb)) in blocks.iter().enumerate() {
        let (head, tail) = rest.split_at_mut(nb);
        parts.push((i * BLOCK, corner, head));
        rest = tail;
        corner += nc;
    }
    let too_wide = AtomicBool::new(false);
    parts.into_par_iter().for_each(|(r0, mut c, buf)| {
        let (mut pos, mut wide) = (0, false);
        for (r, &k) in sizes[r0..(r0 + BLOCK).min(sizes.len())].iter().enumerate() {
            let k = k as usize;
            for f in fields {
                let (vs, ss) = (f.value_size as usize, f.source_size as usize);
                let (a, n) = if f.count == 0 {
                    ((r0 + r) * ss, 1)
                } else {
                    let n = k * f.per as usize;
                    if f.count == 1 {
                        buf[pos] = n as u8;
                    } else {
                        buf[pos..pos + 4].copy_from_slice(&(n as u32).to_le_bytes());
                    }
                    pos += f.count as usize;
                    (c * f.per as usize * ss, n)
                };
                let src = &f.data[a..a + n * ss];
                if ss == vs {
                    put(&mut buf[pos..], src);
                } else {
                    wide |= match n {
                        3 => narrow::<3>(&mut buf[pos..], src),
                        4 => narrow::<4>(&mut buf[pos..], src),
                        _ => narrow_n(&mut buf[pos..], src),
                    };
                }
                pos += n * vs;
            }
            c += k;
        }
        if wide {
            too_wide.store(true, Relaxed);
        }
    });
    if too_wide.load(Relaxed) {
        return Err(bad("a value narrowed from int64 does not fit int32".into()));
    }
    Ok(())
}

/// Faces per chunk of [`write_records`].
const WRITE_CHUNK: usize = 1 << 16;

/// The records of [`join_records`] written to `w`, chunk of faces by chunk
/// through two reused buffers: the next chunk is laid out while this one is
/// written, so the write and the layout overlap and the body never needs
/// fresh pages of its whole size (1M triangles: 26 MB). `chunk` faces per
/// chunk (0: the default).
pub fn write_records<W: std::io::Write + Send>(w: &mut W, sizes: &[i64], fields: &[Field], chunk: usize) -> Result<()> {
    let io = |e: std::io::Error| MeshError::Io(e.to_string());
    check_layout(sizes, fields)?;
    let chunk = if chunk == 0 { WRITE_CHUNK } else { chunk };
    // per chunk: its first face and its first corner
    let mut starts = Vec::with_capacity(sizes.len() / chunk + 2);
    let mut corner = 0usize;
    for (i, c) in sizes.chunks(chunk).enumerate() {
        starts.push((i * chunk, corner));
        corner += c.iter().map(|&k| k as usize).sum::<usize>();
    }
    starts.push((sizes.len(), corner));
    let part = |i: usize, out: &mut Vec<u8>| -> Result<()> {
        let ((r0, c0), (r1, c1)) = (starts[i], starts[i + 1]);
        let sub: Vec<Field> = fields
            .iter()
            .map(|f| {
                let (ss, per) = (f.source_size as usize, f.per as usize);
                let (a, b) = if f.count == 0 { (r0 * ss, r1 * ss) } else { (c0 * per * ss, c1 * per * ss) };
                Field { data: &f.data[a..b], ..*f }
            })
            .collect();
        join_into(&sizes[r0..r1], &sub, out) // each chunk's part of the layout checked above
    };
    let parts = starts.len() - 1;
    let (mut cur, mut next) = (Vec::new(), Vec::new());
    if parts > 0 {
        part(0, &mut cur)?;
    }
    for i in 0..parts {
        crate::cancel::check()?;
        let (written, laid) = rayon::join(|| w.write_all(&cur), || if i + 1 < parts { part(i + 1, &mut next) } else { Ok(()) });
        written.map_err(io)?;
        laid?;
        std::mem::swap(&mut cur, &mut next);
    }
    w.flush().map_err(io)
}

/// Records per parallel block of [`gather`].
const GATHER_BLOCK: usize = 1 << 14;

/// The columns of `n` fixed-length records of `record` bytes starting at
/// byte `start` of `data`: per field `(offset in the record, width)`, the
/// field's bytes of every record, contiguous, in record order. A uniform
/// PLY element (every face of one size) is read this way: one parallel pass
/// per column into pages mapped up front, where NumPy's strided copies of
/// a structured view took 25 ms of a 1M-triangle file's 45 ms read.
pub fn gather(data: &[u8], start: usize, n: usize, record: usize, fields: &[(usize, usize)]) -> Result<Vec<Vec<u8>>> {
    check_records(start as u64, n, record, fields, data.len() as u64)?;
    let mut out = columns(n, fields);
    if !gather_into(&data[start..start + n * record], record, fields, &mut out, 0, GATHER_BLOCK) {
        return Err(MeshError::Interrupted);
    }
    Ok(filled(out, n, fields))
}

/// Bytes of the file per chunk of [`gather_file`]: two such buffers, reused,
/// stay in the cache while their records are gathered.
const FILE_CHUNK: usize = 1 << 20;

/// Records per parallel block of one chunk of [`gather_file`].
const FILE_BLOCK: usize = 1 << 12;

/// Empty columns with room for `n` records per field, their pages mapped:
/// [`gather_into`] writes every byte, then [`filled`] sets their lengths
/// (zeroing them first took 6 % of a gather, `perf`).
fn columns(n: usize, fields: &[(usize, usize)]) -> Vec<Vec<u8>> {
    fields
        .iter()
        .map(|&(_, w)| {
            let mut col = Vec::with_capacity(n * w);
            crate::mesh::populate(&mut col, n * w);
            col
        })
        .collect()
}

/// The columns of [`columns`] once [`gather_into`] has written all their
/// `n` records (every block: each call returned true).
fn filled(mut out: Vec<Vec<u8>>, n: usize, fields: &[(usize, usize)]) -> Vec<Vec<u8>> {
    for (col, &(_, w)) in out.iter_mut().zip(fields) {
        assert!(col.capacity() >= n * w);
        // SAFETY: gather_into wrote bytes 0..n * w of the column's capacity.
        unsafe { col.set_len(n * w) };
    }
    out
}

/// Writes `src` at the start of `dst`, with a fixed-size copy for the usual
/// widths (counts, indices, coordinates): `copy_from_slice` of a 1-byte
/// count was a `memmove` call per record, 19 % of a gather (`perf`).
#[inline(always)]
fn put_uninit(dst: &mut [std::mem::MaybeUninit<u8>], src: &[u8]) {
    #[inline(always)]
    fn fixed<const N: usize>(dst: &mut [std::mem::MaybeUninit<u8>], src: &[u8]) {
        let (d, s) = (&mut dst[..N], &src[..N]);
        // SAFETY: both slices hold N bytes and do not overlap (output and input).
        unsafe { std::ptr::copy_nonoverlapping(s.as_ptr(), d.as_mut_ptr().cast::<u8>(), N) }
    }
    match src.len() {
        1 => dst[0] = std::mem::MaybeUninit::new(src[0]),
        2 => fixed::<2>(dst, src),
        4 => fixed::<4>(dst, src),
        8 => fixed::<8>(dst, src),
        12 => fixed::<12>(dst, src),
        16 => fixed::<16>(dst, src),
        24 => fixed::<24>(dst, src),
        n => {
            let d = &mut dst[..n];
            // SAFETY: both slices hold n bytes and do not overlap.
            unsafe { std::ptr::copy_nonoverlapping(src.as_ptr(), d.as_mut_ptr().cast::<u8>(), n) }
        }
    }
}

/// Gathers the `src.len() / record` records of `src` into the capacity of
/// `out`'s columns (from [`columns`]) from record `first` on, in parallel
/// blocks of `block` records. False when a cancellation left blocks out.
#[must_use]
fn gather_into(src: &[u8], record: usize, fields: &[(usize, usize)], out: &mut [Vec<u8>], first: usize, block: usize) -> bool {
    use rayon::prelude::*;
    if record == 0 {
        return true; // every field is empty
    }
    let n = src.len() / record;
    let mut blocks: Vec<Vec<&mut [std::mem::MaybeUninit<u8>]>> = (0..n.div_ceil(block)).map(|_| Vec::with_capacity(fields.len())).collect();
    for (col, &(_, w)) in out.iter_mut().zip(fields) {
        if w == 0 {
            blocks.iter_mut().for_each(|b| b.push(&mut []));
            continue;
        }
        for (b, dst) in blocks.iter_mut().zip(col.spare_capacity_mut()[first * w..(first + n) * w].chunks_mut(block * w)) {
            b.push(dst);
        }
    }
    blocks.into_par_iter().zip(src.par_chunks(block * record)).all(|(mut dsts, recs)| {
        if crate::cancel::requested() {
            return false;
        }
        for (i, rec) in recs.chunks_exact(record).enumerate() {
            for (dst, &(off, w)) in dsts.iter_mut().zip(fields) {
                put_uninit(&mut dst[i * w..], &rec[off..off + w]);
            }
        }
        true
    })
}

/// Refuses records of [`gather`] that run past the end of `len` bytes, or
/// fields that do not fit a record.
fn check_records(start: u64, n: usize, record: usize, fields: &[(usize, usize)], len: u64) -> Result<()> {
    let bad = |msg: String| MeshError::InvalidArgument(format!("PLY records: {msg}"));
    let end = (n as u64).checked_mul(record as u64).and_then(|b| b.checked_add(start));
    if end.is_none_or(|e| e > len) {
        return Err(bad(format!("{n} records of {record} bytes from byte {start} run past the end of the {len} bytes")));
    }
    if let Some(&(o, w)) = fields.iter().find(|&&(o, w)| o + w > record) {
        return Err(bad(format!("a field of {w} bytes at offset {o} does not fit a record of {record}")));
    }
    Ok(())
}

/// [`gather`] straight from the file at `path`: its records are read in
/// chunks into two reused buffers, the next chunk read while this one is
/// gathered, so the file's bytes never take fresh pages. Reading a 36 MiB
/// PLY whole (`read_file`) took 18-20 ms, most of it faulting in and
/// zeroing the buffer, before the gather could start.
pub fn gather_file(path: &std::path::Path, start: u64, n: usize, record: usize, fields: &[(usize, usize)]) -> Result<Vec<Vec<u8>>> {
    use std::io::{Read, Seek, SeekFrom};
    let io = |e: std::io::Error| MeshError::Io(format!("{}: cannot read ({e})", path.display()));
    let mut f = std::fs::File::open(path).map_err(io)?;
    check_records(start, n, record, fields, f.metadata().map_err(io)?.len())?;
    let bytes = fields.iter().map(|&(_, w)| w as u64).sum::<u64>() * n as u64;
    crate::budget::check("load", &format!("{} ({n} records)", path.display()), bytes)?;
    let mut out = columns(n, fields);
    if n == 0 || record == 0 {
        return Ok(filled(out, n, fields)); // nothing to write
    }
    f.seek(SeekFrom::Start(start)).map_err(io)?;
    let per = (FILE_CHUNK / record).clamp(1, n);
    let mut cur = vec![0u8; per * record];
    let mut next = vec![0u8; per * record];
    f.read_exact(&mut cur).map_err(io)?;
    let mut first = 0;
    while first < n {
        crate::cancel::check()?;
        let nr = per.min(n - first);
        let after = per.min(n - first - nr);
        // one thread reads the next chunk while the others gather this one
        // (the reader joins the gather when its read is done)
        let (read, whole) = rayon::join(
            || f.read_exact(&mut next[..after * record]),
            || gather_into(&cur[..nr * record], record, fields, &mut out, first, FILE_BLOCK),
        );
        read.map_err(io)?;
        if !whole {
            return Err(MeshError::Interrupted);
        }
        std::mem::swap(&mut cur, &mut next);
        first += nr;
    }
    Ok(filled(out, n, fields))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIST_U8_I32: Property = Property { count: Some((1, false)), value_size: 4 };
    const SCALAR_U16: Property = Property { count: None, value_size: 2 };

    fn record(out: &mut Vec<u8>, idx: &[i32], tag: u16) {
        out.push(idx.len() as u8);
        idx.iter().for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
        out.extend_from_slice(&tag.to_le_bytes());
    }

    #[test]
    fn splits_records_of_several_lengths() {
        let faces: [&[i32]; 3] = [&[0, 1, 2], &[3, 4, 5, 6], &[7, 8, 9, 10, 11]];
        let mut data = b"header".to_vec();
        for (t, f) in faces.iter().enumerate() {
            record(&mut data, f, 100 + t as u16);
        }
        let c = split_records(&data, 6, 3, &[LIST_U8_I32, SCALAR_U16], "face").unwrap();
        assert_eq!(c.end, data.len());
        assert_eq!(c.counts[0], vec![3, 4, 5]);
        assert!(c.counts[1].is_empty());
        let idx: Vec<i32> = c.values[0].chunks(4).map(|b| i32::from_le_bytes(b.try_into().unwrap())).collect();
        assert_eq!(idx, (0..12).collect::<Vec<_>>());
        let tags: Vec<u16> = c.values[1].chunks(2).map(|b| u16::from_le_bytes(b.try_into().unwrap())).collect();
        assert_eq!(tags, vec![100, 101, 102]);
    }

    #[test]
    fn truncated_and_lying_files_are_errors() {
        let mut data = Vec::new();
        record(&mut data, &[0, 1, 2], 7);
        let short = &data[..data.len() - 1];
        let e = split_records(short, 0, 1, &[LIST_U8_I32, SCALAR_U16], "face").unwrap_err().to_string();
        assert!(e.contains("record 0 is cut off"), "{e}");
        // a count of 10^9 records is refused before any allocation
        let e = split_records(&data, 0, 1_000_000_000, &[LIST_U8_I32], "face").unwrap_err().to_string();
        assert!(e.contains("cannot fit"), "{e}");
        let neg = [0xffu8, 0, 0, 0, 0];
        let p = Property { count: Some((1, true)), value_size: 4 };
        let e = split_records(&neg, 0, 1, &[p], "face").unwrap_err().to_string();
        assert!(e.contains("negative list length"), "{e}");
    }

    /// Face sizes 3, 0, 5, 1 and a long run over several blocks, a u16 scalar
    /// per face and two doubles per corner: `(sizes, corners, tag, uv)`.
    fn mixed_faces() -> (Vec<i64>, usize, Vec<u8>, Vec<u8>) {
        let mut sizes = vec![3i64, 0, 5, 1];
        sizes.extend(std::iter::repeat_n(4, 2 * BLOCK + 7));
        let nc: usize = sizes.iter().map(|&k| k as usize).sum();
        let tag: Vec<u8> = (0..sizes.len() as u16).flat_map(|i| i.wrapping_mul(7).to_le_bytes()).collect();
        let uv: Vec<u8> = (0..2 * nc as u64).flat_map(|i| (i as f64 * 0.5).to_le_bytes()).collect();
        (sizes, nc, tag, uv)
    }

    #[test]
    fn join_is_the_inverse_of_split() {
        // mixed_faces, with a scalar, a 1-byte-count list and a 4-byte-count list of 2 per corner
        let (sizes, nc, tag, uv) = mixed_faces();
        let idx: Vec<u8> = (0..nc as i32).flat_map(|i| i.to_le_bytes()).collect();
        let fields = [
            Field { count: 1, per: 1, value_size: 4, source_size: 4, data: &idx },
            Field { count: 0, per: 1, value_size: 2, source_size: 2, data: &tag },
            Field { count: 4, per: 2, value_size: 8, source_size: 8, data: &uv },
        ];
        let body = join_records(&sizes, &fields).unwrap();
        // the first record by hand: count 3, indices 0 1 2, tag 0, count 6, six doubles
        assert_eq!(body[0], 3);
        assert_eq!(&body[1..13], &idx[..12]);
        assert_eq!(&body[13..15], &[0, 0]);
        assert_eq!(&body[15..19], &6u32.to_le_bytes());
        let props = [LIST_U8_I32, SCALAR_U16, Property { count: Some((4, false)), value_size: 8 }];
        let c = split_records(&body, 0, sizes.len(), &props, "face").unwrap();
        assert_eq!(c.end, body.len());
        assert_eq!(c.counts[0], sizes);
        assert_eq!(c.counts[2], sizes.iter().map(|k| 2 * k).collect::<Vec<_>>());
        assert_eq!((&c.values[0], &c.values[1], &c.values[2]), (&idx, &tag, &uv));
    }

    #[test]
    fn written_records_are_the_joined_ones() {
        // mixed_faces with an int64 column narrowed, written in chunks of 1, 3
        // and 1000 faces and the default, and in one
        let (sizes, nc, tag, uv) = mixed_faces();
        let idx: Vec<u8> = (0..nc as i64).flat_map(|i| (i - 2).to_le_bytes()).collect();
        let fields = [
            Field { count: 1, per: 1, value_size: 4, source_size: 8, data: &idx },
            Field { count: 0, per: 1, value_size: 2, source_size: 2, data: &tag },
            Field { count: 4, per: 2, value_size: 8, source_size: 8, data: &uv },
        ];
        let whole = join_records(&sizes, &fields).unwrap();
        for chunk in [1, 3, 1000, 0, sizes.len()] {
            let mut out = Vec::new();
            write_records(&mut out, &sizes, &fields, chunk).unwrap();
            assert!(out == whole, "chunk {chunk}");
        }
        let mut out = Vec::new();
        write_records(&mut out, &[], &[], 0).unwrap();
        assert!(out.is_empty());
        // layout errors before anything is written; a value that does not fit, in a later chunk
        let e = write_records(&mut out, &sizes, &[Field { data: &idx[..8], ..fields[0] }], 0).unwrap_err().to_string();
        assert!(e.contains("property 0 has 8 bytes, expected"), "{e}");
        let e = write_records(&mut out, &[3, -1], &[], 0).unwrap_err().to_string();
        assert!(e.contains("face 1 has a negative size"), "{e}");
        assert!(out.is_empty());
        let mut big = idx.clone();
        let at = big.len() - 8;
        big[at..].copy_from_slice(&(1i64 << 40).to_le_bytes());
        let f = [Field { data: &big, ..fields[0] }, fields[1], fields[2]];
        let e = write_records(&mut out, &sizes, &f, 3).unwrap_err().to_string();
        assert!(e.contains("does not fit int32"), "{e}");
        // an I/O error is a MeshError
        struct Full;
        impl std::io::Write for Full {
            fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
                Err(std::io::Error::new(std::io::ErrorKind::StorageFull, "no space left on device"))
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let e = write_records(&mut Full, &sizes, &fields, 0).unwrap_err().to_string();
        assert!(e.contains("no space left on device"), "{e}");
    }

    #[test]
    fn int64_sources_narrow_to_the_same_bytes() {
        // mixed sizes, negative values (twins -1, -2) and both ends of int32
        let sizes = [3i64, 1, 4, 2];
        let vals: Vec<i64> = vec![0, 1, 2, -1, -2, 7, i32::MAX as i64, i32::MIN as i64, 5, 6];
        let wide: Vec<u8> = vals.iter().flat_map(|v| v.to_le_bytes()).collect();
        let narrow: Vec<u8> = vals.iter().flat_map(|&v| (v as i32).to_le_bytes()).collect();
        let f = |data, source_size| [Field { count: 1, per: 1, value_size: 4, source_size, data }];
        assert_eq!(join_records(&sizes, &f(&wide, 8)).unwrap(), join_records(&sizes, &f(&narrow, 4)).unwrap());
        let mut big = wide.clone();
        big[8 * 9..8 * 10].copy_from_slice(&(1i64 << 31).to_le_bytes());
        let e = join_records(&sizes, &f(&big, 8)).unwrap_err().to_string();
        assert!(e.contains("does not fit int32"), "{e}");
        let e = join_records(&sizes, &[Field { count: 1, per: 1, value_size: 2, source_size: 8, data: &wide }]).unwrap_err().to_string();
        assert!(e.contains("2-byte values from 8-byte sources"), "{e}");
    }

    #[test]
    fn gather_reads_the_columns_of_fixed_records() {
        // records [u8 count][3 x i32][u16 tag], 15 bytes, past a block boundary
        let n = GATHER_BLOCK + 5;
        let mut data = b"head".to_vec();
        for r in 0..n {
            record(&mut data, &[r as i32, -(r as i32), 7], r as u16);
        }
        let cols = gather(&data, 4, n, 15, &[(0, 1), (1, 12), (13, 2)]).unwrap();
        assert!(cols[0].iter().all(|&c| c == 3));
        let idx: Vec<i32> = cols[1].chunks(4).map(|b| i32::from_le_bytes(b.try_into().unwrap())).collect();
        assert_eq!(&idx[3 * (n - 1)..], &[(n - 1) as i32, -((n - 1) as i32), 7]);
        let tags: Vec<u16> = cols[2].chunks(2).map(|b| u16::from_le_bytes(b.try_into().unwrap())).collect();
        assert_eq!(tags, (0..n).map(|r| r as u16).collect::<Vec<_>>());
        let e = gather(&data, 5, n, 15, &[(0, 1)]).unwrap_err().to_string();
        assert!(e.contains("run past the end"), "{e}");
        let e = gather(&data, 4, n, 15, &[(14, 2)]).unwrap_err().to_string();
        assert!(e.contains("does not fit a record of 15"), "{e}");
    }

    #[test]
    fn gather_file_equals_the_gather_of_the_bytes() {
        // 15-byte records over several of the file reader's chunks, from byte 4
        let n = 3 * FILE_CHUNK / 15 + 7;
        let mut data = b"head".to_vec();
        for r in 0..n {
            record(&mut data, &[r as i32, -(r as i32), 7], r as u16);
        }
        let path = std::env::temp_dir().join(format!("topomesh-gather-{}.bin", std::process::id()));
        std::fs::write(&path, &data).unwrap();
        let fields = [(0, 1), (1, 12), (13, 2), (5, 0)];
        let from_file = gather_file(&path, 4, n, 15, &fields);
        let short = gather_file(&path, 5, n, 15, &fields).unwrap_err().to_string();
        let wide = gather_file(&path, 4, n, 15, &[(14, 2)]).unwrap_err().to_string();
        let few = gather_file(&path, 4, 2, 15, &fields).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(from_file.unwrap(), gather(&data, 4, n, 15, &fields).unwrap());
        assert_eq!(few, gather(&data, 4, 2, 15, &fields).unwrap());
        assert!(short.contains("run past the end of the"), "{short}");
        assert!(wide.contains("does not fit a record of 15"), "{wide}");
        let e = gather_file(&path, 0, 1, 1, &[]).unwrap_err().to_string();
        assert!(e.contains("cannot read"), "{e}");
    }

    #[test]
    fn join_refuses_what_it_cannot_write() {
        let idx = vec![0u8; 4 * 300];
        let e = join_records(&[300], &[Field { count: 1, per: 1, value_size: 4, source_size: 4, data: &idx }]).unwrap_err().to_string();
        assert!(e.contains("does not fit its 1-byte count"), "{e}");
        let e = join_records(&[3], &[Field { count: 1, per: 1, value_size: 4, source_size: 4, data: &idx[..8] }]).unwrap_err().to_string();
        assert!(e.contains("property 0 has 8 bytes, expected 12"), "{e}");
        let e = join_records(&[-1], &[]).unwrap_err().to_string();
        assert!(e.contains("face 0 has a negative size"), "{e}");
    }
}
