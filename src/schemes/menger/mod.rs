//! Generalized Menger sponges: the remeshing scheme of the high-genus
//! dissertation, ch. VII.3–VII.5, on any closed manifold polygon mesh.
//!
//! One iteration with thickness `D` (per face, see [`MengerOptions`]):
//! steps 1, 4 and 5 are common to both constructions of the inner surface;
//! steps 2–3 below are the dissertation's **merged corners**
//! ([`Offset::Merged`], `offset="merged"`), kept to reproduce its counts.
//! The default is **per-face corners** ([`Offset::PerFace`], "Per-face
//! corners" below): every face corner keeps its own offset corner, no edge
//! collapses, and every case of issue 17's list is free of crossings
//! (the merged corners cross on the octahedron's, icosahedron's and
//! dodecahedron's third iterations and the tetrahedron's fourth).
//!
//! 1. **Remeshing faces** (VII.3 step 1): every corner `p` of a face `f` is
//!    inset to `q = p + D (w₁ + w₂)/(1 + w₁·w₂)`, where `w₁, w₂` are the unit
//!    in-plane inward normals of its two sides: the point at distance `D` from
//!    both side lines. This one formula covers convex corners, non-convex
//!    corners (VII.5.2: the offset reverses) and winged corners (VII.5.3:
//!    `w₁ = w₂`, the offset is `D·(n × e₁)`).
//! 2. **Offset faces** (step 2): `r = q − D n_f`, the remeshing face moved
//!    inward by `D` along the face normal. Where step 3 moves an offset
//!    corner (merging, welding), the remeshing corner follows it: `q` becomes
//!    the offset corner's projection onto the face plane, so every pipe wall
//!    of step 5 stays a planar quad perpendicular to its face (a pipe wall
//!    bent by a moved corner is split into two long thin triangles, which
//!    the next iteration turns into slivers). The inset `q` is kept where the
//!    projection would leave less than `D/2` of frame (depth, or distance
//!    from either side of the corner) or the corner is not convex.
//! 3. **ConnectEdges between offset faces** (step 3) with the edge-collapse
//!    rule of VII.4 by the interior (material) dihedral angle `φ` of the
//!    original edge:
//!    * `φ ≤ 90°` (+ 1e-4 rad, `ANGLE_TOL`: a strip of an edge a hair over
//!      90° is 1e-5·D wide and its near-coincident corners make peers merge
//!      or split vertices): the connecting edges are collapsed; the
//!      offset faces meet along their common edge and the offset corners of
//!      faces joined by collapsed edges around a vertex merge into one vertex,
//!      placed by least squares on the faces' offset planes (exact when the
//!      planes meet in a point or a line, so the faces built on it stay
//!      planar; along a line the planes leave free, at the mean of the
//!      unmerged corners);
//!    * `90° < φ ≤ 180°`: a quad strip joins the two offset edges;
//!    * `φ > 180°` (non-convex edge, VII.4 cases 5–6, VII.5.4): the strip is
//!      split by a new vertex at each end (the fix of Fig. 61, which the
//!      dissertation left out and which keeps the inner surface off the
//!      outer one), giving two quads. The vertex lies exactly on the line
//!      where the two faces' offset planes meet, so both quads are planar,
//!      slid along it as near as it gets to the offset planes of the other
//!      faces around that end (least squares), within `4D` of the vertex.
//!      A face's own offset corner at that vertex (not merged) that would
//!      reach past such a miter vertex lying on its offset plane and inside
//!      its inset corner is moved onto it: the offset face is clipped by the
//!      offset of the concave corner instead of running into it.
//!
//!    Around each original vertex the connecting edges bound a *vertex face*.
//!    Where collapses leave it with two sides it is removed and its two sides
//!    become one edge; with one side (a self-loop) the side is removed and the
//!    strip ends in a point. No two-gon or one-gon is ever output.
//!
//!    **Crossing check.** The rules above are local and do not keep every
//!    vertex's result free of crossings (see the merged construction's
//!    status). After the build, the
//!    output triangles whose corners were placed by one input vertex's
//!    rules (its offset corners, miter vertices, window corners) are tested
//!    pairwise for proper crossings. Every vertex involved in a crossing is
//!    rebuilt *fully collapsed*, and so is every vertex whose vertex face is
//!    non-planar with no planar split (one searched up to 64 corners; a
//!    cone from a new centroid vertex
//!    there leaves a saddle point of up to 500° of face angles, which the
//!    next iteration cannot offset: the dodecahedron's third iteration
//!    crossed at 3720 pairs with such cones, 2280 without). Fully
//!    collapsed: all connecting edges at the vertex collapse (VII.4
//!    case 3 leaves collapsing to a local criterion; here it is extended to
//!    every edge at such a vertex), so all its pipes meet in one point and
//!    its vertex face, strip ends and miter vertices vanish. The point is
//!    the nearest to the vertex that lies `D` below every face around it and
//!    projects at least `D/2` inside every convex corner there, so every
//!    pipe wall at it stays a planar quad perpendicular to its face, as at
//!    the cube's corners. When no point does (saddle vertices), the point
//!    `D` below every face along the direction farthest below all their
//!    planes (the centre of the normals' spherical cap), kept within
//!    `√3·D` like every merged corner; where the normals do not fit in a
//!    hemisphere, the least squares point of step 3. Up to three rounds;
//!    the check is linear in the output (a vertex's triangles are bounded
//!    by its valence). With the thickness reduction on, vertices that still
//!    cross once fully collapsed (and were not coned) are then released:
//!    the level is rebuilt with them as first built, each keeps the state
//!    whose build has fewer crossing pairs with a corner it placed, and
//!    the build with the fewest pairs of the three is kept (icosahedron 3:
//!    1980 → 1800; the others unchanged, `docs/schemes/menger.md`).
//! 4. **Outer remeshing** (step 4): every edge is trisected at distance
//!    `d_e = ½(D₁ + D₂)` (capped at 0.4 |e|) from its ends and every face is
//!    split into one corner quad per corner, one edge quad per side and its
//!    remeshing face.
//! 5. **CreatePipe** (step 5) between each remeshing face and its offset face:
//!    one quad per side; both faces disappear.
//!
//! # Open meshes: refused
//!
//! Every face becomes a wall: its remeshing face, joined by a pipe to its
//! inward offset copy, the offset faces joined across every edge. At a
//! boundary edge there is no face on the other side to join, and the
//! chapter gives no rule for the rim that would close the wall there;
//! treating the hole as a face would fill it. [`menger`] refuses open
//! meshes with a `Precondition` error that says so. (The rind,
//! [`crate::ops::rind`], is one wall for the whole surface, which it closes
//! along each boundary loop by peeling the hole.)
//!
//! # Counts
//!
//! For a connected input with `V, E, F`, genus `g`: the outer surface (genus
//! `g`) and the inner one (a copy of the input's surface, genus `g`) are
//! joined by `F` pipes, so
//!
//! ```text
//! genus' = 2g + F − 1         χ' = 2χ − 2F
//! V' = V + 2E (trisection) + 2E (remeshing corners) + G + 2E_m
//! F' = 4E (corner and edge quads) + 2E (pipe quads) + S + 2E_m + W
//! E' = V' + F' − χ'
//! ```
//!
//! where `E_m` counts non-convex edges, `G` the merged offset corners
//! (per vertex: its valence minus its collapsed edge ends, or 1 when every
//! edge at it collapses), `S` the strips of `90° < φ ≤ 180°` edges that keep
//! three distinct corners, and `W` the vertex faces with at least three
//! sides. Welding (below) and full collapses (the crossing check of step 3:
//! one merged corner, no vertex face, no miter vertices at such a vertex) lower
//! `G + 2E_m` and `S + 2E_m + W` and splitting
//! non-planar faces raises `F'`; [`MengerCounts`] evaluates every term from
//! the input's geometry. The genus formula is purely topological. On the
//! cube with the default thickness every edge collapses, so the first
//! iteration is the classic level-1 sponge (V 64, E 144, F 72, genus 5).
//!
//! With per-face corners ("Per-face corners" below) nothing is collapsed:
//! with `E_m` the non-convex edges (interior angle above 180°) and, at each
//! vertex `v`, a collar of `c_v = valence(v) + m_v` corners (`m_v` the ends
//! of non-convex edges at `v`: one miter point each), every vertex face
//! with `c_v > 3` a cone of `c_v` triangles from one apex and every other
//! one a triangle,
//!
//! ```text
//! V' = V + 4E (trisection, inset corners) + 2E (offset corners) + 2E_m + K − 2W
//! F' = 4E (corner, edge quads) + 2E (pipe walls) + E + E_m (strips, miter
//!      quads) + Σ_{c_v > 3} c_v + #{v : c_v = 3} − 3W + P
//! E' = V' + F' − χ'  (= … − 5W + P)         K = #{v : c_v > 3}
//! ```
//!
//! that is,
//!
//! ```text
//! V' = V + 6E + 2E_m + K − 2W
//! F' = 7E + E_m + Σ_{c_v > 3} c_v + #{v : c_v = 3} − 3W + P
//! ```
//!
//! for inputs whose vertices have valence 3 or more. `W` counts the edges
//! whose two offset edges coincide and are welded (invariant 2: a
//! right-angled edge whose two faces keep depths equal to each other's
//! inset; each removes its strip, two offset corners, and one triangle
//! from the cone at each end) and `P` the pieces added by splitting
//! non-planar faces (a face and an edge each: the outer quads of a
//! non-planar input face, or a miter point held back by its reach,
//! invariant 4). Both are zero off right angles and on planar inputs;
//! `tests/test_menger_offset.py` evaluates the rest from the input alone on
//! every iteration of the tetrahedron (1–4), octahedron, icosahedron (1–3),
//! dodecahedron (1–3) and torus (1–2): exact except the tetrahedron's
//! fourth (`P` = 12; with other depths, before the reduction gave depth
//! back, the octahedron's and icosahedron's third had `W` = 48 and 120, at
//! the pipe walls' right angles). The tetrahedron's
//! first iteration (no non-convex edge, every collar of three corners, no
//! cone): V 40 = 4 + 24 + 12, F 46 = 24 + 12 + 6 strips + 4 triangular
//! vertex faces (the chapter's 36 faces plus the strips and the vertex
//! faces), E 90, genus 3. On a mesh whose edges all meet at right angles
//! (the cube's family) every corner welds as the merged ones collapse, and
//! the counts are the merged construction's above (the classic sponge).
//!
//! # Thickness, welding, planarity
//!
//! With a relative thickness `t` (default 1/3), a face's `D` is `t` times the
//! smallest width among the faces around its vertices (width: twice the
//! distance from a face's centroid to its nearest side line), so a wide face
//! next to a thin wall of an earlier iteration does not reach through it. On
//! the cube every face of every iteration is a square and `D` is a third of
//! its side, as in the dissertation's Fig. 62.
//!
//! Offset corners and miter points around one original vertex are welded
//! when they coincide (the exact offset of an orthogonal corner is one
//! point), and also when they are closer than `0.3·D` (`WELD_TOL`), provided
//! the vertex face then stays one polygon or falls apart entirely into
//! pieces of two sides; a weld that would leave a polygon touching another
//! piece at one point (a pinch) is not made. A face that passes a vertex
//! twice is split there and pieces with fewer than three corners are
//! dropped (their two sides become one edge); a miter strip whose ends are
//! both single points is left out. The near weld removes the thin folded
//! vertex faces that form where a concave (mitered) pipe edge meets the
//! rim of a pipe: with the miter point on all three offset planes (the
//! `4D` bound above; `2D` cut it off the rim's offset plane) it lands
//! within a fraction of `D` of the rim face's offset corner, and the sliver
//! between them crossed the miter strip (tetrahedron, iteration 2). Non-planar faces (the
//! vertex face at a saddle-like vertex folds into two squares) are split along
//! a diagonal into planar parts when one exists; a vertex face that has none
//! makes its vertex fully collapsed (step 3, crossing check; should the
//! rounds run out first, it is a cone of triangles from a new vertex at its
//! centroid), any other face becomes a fan of triangles.
//! The faces are paired by vertex pairs ([`Mesh::from_polygons`]), which also
//! proves the result a manifold.
//!
//! A merged offset corner is kept within `√3·D` of its vertex (the cube
//! corner's offset): a sharp vertex would otherwise push it `D / sin(½·angle)`
//! deep, through a thin corner.
//!
//! # Thickness reduction (never a silent crossing)
//!
//! After the crossing check of step 3 (which tests each vertex's own
//! triangles only), the whole output is scanned with the exact predicate
//! ([`crate::geometry::crossing::crossing_pairs`], coplanar contacts
//! included, as `Mesh.self_intersections`). While it finds crossing pairs,
//! every input face that placed one of their faces (its origin face, the
//! faces of its origin edge or around its origin vertex, and the faces
//! around every input vertex whose rule placed one of its corners: merged
//! corners follow the depths of all the faces around their vertex) gets
//! half its offset depth, and the level is rebuilt. Only the depth is
//! reduced, not the inset `D` (the frame width): a uniform scale of both
//! around a vertex is a similarity of its local structure and cannot undo
//! a crossing there, while a pipe shallower than its frame fits into a
//! sharp wedge (depth below `D·tan φ`, see the merged construction's
//! status). The build with the
//! fewest pairs is kept; the rounds stop at zero pairs, when a round does
//! not lower the count, after [`REDUCTION_ROUNDS`] rebuilds, or when every
//! face involved is at [`REDUCTION_FLOOR`]. An output the first build
//! leaves free of crossings is returned as built (bit for bit the
//! construction without the reduction, e.g. the cube's iterations 1–4).
//! [`MengerReport`] gives the per-face factors and the pairs left, and the
//! Python binding raises a `GeometryWarning` with both whenever a face was
//! reduced or a pair is left. `reduce_thickness: false` skips the scan and
//! the rounds (the per-vertex check alone, which can miss pairs between
//! two vertices' structures). The per-face construction runs the same
//! rounds, then gives the reduced faces part of their depth back where the
//! output stays crossing-free (invariant 6 of "Per-face corners").
//!
//! Measured (crossing pairs with contacts, before → after; faces reduced,
//! smallest factor): see the table in `docs/schemes/menger.md`, every
//! figure confirmed by CGAL's exact test (the 4 "contacts" that used to
//! trigger it on the tetrahedron's third iteration, and the 223 it left on
//! the torus's second, were nearly coplanar neighbours the exact tests no
//! longer count). The reduction removes the proper crossings of the
//! torus's second iteration, and lowers the others by 0–40 %; it does not make the third iterations of the octahedron,
//! icosahedron and dodecahedron crossing-free. Reducing the depth around
//! such a vertex changes which corners merge and where, and past one round
//! the count grows again (octahedron 3: 816 → 624 → 816 → 1056 with
//! further halvings; halving inset and depth together: 816 → 984 → 1176,
//! or 816 → 1584 → 1752 counting only the faces of the crossing triangles
//! themselves). That is the structural cause of item 1 of issue 17 (one
//! merged point per group cannot express two pipe corners on one line),
//! which no thickness fixes.
//!
//! # Per-face corners ([`Offset::PerFace`], `offset="per_face"`)
//!
//! Issue 17's item 1 asks for an exact offset: every face's offset corner
//! on its own offset plane, never one merged point per group. Derived once,
//! with these invariants:
//!
//! 1. every corner of a face gets its own offset corner `r = q − d n_f`,
//!    straight below its inset corner `q` (step 1), on the face's offset
//!    plane; the window is the inset polygon, so every pipe is a right
//!    prism of depth `d` over it (planar walls perpendicular to the face,
//!    `D` from every side);
//! 2. the two offset edges along an input edge are both parallel to it, so
//!    the piece joining them (a strip, for collapsed edges too) is planar;
//!    where they coincide (the cube's right angles) the corners are welded
//!    and it vanishes, as does the vertex face of a cube corner;
//! 3. at a convex edge of interior angle `φ < 90°` the depth of both faces
//!    is at most `0.8·min(D₁, D₂)·tan(φ/2)` (`sharp_edge_depth`), which puts
//!    each offset corner at least the other face's depth below that face
//!    (for `φ ≥ 90°` equal depths up to `min(D₁, D₂)` do):
//!    the strip is then a bevel inside the mitred offset and each pipe stays
//!    in its wedge (item 2: the bound is reported in `face_factor`);
//! 4. non-convex edges keep their miter vertices on the line where the two
//!    offset planes meet (planar miter quads), at the middle of the two
//!    offset corners along the edge, so the miter quads run along the edge
//!    like a strip and stay out of the vertex's neighbourhood; only their
//!    distance from the edge is bounded (`MITER_REACH` times the two faces'
//!    own depths, for nearly flat edges whose planes meet far away), never
//!    their place along it (bounded by the thinnest face around the vertex,
//!    as the merged construction bounds it, a 312° edge's miter point was pulled back to
//!    the vertex: 204 pairs in the tetrahedron's third iteration, 2,976 in
//!    the torus's second, none without);
//! 5. a vertex face with no planar split is a cone from an apex *below
//!    every face around the vertex* by the smallest depth there (the centre
//!    of the normals' spherical cap, `below_every_face`: the nearest point
//!    `x` with every `n·x ≥ 1`, solved exactly over active sets of at most
//!    three normals, `min_norm_above`), not from the
//!    centroid of its corners: where the normals lie in an open hemisphere
//!    the vertex's neighbourhood is star-shaped from that apex, so as the
//!    depth shrinks each cone triangle stays under the faces while its base
//!    (a side of the collar of per-face corners and miter points) does.
//!    Where they do not, no point is below every face; the apex is then
//!    inward along the sum of the normals, by that depth, or ½, ¼ or 2
//!    times it, or the collar's centroid: the first whose cone meets none
//!    of the vertex's outer corner and edge quads (exact predicate; at
//!    the smallest depth alone 12 vertices of the tetrahedron's fourth
//!    iteration, edges of 306°, 135°, 161°, 241°, 180°, 90°, kept 48 pairs;
//!    the centroid alone left 2,760 pairs there and 13,200 in the
//!    dodecahedron's fourth; two apexes, one per run of faces whose
//!    normals fit a hemisphere, 11,722 and crossings in the octahedron's
//!    third). Off right angles every vertex face with
//!    more than three corners is such a cone, planar or not: a planar one
//!    spanning the collar cut through the outer surface at the
//!    tetrahedron's vertices of 60°, 270° and 270° (fourth iteration: 276
//!    pairs, 48 as cones); on the cube's right angles they stay as built,
//!    which keeps the classic sponge;
//! 6. the depth is the requested one: `D` on every face (the cube's family:
//!    invariant 2 welds the corners into the classic sponge), less only
//!    where invariant 3 bounds it at sharp edges and where the thickness
//!    reduction ("Thickness reduction" above, the same loop for both
//!    constructions) halves the depth of the input faces behind a crossing
//!    pair; once the output is crossing-free the reduced faces get part of
//!    their depth back (×√2, then ×2^¼, each step kept only if the output
//!    stays crossing-free, else only for the faces not behind its new
//!    crossings), since a halving overshoots by up to 2×. Every other face
//!    keeps `D`; all of it is reported per face.
//!
//! Invariants 1–5 make the structure at every vertex converge, as the depth
//! shrinks, to a thin layer under its faces, which cannot cross where the
//! vertex's normals fit in a hemisphere: halving the depth of the faces
//! behind a crossing converges. Invariant 6 replaced a measured rule: the
//! depth used to start at ½ of the inset on every face off right angles
//! and be halved for the whole mesh while the output crossed, because a
//! local halving stalled on faces of different depth side by side before
//! invariants 4 and 5 took their present form (octahedron 3: 504 pairs,
//! dodecahedron 3: 963) and starting at full depth then left 408 pairs in
//! the octahedron's third iteration. With them, the local reduction from
//! the requested depth leaves no pair on any case of issue 17's list (as
//! built → after, input faces reduced, their mean depth factor):
//! tetrahedron 3 1,618 → 0 (870 of 874, 0.70), 4 49,011 → 0 (15,994 of
//! 16,102); octahedron 2 288 → 0 (all 108, 0.71), 3 2,470 → 0 (all
//! 1,980); icosahedron 2 720 → 0 (all 270, 0.84), 3 8,649 → 0 (all
//! 4,950); dodecahedron 2 221 → 0 (all 230, 0.84), 3 7,279 → 0 (all
//! 4,370), 4 178,932 → 0 (79,952 of 80,330, 0.63); torus 2 8,086 → 0 (all
//! 5,616, 0.84); the first iterations, the cube's and the genus-2
//! surface's need none. Faces whose structure does not cross keep the
//! requested depth: a subdivided box with one corner pulled into a spike
//! reduces 24 of 96.
//! Each rule was measured alone on the merged construction's first
//! octahedron iteration (its second iteration, full depth, no reduction):
//! centroid cones and slid miter points 384 pairs, apex below every face
//! 168, and the middle miter points 96; at a quarter of the depth 0 with
//! either cone, at a twentieth 0 with the apex below every face and 384
//! with centroid cones (they poke through the outer surface).
//!
//! Measured (crossing pairs with contacts, every iteration on its own
//! previous output, `menger::diagnose::compare_offsets`; merged →
//! per-face): cube 1–4 0 → 0 (the classic sponge, same counts); genus
//! surface(2) 1–2 0 → 0; octahedron 1–2 0 → 0, 3 624 → **0**; icosahedron
//! 1–2 0 → 0, 3 1800 → **0**; dodecahedron 1–2 0 → 0, 3 900 → **0**, 4
//! 76817 → **0**; tetrahedron 1–3 0 → 0, 4 4646 → **0**; torus(24, 12)
//! 1–2 0 → 0: every case of issue 17's list, the tetrahedron's fourth and
//! the cube's fourth confirmed by CGAL's exact test as well (and, once by
//! hand, the dodecahedron's fourth: 2,569,880 triangles, none meeting). It is the
//! default for that; it drops the dissertation's VII.4 collapses (every
//! edge gets a strip unless its corners coincide, so `collapse_angle` does
//! not apply: the Python binding refuses it), whose counts the merged
//! construction keeps.

//! # The merged construction's status
//!
//! Its measured status, the crossing figures of its rules and the forty-odd
//! alternatives measured and left out are recorded in
//! `docs/schemes/menger.md` ("The merged construction: status and what was
//! tried"); the per-face construction above replaced that stack as the
//! default, and `offset="merged"` keeps it only to reproduce the chapter.

mod check;
mod connect;
mod counts;
mod inset;
mod offset;
mod pipe;
mod remesh;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod diagnose;

pub use counts::{menger_counts, MengerCounts};
pub(crate) use remesh::Built;

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;

/// Thickness and collapse rule of [`menger`].
#[derive(Clone, Copy, Debug)]
pub struct MengerOptions {
    /// The thickness `D`: absolute, or (when `relative`) a fraction of each
    /// face's width, twice the distance from its centroid to its nearest side
    /// line (the side length for a square). Default 1/3: the classic cube.
    pub thickness: f64,
    /// Whether `thickness` is a fraction of each face's width (default true).
    pub relative: bool,
    /// Edges whose interior dihedral angle is at most this (degrees) are
    /// collapsed (VII.4); default 90. [`Offset::Merged`] only.
    pub collapse_angle: f64,
    /// Whether the thickness of faces whose result crosses is reduced until
    /// it does not (module docs, "Thickness reduction"); default true.
    pub reduce_thickness: bool,
    /// The inner surface's construction (module docs, "Per-face corners");
    /// default [`Offset::PerFace`].
    pub offset: Offset,
}

/// How the offset corners of the faces around a vertex are placed (module
/// docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Offset {
    /// One merged point per group of faces joined by collapsed edges, with
    /// the crossing check's full collapses (steps 2–3): the dissertation's
    /// construction and counts (VII.4), kept to reproduce them.
    Merged,
    /// One offset corner per face corner, never merged (module docs,
    /// "Per-face corners"); the default: crossing-free on every case the
    /// module docs list.
    #[default]
    PerFace,
}

impl Default for MengerOptions {
    fn default() -> Self {
        MengerOptions { thickness: 1.0 / 3.0, relative: true, collapse_angle: 90.0, reduce_thickness: true, offset: Offset::PerFace }
    }
}

/// Per-face factors of the offset depth (module docs, "Thickness
/// reduction"); the inset `D` keeps its value.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Reduction {
    pub(crate) depth: Vec<f64>,
}

/// What one iteration's thickness reduction did (module docs, "Thickness
/// reduction").
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MengerReport {
    /// Per input face, the factor its requested offset depth was multiplied
    /// by: 1 where it was not reduced, down to [`REDUCTION_FLOOR`].
    pub face_factor: Vec<f64>,
    /// Halving rounds made by the reduction (0 when the first build had no
    /// crossing, or the reduction is off; the per-face builds that give
    /// depth back are not counted).
    pub rounds: usize,
    /// Crossing triangle pairs of the output by the exact predicate, with
    /// coplanar contacts ([`crate::geometry::crossing::mesh_crossing_pairs`]
    /// with `coplanar`, as `Mesh.self_intersections`); `None` when the
    /// reduction is off (no whole-output scan).
    pub crossing_pairs: Option<usize>,
    /// Input vertices whose own triangles still cross when the per-vertex
    /// check of step 3 ends (see [`menger_checked`]).
    pub crossing_vertices: usize,
    /// The depth factor before any reduction: 1 (the requested thickness)
    /// for both constructions; faces below it count as reduced.
    pub nominal: f64,
}

impl MengerReport {
    /// Faces whose thickness was reduced below the construction's own
    /// depth ([`MengerReport::nominal`]), and the smallest factor (1 if none).
    pub fn reduced(&self) -> (usize, f64) {
        let n = self.face_factor.iter().filter(|&&x| x < self.nominal * (1.0 - 1e-12)).count();
        (n, self.face_factor.iter().copied().fold(1.0, f64::min))
    }
}

pub use check::{REDUCTION_FLOOR, REDUCTION_ROUNDS};

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum EdgeKind {
    Collapse,
    Strip,
    Miter,
}

pub(super) const ANGLE_TOL: f64 = 1e-4; // radians

/// A miter point stays within this many `D` of its vertex (module docs).
pub(super) const MITER_REACH: f64 = 4.0;
/// Inner points around one vertex closer than this many `D` are welded
/// (module docs, "Thickness, welding, planarity").
pub(super) const WELD_TOL: f64 = 0.3;

/// Peak of an iteration with the thickness reduction over the stored bytes
/// of its upper-bound output counts (measured up to 9.0, see
/// [`checked_build`]).
const REDUCTION_PEAK: u64 = 12;

/// One generalized Menger iteration (module docs).
pub fn menger(m: &Mesh, o: &MengerOptions) -> Result<Mesh> {
    Ok(menger_checked(m, o)?.0)
}

/// One generalized Menger iteration and the number of input vertices whose
/// local result still crosses itself when the crossing check (module docs,
/// step 3) ends: the output is a valid manifold either way, but with
/// self-intersections when this is not zero. Zero does not prove the output
/// free of them: the check tests each vertex's own triangles only.
pub fn menger_checked(m: &Mesh, o: &MengerOptions) -> Result<(Mesh, usize)> {
    let ((_, mesh), report) = checked_build(m, o)?;
    Ok((mesh, report.crossing_vertices))
}

/// One iteration and what its thickness reduction did (module docs,
/// "Thickness reduction").
pub fn menger_reported(m: &Mesh, o: &MengerOptions) -> Result<(Mesh, MengerReport)> {
    let ((_, mesh), report) = checked_build(m, o)?;
    Ok((mesh, report))
}

/// [`menger_reported`] with the polygons it was built from.
pub(crate) fn checked_build(m: &Mesh, o: &MengerOptions) -> Result<((Built, Mesh), MengerReport)> {
    m.refuse_open(
        "menger",
        "the generalized sponge (dissertation ch. VII.3) thickens every face into a wall, a remeshing face joined by \
         a pipe to its inward offset copy, and has no rule for the rim such a wall would need at a boundary; treating \
         the holes as faces would fill them, so open meshes are refused; close the holes with faces first",
    )?;
    if crate::geometry::extreme_scale(m.positions()).is_some() {
        let top = crate::geometry::coordinate_range(m.positions()).1;
        return Err(MeshError::Precondition(format!(
            "menger: coordinates reach {top:e}, outside [2^-200, 2^200] where the offsets' lengths and normals stay \
             within float64; scale the mesh first"
        )));
    }
    if o.reduce_thickness {
        // the thickness reduction keeps two builds, a triangulation and the
        // whole-output scan's hierarchy alive at once: measured 7.8–9.0× the
        // stored bytes of the output's upper-bound counts (dodecahedron 4:
        // 1,310 MiB), above the 4× every level is checked for
        use crate::budget::{check, mesh_bytes, predict, Counts};
        let input = Counts::of(m);
        let need = mesh_bytes(&input).saturating_add(mesh_bytes(&predict::menger(&input).1).saturating_mul(REDUCTION_PEAK));
        check("menger", "one iteration with the thickness reduction (reduce_thickness=False skips it)", need)?;
    }
    let ((built, mesh), crossing) = check::build_reduced(m, o, o.reduce_thickness)?;
    // a thickness under the face-width bound can still exceed what the body
    // allows (a thin slab of wide faces): an outward input must stay outward
    if !o.relative && m.signed_volume() > 0.0 && !(mesh.signed_volume() > 0.0) {
        return Err(MeshError::InvalidArgument(format!(
            "menger: thickness = {} (absolute) is too large for this mesh: the result would be inside out (signed volume {:.6e}); use a smaller thickness",
            o.thickness,
            mesh.signed_volume()
        )));
    }
    Ok(((built, mesh), crossing))
}

/// `iterations` Menger steps with the same options.
pub fn menger_iterated(m: &Mesh, iterations: usize, o: &MengerOptions) -> Result<Mesh> {
    let mut cur = m.clone();
    for _ in 0..iterations {
        cur = menger(&cur, o)?;
    }
    Ok(cur)
}
