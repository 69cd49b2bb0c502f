//! Fractal schemes: `Mesh.sierpinski` and `topomesh.menger_sponge`.

use super::big_int;
use crate::budget::predict;
use super::mesh::PyMesh;
use crate::schemes::{menger as mg, menger_sponge as sponge, sierpinski as sp};
use pyo3::prelude::*;

#[pymethods]
impl PyMesh {
    /// Generalized Sierpinski polyhedron (Srinivasan & Akleman, section 4;
    /// dissertation ch. VI.5).
    ///
    /// Each iteration subdivides every edge that is not a self-loop at its
    /// midpoint, cuts off the corner triangle at every corner of every old
    /// vertex, and inserts a self-loop at each midpoint between its two
    /// corners on the central faces, which opens them. The result is one
    /// connected manifold per input component; the self-loops have zero
    /// length, so smooth it (Doo-Sabin, Catmull-Clark) for a geometric
    /// realization without pinches.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// progress : bool, default False
    ///     Show a tqdm bar, one step per iteration.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///     Vertices ``0..V`` are the input's; midpoints follow in edge order.
    ///     With ``N`` non-loop edges, ``K`` vertex cones (``V`` when there are
    ///     no self-loops) and no self-loop-only faces, one iteration gives
    ///     ``V + N`` vertices, ``E + 4N`` edges, ``2N + K`` faces and
    ///     ``N`` more self-loops; the tetrahedron's genus is 3, 15, 63, ...
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``iterations`` out of range, or an open mesh (with boundary loops):
    ///     the paper's rule has no boundary version, and its natural
    ///     extension would make every boundary midpoint a pinch on two
    ///     boundary loops; close the holes first.
    #[pyo3(signature = (iterations = 1, progress = false, *, correspondence = false))]
    fn sierpinski<'py>(&self, py: Python<'py>, #[pyo3(from_py_with = big_int)] iterations: i128, progress: bool, correspondence: bool) -> PyResult<Bound<'py, PyAny>> {
        let spec = super::levels::Spec::plain("sierpinski", predict::sierpinski).with_corners(crate::schemes::corner_direct::sierpinski);
        super::levels::run(py, self, iterations, progress, spec, correspondence, sp::sierpinski_level)
    }

    /// Generalized Menger sponge (dissertation ch. VII): every face is
    /// inset by the thickness ``D`` into a remeshing face, a copy is offset
    /// inward (by default every face corner with its own offset corner, so
    /// every pipe is a right prism; see ``offset``), the offset faces are
    /// joined across edges by strips (split by a miter point at non-convex
    /// edges) and around vertices by cones, every original face is remeshed
    /// into corner and edge quads, and a pipe joins each remeshing face to
    /// its offset face.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 1
    /// thickness : float, default 1/3
    ///     ``D`` as a fraction of each face's width (twice the distance from
    ///     its centroid to its nearest side; the side of a square), below 1/2;
    ///     with ``absolute=True`` a length.
    /// absolute : bool, default False
    /// collapse_angle : float, optional
    ///     ``offset="merged"`` only: edges with an interior dihedral angle up
    ///     to this (degrees) collapse; default 90 (VII.4). Passed with the
    ///     per-face construction, which collapses no edge, it is refused
    ///     (``MeshError``) rather than ignored.
    /// progress : bool, default False
    /// correspondence : bool, default False, keyword-only
    ///     Also return a :class:`topomesh.Correspondence`: parent faces and
    ///     vertex/face origins as for the smoothing schemes; the positions
    ///     are not linear in the input's, so it has no subdivision matrix,
    ///     only the attribute ``transfer``.
    /// reduce_thickness : bool, default True, keyword-only
    ///     Where an iteration's output has crossing triangle pairs (exact
    ///     predicate, the whole output), halve the offset depth of the
    ///     input faces whose structure placed them (no other face) and
    ///     rebuild, at most 6 times, keeping the build with the fewest
    ///     pairs (``src/schemes/menger/mod.rs``, "Thickness reduction");
    ///     with ``"per_face"``, a crossing-free result then gives the
    ///     reduced faces part of their depth back where it stays
    ///     crossing-free. Outputs without crossings are unchanged.
    ///     False: the construction without it (no whole-output scan;
    ///     faster, about 1.6x on a 100k-face torus).
    /// report : bool, default False, keyword-only
    ///     Also return a dict of per-iteration lists: ``face_factor``
    ///     (float64 array per input face of that iteration: the factor its
    ///     offset depth was multiplied by, 1 where not reduced),
    ///     ``reduced_faces``, ``min_factor``, ``rounds`` (halving rounds),
    ///     ``crossing_pairs`` (crossing triangle pairs left in the output,
    ///     None with ``reduce_thickness=False``), ``crossing_vertices`` and
    ///     ``nominal_factor`` (the depth factor before any reduction: 1,
    ///     the requested thickness, for both constructions; faces below it
    ///     count as reduced).
    /// offset : {"per_face", "merged"}, default "per_face", keyword-only
    ///     How the inner surface is built (``src/schemes/menger/mod.rs``).
    ///     ``"per_face"``: every face corner gets its own offset corner
    ///     straight below its window, so every pipe is a right prism; vertex
    ///     faces are cones from a point below every face around the vertex,
    ///     and the depth is the requested thickness, halved only on the
    ///     faces behind a crossing (see ``reduce_thickness``; the cube's
    ///     right angles keep it: the classic sponge). ``"merged"``: the
    ///     dissertation's construction (VII.4),
    ///     one offset corner per group of faces joined by collapsed edges
    ///     (edges up to ``collapse_angle``), kept to reproduce the chapter's
    ///     counts (the tetrahedron's first iteration: 36 faces, against 46
    ///     per-face, where every edge keeps a strip); it crosses itself on
    ///     the octahedron's, icosahedron's and dodecahedron's third
    ///     iterations and the tetrahedron's fourth (624, 1,800, 900 and
    ///     4,646 pairs), where ``"per_face"`` has none.
    ///
    /// Returns
    /// -------
    /// Mesh, or (Mesh, Correspondence) with ``correspondence=True``, with
    /// the report dict appended (a tuple) when ``report=True``
    ///     Per iteration on a connected mesh: genus ``2g + F - 1``. On the
    ///     cube the first iteration is the classic level-1 sponge. Face
    ///     attributes are inherited from the parent faces (a strip's from a
    ///     face beside its edge, a vertex face's from a face at its vertex);
    ///     vertex attributes are copied from the input vertex whose rule
    ///     placed each point, and interpolated along the edge for the
    ///     trisection points. Creases are dropped; corner attributes are
    ///     refused (no face-varying rule).
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     Arguments out of range, an unknown ``offset``, ``collapse_angle``
    ///     without ``offset="merged"``, or an open mesh (with boundary loops):
    ///     every face becomes a wall joined to its inward offset, and the
    ///     chapter has no rule for the rim such a wall needs at a boundary.
    ///
    /// Notes
    /// -----
    /// The result is always a valid oriented manifold, and free of
    /// geometric self-intersections where measured so (exact predicate,
    /// confirmed by CGAL's test): the cube's, the tetrahedron's and the
    /// dodecahedron's iterations 1-4, the octahedron's and icosahedron's
    /// 1-3, the torus's and the genus-2 surface's 1-2. Elsewhere the
    /// thickness is halved while crossings remain and any left are warned
    /// about; with ``offset="merged"`` vertices whose local result crosses
    /// are first rebuilt with all their pipes meeting in one point. The
    /// measured figures (crossing pairs left, per case and construction)
    /// are in ``docs/schemes/menger.md``.
    ///
    /// Warns
    /// -----
    /// GeometryWarning
    ///     Once per iteration whose thickness was reduced (how many faces,
    ///     the smallest factor) or whose output still has crossing triangle
    ///     pairs (their count, from the exact whole-output check). With
    ///     ``reduce_thickness=False``, when the per-vertex check left
    ///     vertices crossing (that check alone can miss pairs).
    #[pyo3(signature = (iterations = 1, thickness = 1.0 / 3.0, absolute = false, collapse_angle = None, progress = false, *, correspondence = false, reduce_thickness = true, report = false, offset = "per_face"))]
    #[allow(clippy::too_many_arguments)]
    fn menger<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = big_int)] iterations: i128,
        thickness: f64,
        absolute: bool,
        collapse_angle: Option<f64>,
        progress: bool,
        correspondence: bool,
        reduce_thickness: bool,
        report: bool,
        offset: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let offset = match offset {
            "merged" => mg::Offset::Merged,
            "per_face" => mg::Offset::PerFace,
            other => {
                return Err(super::err(crate::error::MeshError::InvalidArgument(format!("menger: offset = {other:?} is not a construction; use \"per_face\" (the default) or \"merged\""))))
            }
        };
        if let (mg::Offset::PerFace, Some(a)) = (offset, collapse_angle) {
            return Err(super::err(crate::error::MeshError::InvalidArgument(format!(
                "menger: collapse_angle = {} applies to offset=\"merged\" only (the dissertation's edge collapses, VII.4); the per-face construction, the default, collapses no edge",
                crate::error::num(a)
            ))));
        }
        let collapse_angle = collapse_angle.unwrap_or(mg::MengerOptions::default().collapse_angle);
        let o = mg::MengerOptions { thickness, relative: !absolute, collapse_angle, reduce_thickness, offset };
        // every iteration's report, in order
        let reports = std::sync::Mutex::new(Vec::<mg::MengerReport>::new());
        let spec = super::levels::Spec::nonlinear("menger", predict::menger);
        let out = super::levels::run(py, self, iterations, progress, spec, correspondence, |m, req| {
            let (lv, r) = crate::schemes::menger_level::menger_level(m, &o, req)?;
            reports.lock().unwrap_or_else(|e| e.into_inner()).push(r);
            Ok(lv)
        })?;
        let reports = reports.into_inner().unwrap_or_else(|e| e.into_inner());
        for (k, r) in reports.iter().enumerate() {
            if let Some(msg) = warning_text(k + 1, iterations, r) {
                super::warn_geometry(py, msg)?;
            }
        }
        if !report {
            return Ok(out);
        }
        let d = pyo3::types::PyDict::new(py);
        let factors: Vec<Bound<'py, numpy::PyArray1<f64>>> = reports.iter().map(|r| numpy::PyArray1::from_slice(py, &r.face_factor)).collect();
        d.set_item("face_factor", factors)?;
        d.set_item("reduced_faces", reports.iter().map(|r| r.reduced().0).collect::<Vec<_>>())?;
        d.set_item("min_factor", reports.iter().map(|r| r.reduced().1).collect::<Vec<_>>())?;
        d.set_item("rounds", reports.iter().map(|r| r.rounds).collect::<Vec<_>>())?;
        d.set_item("crossing_pairs", reports.iter().map(|r| r.crossing_pairs).collect::<Vec<_>>())?;
        d.set_item("crossing_vertices", reports.iter().map(|r| r.crossing_vertices).collect::<Vec<_>>())?;
        d.set_item("nominal_factor", reports.iter().map(|r| r.nominal).collect::<Vec<_>>())?;
        let items: Vec<Bound<'py, PyAny>> = match out.cast::<pyo3::types::PyTuple>() {
            Ok(t) => t.iter().collect(),
            Err(_) => vec![out.clone()],
        };
        let mut items = items;
        items.push(d.into_any());
        Ok(pyo3::types::PyTuple::new(py, items)?.into_any())
    }
}

/// The `GeometryWarning` of iteration `k` (none when it is free of
/// crossings at the requested thickness): where the thickness was reduced
/// (module docs of `schemes::menger`, "Thickness reduction") and what
/// crossings remain, so no crossing is output silently.
fn warning_text(k: usize, iterations: i128, r: &mg::MengerReport) -> Option<String> {
    let (n, fmin) = r.reduced();
    let nf = r.face_factor.len();
    let reduced = (n > 0).then(|| format!("the thickness was reduced on {n} of {nf} faces (smallest factor {fmin:.4}; per face: report=True)"));
    match (r.crossing_pairs, reduced) {
        (Some(0), None) => None,
        (Some(0), Some(red)) => Some(format!("menger: iteration {k} of {iterations}: {red} to keep it free of crossings")),
        (Some(p), red) => Some(format!(
            "menger: iteration {k} of {iterations} self-intersects: {p} crossing triangle pairs remain (exact predicate){}; the mesh is a valid closed manifold (see the Mesh.menger notes for the measured cases, and its other construction, offset=\"merged\" or \"per_face\")",
            red.map_or(String::new(), |s| format!(" after {s}, the most the reduction could remove"))
        )),
        (None, _) if r.crossing_vertices > 0 => Some(format!(
            "menger: iteration {k} of {iterations} self-intersects: the crossing check left {} input vertices whose pipes or inner surface cross other faces (reduce_thickness=False: no whole-mesh count; the mesh is a valid closed manifold)",
            r.crossing_vertices
        )),
        (None, _) => None,
    }
}

/// The classic Menger sponge of ``level`` as one closed manifold mesh.
///
/// The cube ``[-1, 1]^3`` cut into ``3**level`` cells per side, keeping the
/// ``20**level`` cells with at most one base-3 digit 1 per digit position
/// among their coordinates; the mesh is the boundary of their union, unit
/// squares kept (not merged), oriented outward.
///
/// Parameters
/// ----------
/// level : int
///     0 (the cube) to 5 (6.5 M quads).
///
/// Returns
/// -------
/// Mesh
///     ``F = 2*20**n + 4*8**n`` quads, ``E = 2F``, genus
///     ``(21*20**n + 38*8**n - 59) / 133`` (0, 5, 81, 1409, 26433, 514625),
///     volume ``8 * (20/27)**n``.
#[pyfunction]
fn menger_sponge(py: Python<'_>, #[pyo3(from_py_with = super::big_int)] level: i128) -> PyResult<PyMesh> {
    let level = super::int_in("menger_sponge", "level", level, 0, sponge::MAX_LEVEL as i64)? as u32;
    super::run_interruptible(py, || sponge::menger_sponge(level)).map(PyMesh::wrap)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(menger_sponge, m)?)?;
    Ok(())
}
