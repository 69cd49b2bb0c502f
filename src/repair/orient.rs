//! Pairing face sides into edges, consistent orientation (BFS over face
//! adjacency) and outward orientation (signed volume per closed component).

use super::{Faces, NONE};
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// A closed component counts as inside out when its signed volume is below
/// `-INSIDE_OUT_REL` times the sum of the absolute volumes of its fan
/// tetrahedra (taken from a vertex of the component, so translation adds no
/// cancellation): flat components (zero volume up to rounding) never do.
const INSIDE_OUT_REL: f64 = 1e-10;

/// Twin side of every corner (`NONE`: boundary), sides of one undirected
/// vertex pair grouped by a parallel sort. Two sides pair whatever their
/// directions (orientation is fixed afterwards). On an edge with more than two
/// sides, sides are paired greedily in face order, each with the first later
/// unpaired side running the other way; the rest stay unpaired (detached,
/// their vertices are split later). If no two sides run opposite ways, the
/// first two pair. Returns the twins and the number of such edges.
pub(super) fn pair_sides(f: &Faces) -> (Vec<u32>, usize) {
    let n = f.verts.len();
    let mut sides: Vec<(u64, u32)> = (0..n)
        .into_par_iter()
        .map(|c| {
            let (a, b) = (f.verts[c], f.verts[f.next(c)]);
            (((a.min(b) as u64) << 32) | a.max(b) as u64, c as u32)
        })
        .collect();
    sides.par_sort_unstable();
    let mut twin = vec![NONE; n];
    let mut non_manifold = 0;
    let mut i = 0;
    while i < n {
        let mut j = i + 1;
        while j < n && sides[j].0 == sides[i].0 {
            j += 1;
        }
        let g = &sides[i..j];
        match g.len() {
            1 => {}
            2 => {
                twin[g[0].1 as usize] = g[1].1;
                twin[g[1].1 as usize] = g[0].1;
            }
            _ => {
                non_manifold += 1;
                let mut any = false;
                for x in 0..g.len() {
                    let cx = g[x].1 as usize;
                    if twin[cx] != NONE {
                        continue;
                    }
                    let opposite = (x + 1..g.len()).find(|&y| {
                        let cy = g[y].1 as usize;
                        twin[cy] == NONE && f.verts[cy] != f.verts[cx]
                    });
                    if let Some(y) = opposite {
                        twin[cx] = g[y].1;
                        twin[g[y].1 as usize] = cx as u32;
                        any = true;
                    }
                }
                if !any {
                    twin[g[0].1 as usize] = g[1].1;
                    twin[g[1].1 as usize] = g[0].1;
                }
            }
        }
        i = j;
    }
    (twin, non_manifold)
}

/// What [`orient`] did.
pub(super) struct Orientation {
    /// Faces to reverse.
    pub flip: Vec<bool>,
    /// Faces reversed to agree with the majority of their component.
    pub faces_flipped: usize,
    /// Closed components reversed because their volume was negative.
    pub components_flipped: usize,
    /// Edges cut because their faces could not agree (non-orientable surfaces).
    pub cuts: usize,
}

/// Orients every face-connected component consistently (breadth first from
/// its lowest face, then the orientation of the majority of its faces wins)
/// and outward: a closed component with negative signed volume is reversed.
/// An edge whose two faces cannot agree (a Möbius band, a Klein bottle) is
/// cut (`twin` entries set to `NONE`).
pub(super) fn orient(f: &Faces, pos: &[DVec3], twin: &mut [u32]) -> Orientation {
    let nf = f.n_faces();
    let mut flip = vec![false; nf];
    let mut comp = vec![NONE; nf];
    let mut n_comp = 0u32;
    let mut queue: Vec<u32> = Vec::new();
    let mut cuts = 0;
    for root in 0..nf {
        if comp[root] != NONE {
            continue;
        }
        comp[root] = n_comp;
        queue.clear();
        queue.push(root as u32);
        let mut head = 0;
        while head < queue.len() {
            let g = queue[head] as usize;
            head += 1;
            for c in f.corners(g) {
                let t = twin[c];
                if t == NONE {
                    continue;
                }
                let h = f.face[t as usize] as usize;
                // the same direction on both sides means opposite orientations
                let want = flip[g] ^ (f.verts[c] == f.verts[t as usize]);
                if comp[h] == NONE {
                    comp[h] = n_comp;
                    flip[h] = want;
                    queue.push(h as u32);
                } else if flip[h] != want {
                    twin[c] = NONE;
                    twin[t as usize] = NONE;
                    cuts += 1;
                }
            }
        }
        n_comp += 1;
    }
    let nc = n_comp as usize;
    // majority, closedness and signed volume per component
    let mut size = vec![0usize; nc];
    let mut flipped = vec![0usize; nc];
    let mut open = vec![false; nc];
    let mut origin = vec![None::<DVec3>; nc];
    for g in 0..nf {
        let k = comp[g] as usize;
        size[k] += 1;
        flipped[k] += flip[g] as usize;
        origin[k].get_or_insert(pos[f.verts[f.off[g] as usize] as usize]);
        if f.corners(g).any(|c| twin[c] == NONE) {
            open[k] = true;
        }
    }
    let majority: Vec<bool> = (0..nc).map(|k| 2 * flipped[k] > size[k]).collect();
    let (vol, scale) = component_volumes(nf, nc, |g| comp[g] as usize, |g| {
        let s = if flip[g] != majority[comp[g] as usize] { -1.0 } else { 1.0 };
        let o = origin[comp[g] as usize].unwrap_or_default();
        let (v, a) = fan_volume(f.corners(g).map(|c| pos[f.verts[c] as usize] - o));
        (s * v, a)
    });
    let outward_flip: Vec<bool> = (0..nc).map(|k| !open[k] && is_inside_out(vol[k], scale[k])).collect();
    let mut faces_flipped = 0;
    for g in 0..nf {
        let k = comp[g] as usize;
        if flip[g] != majority[k] {
            faces_flipped += 1;
        }
        flip[g] ^= majority[k] ^ outward_flip[k];
    }
    Orientation { flip, faces_flipped, components_flipped: outward_flip.iter().filter(|&&b| b).count(), cuts }
}

/// Six times the signed volume of the fan of one face from the origin, and
/// six times the sum of the absolute volumes of its tetrahedra.
fn fan_volume(mut it: impl Iterator<Item = DVec3>) -> (f64, f64) {
    let Some(p0) = it.next() else { return (0.0, 0.0) };
    let Some(mut prev) = it.next() else { return (0.0, 0.0) };
    let (mut v, mut a) = (0.0, 0.0);
    for p in it {
        let t = p0.dot(prev.cross(p));
        v += t;
        a += t.abs();
        prev = p;
    }
    (v, a)
}

/// Per-component sums of `face(g)` = (6·volume, 6·scale), faces in parallel.
fn component_volumes(
    nf: usize,
    nc: usize,
    comp: impl Fn(usize) -> usize + Sync,
    face: impl Fn(usize) -> (f64, f64) + Sync,
) -> (Vec<f64>, Vec<f64>) {
    let per: Vec<(f64, f64)> = (0..nf).into_par_iter().with_min_len(4096).map(&face).collect();
    let mut vol = vec![0.0; nc];
    let mut scale = vec![0.0; nc];
    for (g, (v, a)) in per.into_iter().enumerate() {
        vol[comp(g)] += v;
        scale[comp(g)] += a;
    }
    (vol, scale)
}

fn is_inside_out(vol6: f64, scale6: f64) -> bool {
    vol6 < -INSIDE_OUT_REL * scale6
}

/// The closed components of `m` (no hole face) whose signed volume is
/// negative beyond rounding, as `(component, volume)`; components numbered as
/// by [`Mesh::vertex_components`]. Flat (zero-volume) components are not
/// listed. Linear: one union-find over the edges and one pass over the faces.
pub fn inside_out_components(m: &Mesh) -> Vec<(usize, f64)> {
    let (label, nc) = m.vertex_components();
    if nc == 0 {
        return Vec::new();
    }
    let first_vertex = |f: crate::FaceId| match m.face_start(f) {
        crate::FaceStart::Point(v) => v,
        crate::FaceStart::Halfedge(h) => m.vertex(h),
    };
    let mut origin = vec![None::<DVec3>; nc];
    let mut has_hole = vec![false; nc];
    for f in m.faces() {
        let k = label[first_vertex(f).idx()] as usize;
        origin[k].get_or_insert(m.position(first_vertex(f)));
        has_hole[k] |= m.is_hole(f);
    }
    let comp = |g: usize| label[first_vertex(crate::FaceId(g as u32)).idx()] as usize;
    let (vol, scale) = component_volumes(m.n_faces(), nc, comp, |g| {
        let f = crate::FaceId(g as u32);
        if matches!(m.face_start(f), crate::FaceStart::Point(_)) {
            return (0.0, 0.0);
        }
        let o = origin[comp(g)].unwrap_or_default();
        fan_volume(m.face_halfedges(f).map(|h| m.position(m.vertex(h)) - o))
    });
    (0..nc).filter(|&k| !has_hole[k] && is_inside_out(vol[k], scale[k])).map(|k| (k, vol[k] / 6.0)).collect()
}
