//! Generalized Menger sponges: the remeshing scheme of the high-genus
//! dissertation, ch. VII.3–VII.5, on any closed manifold polygon mesh.
//!
//! One iteration with thickness `D` (per face, see [`MengerOptions`]):
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
//!    vertex's result free of crossings (see Status). After the build, the
//!    output triangles whose corners were placed by one input vertex's
//!    rules (its offset corners, miter vertices, window corners) are tested
//!    pairwise for proper crossings. Every vertex involved in a crossing is
//!    rebuilt *fully collapsed*, and so is every vertex whose vertex face is
//!    non-planar with no planar split (a cone from a new centroid vertex
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
//!    by its valence).
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
//! # Status (measured)
//!
//! Cube, iterations 1–4: quads only, genus 5, 81, 1121, 15585, the first two
//! with the classic sponge's volume; trimesh and manifold3d agree (watertight,
//! genus, volume) and a triangle-crossing scan finds no self-intersection
//! (the output is unchanged by the welding and miter rules above).
//! Tetrahedron 1–4 and dodecahedron 1–3: valid oriented manifolds with
//! positive volume and the genus formula, no one- or two-gons, accepted by
//! both peers; the dodecahedron's fourth iteration is valid too. The
//! tetrahedron's fourth iteration has 148 thin faces (area below 1e-4 of
//! the longest side squared) among 117 k.
//!
//! Crossing-free (proper triangle crossings, `crossing_report`, with
//! orientation tests relative to the size of the triangles involved, so
//! small features are tested as strictly as large ones): cube 1–4,
//! tetrahedron 1–3 (thickness 1/4 and 1/3), dodecahedron 1–2. Still
//! crossing, in crossing triangle pairs (the rules of steps 1–5 alone →
//! with the crossing check):
//!
//! | input, iteration | t = 1/3 | t = 1/4 |
//! |---|---|---|
//! | tetrahedron 3 | 1304 → 0 | 1488 → 0 |
//! | tetrahedron 4 | 70526 → 5754 | 80476 → 5787 |
//! | dodecahedron 3 | 18206 → 1080 | 30793 → 1920 |
//! | dodecahedron 4 | — → 82383 (660191 faces) | |
//!
//! [`menger_checked`] returns how many input vertices still cross when the
//! check ends (180 in the dodecahedron's third iteration, 1056 in the
//! tetrahedron's fourth, 0 wherever the table says crossing-free); the Python binding raises
//! `topomesh.GeometryWarning` with that number.
//!
//! Where the dodecahedron's third iteration crosses (measured): every one
//! of the 1080 pairs is a pipe wall triangle crossing an outer corner or
//! edge quad of a neighbouring face. The second iteration's output has 240
//! window edges (outer frame quad to pipe wall) with dihedral angles of
//! 20–35°, where the first iteration's has none under 75°; a pipe of depth
//! `D` whose window lies `D` from an edge of dihedral angle φ < 45° leaves
//! the wedge (its thickness there is `D·tan φ`) whatever `D` is, which is
//! why no thickness and no meeting point removes these crossings. The
//! sharp window edges come from the second iteration's 120 full collapses
//! (all its window corners and offset corners of the first iteration's
//! pipes: saddles of valence 5 whose vertex faces have no planar split): the
//! windows of coplanar frame faces cannot all lie above their one meeting
//! point, so some pipe walls lean under the frame. At the window corners the
//! vertex face is non-planar only because the `√3·D` bound pulls a merged
//! corner of two faces with different `D` (0.109 and 0.071) off their offset
//! planes; sliding it along their line instead (bound kept) lets 60 of the
//! 120 keep their vertex face and halves the dodecahedron's third iteration
//! (540 pairs), but the tetrahedron's third then crosses (384) and its
//! fourth doubles (12132), also when only groups with unequal `D` slide
//! (then no change) or only vertices that would be collapsed try it first
//! (1080 / 6714); left out. At the offset corners all `D` are equal and the
//! eight-sided vertex face spans five offset planes: it needs the envelope
//! above. For every remaining vertex of the third iteration, nine meeting
//! points (cap centre at ½–2½·D, the vertex normal at ½ and 1·D, the mean of
//! the offset corners, clamped or not, or halfway to it) all leave it
//! crossing (4 to 56 pairs per vertex), and one `D` for the whole mesh
//! gives 1440 / 6542.
//!
//! Also measured and left out (dodecahedron 3 / tetrahedron 4; the
//! tetrahedron's third iteration stays crossing-free unless noted):
//! * pipes shallower than their inset next to sharp edges (offset depth
//!   `min(D, κ·D·tan φ)` for the smallest convex φ < 90° of the face,
//!   κ = 0.5 … 0.9, the wedge bound above): 780–900 / 5292–6696. The
//!   wedge bound is not the whole story: the 180 vertices all still cross;
//! * one `D` per group of coplanar faces joined by flat edges: 1080 / 6054;
//! * every convex edge collapsed (collapse angle 150° or 180°): 360 / 5544;
//! * *slab walls*: a window side along a convex edge lies on the
//!   neighbouring face's offset plane (the wall is parallel to that face, so
//!   it cannot leave a sharp wedge) instead of `D` from the edge. At a
//!   vertex whose faces span three planes with one `D` each, every wall and
//!   every pipe corner then lies on the three offset planes and the result
//!   is exact; at every corner, with every convex edge collapsed:
//!   19968 / 74558 (tetrahedron 3: 8652); only at vertices whose edges are
//!   all convex: 180 / 8068 (720 / 10094 with the VII.4 collapse rule).
//!   At the mixed vertices of later iterations (convex, flat and concave
//!   edges around one vertex) the two faces of a collapsed edge then need
//!   two distinct pipe corners on the line where their offset planes meet,
//!   which one merged point per group cannot express.
//!
//! What remains: vertices whose local result still crosses once fully
//! collapsed. In the dodecahedron's third iteration they are 180 (three
//! symmetry classes of 60): saddles of valence 5 and 6, and vertices of
//! valence 13 with about 550° of face angles (down to 9°) whose normals
//! fit in no hemisphere. The latter are the second iteration's full
//! collapses at the corners where a pipe's bottom meets the vertex
//! triangle of the first iteration's inner surface (a vertex face with no
//! planar split there). The true offset near such a saddle is the boundary
//! of what the swept faces (each face ⊕ a ball of radius `D`) leave of the
//! solid, an envelope of convex pieces in which faces that are not
//! neighbours around the vertex meet along new edges, which one offset
//! corner per face and vertex cannot express. A per-vertex
//! check also misses pairs between two vertices' structures; testing each
//! vertex's triangles against its neighbours' as well found no further
//! vertex to fix (2280 pairs either way, before the fallback point above)
//! at six times the cost.
//! Measured with the fallback point (dodecahedron 3 / tetrahedron 4 at
//! 1080 / 5754) and left out: its depth `D` along the cap's centre
//! without the `√3·D` bound (1620 / 8611 at 3·D, 1260 / 6552 at 2·D); a
//! fixed depth of ¾·D … 1½·D along it (900–1260 / 5874–9979, with shells
//! up to 45% thinner); bounding merged corners by `√3` times the largest
//! `D` of their faces instead of the smallest (1260 / 5826, and 60 vertex
//! pairs of the dodecahedron's fourth iteration within 1e-6 of its
//! diagonal, none before); where the normals fit in no hemisphere, the
//! point ½ … √3 `D` along the angle-weighted vertex normal instead of the
//! least squares point (1020–1080 / 9186–10990); cones from a centroid
//! vertex instead of full collapses (1920 / 5894). The collapse angle
//! option at 120° (every dodecahedron edge collapses) gives 360 / 5544:
//! not crossing-free either, and not the VII.4 default.
//! Measured before (earlier rounds of this work) and left out: a second
//! fallback at such vertices (the nearest point `D` below every face,
//! without the window condition or the `√3·D` bound): the
//! dodecahedron's third iteration 3720 → 3000 (before the cone rule), but
//! the tetrahedron's fourth 11512 → 13392; that point as the only rule:
//! 11700 and 16830; capping sharp inset corners at 2–3 `D` (no gain); the
//! other diagonal for non-planar quads (no change). With the check and the
//! cone rule in place (dodecahedron 3 / tetrahedron 4 at 2280 / 10684):
//! splitting a full vertex's corners into the fewest consecutive runs that
//! each have a meeting point (12096 / 69945, and the tetrahedron's third
//! iteration crosses again); keeping corners under 20° or 35° out of the
//! merge (2280 / 16216, 8880 / 29236); halving `D` around vertices that
//! still cross (2340); a per-vertex search over six meeting points
//! (3960 / 13751); windows clamped into the corner nearest the meeting
//! point's projection (3180 / 11518); a window margin of `D/4` instead of
//! `D/2` (1260 / 9829 at t = 1/3, but 3060 at 1/4); any single thickness
//! from 0.15 to 0.45 (dodecahedron 3: 1920–3900, none crossing-free).
//! Before the crossing check, the remaining crossings all involved the
//! inner surface (miter quads, vertex faces, strips) at vertices of the
//! second iteration's inner surface where a concave edge meets others, and
//! they did not shrink with the thickness (tetrahedron 3: 1740 pairs at
//! t = 0.45, 2538 at 0.1): the local rules give the wrong shape there at
//! any scale. Two cases were traced: a miter vertex that lands inside a
//! neighbouring face's inset corner (the clip above fixes it) and vertices
//! where faces with corners of about 11° meet (the inner tips of the
//! tetrahedron's second iteration), whose inset corners lie 10 `D` out and
//! pull the vertex face into spikes. The near weld and the `4D` miter bound
//! are local rules with tuned constants (a weld threshold of `0.2·D`
//! already leaves 72 crossing pairs in the tetrahedron's second
//! iteration), and where they do not give a manifold the iteration is
//! rebuilt with the `2D` bound and coincident welds only.
//!
//! What was tried and measured without effect: a thickness tied to the
//! material behind each face (`D ≤ 0.4 ×` the distance along `−n` from the
//! face's centroid and from the midpoints towards its corners to the
//! opposite surface, by ray casts on a uniform triangle grid), and the same
//! bound on the offset corners and miter points along their offset
//! direction. On the inputs above the vertex bound never binds and the face
//! bound changes the third iterations by a few percent either way, while it
//! makes the tetrahedron's fourth iteration fail the peers (near-coincident
//! points from tiny `D`); it was left out. The dissertation (VII.3) takes `D`
//! as one user constant and VII.4 case 5 already notes that the offset
//! surface comes closer than `D` at non-convex edges; it stops at two
//! iterations (VII.6). Also measured and left out: one `D` per iteration
//! (`t` times the narrowest face of the whole mesh, the dissertation's
//! constant): tetrahedron 3 gives 1068 pairs instead of 1304, but `D`
//! follows the thinnest sliver everywhere, and the dodecahedron's fourth
//! iteration then fails on a zero-angle corner; sliding merged corners
//! onto the offset planes of the other faces around their vertex (as the
//! miter vertices are): it breaks the cube's second iteration (the third
//! plane of a concave neighbour meets the line on the wrong side). A
//! crossing-free third iteration needs the true offset's combinatorics at
//! such vertices (a straight-skeleton-like event where an inset corner
//! runs away), not a per-vertex point rule. The least-area triangulation of
//! non-planar vertex faces (instead of the cone from the centroid) cut the
//! third iterations to 768 (tetrahedron) and 10380 (dodecahedron) pairs
//! before the crossing check (1740 for the dodecahedron with it), but
//! leaves nearly folded edges (φ ≈ 0) in the dodecahedron's third
//! iteration; in the fourth, the merged corner of such an edge's faces sits
//! on a face plane (least squares between opposite normals), the pipe edge
//! above it has zero length and manifold3d merges 24–26 vertices. Fully
//! collapsing such vertices instead (crossing check) leaves no two vertices
//! of the dodecahedron's fourth iteration within 1e-6 of its diagonal.

use crate::geometry::crossing::local_crossings;
use crate::geometry::triangles_with_points;
use crate::error::{MeshError, Result};
use crate::mesh::{BuildOptions, HalfedgeId, Mesh};
use glam::{DMat3, DVec3};

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
    /// collapsed (VII.4); default 90.
    pub collapse_angle: f64,
}

impl Default for MengerOptions {
    fn default() -> Self {
        MengerOptions { thickness: 1.0 / 3.0, relative: true, collapse_angle: 90.0 }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum EdgeKind {
    Collapse,
    Strip,
    Miter,
}

const ANGLE_TOL: f64 = 1e-4; // radians

/// A miter point stays within this many `D` of its vertex (module docs).
const MITER_REACH: f64 = 4.0;
/// Inner points around one vertex closer than this many `D` are welded
/// (module docs, "Thickness, welding, planarity").
const WELD_TOL: f64 = 0.3;

/// Everything one iteration derives from the input's geometry.
struct Plan {
    face_n: Vec<DVec3>,
    face_d: Vec<f64>,
    /// Inset corner per half-edge (the corner at its tail in its face).
    q: Vec<DVec3>,
    kind: Vec<EdgeKind>,
    /// Merged offset-corner group per half-edge, and the group positions.
    group: Vec<u32>,
    group_pos: Vec<DVec3>,
}

/// The least-squares solution of `a x = b` (`a` a sum of `n nᵀ` over plane
/// normals) nearest to `x0` along directions `a` barely constrains. Iterative
/// refinement of a slightly regularized solve: exact (to rounding) when the
/// planes are consistent, so faces built on them stay planar, where a plain
/// regularized solve leaves them off by the regularization (about 1e-11 of
/// the thickness, enough to fail the planarity test and fan the face).
fn least_squares_from(a: DMat3, b: DVec3, x0: DVec3) -> DVec3 {
    let lam = 1e-6 * (a.x_axis.x + a.y_axis.y + a.z_axis.z);
    let inv = (a + DMat3::from_diagonal(DVec3::splat(lam))).inverse();
    let mut x = x0;
    for _ in 0..6 {
        x += inv * (b - a * x);
    }
    x
}

/// The corner at the tail of `h` in its face (unit normal `n`): the unit
/// in-plane inward normals of its outgoing and incoming sides, and whether
/// the corner is convex.
fn corner_sides(m: &Mesh, n: DVec3, h: HalfedgeId) -> (DVec3, DVec3, bool) {
    let pos = m.positions();
    let pv = pos[m.vertex(h).idx()];
    let t1 = (pos[m.head(h).idx()] - pv).normalize_or_zero();
    let t0 = (pv - pos[m.vertex(m.prev(h)).idx()]).normalize_or_zero();
    (n.cross(t1).normalize_or_zero(), n.cross(t0).normalize_or_zero(), t0.cross(t1).dot(n) > 0.0)
}

/// Whether `x` lies at least `dist` inside both sides of the corner at `pv`
/// with inward side normals `w1, w2` ([`corner_sides`]).
fn inside_corner(x: DVec3, pv: DVec3, (w1, w2): (DVec3, DVec3), dist: f64) -> bool {
    (x - pv).dot(w1) >= dist && (x - pv).dot(w2) >= dist
}

fn plan(m: &Mesh, o: &MengerOptions, full: &[bool]) -> Result<Plan> {
    if !(o.thickness > 0.0 && o.thickness.is_finite()) || (o.relative && o.thickness >= 0.5) {
        return Err(MeshError::InvalidArgument(format!(
            "menger: thickness must be positive{} (got {})",
            if o.relative { " and below 1/2 of the face width" } else { "" },
            o.thickness
        )));
    }
    if !(o.collapse_angle.is_finite() && (0.0..=180.0).contains(&o.collapse_angle)) {
        return Err(MeshError::InvalidArgument(format!(
            "menger: collapse_angle = {} is out of range; it must be a finite angle in [0, 180] degrees",
            o.collapse_angle
        )));
    }
    let nh = m.n_halfedges();
    let nf = m.n_faces();
    for f in m.faces() {
        crate::cancel::poll(f.0 as usize)?;
        if m.face_halfedge(f).is_none() || m.face_degree(f) < 3 {
            return Err(MeshError::InvalidArgument(format!(
                "menger: face {} has {} corner(s); every face needs at least three",
                f.0,
                m.face_degree(f)
            )));
        }
    }
    if m.n_self_loops() > 0 {
        return Err(MeshError::InvalidArgument("menger: self-loops have no length to thicken; smooth the mesh first".into()));
    }
    let pos = m.positions();
    let p = |h: HalfedgeId| pos[m.vertex(h).idx()];
    // --- faces: normal, width, thickness
    let mut face_n = vec![DVec3::ZERO; nf];
    let mut face_d = vec![0.0; nf];
    for f in m.faces() {
        crate::cancel::poll(f.0 as usize)?;
        let nw = m.face_newell(f);
        let n = nw.normalize_or_zero();
        if n == DVec3::ZERO {
            return Err(MeshError::InvalidArgument(format!("menger: face {} has zero area", f.0)));
        }
        let hs: Vec<HalfedgeId> = m.face_halfedges(f).collect();
        let c = hs.iter().map(|&h| p(h)).sum::<DVec3>() / hs.len() as f64;
        let mut width = f64::INFINITY;
        for &h in &hs {
            let (a, b) = (p(h), p(m.next(h)));
            let t = (b - a).normalize_or_zero();
            let d = ((c - a) - t * (c - a).dot(t)).length();
            width = width.min(2.0 * d);
        }
        face_n[f.idx()] = n;
        face_d[f.idx()] = width;
    }
    if o.relative {
        // D = t · the smallest width among the faces around the face's
        // vertices, so a wide face next to a thin wall does not reach through it
        let width = face_d.clone();
        let mut vmin = vec![f64::INFINITY; m.n_vertices()];
        for h in m.halfedges() {
            let v = m.vertex(h).idx();
            vmin[v] = vmin[v].min(width[m.face(h).idx()]);
        }
        for f in m.faces() {
            let w = m.face_halfedges(f).map(|h| vmin[m.vertex(h).idx()]).fold(f64::INFINITY, f64::min);
            face_d[f.idx()] = o.thickness * w;
        }
    } else {
        // the relative rule's bound (t < 1/2 of the smallest width around a
        // face) in absolute terms: beyond it inset corners cross and the
        // offset surface turns inside out (cube of side 2 at D = 10: volume −13600)
        let limit = 0.5 * face_d.iter().copied().fold(f64::INFINITY, f64::min);
        if o.thickness >= limit {
            return Err(MeshError::InvalidArgument(format!(
                "menger: thickness = {} (absolute) is out of range; on this mesh it must be in (0, {limit}) (half the smallest face width)",
                o.thickness
            )));
        }
        face_d.iter_mut().for_each(|d| *d = o.thickness);
    }
    // --- inset corners
    let mut q = vec![DVec3::ZERO; nh];
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        let f = m.face(h).idx();
        let n = face_n[f];
        let pv = p(h);
        let (w1, w2, _) = corner_sides(m, n, h);
        let den = 1.0 + w1.dot(w2);
        if den < 1e-9 || w1 == DVec3::ZERO || w2 == DVec3::ZERO {
            return Err(MeshError::InvalidArgument(format!(
                "menger: corner at vertex {} of face {} is a zero-angle spike",
                m.vertex(h).0,
                f
            )));
        }
        q[h.idx()] = pv + face_d[f] * (w1 + w2) / den;
    }
    // --- edge classes by the interior dihedral angle
    let collapse = o.collapse_angle.to_radians() + ANGLE_TOL;
    let kind: Vec<EdgeKind> = m
        .edges()
        .map(|e| {
            let h = e.halfedge();
            let (n1, n2) = (face_n[m.face(h).idx()], face_n[m.face(h.twin()).idx()]);
            let t = (pos[m.head(h).idx()] - p(h)).normalize_or_zero();
            let phi = std::f64::consts::PI - n1.cross(n2).dot(t).atan2(n1.dot(n2));
            if phi <= collapse {
                EdgeKind::Collapse
            } else if phi <= std::f64::consts::PI + ANGLE_TOL {
                EdgeKind::Strip
            } else {
                EdgeKind::Miter
            }
        })
        .collect();
    // --- merge offset corners across collapsed edges, per vertex
    let mut parent: Vec<u32> = (0..nh as u32).collect();
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        if kind[h.edge().idx()] == EdgeKind::Collapse {
            // corners h and next(twin(h)) lie on either side of edge(h) at its tail
            crate::union_find::union(&mut parent, h.0, m.next(h.twin()).0);
        }
    }
    for v in m.vertices() {
        crate::cancel::poll(v.0 as usize)?;
        if !full[v.idx()] {
            continue;
        }
        let hs: Vec<HalfedgeId> = m.vertex_halfedges(v).collect();
        for w in hs.windows(2) {
            crate::union_find::union(&mut parent, w[0].0, w[1].0);
        }
    }
    let mut group = vec![u32::MAX; nh];
    let mut members: Vec<Vec<u32>> = Vec::new();
    for h in 0..nh as u32 {
        crate::cancel::poll(h as usize)?;
        let r = crate::union_find::root(&mut parent, h);
        if group[r as usize] == u32::MAX {
            group[r as usize] = members.len() as u32;
            members.push(Vec::new());
        }
        let g = group[r as usize];
        group[h as usize] = g;
        members[g as usize].push(h);
    }
    let group_pos: Vec<DVec3> = members
        .iter()
        .map(|hs| {
            let raw = |h: u32| {
                let f = m.face(HalfedgeId(h)).idx();
                q[h as usize] - face_d[f] * face_n[f]
            };
            if hs.len() == 1 {
                return raw(hs[0]);
            }
            let pv = p(HalfedgeId(hs[0]));
            let dmin = hs.iter().map(|&h| face_d[m.face(HalfedgeId(h)).idx()]).fold(f64::INFINITY, f64::min);
            if full[m.vertex(HalfedgeId(hs[0])).idx()] {
                if let Some(y) = pipe_meeting_point(m, &face_n, &face_d, hs, pv, dmin) {
                    return y;
                }
                let normals: Vec<DVec3> = hs.iter().map(|&h| face_n[m.face(HalfedgeId(h)).idx()]).collect();
                if let Some(y) = below_every_face(pv, &normals, dmin) {
                    return y;
                }
            }
            // least squares on the offset planes; the mean of the raw offset
            // corners along any direction the planes leave free
            let avg = hs.iter().map(|&h| raw(h)).sum::<DVec3>() / hs.len() as f64;
            let (mut a, mut b) = (DMat3::ZERO, DVec3::ZERO);
            for &h in hs {
                let f = m.face(HalfedgeId(h)).idx();
                let n = face_n[f];
                a += DMat3::from_cols(n * n.x, n * n.y, n * n.z);
                b += n * (n.dot(pv) - face_d[f]);
            }
            let x = least_squares_from(a, b, avg);
            // a sharp vertex amplifies the offset (D / sin of its half
            // angle); keep the merged corner within √3·D of the vertex, the
            // cube corner's offset, so it stays inside thin corners
            let dmax = 3f64.sqrt() * dmin;
            let off = x - pv;
            if off.length() > dmax * (1.0 + 1e-9) { pv + off * (dmax / off.length()) } else { x }
        })
        .collect();
    Ok(Plan { face_n, face_d, q, kind, group, group_pos })
}

/// The meeting point of all pipes at a fully collapsed vertex (module docs,
/// "Crossing check"): the point nearest the vertex that lies at least `D`
/// below every face around it and projects onto every convex corner at
/// least `D/2` inside both its sides, so each pipe wall there is a planar
/// quad perpendicular to its face (as at the cube's corners). `None` when
/// no point does (a saddle whose corners' projections cannot all hold it).
/// `pv` is the vertex, `dmin` the smallest `D` of its faces.
fn pipe_meeting_point(m: &Mesh, face_n: &[DVec3], face_d: &[f64], hs: &[u32], pv: DVec3, dmin: f64) -> Option<DVec3> {
    let mut planes: Vec<(DVec3, f64)> = Vec::with_capacity(3 * hs.len());
    for &h in hs {
        let f = m.face(HalfedgeId(h)).idx();
        let (n, d) = (face_n[f], face_d[f]);
        planes.push((n, n.dot(pv) - d));
        let (w1, w2, convex) = corner_sides(m, n, HalfedgeId(h));
        if convex {
            planes.push((-w1, -w1.dot(pv) - 0.5 * d));
            planes.push((-w2, -w2.dot(pv) - 0.5 * d));
        }
    }
    nearest_in_halfspaces(&planes, pv, dmin)
}

/// The fallback point of a fully collapsed vertex at `pv` with no
/// [`pipe_meeting_point`] (module docs, "Crossing check"): `dmin` below
/// every face around it (outward unit `normals`) along the direction `u`
/// farthest below all their planes (the largest `min u·nᵢ`, the centre of
/// the normals' spherical cap), kept within `√3·dmin` of the vertex like
/// every merged corner; at a cube corner it is the corner's exact offset.
/// `None` when the normals do not lie in an open hemisphere (no direction
/// points below every face).
fn below_every_face(pv: DVec3, normals: &[DVec3], dmin: f64) -> Option<DVec3> {
    // the point nearest the origin with n·x ≥ 1 for every normal: x / |x|
    // is the direction, 1 / |x| its margin
    let planes: Vec<(DVec3, f64)> = normals.iter().map(|&n| (-n, -1.0)).collect();
    let x = nearest_in_halfspaces(&planes, DVec3::ZERO, 1.0)?;
    let len = x.length();
    (len.is_finite() && len > 0.0).then(|| pv - x * (dmin * len.min(3f64.sqrt()) / len))
}

/// The point of the half-spaces `n·x ≤ c` nearest to `pv` (Dykstra's
/// alternating projections), or `None` when they leave no point (within
/// `1e-9·scale`).
fn nearest_in_halfspaces(planes: &[(DVec3, f64)], pv: DVec3, scale: f64) -> Option<DVec3> {
    let mut y = pv;
    let mut inc = vec![DVec3::ZERO; planes.len()];
    for _ in 0..500 {
        let y0 = y;
        for (k, &(n, c)) in planes.iter().enumerate() {
            let z = y + inc[k];
            let viol = n.dot(z) - c;
            let pz = if viol > 0.0 { z - viol * n } else { z };
            inc[k] = z - pz;
            y = pz;
        }
        if y.distance(y0) <= 1e-13 * scale {
            break;
        }
    }
    planes.iter().all(|&(n, c)| n.dot(y) - c <= 1e-9 * scale).then_some(y)
}

/// A face's own offset corner (not merged) moves onto a miter vertex at the
/// same original vertex that lies on the face's offset plane, inside the
/// face's inset corner: the offset face is clipped by the offset of the
/// concave corner instead of reaching into it (module docs, step 3).
fn clip_to_miter_vertices(m: &Mesh, pl: &Plan, ip: &mut [DVec3]) {
    let pos = m.positions();
    let ng = pl.group_pos.len();
    let mut gsize = vec![0u32; ng];
    for h in m.halfedges() {
        gsize[pl.group[h.idx()] as usize] += 1;
    }
    let mut ends: Vec<usize> = Vec::new();
    for v in m.vertices() {
        ends.clear();
        ends.extend(m.vertex_halfedges(v).filter(|h| pl.kind[h.edge().idx()] == EdgeKind::Miter).map(|h| ng + 2 * h.edge().idx() + (h.0 & 1) as usize));
        if ends.is_empty() {
            continue;
        }
        let pv = pos[v.idx()];
        for h in m.vertex_halfedges(v) {
            let g = pl.group[h.idx()] as usize;
            let f = m.face(h).idx();
            let (n, d) = (pl.face_n[f], pl.face_d[f]);
            let (w1, w2, convex) = corner_sides(m, n, h);
            if gsize[g] != 1 || !convex {
                continue;
            }
            let on_plane = |x: DVec3| (n.dot(x) - (n.dot(pv) - d)).abs() <= 1e-7 * d;
            if let Some(&i) = ends.iter().find(|&&i| on_plane(ip[i]) && inside_corner(ip[i], pv, (w1, w2), d * (1.0 - 1e-7))) {
                ip[g] = ip[i];
            }
        }
    }
}

/// The inner surface's points: merged offset corners (`group`), then two
/// miter points per edge (`G + 2e + end`, end 0 at the tail of `2e`), welded
/// where they coincide around one original vertex.
struct Inner {
    pos: Vec<DVec3>,
    /// Representative of every inner point after welding.
    rep: Vec<u32>,
}

fn inner_points(m: &Mesh, pl: &Plan, refined: bool, full: &[bool]) -> Result<Inner> {
    let pos = m.positions();
    let ng = pl.group_pos.len();
    let ne = m.n_edges();
    let mut ip = pl.group_pos.clone();
    ip.resize(ng + 2 * ne, DVec3::NAN);
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        if pl.kind[e.idx()] != EdgeKind::Miter {
            continue;
        }
        let h = e.halfedge();
        let th = h.twin();
        let (f1, f2) = (m.face(h).idx(), m.face(th).idx());
        let (n1, n2) = (pl.face_n[f1], pl.face_n[f2]);
        let u = (pos[m.head(h).idx()] - pos[m.vertex(h).idx()]).normalize();
        // end 0 at tail(h): corners h (f1) and next(th) (f2); end 1: next(h) and th
        for (end, (c1, c2)) in [(h, m.next(th)), (m.next(h), th)].into_iter().enumerate() {
            let pv = pos[m.vertex(c1).idx()];
            // exactly on L_e, the line where the two offset planes meet, so
            // the two miter quads stay planar (VII.5.4, Fig. 61): start at
            // the point of L_e in the plane through the vertex normal to the
            // edge, then slide along L_e towards the offset planes of the
            // other faces around the vertex (least squares), or to the
            // middle of the two offset corners when none of them fixes it
            let x0 = DMat3::from_cols(n1, n2, u).transpose().inverse() * DVec3::new(n1.dot(pv) - pl.face_d[f1], n2.dot(pv) - pl.face_d[f2], u.dot(pv));
            if !x0.is_finite() {
                return Err(MeshError::InvalidArgument(format!("menger: edge {} folds back on itself (φ = 360°)", e.0)));
            }
            let (mut num, mut den) = (0.0, 0.0);
            let mut dmin = f64::INFINITY;
            for hh in m.vertex_halfedges(m.vertex(c1)) {
                let f = m.face(hh).idx();
                dmin = dmin.min(pl.face_d[f]);
                if f == f1 || f == f2 {
                    continue;
                }
                let n = pl.face_n[f];
                num += (n.dot(x0) - (n.dot(pv) - pl.face_d[f])) * n.dot(u);
                den += n.dot(u) * n.dot(u);
            }
            let (r1, r2) = (pl.group_pos[pl.group[c1.idx()] as usize], pl.group_pos[pl.group[c2.idx()] as usize]);
            let s = if den > 1e-6 { -num / den } else { (0.5 * (r1 + r2) - x0).dot(u) };
            // kept within MITER_REACH·D of the vertex (near-parallel planes)
            let dmax = if refined { MITER_REACH } else { 2.0 } * dmin;
            let r0 = (x0 - pv).length();
            ip[ng + 2 * e.idx() + end] = if r0 > dmax {
                // nearly parallel offset planes (φ just above 180°) meet far
                // away: pulled back towards the vertex, off the planes
                pv + (x0 - pv) * (dmax / r0)
            } else {
                let smax = (dmax * dmax - r0 * r0).sqrt();
                x0 + u * s.clamp(-smax, smax)
            };
        }
    }
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        if pl.kind[e.idx()] != EdgeKind::Miter {
            continue;
        }
        let h = e.halfedge();
        for (end, c1) in [h, m.next(h)].into_iter().enumerate() {
            if full[m.vertex(c1).idx()] {
                ip[ng + 2 * e.idx() + end] = pl.group_pos[pl.group[c1.idx()] as usize];
            }
        }
    }
    clip_to_miter_vertices(m, pl, &mut ip);
    // weld inner points around each original vertex: neighbours along the
    // vertex face's cycle when closer than WELD_TOL·D (an edge of the inner
    // surface collapses), any two when they coincide
    let mut parent: Vec<u32> = (0..ip.len() as u32).collect();
    let mut cyc: Vec<u32> = Vec::new();
    for v in m.vertices() {
        crate::cancel::poll(v.0 as usize)?;
        let Some(h0) = m.vertex_halfedge(v) else { continue };
        cyc.clear();
        let mut dmin = f64::INFINITY;
        let mut h = h0;
        loop {
            cyc.push(pl.group[h.idx()]);
            dmin = dmin.min(pl.face_d[m.face(h).idx()]);
            if pl.kind[h.edge().idx()] == EdgeKind::Miter {
                cyc.push((ng + 2 * h.edge().idx() + (h.0 & 1) as usize) as u32);
            }
            h = m.next(h.twin());
            if h == h0 {
                break;
            }
        }
        // near points (closer than WELD_TOL·D) are welded when that keeps
        // the vertex face one polygon or removes it entirely (it then splits
        // into pieces of two sides, whose sides are glued); a split that
        // leaves a polygon touching another piece at one point would pinch
        // the surface, so then only coincident points are welded
        let k = cyc.len();
        let close = |tol: f64, i: usize, j: usize| cyc[i] != cyc[j] && ip[cyc[i] as usize].distance(ip[cyc[j] as usize]) <= tol;
        let mut local: Vec<u32> = (0..k as u32).collect();
        for i in 0..k {
            for j in i + 1..k {
                if close(WELD_TOL * dmin, i, j) {
                    crate::union_find::union(&mut local, i as u32, j as u32);
                }
            }
        }
        let welded: Vec<u32> = (0..k).map(|i| cyc[crate::union_find::root(&mut local, i as u32) as usize]).collect();
        let pieces = split_cycle(&welded);
        let mut pairs: Vec<(u32, u32)> = pieces.iter().filter(|p| p.len() == 2).map(|p| (p[0].min(p[1]), p[0].max(p[1]))).collect();
        pairs.sort_unstable();
        pairs.dedup();
        let ok = refined && (pieces.len() == 1 || (pieces.iter().all(|p| p.len() == 2) && pairs.len() == pieces.len()));
        let tol = if ok { WELD_TOL * dmin } else { 1e-7 * dmin };
        for i in 0..k {
            for j in i + 1..k {
                if close(tol, i, j) {
                    crate::union_find::union(&mut parent, cyc[i], cyc[j]);
                }
            }
        }
    }
    let rep: Vec<u32> = (0..ip.len() as u32).map(|i| crate::union_find::root(&mut parent, i)).collect();
    Ok(Inner { pos: ip, rep })
}

/// Corners of every output face, with vertices as: `0..V` old, then
/// `tri(e, end)`, `qv(h)` and `inner(i)` (raw inner point ids, see [`Inner`]).
/// Faces left with fewer than three distinct corners are dropped. Also
/// returns each face's kind: 0 corner quad, 1 edge quad, 2 pipe quad,
/// 3 strip, 4 miter quad, 5 vertex face.
/// Polygons with a tag (which step made them) and their origin (the input
/// element they belong to, as in [`crate::schemes::level::Origins`]).
type Emitted = (Vec<i64>, Vec<i64>, Vec<u8>, Vec<(u8, u32)>);

fn emit_faces(m: &Mesh, pl: &Plan, inner: &Inner, tri: &dyn Fn(usize) -> u32, qv: &dyn Fn(usize) -> u32, iv: &dyn Fn(u32) -> u32) -> Emitted {
    use crate::schemes::level::{EDGE, FACE, VERTEX};
    let ng = pl.group_pos.len();
    let t_near = |h: HalfedgeId, near_tail: bool| -> u32 {
        let near_tail_of_2e = (h.0 & 1 == 0) == near_tail;
        tri(2 * h.edge().idx() + if near_tail_of_2e { 0 } else { 1 })
    };
    let r = |h: HalfedgeId| iv(inner.rep[pl.group[h.idx()] as usize]);
    let mid = |e: usize, end: usize| iv(inner.rep[ng + 2 * e + end]);
    let mut sizes: Vec<i64> = Vec::new();
    let mut idx: Vec<i64> = Vec::new();
    let mut tags: Vec<u8> = Vec::new();
    let mut origin: Vec<(u8, u32)> = Vec::new();
    let mut push = |poly: &[u32], tag: u8, from: (u8, u32)| {
        for d in split_cycle(poly) {
            if d.len() >= 3 {
                sizes.push(d.len() as i64);
                idx.extend(d.iter().map(|&x| x as i64));
                tags.push(tag);
                origin.push(from);
            }
        }
    };
    // outer remeshing (corner and edge quads) and the pipes
    for f in m.faces() {
        for h in m.face_halfedges(f) {
            let (pr, nx) = (m.prev(h), m.next(h));
            let of = (FACE, f.0);
            push(&[m.vertex(h).0, t_near(h, true), qv(h.idx()), t_near(pr, false)], 0, of);
            push(&[t_near(h, true), t_near(h, false), qv(nx.idx()), qv(h.idx())], 1, of);
            push(&[qv(h.idx()), qv(nx.idx()), r(nx), r(h)], 2, of);
        }
    }
    // inner surface: strips, miter quad pairs, vertex faces
    for e in m.edges() {
        let h = e.halfedge();
        let t = h.twin();
        match pl.kind[e.idx()] {
            EdgeKind::Collapse => {}
            EdgeKind::Strip => push(&[r(h), r(m.next(h)), r(t), r(m.next(t))], 3, (EDGE, e.0)),
            EdgeKind::Miter => {
                if r(h) == r(m.next(t)) && r(m.next(h)) == r(t) {
                    // both ends already one offset corner (every other edge
                    // around collapsed): the offset faces meet, no strip
                    continue;
                }
                let (m0, m1) = (mid(e.idx(), 0), mid(e.idx(), 1));
                push(&[r(h), r(m.next(h)), m1, m0], 4, (EDGE, e.0));
                push(&[m0, m1, r(t), r(m.next(t))], 4, (EDGE, e.0));
            }
        }
    }
    let mut poly = Vec::new();
    for v in m.vertices() {
        let Some(h0) = m.vertex_halfedge(v) else { continue };
        poly.clear();
        let mut h = h0;
        loop {
            poly.push(r(h));
            if pl.kind[h.edge().idx()] == EdgeKind::Miter {
                poly.push(mid(h.edge().idx(), (h.0 & 1) as usize));
            }
            h = m.next(h.twin());
            if h == h0 {
                break;
            }
        }
        push(&poly, 5, (VERTEX, v.0));
    }
    (sizes, idx, tags, origin)
}

/// A face cycle after welding: consecutive repeats removed, then split
/// wherever it passes a vertex twice (the pieces touch only there).
fn split_cycle(poly: &[u32]) -> Vec<Vec<u32>> {
    let d = dedup_cycle(poly);
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            if d[i] == d[j] {
                let mut out = split_cycle(&d[i..j]);
                let rest: Vec<u32> = d[j..].iter().chain(&d[..i]).copied().collect();
                out.extend(split_cycle(&rest));
                return out;
            }
        }
    }
    vec![d]
}

/// The cycle with consecutive repeated vertices (cyclically) removed.
fn dedup_cycle(poly: &[u32]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::with_capacity(poly.len());
    for &x in poly {
        if out.last() != Some(&x) {
            out.push(x);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// Quantities of the count formulas (module docs), measured on the input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct MengerCounts {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub genus: i64,
    /// Edges collapsed, kept as strips, split by miter points.
    pub collapsed: usize,
    pub strips: usize,
    pub mitered: usize,
    /// `G + 2E_m` after welding: the inner surface's vertices.
    pub inner_vertices: usize,
    /// Strip and miter quads and vertex faces with at least three corners.
    pub inner_faces: usize,
    /// Faces added by splitting non-planar faces into planar pieces.
    pub planar_splits: usize,
}

/// The counts one [`menger`] iteration will produce on `m` (module docs):
/// `V' = V + 4E + inner vertices`, `F' = 6E + inner faces`,
/// `genus' = 2g + F − 1` per component, `E' = V' + F' − χ'`.
pub fn menger_counts(m: &Mesh, o: &MengerOptions) -> Result<MengerCounts> {
    let pl = plan(m, o, &vec![false; m.n_vertices()])?;
    let (e, f) = (m.n_edges(), m.n_faces());
    let n_miter = pl.kind.iter().filter(|&&k| k == EdgeKind::Miter).count();
    let n_coll = pl.kind.iter().filter(|&&k| k == EdgeKind::Collapse).count();
    let built = build_valid(m, o)?.0 .0;
    let inner_vertices = built.inner_vertices;
    let inner_faces = built.sizes.len() - built.split_extra - 3 * m.n_halfedges();
    let chi2 = 2 * m.euler_characteristic() - 2 * f as i64;
    let vertices = m.n_vertices() + 4 * e + inner_vertices;
    let faces = 6 * e + inner_faces + built.split_extra;
    Ok(MengerCounts {
        vertices,
        edges: (vertices as i64 + faces as i64 - chi2) as usize,
        faces,
        genus: (m.n_components() as i64 * 2 - chi2) / 2,
        collapsed: n_coll,
        strips: e - n_coll - n_miter,
        mitered: n_miter,
        inner_vertices,
        inner_faces,
        planar_splits: built.split_extra,
    })
}

/// Positions and polygon faces of one iteration, with the number of inner
/// points used and of faces added by splitting non-planar faces.
pub(super) struct Built {
    pos: Vec<DVec3>,
    sizes: Vec<i64>,
    idx: Vec<i64>,
    inner_vertices: usize,
    split_extra: usize,
    /// Output vertices from here on are inner points (offset corners, miter
    /// vertices, cone apices); below are the outer remeshing's.
    first_inner: u32,
    /// Input vertices whose vertex face became a cone.
    coned: Vec<u32>,
    /// The input vertex whose local rule placed each output vertex
    /// (`u32::MAX` for the input's vertices and the trisection points).
    pub(super) owner: Vec<u32>,
    /// The input element every output face belongs to (`Origins` kinds).
    pub(super) face_origin: Vec<(u8, u32)>,
}

fn build_polygons(m: &Mesh, o: &MengerOptions, refined: bool, full: &[bool]) -> Result<Built> {
    let pl = plan(m, o, full)?;
    let inner = inner_points(m, &pl, refined, full)?;
    let pos = m.positions();
    let (nv, ne, nh) = (m.n_vertices(), m.n_edges(), m.n_halfedges());
    // vertex layout: [old | trisection 2 per edge | inset corner per half-edge | used welded inner points]
    let t0 = nv;
    let q0 = t0 + 2 * ne;
    let i0 = q0 + nh;
    let mut out_pos: Vec<DVec3> = Vec::with_capacity(i0 + pl.group_pos.len());
    out_pos.extend_from_slice(pos);
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        let h = e.halfedge();
        let (a, b) = (pos[m.vertex(h).idx()], pos[m.head(h).idx()]);
        let len = (b - a).length();
        let d = (0.5 * (pl.face_d[m.face(h).idx()] + pl.face_d[m.face(h.twin()).idx()])).min(0.4 * len);
        let u = (b - a) / len;
        out_pos.push(a + d * u);
        out_pos.push(b - d * u);
    }
    {
        // window corners: the offset corners (after merging and welding)
        // projected back onto the face plane, so every pipe wall is a planar
        // quad perpendicular to its face (module docs); the inset corner
        // where the projection would leave less than D/2 of frame (depth
        // below the face, distance from the corner's two sides) or the
        // corner is not convex
        for h in m.halfedges() {
            let f = m.face(h).idx();
            let (n, d) = (pl.face_n[f], pl.face_d[f]);
            let pv = pos[m.vertex(h).idx()];
            let r = inner.pos[inner.rep[pl.group[h.idx()] as usize] as usize];
            let depth = (pv - r).dot(n);
            let x = r + depth * n;
            let (w1, w2, convex) = corner_sides(m, n, h);
            let ok = convex && depth >= 0.5 * d && inside_corner(x, pv, (w1, w2), 0.5 * d);
            out_pos.push(if ok { x } else { pl.q[h.idx()] });
        }
    }
    // inner points get ids in order of first use
    let base = u32::MAX / 2;
    let (sizes, mut idx, tags, origin) = emit_faces(m, &pl, &inner, &|i| (t0 + i) as u32, &|h| (q0 + h) as u32, &|i| base + i);
    let mut inner_id = vec![u32::MAX; inner.pos.len()];
    for x in idx.iter_mut() {
        if *x >= base as i64 {
            let i = (*x - base as i64) as usize;
            if inner_id[i] == u32::MAX {
                inner_id[i] = out_pos.len() as u32;
                out_pos.push(inner.pos[i]);
            }
            *x = inner_id[i] as i64;
        }
    }
    let inner_vertices = out_pos.len() - i0;
    let ng = pl.group_pos.len();
    let mut group_vertex = vec![u32::MAX; ng];
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        group_vertex[pl.group[h.idx()] as usize] = m.vertex(h).0;
    }
    let mut owner = vec![u32::MAX; q0];
    owner.extend(m.halfedges().map(|h| m.vertex(h).0));
    owner.resize(out_pos.len(), u32::MAX);
    for (i, &id) in inner_id.iter().enumerate() {
        if id != u32::MAX {
            owner[id as usize] = if i < ng {
                group_vertex[i]
            } else {
                let e = crate::mesh::EdgeId(((i - ng) / 2) as u32);
                let h = e.halfedge();
                if (i - ng) % 2 == 0 { m.vertex(h).0 } else { m.head(h).0 }
            };
        }
    }
    // non-planar faces (vertex faces at saddle-like vertices, faces of a
    // non-planar input) are split into planar pieces
    let tol = 1e-9 * pl.face_d.iter().cloned().fold(f64::INFINITY, f64::min).max(1e-300);
    let (mut sz2, mut idx2) = (Vec::with_capacity(sizes.len()), Vec::with_capacity(idx.len()));
    let mut face_origin = Vec::with_capacity(sizes.len());
    let mut k = 0;
    let mut pieces = Vec::new();
    let mut coned: Vec<u32> = Vec::new();
    for (fi, &n) in sizes.iter().enumerate() {
        let poly: Vec<u32> = idx[k..k + n as usize].iter().map(|&x| x as u32).collect();
        k += n as usize;
        pieces.clear();
        split_planar(&poly, &out_pos, tol, &mut pieces);
        if pieces.len() == poly.len() - 2 && poly.len() > 3 && tags[fi] == 5 {
            // a vertex face with no planar split: a cone from its centroid
            // (a fan from a corner can fold through the outer surface)
            pieces.clear();
            let c = out_pos.len() as u32;
            out_pos.push(poly.iter().map(|&i| out_pos[i as usize]).sum::<DVec3>() / poly.len() as f64);
            for i in 0..poly.len() {
                pieces.push(vec![c, poly[i], poly[(i + 1) % poly.len()]]);
            }
            owner.push(owner[poly[0] as usize]);
            coned.push(owner[poly[0] as usize]);
        }
        for p in &pieces {
            sz2.push(p.len() as i64);
            idx2.extend(p.iter().map(|&x| x as i64));
            face_origin.push(origin[fi]);
        }
    }
    let split_extra = sz2.len() - sizes.len();
    Ok(Built { pos: out_pos, sizes: sz2, idx: idx2, inner_vertices: inner_vertices + coned.len(), split_extra, owner, first_inner: i0 as u32, coned, face_origin })
}

/// Largest distance of the polygon's points from its best-fit plane through
/// the centroid along the Newell normal.
fn planarity(poly: &[u32], pos: &[DVec3]) -> f64 {
    let pts: Vec<DVec3> = poly.iter().map(|&i| pos[i as usize]).collect();
    let c = pts.iter().sum::<DVec3>() / pts.len() as f64;
    let mut n = DVec3::ZERO;
    for i in 0..pts.len() {
        n += pts[i].cross(pts[(i + 1) % pts.len()]);
    }
    let n = n.normalize_or_zero();
    pts.iter().map(|p| (p - c).dot(n).abs()).fold(0.0, f64::max)
}

/// Splits a non-planar polygon along a diagonal into planar parts when one
/// exists (a saddle vertex face folds into squares), else fans it into
/// triangles from its first corner.
fn split_planar(poly: &[u32], pos: &[DVec3], tol: f64, out: &mut Vec<Vec<u32>>) {
    let n = poly.len();
    if n <= 3 || planarity(poly, pos) <= tol {
        out.push(poly.to_vec());
        return;
    }
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let a: Vec<u32> = poly[i..=j].to_vec();
            let b: Vec<u32> = poly[j..].iter().chain(&poly[..=i]).copied().collect();
            if planarity(&a, pos) <= tol && planarity(&b, pos) <= tol {
                out.push(a);
                out.push(b);
                return;
            }
        }
    }
    for i in 1..n - 1 {
        out.push(vec![poly[0], poly[i], poly[i + 1]]);
    }
}

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
    let ((_, mesh), crossing) = checked_build(m, o)?;
    Ok((mesh, crossing))
}

/// [`menger_checked`] with the polygons it was built from.
pub(super) fn checked_build(m: &Mesh, o: &MengerOptions) -> Result<((Built, Mesh), usize)> {
    m.refuse_open(
        "menger",
        "the generalized sponge (dissertation ch. VII.3) thickens every face into a wall, a remeshing face joined by \
         a pipe to its inward offset copy, and has no rule for the rim such a wall would need at a boundary; treating \
         the holes as faces would fill them, so open meshes are refused; close the holes with faces first",
    )?;
    let ((built, mesh), crossing) = build_valid(m, o)?;
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

/// Rounds of the crossing check (module docs): a vertex found crossing is
/// rebuilt fully collapsed; a second round catches vertices whose
/// neighbourhood changed.
const CROSSING_ROUNDS: usize = 3;

/// The polygons and the mesh of one iteration (module docs): built with the
/// rules of VII.3–VII.5, then every input vertex whose local result crosses
/// itself is rebuilt fully collapsed, for up to [`CROSSING_ROUNDS`] rounds.
/// Also returns how many input vertices still cross at the end.
fn build_valid(m: &Mesh, o: &MengerOptions) -> Result<((Built, Mesh), usize)> {
    let mut full = vec![false; m.n_vertices()];
    // after the first round only vertices next to a change are checked again
    let mut recheck = vec![false; m.n_vertices()];
    // whether each vertex crossed when it was last checked
    let mut crossing = vec![false; m.n_vertices()];
    let mut round = 0;
    loop {
        // (the previous round's build is dropped before this one is made)
        let cur = build_once(m, o, &full)?;
        let (tris, tri_pos) = triangles_with_points(&cur.1);
        let only = (round > 0).then_some(&recheck[..]);
        let mut lc = local_crossings(&tri_pos, &tris, &cur.0.owner, cur.0.first_inner, only);
        drop((tris, tri_pos));
        crate::cancel::check()?;
        for (v, c) in crossing.iter_mut().enumerate() {
            if only.map_or(true, |r| r[v]) {
                *c = false;
            }
        }
        for &v in &lc {
            crossing[v as usize] = true;
        }
        if round == CROSSING_ROUNDS {
            return Ok((cur, crossing.iter().filter(|&&c| c).count()));
        }
        // a vertex face with no planar split would be coned from a new
        // vertex, a saddle-like point the next iteration cannot offset:
        // such vertices are fully collapsed too (no vertex face)
        lc.extend(cur.0.coned.iter().copied());
        let mut changed = false;
        recheck.iter_mut().for_each(|x| *x = false);
        for v in lc {
            if !full[v as usize] {
                full[v as usize] = true;
                changed = true;
                // its neighbours' structures share its pipes and strips
                recheck[v as usize] = true;
                for h in m.vertex_halfedges(crate::mesh::VertexId(v)) {
                    recheck[m.head(h).idx()] = true;
                }
            }
        }
        if !changed {
            return Ok((cur, crossing.iter().filter(|&&c| c).count()));
        }
        round += 1;
    }
}

/// One build with the given fully collapsed vertices: with the `4D` miter
/// bound and the near weld, or, when that does not give a manifold, with a
/// `2D` miter bound and coincident points welded only.
fn build_once(m: &Mesh, o: &MengerOptions, full: &[bool]) -> Result<(Built, Mesh)> {
    let b = build_polygons(m, o, true, full)?;
    match Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default()) {
        Ok(mesh) => Ok((b, mesh)),
        Err(_) => {
            let b = build_polygons(m, o, false, full)?;
            let mesh = Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default())?;
            Ok((b, mesh))
        }
    }
}

/// `iterations` Menger steps with the same options.
pub fn menger_iterated(m: &Mesh, iterations: usize, o: &MengerOptions) -> Result<Mesh> {
    let mut cur = m.clone();
    for _ in 0..iterations {
        cur = menger(&cur, o)?;
    }
    Ok(cur)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    fn check(m0: &Mesh, n: usize, o: &MengerOptions) -> Mesh {
        let mut m = m0.clone();
        for i in 1..=n {
            let c = menger_counts(&m, o).unwrap();
            let (g, f) = (m.genus(), m.n_faces() as i64);
            m = menger(&m, o).unwrap();
            m.validate().unwrap();
            assert_eq!(
                (m.n_vertices(), m.n_edges(), m.n_faces(), m.genus()),
                (c.vertices, c.edges, c.faces, c.genus),
                "iteration {i}: {c:?}"
            );
            assert_eq!(m.genus(), 2 * g + f - 1);
            assert_eq!(m.n_components(), 1);
            assert!(m.signed_volume() > 0.0);
            let hist = m.face_size_histogram();
            assert!(hist.keys().all(|&k| k >= 3), "iteration {i}: {hist:?}");
        }
        m
    }

    #[test]
    fn cube_first_iteration_is_classic_level_one() {
        let o = MengerOptions::default();
        let m = menger(&primitives::cube(), &o).unwrap();
        m.validate().unwrap();
        assert_eq!((m.n_vertices(), m.n_edges(), m.n_faces(), m.genus()), (64, 144, 72, 5));
        assert!((m.signed_volume() - 8.0 * 20.0 / 27.0).abs() < 1e-9);
    }

    #[test]
    fn platonic_iterations() {
        let o = MengerOptions::default();
        let c = check(&primitives::cube(), 4, &o);
        assert_eq!(c.genus(), 15585); // 5, 81, 1121, 15585
        assert_eq!(c.face_size_histogram().keys().copied().collect::<Vec<_>>(), vec![4]);
        check(&primitives::tetrahedron(), 3, &o);
        check(&primitives::dodecahedron(), 3, &o);
        // the second cube iteration has the classic level-2 volume
        let c2 = menger_iterated(&primitives::cube(), 2, &o).unwrap();
        assert!((c2.signed_volume() - 8.0 * (20.0f64 / 27.0).powi(2)).abs() < 1e-9);
    }

    #[test]
    fn rejects_bad_input() {
        let o = MengerOptions::default();
        assert!(menger(&primitives::cube(), &MengerOptions { thickness: 0.5, ..o }).is_err());
        assert!(menger(&primitives::cube(), &MengerOptions { thickness: -1.0, ..o }).is_err());
        let s = crate::schemes::sierpinski::sierpinski(&primitives::cube()).unwrap();
        assert!(menger(&s, &o).is_err()); // self-loops
        // absolute thickness
        let a = menger(&primitives::cube(), &MengerOptions { thickness: 0.25, relative: false, ..o }).unwrap();
        a.validate().unwrap();
        assert_eq!(a.genus(), 5);
    }
}

/// Test support: proper crossing pairs of the whole triangulation of `m`.
#[cfg(test)]
pub(crate) fn count_self_intersections(m: &Mesh) -> usize {
    crossing_pairs(m).len()
}

#[cfg(test)]
pub(crate) fn crossing_pairs(m: &Mesh) -> std::collections::HashSet<(u32, u32)> {
    let (tris, p) = triangles_with_points(m);
    crate::geometry::crossing::crossing_pairs(&p, &tris, None, false).into_iter().collect()
}

#[cfg(test)]
mod intersection_tests {
    use super::*;
    use crate::primitives;

    /// Proper triangle crossings: none on the cube's iterations 1–4, the
    /// tetrahedron's 1–2 and the dodecahedron's 1–2. (Their third
    /// iterations still cross; see the module docs.)
    #[test]
    fn cube4_no_crossings() {
        let m = menger_iterated(&primitives::cube(), 4, &MengerOptions::default()).unwrap();
        assert_eq!(count_self_intersections(&m), 0);
    }

    /// The tetrahedron's third iteration is crossing-free with the crossing
    /// check (1304 and 1488 crossing pairs without it); the dodecahedron's
    /// still crosses, at a seventeenth of the pairs (18206 without it; 1080 now).
    #[test]
    fn third_iterations_with_crossing_check() {
        for t in [1.0 / 3.0, 0.25] {
            let o = MengerOptions { thickness: t, ..Default::default() };
            let m = menger_iterated(&primitives::tetrahedron(), 3, &o).unwrap();
            m.validate().unwrap();
            assert_eq!(count_self_intersections(&m), 0, "thickness {t}");
        }
        let m = menger_iterated(&primitives::dodecahedron(), 3, &MengerOptions::default()).unwrap();
        let n = count_self_intersections(&m);
        assert!(n < 1500, "{n} crossing pairs");
    }

    /// `menger_checked` reports the vertices still crossing exactly when the
    /// global scan finds crossings: none on the tetrahedron's and the
    /// cube's third iterations, some on the dodecahedron's (whose every
    /// remaining crossing pair has a triangle of a reported vertex).
    #[test]
    fn checked_reports_remaining_crossings() {
        let o = MengerOptions::default();
        for (m0, clean) in [(primitives::tetrahedron(), true), (primitives::cube(), true), (primitives::dodecahedron(), false)] {
            let input = menger_iterated(&m0, 2, &o).unwrap();
            let (m, left) = menger_checked(&input, &o).unwrap();
            let global = count_self_intersections(&m);
            assert_eq!(global == 0, clean);
            assert_eq!(left == 0, clean, "{left} vertices reported, {global} crossing pairs");
            assert!(left <= input.n_vertices());
            let again = menger(&input, &o).unwrap();
            assert!(again.positions() == m.positions() && again.to_polygons() == m.to_polygons());
        }
    }

    /// The per-vertex check finds what the global scan finds on a mesh
    /// built without it, and flags nothing on a crossing-free one.
    #[test]
    fn local_check_matches_global_scan() {
        let o = MengerOptions::default();
        let t2 = menger_iterated(&primitives::tetrahedron(), 2, &o).unwrap();
        let (b, mesh) = build_once(&t2, &o, &vec![false; t2.n_vertices()]).unwrap();
        let (tris, p) = triangles_with_points(&mesh);
        let global = crossing_pairs(&mesh);
        assert!(!global.is_empty());
        let local = local_crossings(&p, &tris, &b.owner, b.first_inner, None);
        // every globally crossing pair has an owner the local check flags
        for &(i, j) in &global {
            let owners: Vec<u32> = tris[i as usize].iter().chain(&tris[j as usize]).map(|&v| b.owner.get(v as usize).copied().unwrap_or(u32::MAX)).filter(|&x| x != u32::MAX).collect();
            assert!(owners.iter().any(|x| local.binary_search(x).is_ok()), "pair ({i}, {j}) unseen");
        }
        let (b, mesh) = build_once(&primitives::cube(), &o, &vec![false; 8]).unwrap();
        let (tris, p) = triangles_with_points(&mesh);
        assert!(local_crossings(&p, &tris, &b.owner, b.first_inner, None).is_empty());
    }

    #[test]
    fn nearest_point_in_halfspaces() {
        // the cube corner's offset: D below all three faces
        let planes = [(DVec3::X, -0.5), (DVec3::Y, -0.5), (DVec3::Z, -0.5)];
        let x = nearest_in_halfspaces(&planes, DVec3::ZERO, 1.0).unwrap();
        assert!(x.distance(DVec3::splat(-0.5)) < 1e-12, "{x}");
        // already inside: the point itself
        assert_eq!(nearest_in_halfspaces(&planes, DVec3::splat(-2.0), 1.0), Some(DVec3::splat(-2.0)));
        // a slab thinner than nothing: no point
        assert!(nearest_in_halfspaces(&[(DVec3::X, -0.5), (-DVec3::X, -0.5)], DVec3::ZERO, 1.0).is_none());
    }

    #[test]
    fn point_below_every_face() {
        let pv = DVec3::new(1.0, 2.0, 3.0);
        // cube corner: the exact offset, D below all three faces
        let x = below_every_face(pv, &[DVec3::X, DVec3::Y, DVec3::Z], 0.25).unwrap();
        assert!(x.distance(pv - DVec3::splat(0.25)) < 1e-9, "{x}");
        // flat vertex: straight below
        let n = DVec3::new(0.0, 0.6, 0.8);
        let x = below_every_face(pv, &[n, n, n, n], 0.5).unwrap();
        assert!(x.distance(pv - 0.5 * n) < 1e-9, "{x}");
        // a saddle whose normals lean 60° from z: D below every face would
        // need 2D of depth, which the √3·D bound cuts to √3·D straight down
        let tilt = |a: f64| DVec3::new(0.75f64.sqrt() * a.cos(), 0.75f64.sqrt() * a.sin(), 0.5);
        let ns: Vec<DVec3> = (0..5).map(|k| tilt(k as f64 * 2.0 * std::f64::consts::PI / 5.0)).collect();
        let x = below_every_face(pv, &ns, 1.0).unwrap();
        assert!(x.distance(pv - 3f64.sqrt() * DVec3::Z) < 1e-6, "{x}");
        // normals not in an open hemisphere: no direction
        assert!(below_every_face(pv, &[DVec3::X, -DVec3::X, DVec3::Y], 1.0).is_none());
    }

    /// `cargo test --release --lib crossing_report -- --ignored --nocapture`:
    /// crossing counts per iteration (the figures of the module docs).
    #[test]
    #[ignore]
    fn crossing_report() {
        for t in [1.0 / 3.0, 0.25] {
            let o = MengerOptions { thickness: t, ..Default::default() };
            for (name, m0, n) in [("cube", primitives::cube(), 4), ("tetrahedron", primitives::tetrahedron(), 4), ("dodecahedron", primitives::dodecahedron(), 3)] {
                let mut m = m0;
                for k in 1..=n {
                    m = match menger(&m, &o) {
                        Ok(x) => x,
                        Err(e) => {
                            eprintln!("t {t:.3} {name} {k}: {e}");
                            break;
                        }
                    };
                    eprintln!("t {t:.3} {name} {k}: F {} crossings {}", m.n_faces(), count_self_intersections(&m));
                }
            }
        }
    }

    #[test]
    fn no_self_intersections() {
        let o = MengerOptions::default();
        let mut m = primitives::cube();
        for _ in 0..3 {
            m = menger(&m, &o).unwrap();
            assert_eq!(count_self_intersections(&m), 0);
        }
        let t1 = menger(&primitives::tetrahedron(), &o).unwrap();
        assert_eq!(count_self_intersections(&t1), 0);
        // 24 crossing pairs before the material-depth rule (module docs)
        for t in [0.25, 1.0 / 3.0] {
            let t2 = menger_iterated(&primitives::tetrahedron(), 2, &MengerOptions { thickness: t, ..o }).unwrap();
            t2.validate().unwrap();
            assert_eq!(count_self_intersections(&t2), 0, "thickness {t}");
        }
        let d2 = menger_iterated(&primitives::dodecahedron(), 2, &o).unwrap();
        assert_eq!(count_self_intersections(&d2), 0);
        // the checker does see crossings: two overlapping cubes in one mesh
        let c = primitives::cube();
        let p = c.to_polygons();
        let mut pos = c.positions().to_vec();
        pos.extend(c.positions().iter().map(|&x| x + DVec3::new(0.5, 0.3, 0.1)));
        let mut idx: Vec<i64> = p.indices.iter().map(|&i| i as i64).collect();
        idx.extend(p.indices.iter().map(|&i| i as i64 + 8));
        let sizes: Vec<i64> = p.sizes.iter().chain(&p.sizes).map(|&s| s as i64).collect();
        let two = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap();
        assert!(count_self_intersections(&two) > 0);
    }
}
