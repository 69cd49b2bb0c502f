//! A small, fast Wavefront OBJ reader for polygon meshes, keeping the file's
//! own global `v` numbering.
//!
//! Why not the `tobj` crate: it builds one mesh per `o`/`g` model and
//! re-indexes positions per model (and per distinct `v/vt/vn` triple), so a
//! vertex shared by two groups comes back twice and the file's numbering is
//! lost; welding the copies back by position would also merge vertices that
//! the file keeps apart. This reader keeps the `v` numbering and gives the
//! face-varying data beside it: the `vt` and `vn` tables with each corner's
//! index into them (so UV seams stay exactly as written), and each face's
//! group (`g`/`o`) and material (`usemtl`).
//!
//! Read as Blender, Maya, trimesh and pyvista write it: `v x y z [w | r g b]`,
//! `vt u [v [w]]`, `vn x y z`, `f` corners as `v`, `v/vt`, `v/vt/vn` or
//! `v//vn` (the three have their own counts), negative (relative) indices,
//! comments (`#` to the end of the line), `\` line continuations, CRLF.
//! `vp`, `s`, `mtllib` and other statements are ignored; `l` (polyline) and
//! `p` (point) elements are not faces: they are skipped and counted. Errors
//! name the file and the line (1-based, where the statement starts) and the
//! index as written in the file.

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::DVec3;
use std::io::Write;
use std::path::Path;

/// What [`read_obj`] returns: positions in file order, faces as sizes and
/// 0-based flat vertex indices, and the number of skipped `l` / `p` elements;
/// then the face-varying data.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjData {
    pub positions: Vec<DVec3>,
    pub sizes: Vec<i64>,
    pub indices: Vec<i64>,
    pub n_polylines: usize,
    pub n_points: usize,
    /// `vt` rows (missing components 0) and the most components any had (1 to 3).
    pub texcoords: Vec<[f64; 3]>,
    pub texcoord_dim: usize,
    /// Per corner (aligned with `indices`), 0-based `vt` index or -1 where the
    /// corner has none; empty when no corner has one.
    pub corner_texcoords: Vec<i64>,
    pub normals: Vec<DVec3>,
    /// Per corner `vn` index or -1, as `corner_texcoords`.
    pub corner_normals: Vec<i64>,
    /// Per face, an index into `group_names` (the last `g` or `o` before the
    /// face; names of a `g` with several joined by a space; "" before any);
    /// empty when the file has no `g`/`o`.
    pub face_groups: Vec<u32>,
    pub group_names: Vec<String>,
    /// Per face, an index into `material_names` (the last `usemtl`; "" before
    /// any); empty when the file has no `usemtl`.
    pub face_materials: Vec<u32>,
    pub material_names: Vec<String>,
}

/// Names met so far, numbered in order of first use, and the current one.
#[derive(Default)]
struct Names {
    names: Vec<String>,
    ids: std::collections::HashMap<String, u32>,
    current: u32,
    seen: bool,
}

impl Names {
    fn set(&mut self, name: String) {
        if !self.seen {
            self.seen = true;
            self.names.push(String::new()); // id 0: faces before the first statement
            self.ids.insert(String::new(), 0);
        }
        let next = self.names.len() as u32;
        self.current = *self.ids.entry(name.clone()).or_insert_with(|| next);
        if self.current == next {
            self.names.push(name);
        }
    }
}

/// Per-corner references into a side table (`vt` or `vn`), with the
/// forward references to check once the table is complete.
#[derive(Default)]
struct CornerRefs {
    refs: Vec<i64>,
    forward: Vec<(usize, i64)>,
}

impl CornerRefs {
    /// Records the reference `t` (as written; None for an empty field) of the corner `corner`.
    fn push(&mut self, corner: usize, t: Option<i64>, n: i64, lineno: usize, what: &str) -> std::result::Result<(), String> {
        let idx = match t {
            None => -1,
            Some(0) => return Err(format!("{what} index 0 is invalid (OBJ indices start at 1, or count back from -1)")),
            Some(k) if k < 0 => {
                if k < -n {
                    return Err(format!("{what} index {k} is out of range ({n} {what} rows before this line)"));
                }
                n + k
            }
            Some(k) => {
                if k > n {
                    self.forward.push((lineno, k));
                }
                k - 1
            }
        };
        if idx >= 0 && self.refs.len() < corner {
            self.refs.resize(corner, -1); // the first reference: earlier corners had none
        }
        if idx >= 0 || !self.refs.is_empty() {
            self.refs.push(idx);
        }
        Ok(())
    }

    fn finish(&mut self, n_corners: usize, n: usize, name: &str, what: &str) -> Result<Vec<i64>> {
        if let Some(&(lineno, k)) = self.forward.iter().find(|&&(_, k)| k as usize > n) {
            return Err(MeshError::InvalidArgument(format!("{name}:{lineno}: {what} index {k} is out of range ({n} {what} rows)")));
        }
        if !self.refs.is_empty() {
            self.refs.resize(n_corners, -1);
        }
        Ok(std::mem::take(&mut self.refs))
    }
}

/// Reads the OBJ file at `path` (see the module docs).
pub fn read_obj(path: &Path) -> Result<ObjData> {
    let bytes = super::read_file(path)?;
    parse_obj(&bytes, &path.display().to_string())
}

/// Parses OBJ text; `name` prefixes error messages (`name:line: ...`).
pub fn parse_obj(bytes: &[u8], name: &str) -> Result<ObjData> {
    let mut out = ObjData::default();
    // a rough capacity guess: files are mostly v and f lines of ~30 bytes
    out.positions.reserve(bytes.len() / 80);
    out.sizes.reserve(bytes.len() / 80);
    out.indices.reserve(bytes.len() / 20);
    // indices beyond the vertices read so far (forward references): checked at the end
    let mut forward: Vec<(usize, i64)> = Vec::new();
    let (mut vt, mut vn) = (CornerRefs::default(), CornerRefs::default());
    let (mut groups, mut materials) = (Names::default(), Names::default());
    let (mut face_groups, mut face_materials) = (Vec::new(), Vec::new());
    let mut joined: Vec<u8> = Vec::new();
    let mut lines = bytes.split(|&b| b == b'\n').enumerate();
    while let Some((i, raw)) = lines.next() {
        crate::cancel::poll(i)?;
        let lineno = i + 1;
        let mut line = strip_cr(raw);
        // `\` at the end continues the statement on the next line
        if line.last() == Some(&b'\\') {
            joined.clear();
            joined.extend_from_slice(&line[..line.len() - 1]);
            for (_, more) in lines.by_ref() {
                let more = strip_cr(more);
                joined.push(b' ');
                if more.last() == Some(&b'\\') {
                    joined.extend_from_slice(&more[..more.len() - 1]);
                } else {
                    joined.extend_from_slice(more);
                    break;
                }
            }
            line = &joined;
        }
        if let Some(h) = line.iter().position(|&b| b == b'#') {
            line = &line[..h];
        }
        let mut toks = line.split(|b| b.is_ascii_whitespace()).filter(|t| !t.is_empty());
        let Some(key) = toks.next() else { continue };
        let err = |msg: String| MeshError::InvalidArgument(format!("{name}:{lineno}: {msg}"));
        match key {
            b"v" => {
                let mut c = [0.0f64; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let t = toks.next().ok_or_else(|| err(format!("vertex has {k} coordinates, needs 3")))?;
                    *slot = parse_f64(t).ok_or_else(|| err(format!("vertex coordinate {:?} is not a number", lossy(t))))?;
                }
                out.positions.push(DVec3::from_array(c));
            }
            b"vt" => {
                let mut c = [0.0f64; 3];
                let mut k = 0;
                for t in toks.take(3) {
                    c[k] = parse_f64(t).ok_or_else(|| err(format!("texture coordinate {:?} is not a number", lossy(t))))?;
                    k += 1;
                }
                if k == 0 {
                    return Err(err("texture coordinate (vt) has no components".into()));
                }
                out.texcoord_dim = out.texcoord_dim.max(k);
                out.texcoords.push(c);
            }
            b"vn" => {
                let mut c = [0.0f64; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let t = toks.next().ok_or_else(|| err(format!("normal has {k} coordinates, needs 3")))?;
                    *slot = parse_f64(t).ok_or_else(|| err(format!("normal coordinate {:?} is not a number", lossy(t))))?;
                }
                out.normals.push(DVec3::from_array(c));
            }
            b"g" | b"o" => {
                let names: Vec<String> = toks.map(lossy).collect();
                groups.set(names.join(" "));
            }
            b"usemtl" => {
                let names: Vec<String> = toks.map(lossy).collect();
                materials.set(names.join(" "));
            }
            b"f" => {
                let nv = out.positions.len() as i64;
                let (nt, nn) = (out.texcoords.len() as i64, out.normals.len() as i64);
                let before = out.indices.len();
                for t in toks {
                    let mut fields = t.split(|&b| b == b'/');
                    let v = fields.next().unwrap_or(t);
                    let side = |field: Option<&[u8]>, refs: &mut CornerRefs, n: i64, what: &str| -> Result<()> {
                        let f = match field {
                            None | Some(b"") => None,
                            Some(f) => Some(parse_i64(f).ok_or_else(|| err(format!("{what} index {:?} is not an integer", lossy(t))))?),
                        };
                        refs.push(out.indices.len(), f, n, lineno, what).map_err(err)
                    };
                    side(fields.next(), &mut vt, nt, "texture coordinate")?;
                    side(fields.next(), &mut vn, nn, "normal")?;
                    let k = parse_i64(v).ok_or_else(|| err(format!("face index {:?} is not an integer", lossy(t))))?;
                    let idx = match k {
                        0 => return Err(err("face index 0 is invalid (OBJ indices start at 1, or count back from -1)".into())),
                        k if k < 0 => {
                            if k < -nv {
                                return Err(err(format!(
                                    "face index {k} is out of range ({nv} vertices before this line)"
                                )));
                            }
                            nv + k
                        }
                        k => {
                            if k > nv {
                                forward.push((lineno, k));
                            }
                            k - 1
                        }
                    };
                    out.indices.push(idx);
                }
                if out.indices.len() == before {
                    return Err(err("face has no vertices".into()));
                }
                out.sizes.push((out.indices.len() - before) as i64);
                if groups.seen {
                    face_groups.resize(out.sizes.len() - 1, 0);
                    face_groups.push(groups.current);
                }
                if materials.seen {
                    face_materials.resize(out.sizes.len() - 1, 0);
                    face_materials.push(materials.current);
                }
            }
            b"l" => out.n_polylines += 1,
            b"p" => out.n_points += 1,
            _ => {}
        }
    }
    let nv = out.positions.len();
    if let Some(&(lineno, k)) = forward.iter().find(|&&(_, k)| k as usize > nv) {
        return Err(MeshError::InvalidArgument(format!(
            "{name}:{lineno}: face index {k} is out of range ({nv} vertices)"
        )));
    }
    let nc = out.indices.len();
    out.corner_texcoords = vt.finish(nc, out.texcoords.len(), name, "texture coordinate")?;
    out.corner_normals = vn.finish(nc, out.normals.len(), name, "normal")?;
    let nf = out.sizes.len();
    if groups.seen {
        face_groups.resize(nf, 0);
        out.face_groups = face_groups;
        out.group_names = groups.names;
    }
    if materials.seen {
        face_materials.resize(nf, 0);
        out.face_materials = face_materials;
        out.material_names = materials.names;
    }
    Ok(out)
}

/// Face-varying data for [`write_obj`]: per-corner rows (aligned with the
/// exported corners) of `vt` (k components, 1 to 3) and `vn` (3), and per
/// exported face an index into a list of group and of material names.
#[derive(Default)]
pub struct ObjAttributes<'a> {
    pub texcoords: Option<(&'a [f64], usize)>,
    pub normals: Option<&'a [f64]>,
    pub groups: Option<(&'a [i64], &'a [String])>,
    pub materials: Option<(&'a [i64], &'a [String])>,
}

/// The distinct rows of `k` values per corner in order of first use and
/// each corner's row (bit equality, with -0.0 taken as 0.0): corners that
/// share a value share a row, so a seam stays a seam. Also the value table
/// of the face-varying levels (`python/levels.rs`).
pub(crate) fn distinct_rows(values: &[f64], k: usize) -> (Vec<usize>, Vec<u32>) {
    let bits = |x: f64| (x + 0.0).to_bits();
    // rows of up to 4 values (uv, normals, colours) as fixed keys
    if k <= 4 {
        rows_by(values, k, |row| {
            let mut key = [0u64; 4];
            row.iter().zip(&mut key).for_each(|(&x, b)| *b = bits(x));
            key
        })
    } else {
        rows_by(values, k, |row| row.iter().map(|&x| bits(x)).collect::<Vec<u64>>())
    }
}

/// [`distinct_rows`] by a key per row, hashed with Fx (SipHash was a fifth
/// of a save of 1.3M triangles with uv).
fn rows_by<K: std::hash::Hash + Eq>(values: &[f64], k: usize, key: impl Fn(&[f64]) -> K) -> (Vec<usize>, Vec<u32>) {
    let k = k.max(1);
    let mut first: Vec<usize> = Vec::new();
    let mut ids: rustc_hash::FxHashMap<K, u32> = rustc_hash::FxHashMap::with_capacity_and_hasher(values.len() / k / 2, Default::default());
    let index = values
        .chunks_exact(k)
        .enumerate()
        .map(|(c, row)| {
            *ids.entry(key(row)).or_insert_with(|| {
                first.push(c);
                (first.len() - 1) as u32
            })
        })
        .collect();
    (first, index)
}

/// Writes the exported polygons of `m` (holes left out) as OBJ with `vt`/`vn`
/// tables of the distinct per-corner values, `f v/vt/vn` corners, and a `g`
/// or `usemtl` line wherever a face's name differs from the previous face's.
/// Floats as the shortest decimal that reads back to the same bits.
pub fn write_obj<W: Write + Send>(m: &Mesh, attrs: &ObjAttributes<'_>, out: W) -> Result<()> {
    let io = |e: std::io::Error| MeshError::Io(e.to_string());
    let p = m.to_polygons();
    let (nc, nf) = (p.indices.len(), p.sizes.len());
    let bad = |what: &str, n: usize, want: usize| {
        MeshError::InvalidArgument(format!("write_obj: {what} has {n} values, expected {want}"))
    };
    if let Some((t, k)) = attrs.texcoords {
        if !(1..=3).contains(&k) || t.len() != nc * k {
            return Err(bad("the texture coordinates", t.len(), nc * k.clamp(1, 3)));
        }
    }
    if let Some(n) = attrs.normals {
        if n.len() != nc * 3 {
            return Err(bad("the normals", n.len(), nc * 3));
        }
    }
    for (what, names) in [("group", attrs.groups), ("material", attrs.materials)] {
        if let Some((ids, list)) = names {
            if ids.len() != nf {
                return Err(bad(&format!("the {what} ids"), ids.len(), nf));
            }
            if let Some(&i) = ids.iter().find(|&&i| i < 0 || i as usize >= list.len()) {
                return Err(MeshError::InvalidArgument(format!("write_obj: {what} id {i} outside the {} names", list.len())));
            }
        }
    }
    let mut w = std::io::BufWriter::with_capacity(1 << 20, out);
    writeln!(w, "# written by topomesh").map_err(io)?;
    let vt = attrs.texcoords.map(|(t, k)| {
        let (first, index) = distinct_rows(t, k);
        (t, k, first, index)
    });
    let vn = attrs.normals.map(|n| (n, distinct_rows(n, 3)));
    // the file's sections (v, vt, vn, then faces), each in chunks of TEXT_CHUNK lines
    // formatted in parallel and written in order (writer::write_pieces)
    use super::writer::{face_chunk_starts, vertex_lines, write_pieces, TEXT_CHUNK};
    let pos = m.positions();
    let chunks = |n: usize| n.div_ceil(TEXT_CHUNK);
    let (n_v, n_t, n_n) = (chunks(pos.len()), chunks(vt.as_ref().map_or(0, |x| x.2.len())), chunks(vn.as_ref().map_or(0, |x| x.1 .0.len())));
    let starts = face_chunk_starts(&p.sizes);
    // the lines of chunk j of a section of n lines
    let span = |j: usize, n: usize| j * TEXT_CHUNK..((j + 1) * TEXT_CHUNK).min(n);
    let piece = |j: usize| -> Vec<u8> {
        if j < n_v {
            return vertex_lines(pos, j, "v ");
        }
        // a Vec takes every write: the results below are all Ok
        let mut b = Vec::with_capacity(64 * TEXT_CHUNK);
        let j = j - n_v;
        if j < n_t {
            let (t, k, first, _) = vt.as_ref().expect("n_t > 0 only with texture coordinates");
            for &c in &first[span(j, first.len())] {
                b.extend_from_slice(b"vt");
                for x in &t[c * k..(c + 1) * k] {
                    let _ = write!(b, " {x:?}");
                }
                b.push(b'\n');
            }
            return b;
        }
        let j = j - n_t;
        if j < n_n {
            let (n, (first, _)) = vn.as_ref().expect("n_n > 0 only with normals");
            for &c in &first[span(j, first.len())] {
                let _ = writeln!(b, "vn {:?} {:?} {:?}", n[3 * c], n[3 * c + 1], n[3 * c + 2]);
            }
            return b;
        }
        let j = j - n_n;
        let faces = span(j, nf);
        // a `g` or `usemtl` line where a face's name differs from the previous face's
        // (the chunk's first face compares with the last face of the chunk before)
        let before = |ids: &[i64]| (faces.start > 0).then(|| ids[faces.start - 1]);
        let (mut group, mut material) = (attrs.groups.and_then(|(ids, _)| before(ids)), attrs.materials.and_then(|(ids, _)| before(ids)));
        let mut k = starts[j];
        for f in faces {
            let s = p.sizes[f] as usize;
            for (key, names, current) in [("g", attrs.groups, &mut group), ("usemtl", attrs.materials, &mut material)] {
                if let Some((ids, list)) = names {
                    if *current != Some(ids[f]) {
                        *current = Some(ids[f]);
                        let name = &list[ids[f] as usize];
                        let _ = if name.is_empty() { writeln!(b, "{key}") } else { writeln!(b, "{key} {name}") };
                    }
                }
            }
            b.push(b'f');
            for c in k..k + s {
                let _ = write!(b, " {}", p.indices[c] + 1);
                let _ = match (&vt, &vn) {
                    (Some((_, _, _, ti)), Some((_, (_, ni)))) => write!(b, "/{}/{}", ti[c] + 1, ni[c] + 1),
                    (Some((_, _, _, ti)), None) => write!(b, "/{}", ti[c] + 1),
                    (None, Some((_, (_, ni)))) => write!(b, "//{}", ni[c] + 1),
                    (None, None) => Ok(()),
                };
            }
            k += s;
            b.push(b'\n');
        }
        b
    };
    write_pieces(&mut w, n_v + n_t + n_n + starts.len(), piece)?;
    w.flush().map_err(io)
}

fn strip_cr(l: &[u8]) -> &[u8] {
    l.strip_suffix(b"\r").unwrap_or(l)
}

fn lossy(t: &[u8]) -> String {
    String::from_utf8_lossy(t).into_owned()
}

fn parse_f64(t: &[u8]) -> Option<f64> {
    std::str::from_utf8(t).ok()?.parse().ok()
}

/// A decimal integer with optional sign, without overflow.
fn parse_i64(t: &[u8]) -> Option<i64> {
    let (neg, digits) = match t.first()? {
        b'-' => (true, &t[1..]),
        b'+' => (false, &t[1..]),
        _ => (false, t),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_sub((d - b'0') as i64)?; // accumulate negatively: i64::MIN fits
    }
    if neg { Some(v) } else { v.checked_neg() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blender_style_file() {
        let text = b"# Blender\r\nmtllib a.mtl\r\no Cube\r\nv 1 1 -1\r\nv 1 -1 -1\r\nv 1 1 1\r\nvt 0.5 0.5\r\nvn 0 0 1\r\nvn 0 1 0\r\ns 0\r\nusemtl M\r\nf 1/1/1 2/1/1 \\\r\n 3/1/2\r\ng other\r\nf -3//2 -2//2 -1//2\r\nl 1 2\r\n";
        let d = parse_obj(text, "x.obj").unwrap();
        assert_eq!(d.positions.len(), 3);
        assert_eq!(d.sizes, vec![3, 3]);
        assert_eq!(d.indices, vec![0, 1, 2, 0, 1, 2]);
        assert_eq!(d.n_polylines, 1);
    }

    #[test]
    fn errors_name_line_and_index_as_written() {
        let e = parse_obj(b"v 0 0 0\nv 1 0 0\n\nf 1 2 9\n", "m.obj").unwrap_err().to_string();
        assert_eq!(e, "m.obj:4: face index 9 is out of range (2 vertices)");
        let e = parse_obj(b"v 0 0 0\nf -2 1 1\n", "m.obj").unwrap_err().to_string();
        assert!(e.starts_with("m.obj:2: face index -2 is out of range"), "{e}");
        let e = parse_obj(b"v 0 0 0\nf 0 1 1\n", "m.obj").unwrap_err().to_string();
        assert!(e.starts_with("m.obj:2: face index 0"), "{e}");
        let e = parse_obj(b"v 0 x 0\n", "m.obj").unwrap_err().to_string();
        assert!(e.starts_with("m.obj:1: vertex coordinate \"x\""), "{e}");
        assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
        assert_eq!(parse_i64(b"9223372036854775808"), None);
    }

    #[test]
    fn texcoords_normals_groups_and_materials_per_corner_and_face() {
        let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1 0.5\nvn 0 0 1\n\
f 1 2 3\ng a b\nusemtl M\nf 1/1 3/-1 4/2/1\no x\nf 1//1 2//1 -1//-1\ng a b\nusemtl N\nf 2/3 3/3 4/3\n";
        let d = parse_obj(text, "m.obj").unwrap();
        assert_eq!(d.texcoord_dim, 3);
        assert_eq!(d.texcoords[2], [1.0, 1.0, 0.5]);
        assert_eq!(d.corner_texcoords, vec![-1, -1, -1, 0, 2, 1, -1, -1, -1, 2, 2, 2]);
        assert_eq!(d.corner_normals, vec![-1, -1, -1, -1, -1, 0, 0, 0, 0, -1, -1, -1]);
        assert_eq!(d.group_names, vec!["", "a b", "x"]);
        assert_eq!(d.face_groups, vec![0, 1, 2, 1]);
        assert_eq!(d.material_names, vec!["", "M", "N"]);
        assert_eq!(d.face_materials, vec![0, 1, 1, 2]);
        let plain = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj").unwrap();
        assert!(plain.corner_texcoords.is_empty() && plain.face_groups.is_empty() && plain.face_materials.is_empty());
        let e = parse_obj(b"v 0 0 0\nvt 0 0\nf 1/2 1/1 1/1\n", "m.obj").unwrap_err().to_string();
        assert_eq!(e, "m.obj:3: texture coordinate index 2 is out of range (1 texture coordinate rows)");
        let e = parse_obj(b"v 0 0 0\nvn 0 0 1\nf 1//-2 1 1\n", "m.obj").unwrap_err().to_string();
        assert!(e.starts_with("m.obj:3: normal index -2 is out of range"), "{e}");
        let e = parse_obj(b"v 0 0 0\nf 1/x 1 1\n", "m.obj").unwrap_err().to_string();
        assert!(e.starts_with("m.obj:2: texture coordinate index \"1/x\""), "{e}");
    }

    #[test]
    fn written_attributes_read_back() {
        let m = crate::primitives::cube();
        let nc: usize = m.to_polygons().indices.len();
        // per-face UV squares: 4 distinct values per face, repeated across faces
        let uv: Vec<f64> = (0..nc).flat_map(|c| [(c % 4 == 1 || c % 4 == 2) as u8 as f64, (c % 4 >= 2) as u8 as f64]).collect();
        let names = vec!["".to_string(), "top".to_string()];
        let ids = [0i64, 1, 1, 0, 0, 1];
        let attrs = ObjAttributes { texcoords: Some((&uv, 2)), groups: Some((&ids, &names)), ..Default::default() };
        let mut out = Vec::new();
        write_obj(&m, &attrs, &mut out).unwrap();
        let d = parse_obj(&out, "w.obj").unwrap();
        assert_eq!(d.texcoords.len(), 4);
        let back: Vec<f64> = d.corner_texcoords.iter().flat_map(|&i| d.texcoords[i as usize][..2].to_vec()).collect();
        assert_eq!(back, uv);
        let got: Vec<&str> = d.face_groups.iter().map(|&g| d.group_names[g as usize].as_str()).collect();
        assert_eq!(got, vec!["", "top", "top", "", "", "top"]);
        let e = write_obj(&m, &ObjAttributes { texcoords: Some((&uv[1..], 2)), ..Default::default() }, Vec::new()).unwrap_err();
        assert!(e.to_string().contains("texture coordinates"), "{e}");
    }

    /// The writer as it wrote one line after another before it ran in parallel.
    fn sequential(m: &Mesh, attrs: &ObjAttributes<'_>) -> Vec<u8> {
        let p = m.to_polygons();
        let mut w: Vec<u8> = Vec::new();
        writeln!(w, "# written by topomesh").unwrap();
        for q in m.positions() {
            writeln!(w, "v {:?} {:?} {:?}", q.x, q.y, q.z).unwrap();
        }
        let vt = attrs.texcoords.map(|(t, k)| {
            let (first, index) = distinct_rows(t, k);
            (t, k, first, index)
        });
        if let Some((t, k, first, _)) = &vt {
            for &c in first {
                w.write_all(b"vt").unwrap();
                for x in &t[c * k..(c + 1) * k] {
                    write!(w, " {x:?}").unwrap();
                }
                w.write_all(b"\n").unwrap();
            }
        }
        let vn = attrs.normals.map(|n| (n, distinct_rows(n, 3)));
        if let Some((n, (first, _))) = &vn {
            for &c in first {
                writeln!(w, "vn {:?} {:?} {:?}", n[3 * c], n[3 * c + 1], n[3 * c + 2]).unwrap();
            }
        }
        let (mut group, mut material) = (None, None);
        let mut k = 0;
        for (f, &s) in p.sizes.iter().enumerate() {
            for (key, names, current) in [("g", attrs.groups, &mut group), ("usemtl", attrs.materials, &mut material)] {
                if let Some((ids, list)) = names {
                    if *current != Some(ids[f]) {
                        *current = Some(ids[f]);
                        let name = &list[ids[f] as usize];
                        if name.is_empty() {
                            writeln!(w, "{key}").unwrap();
                        } else {
                            writeln!(w, "{key} {name}").unwrap();
                        }
                    }
                }
            }
            w.write_all(b"f").unwrap();
            for c in k..k + s as usize {
                write!(w, " {}", p.indices[c] + 1).unwrap();
                match (&vt, &vn) {
                    (Some((_, _, _, ti)), Some((_, (_, ni)))) => write!(w, "/{}/{}", ti[c] + 1, ni[c] + 1),
                    (Some((_, _, _, ti)), None) => write!(w, "/{}", ti[c] + 1),
                    (None, Some((_, (_, ni)))) => write!(w, "//{}", ni[c] + 1),
                    (None, None) => Ok(()),
                }
                .unwrap();
            }
            k += s as usize;
            w.write_all(b"\n").unwrap();
        }
        w
    }

    #[test]
    fn parallel_obj_is_the_sequential_obj() {
        // several chunks of every section; names that change at a chunk's first face and
        // names that carry over it; empty names; all attributes, some, none
        let m = crate::primitives::torus(300, 200, 3.0, 1.0).unwrap();
        let (nc, nf) = (m.to_polygons().indices.len(), m.n_faces());
        assert!(nf > 3 * super::super::writer::TEXT_CHUNK);
        let uv: Vec<f64> = (0..2 * nc).map(|i| ((i * 7919) % 100_003) as f64 / 1000.0).collect();
        let normals: Vec<f64> = (0..3 * nc).map(|i| ((i * 104_729) % 65_521) as f64 * 1e-5 - 0.3).collect();
        let names: Vec<String> = ["", "a", "b c"].iter().map(|s| s.to_string()).collect();
        let t = super::super::writer::TEXT_CHUNK;
        let groups: Vec<i64> = (0..nf).map(|f| if f == t { 2 } else { ((f / 1000) % 3) as i64 }).collect();
        let materials: Vec<i64> = (0..nf).map(|f| ((f / (t / 2)) % 2) as i64).collect();
        let all = ObjAttributes { texcoords: Some((&uv, 2)), normals: Some(&normals), groups: Some((&groups, &names)), materials: Some((&materials, &names)) };
        let some = ObjAttributes { normals: Some(&normals), materials: Some((&materials, &names)), ..Default::default() };
        for (what, attrs) in [("all", all), ("some", some), ("none", ObjAttributes::default())] {
            let mut out = Vec::new();
            write_obj(&m, &attrs, &mut out).unwrap();
            assert!(out == sequential(&m, &attrs), "{what}");
        }
    }

    #[test]
    fn forward_references_are_allowed_within_the_file() {
        let d = parse_obj(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "m.obj").unwrap();
        assert_eq!(d.indices, vec![0, 1, 2]);
    }
}
