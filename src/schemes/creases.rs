//! Boundaries and semi-sharp creases for Catmull-Clark and Loop, as
//! OpenSubdiv defines them (DeRose, Kass & Truong, "Subdivision surfaces in
//! character animation", SIGGRAPH 1998, §3; OpenSubdiv 3.6 `sdc/crease.cpp`
//! and `sdc/scheme.h`, read for the exact transition rules).
//!
//! * Sharpness `s ≥ 0` per edge and per vertex; `s ≥ 10` is infinitely
//!   sharp (OpenSubdiv's `SHARPNESS_INFINITE`). Boundary edges (one side in
//!   a hole face) are always infinitely sharp; with
//!   [`Boundary::EdgeAndCorner`] (OpenSubdiv's default) a boundary vertex
//!   with one face and two edges is an infinitely sharp corner too.
//! * Vertex rule from the number of sharp incident edges: 0 smooth, 1 dart
//!   (smooth mask), 2 crease (`3/4 v + 1/8 (a + b)`, a and b the other ends
//!   of the two sharp edges), more, or a sharp vertex, corner (`v`).
//! * Edge point of a sharp edge: the midpoint when the edge's point is a
//!   crease vertex of the next level (both child edges still sharp), else
//!   the smooth point blended with the midpoint by weight `s`.
//! * Each level the sharpness decays: uniform method `s − 1` (clamped at 0);
//!   Chaikin method, for the child edge at vertex v,
//!   `0.75 s + 0.25 · mean of the other semi-sharp edges at v − 1`. A vertex
//!   whose rule changes between levels (a crease dying out) blends its
//!   parent and child masks by the mean sharpness of the transitioning
//!   edges and vertex (clamped to 1).

use crate::mesh::{Mesh, POINT};

/// OpenSubdiv's infinite sharpness: every value at or above it is infinite.
pub const INFINITE: f64 = 10.0;

/// Per-edge and per-vertex sharpness of a mesh (aligned with edge and
/// vertex ids). Empty vectors mean all zero.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Creases {
    pub edge: Vec<f64>,
    pub vertex: Vec<f64>,
}

impl Creases {
    /// All zero (or empty).
    pub fn is_smooth(&self) -> bool {
        self.edge.iter().chain(&self.vertex).all(|&s| s <= 0.0)
    }
    #[inline]
    pub fn edge(&self, e: usize) -> f64 {
        self.edge.get(e).copied().unwrap_or(0.0)
    }
    #[inline]
    pub fn vertex(&self, v: usize) -> f64 {
        self.vertex.get(v).copied().unwrap_or(0.0)
    }
}

/// OpenSubdiv's vertex boundary interpolation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Boundary {
    /// Boundary edges are creases; boundary vertices follow the crease rule.
    EdgeOnly,
    /// As `EdgeOnly`, and boundary vertices with one face are corners.
    #[default]
    EdgeAndCorner,
}

/// OpenSubdiv's creasing method.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CreaseMethod {
    #[default]
    Uniform,
    Chaikin,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SubdivOptions {
    pub boundary: Boundary,
    pub crease_method: CreaseMethod,
}

#[inline]
pub fn is_infinite(s: f64) -> bool {
    s >= INFINITE
}

#[inline]
fn is_semi_sharp(s: f64) -> bool {
    s > 0.0 && s < INFINITE
}

/// One level of decay of the uniform method.
#[inline]
pub fn decrement(s: f64) -> f64 {
    if s <= 0.0 {
        0.0
    } else if is_infinite(s) {
        INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// A vertex's subdivision rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    Smooth,
    Dart,
    Crease,
    Corner,
}

fn rule(vertex_sharpness: f64, sharp_edges: usize) -> Rule {
    if vertex_sharpness > 0.0 {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// The sharpness one level sees: boundary edges and (with
/// `EdgeAndCorner`) corners made infinite, and the sharpness of every child
/// edge at each end.
pub struct LevelSharpness {
    /// Effective sharpness per edge.
    pub edge: Vec<f64>,
    /// Effective sharpness per vertex.
    pub vertex: Vec<f64>,
    /// Child sharpness of edge `h >> 1` at the tail of half-edge `h`, stored
    /// only where the Chaikin method makes the two ends differ; otherwise
    /// empty and [`Self::child`] is the edge's sharpness decremented (8
    /// bytes per input half-edge that an open level no longer holds at its
    /// peak, issue 19).
    child: Vec<f64>,
    /// Whether any sharpness is nonzero (otherwise every rule is smooth).
    pub any: bool,
}

/// A vertex's masks: the parent rule's mask, and when the rule changes in
/// the child level, the child rule's mask with the parent's weight.
pub struct VertexRule {
    pub parent: Rule,
    /// Crease ends of the parent rule: outgoing half-edges of the two sharp edges.
    pub parent_ends: [u32; 2],
    /// `Some((child rule, child crease ends, parent weight))` on a transition.
    pub child: Option<(Rule, [u32; 2], f64)>,
}

impl LevelSharpness {
    pub fn new(m: &Mesh, creases: Option<&Creases>, opts: SubdivOptions) -> LevelSharpness {
        let (_, _, face) = m.halfedge_columns();
        let hole = |h: usize| m.f_hole[face[h] as usize];
        let edge: Vec<f64> = (0..m.n_edges())
            .map(|e| {
                if hole(2 * e) || hole(2 * e + 1) {
                    INFINITE
                } else {
                    let s = creases.map_or(0.0, |c| c.edge(e));
                    if is_infinite(s) {
                        INFINITE
                    } else {
                        s.max(0.0)
                    }
                }
            })
            .collect();
        let vertex: Vec<f64> = (0..m.n_vertices())
            .map(|v| {
                let s = creases.map_or(0.0, |c| c.vertex(v)).max(0.0);
                let o = m.v_out[v];
                if o & POINT == 0 && opts.boundary == Boundary::EdgeAndCorner {
                    // one face and two edges: the two outgoing half-edges, one in a hole
                    let h2 = m.he_prev[o as usize] ^ 1;
                    if m.he_prev[h2 as usize] ^ 1 == o && (hole(o as usize) != hole(h2 as usize)) {
                        return INFINITE;
                    }
                }
                if is_infinite(s) {
                    INFINITE
                } else {
                    s
                }
            })
            .collect();
        let any = edge.iter().chain(&vertex).any(|&s| s > 0.0);
        let mut child = Vec::new();
        if any && opts.crease_method == CreaseMethod::Chaikin {
            child = (0..m.n_halfedges()).map(|h| decrement(edge[h >> 1])).collect();
            for v in 0..m.n_vertices() {
                let o = m.v_out[v];
                if o & POINT != 0 {
                    continue;
                }
                let ring: Vec<u32> = ring(m, o).collect();
                let semi: Vec<f64> = ring.iter().map(|&h| edge[(h >> 1) as usize]).filter(|&s| is_semi_sharp(s)).collect();
                if ring.len() < 2 || semi.is_empty() {
                    if ring.len() >= 2 {
                        // no semi-sharp edge: OpenSubdiv keeps the parent values
                        for &h in &ring {
                            child[h as usize] = edge[(h >> 1) as usize];
                        }
                    }
                    continue;
                }
                let sum: f64 = semi.iter().sum();
                for &h in &ring {
                    let p = edge[(h >> 1) as usize];
                    child[h as usize] = if p <= 0.0 {
                        0.0
                    } else if is_infinite(p) {
                        INFINITE
                    } else if semi.len() == 1 {
                        decrement(p)
                    } else {
                        let other = (sum - p) / (semi.len() - 1) as f64;
                        let c = 0.75 * p + 0.25 * other - 1.0;
                        c.max(0.0)
                    };
                }
            }
        }
        LevelSharpness { edge, vertex, child, any }
    }

    /// Child sharpness of edge `h >> 1` at the tail of half-edge `h`.
    #[inline]
    pub fn child(&self, h: u32) -> f64 {
        match self.child.get(h as usize) {
            Some(&c) => c,
            None => decrement(self.edge[(h >> 1) as usize]),
        }
    }

    /// The rules of vertex `v` (not a point-sphere) in this level and the
    /// next, and OpenSubdiv's fractional weight on a transition.
    pub fn vertex_rule(&self, m: &Mesh, v: usize, method: CreaseMethod) -> VertexRule {
        let o = m.v_out[v];
        let smooth = VertexRule { parent: Rule::Smooth, parent_ends: [0, 0], child: None };
        if !self.any {
            return smooth;
        }
        let (mut n_sharp, mut ends) = (0usize, [0u32; 2]);
        let (mut n_csharp, mut cends) = (0usize, [0u32; 2]);
        let (mut tsum, mut tcount) = (0.0f64, 0usize);
        let pv = self.vertex[v];
        let cv = decrement(pv);
        if pv > 0.0 && cv <= 0.0 {
            tsum += pv;
            tcount += 1;
        }
        for h in ring(m, o) {
            let p = self.edge[(h >> 1) as usize];
            let c = self.child(h);
            if p > 0.0 {
                if n_sharp < 2 {
                    ends[n_sharp] = h;
                }
                n_sharp += 1;
            }
            if c > 0.0 {
                if n_csharp < 2 {
                    cends[n_csharp] = h;
                }
                n_csharp += 1;
            }
            let transition = match method {
                CreaseMethod::Uniform => p > 0.0 && p <= 1.0,
                CreaseMethod::Chaikin => p > 0.0 && c <= 0.0,
            };
            if transition {
                tsum += p;
                tcount += 1;
            }
        }
        let parent = rule(pv, n_sharp);
        if matches!(parent, Rule::Smooth | Rule::Dart) {
            return VertexRule { parent, ..smooth };
        }
        let crule = rule(cv, n_csharp);
        let child = if crule == parent {
            None
        } else {
            let w = if tcount == 0 { 0.0 } else { (tsum / tcount as f64).min(1.0) };
            Some((crule, cends, w))
        };
        VertexRule { parent, parent_ends: ends, child }
    }

    /// Whether edge `e`'s point follows the crease (midpoint) rule, and
    /// otherwise the weight of the midpoint blended into the smooth point.
    #[inline]
    pub fn edge_rule(&self, e: usize) -> EdgeRule {
        let s = self.edge[e];
        if s <= 0.0 {
            EdgeRule::Smooth
        } else if self.child(2 * e as u32) > 0.0 && self.child(2 * e as u32 + 1) > 0.0 {
            EdgeRule::Crease
        } else {
            EdgeRule::Blend(s)
        }
    }

    /// Sharpness of the output: child edges of input edges from
    /// `child_of[h]` (the input half-edge whose tail end the output edge is
    /// the child of, or `NONE` for edges inside faces), vertex points'
    /// vertex sharpness decremented. Boundary edges keep the user's value
    /// decremented (they are infinite in every level anyway).
    pub fn child_creases(&self, m: &Mesh, user: Option<&Creases>, out_edge_parent: &[u32], n_out_vertices: usize) -> Creases {
        let (_, _, face) = m.halfedge_columns();
        let edge = out_edge_parent
            .iter()
            .map(|&h| {
                if h == crate::mesh::NONE {
                    return 0.0;
                }
                let e = (h >> 1) as usize;
                if m.f_hole[face[2 * e] as usize] || m.f_hole[face[2 * e + 1] as usize] {
                    decrement(user.map_or(0.0, |c| c.edge(e)))
                } else {
                    self.child(h)
                }
            })
            .collect();
        let mut vertex = vec![0.0; n_out_vertices];
        for (v, s) in vertex.iter_mut().enumerate().take(m.n_vertices()) {
            *s = decrement(user.map_or(0.0, |c| c.vertex(v)));
        }
        Creases { edge, vertex }
    }
}

/// Whether an edge point is smooth, a crease midpoint or a blend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EdgeRule {
    Smooth,
    Crease,
    /// Weight of the midpoint (the parent sharpness, as in OpenSubdiv).
    Blend(f64),
}

/// Outgoing half-edges around the tail of `o`, in rotation order.
pub fn ring(m: &Mesh, o: u32) -> impl Iterator<Item = u32> + '_ {
    ring_in(&m.he_prev, o)
}

/// [`ring`] over a bare prev column (a level that has taken its input's
/// columns out of the mesh to free them one by one).
pub fn ring_in(prev: &[u32], o: u32) -> impl Iterator<Item = u32> + '_ {
    let mut h = o;
    let mut first = true;
    std::iter::from_fn(move || {
        if !first && h == o {
            return None;
        }
        first = false;
        let r = h;
        h = prev[h as usize] ^ 1;
        Some(r)
    })
}

/// Edges whose dihedral angle (between the normals of their two faces)
/// exceeds `angle` radians; boundary edges are not listed (they are sharp
/// already).
pub fn edges_sharper_than(m: &Mesh, angle: f64) -> Vec<u32> {
    let normals = m.face_normals();
    let (_, _, face) = m.halfedge_columns();
    let cos = angle.cos();
    (0..m.n_edges())
        .filter(|&e| {
            let (f1, f2) = (face[2 * e] as usize, face[2 * e + 1] as usize);
            if m.f_hole[f1] || m.f_hole[f2] {
                return false;
            }
            let (a, b) = (normals[f1], normals[f2]);
            if a.length_squared() == 0.0 || b.length_squared() == 0.0 {
                return false;
            }
            a.normalize().dot(b.normalize()) < cos
        })
        .map(|e| e as u32)
        .collect()
}
