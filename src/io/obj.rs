//! A small, fast Wavefront OBJ reader for polygon meshes, keeping the file's
//! own global `v` numbering.
//!
//! Why not the `tobj` crate: it builds one mesh per `o`/`g` model and
//! re-indexes positions per model (and per distinct `v/vt/vn` triple), so a
//! vertex shared by two groups comes back twice and the file's numbering is
//! lost; welding the copies back by position would also merge vertices that
//! the file keeps apart. The polygon topology is all topomesh reads, so this
//! reader parses `v` and `f` and skips the rest.
//!
//! Read as Blender, Maya, trimesh and pyvista write it: `v x y z [w | r g b]`,
//! `f` corners as `v`, `v/vt`, `v/vt/vn` or `v//vn` (only `v` is used, so `vt`
//! and `vn` may have their own counts), negative (relative) indices, comments
//! (`#` to the end of the line), `\` line continuations, CRLF. `vt`, `vn`,
//! `vp`, `g`, `o`, `s`, `usemtl`, `mtllib` and other statements are ignored;
//! `l` (polyline) and `p` (point) elements are not faces: they are skipped
//! and counted. Errors name the file and the line (1-based, where the
//! statement starts) and the index as written in the file.

use crate::error::{MeshError, Result};
use glam::DVec3;
use std::path::Path;

/// What [`read_obj`] returns: positions in file order, faces as sizes and
/// 0-based flat vertex indices, and the number of skipped `l` / `p` elements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjData {
    pub positions: Vec<DVec3>,
    pub sizes: Vec<i64>,
    pub indices: Vec<i64>,
    pub n_polylines: usize,
    pub n_points: usize,
}

/// Reads the OBJ file at `path` (see the module docs).
pub fn read_obj(path: &Path) -> Result<ObjData> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::Io(format!("{}: cannot read ({e})", path.display())))?;
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
            b"f" => {
                let nv = out.positions.len() as i64;
                let before = out.indices.len();
                for t in toks {
                    let v = t.split(|&b| b == b'/').next().unwrap_or(t);
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
    Ok(out)
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
    fn forward_references_are_allowed_within_the_file() {
        let d = parse_obj(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "m.obj").unwrap();
        assert_eq!(d.indices, vec![0, 1, 2]);
    }
}
