//! Bindings of Conway's polyhedron operators (`crate::schemes::conway`):
//! `topomesh.conway`, `topomesh.conway_operators`, `Mesh.conway`, one
//! `Mesh` method per operator and `Mesh.canonicalize`.

use super::mesh::PyMesh;
use super::{big_int, run_interruptible, usize_in};
use crate::schemes::conway::{self, canonical, seeds::MAX_SIDES, Op};
use pyo3::prelude::*;
use pyo3::types::PyDict;

fn run(py: Python<'_>, m: &crate::Mesh, want: bool, name: &str, op: Op) -> PyResult<(crate::Mesh, Option<Vec<u32>>)> {
    run_interruptible(py, || super::data::build_traced(want, m, || conway::apply_all(name, m, &[op])))
}

/// The output with what it keeps of the input's data: reflect keeps its
/// vertices and faces in order (vertex and face attributes survive); every
/// other operator rebuilds both and its faces inherit the face attributes
/// of the input face they descend from (`crate::schemes::face_parents`);
/// the data it drops is named in a `GeometryWarning`.
fn data_of(py: Python<'_>, data: &super::data::MeshData, name: &str, op: Op, input: &crate::Mesh, (out, parents): (crate::Mesh, Option<Vec<u32>>)) -> PyResult<PyMesh> {
    if op == Op::Reflect && !data.is_empty() {
        let d = super::data::kept(py, data, name, false, true, true)?;
        return Ok(PyMesh::with_data(out, d));
    }
    super::data::inherited(py, data, name, input, out, parents)
}

fn sides(name: &str, n: Option<&Bound<'_, PyAny>>) -> PyResult<Option<usize>> {
    n.map(|n| usize_in(name, "n", big_int(n)?, 1, MAX_SIDES)).transpose()
}

/// One method per operator without a number.
macro_rules! plain_op {
    ($name:ident, $op:expr, $doc:expr) => {
        #[pymethods]
        impl PyMesh {
            #[doc = $doc]
            fn $name(&self, py: Python<'_>) -> PyResult<PyMesh> {
                data_of(py, &self.data, stringify!($name), $op, &self.inner, run(py, &self.inner, !self.data.face.is_empty(), stringify!($name), $op)?)
            }
        }
    };
}

/// One method per operator with an optional number `n`.
macro_rules! sized_op {
    ($name:ident, $op:path, $doc:expr) => {
        #[pymethods]
        impl PyMesh {
            #[doc = $doc]
            #[pyo3(signature = (n = None))]
            fn $name(&self, py: Python<'_>, n: Option<&Bound<'_, PyAny>>) -> PyResult<PyMesh> {
                let n = sides(stringify!($name), n)?;
                data_of(py, &self.data, stringify!($name), $op(n), &self.inner, run(py, &self.inner, !self.data.face.is_empty(), stringify!($name), $op(n))?)
            }
        }
    };
}

macro_rules! doc {
    ($summary:literal, $counts:literal) => {
        concat!(
            $summary,
            "\n\nCounts from the input's V, E, F: ",
            $counts,
            "; genus, Euler characteristic and components are kept. Any closed mesh \
             (self-loops, two-gons, point-spheres, any genus).\n\n\
             Returns\n-------\nMesh\n\n\
             Raises\n------\nMeshError\n    The mesh has boundary loops, or the output would exceed \
             the memory budget or 31-bit ids."
        )
    };
}

macro_rules! sized_doc {
    ($summary:literal, $counts:literal, $n:literal) => {
        concat!(
            $summary,
            "\n\nCounts from the input's V, E, F (all chosen): ",
            $counts,
            "; genus, Euler characteristic and components are kept. Any closed mesh \
             (self-loops, two-gons, point-spheres, any genus).\n\n\
             Parameters\n----------\nn : int or None, default None\n    ",
            $n,
            " (>= 1); None for all.\n\n\
             Returns\n-------\nMesh\n\n\
             Raises\n------\nMeshError\n    ``n`` < 1, the mesh has boundary loops, or the output would \
             exceed the memory budget or 31-bit ids."
        )
    };
}

plain_op!(ambo, Op::Ambo, doc!("Ambo (Conway ``a``, rectify): a vertex at every edge midpoint, a face inside every face and one around every vertex.", "V' = E, E' = 2E, F' = F + V"));
sized_op!(truncate, Op::Truncate, sized_doc!("Truncate (Conway ``t``, ``tN`` = ``dkNd``): cut every vertex (or the N-valent ones) off.", "V' = 2E, E' = 3E, F' = F + V", "Truncate only the vertices of this valence"));
sized_op!(kis, Op::Kis, sized_doc!("Kis (Conway ``k``, ``kN``): a pyramid on every face (or on the N-sided ones), apex over the centroid at 0.1 of the face's size along its normal.", "V' = V + F, E' = 3E, F' = 2E", "Raise only the faces with this many corners"));
plain_op!(join, Op::Join, doc!("Join (Conway ``j`` = ``da``): one quad per edge.", "V' = V + F, E' = 2E, F' = E"));
plain_op!(expand, Op::Expand, doc!("Expand (Conway ``e`` = ``aa``, cantellate): faces pulled apart, a quad per edge, a face per vertex.", "V' = 2E, E' = 4E, F' = F + V + E"));
plain_op!(ortho, Op::Ortho, doc!("Ortho (Conway ``o`` = ``de``): every n-gon into n quads.", "V' = V + F + E, E' = 4E, F' = 2E"));
plain_op!(gyro, Op::Gyro, doc!("Gyro (Conway ``g``): every half-edge becomes a pentagon (face centre, two edge points at 1/3, the next vertex), twisted counter-clockwise seen from outside on every face of every genus; ``reflect`` gives the other hand.", "V' = V + F + 2E, E' = 5E, F' = 2E"));
plain_op!(snub, Op::Snub, doc!("Snub (Conway ``s`` = ``dg``): the dual of gyro; chiral like it.", "V' = 2E, E' = 5E, F' = F + V + 2E"));
plain_op!(bevel, Op::Bevel, doc!("Bevel (Conway ``b`` = ``ta``, omnitruncate).", "V' = 4E, E' = 6E, F' = F + V + E"));
plain_op!(meta, Op::Meta, doc!("Meta (Conway ``m`` = ``kj``): the dual of bevel, 4E triangles.", "V' = V + F + E, E' = 6E, F' = 4E"));
sized_op!(needle, Op::Needle, sized_doc!("Needle (Conway ``n``, ``nN`` = ``kNd``): kis of the dual, 2E triangles.", "V' = V + F, E' = 3E, F' = 2E", "Act only at the vertices of this valence (the dual's faces of this size)"));
sized_op!(zip, Op::Zip, sized_doc!("Zip (Conway ``z``, ``zN`` = ``dkN``): the dual of kis.", "V' = 2E, E' = 3E, F' = F + V", "Act only on the faces with this many corners"));
plain_op!(chamfer, Op::Chamfer, doc!("Chamfer (Conway ``c``): every face shrunk to a copy a third of the way towards its centroid, every edge replaced by a hexagon; the input vertices stay.", "V' = V + 2E, E' = 4E, F' = F + E"));
plain_op!(conway_subdivide, Op::Subdivide, doc!("Conway subdivide (``u`` = ``dcd``): ambo keeping the input vertices, a triangle at every corner.", "V' = V + E, E' = 4E, F' = F + 2E"));
plain_op!(whirl, Op::Whirl, doc!("Whirl (Conway ``w``): two hexagons per edge around a twisted, shrunk copy of every face; chiral like gyro.", "V' = V + 4E, E' = 7E, F' = F + 2E"));
plain_op!(volute, Op::Volute, doc!("Volute (Conway ``v`` = ``dwd``): the dual of whirl; chiral.", "V' = V + 2E, E' = 7E, F' = F + 4E"));
plain_op!(propellor, Op::Propellor, doc!("Propellor (Conway ``p``): a twisted copy of every face through the edge points at 1/3, a quad per half-edge; chiral like gyro.", "V' = V + 2E, E' = 5E, F' = F + 2E"));
plain_op!(quinto, Op::Quinto, doc!("Quinto (Conway ``q``): a pentagon at every corner around a smaller copy of every face.", "V' = V + 3E, E' = 6E, F' = F + 2E"));
sized_op!(loft, Op::Loft, sized_doc!("Loft (Conway ``l``, ``lN``): a copy of every face (or of the N-sided ones) inset halfway to its centroid, joined by quads.", "V' = V + 2E, E' = 5E, F' = F + 2E", "Loft only the faces with this many corners"));
plain_op!(reflect, Op::Reflect, doc!("Reflect (Conway ``r``): the mirror image through the origin, faces reversed so they still face outwards.", "V' = V, E' = E, F' = F"));

#[pymethods]
impl PyMesh {
    /// Applies Conway operators in George Hart's notation to this mesh,
    /// right to left: ``m.conway("tk")`` is ``m.kis().truncate()``.
    ///
    /// Parameters
    /// ----------
    /// notation : str
    ///     Operator letters ``d a t k j e o g s b m n z c u w v p q l r``,
    ///     ``t k n z l`` optionally followed by a number (``t5``), and no
    ///     seed letter. See :func:`topomesh.conway`.
    ///
    /// Returns
    /// -------
    /// Mesh
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     A parse error (naming the position and the character), a seed
    ///     letter in ``notation``, boundary loops, or an output beyond the
    ///     memory budget.
    fn conway(&self, py: Python<'_>, notation: &str) -> PyResult<PyMesh> {
        let m = &self.inner;
        let r = run_interruptible(py, || super::data::build_traced(!self.data.face.is_empty(), m, || conway::conway(notation, Some(m))))?;
        super::data::inherited(py, &self.data, "conway", m, r.0, r.1)
    }

    /// Hart's canonical form: planar faces, every edge tangent to the unit
    /// sphere, the tangent points centred on the origin. Only positions
    /// move (first centred and scaled to a mean edge distance of 1).
    ///
    /// The iteration is polyhedronisme's (tangentify, recenter, planarize,
    /// step 0.1). It converges on convex genus-0 polyhedra (the canonical
    /// form exists there); elsewhere the residual says how far it got.
    ///
    /// Parameters
    /// ----------
    /// iterations : int, default 200
    ///     At most this many steps (>= 0).
    /// tol : float, default 1e-8
    ///     Stop once no vertex moves more than this in a step, in [0, 1]
    ///     (positions are scaled to unit size first).
    ///
    /// Returns
    /// -------
    /// mesh : Mesh
    /// residual : float
    ///     The largest of: an edge line's distance from the unit sphere
    ///     (``|1 - d|``), a corner's distance from its face's mean plane,
    ///     the norm of the mean edge tangent point. 0 for a canonical
    ///     polyhedron.
    ///
    /// Raises
    /// ------
    /// MeshError
    ///     ``iterations`` or ``tol`` out of range, boundary loops, or the
    ///     iteration diverging (positions no longer finite).
    #[pyo3(signature = (iterations = 200, tol = 1e-8))]
    fn canonicalize(&self, py: Python<'_>, #[pyo3(from_py_with = big_int)] iterations: i128, tol: f64) -> PyResult<(PyMesh, f64)> {
        let it = usize_in("canonicalize", "iterations", iterations, 0, usize::MAX)?;
        let (m, r) = run_interruptible(py, || canonical::canonicalize(&self.inner, it, tol))?;
        // only positions move: every attribute and crease stays valid
        Ok((PyMesh::with_data(m, self.data.clone_ref(py)), r))
    }
}

/// Builds a polyhedron from George Hart's Conway notation, read right to
/// left: ``conway("dtkC")`` is the dual of the truncated kis cube.
///
/// Seeds (the rightmost letter): ``T C O D I`` (the Platonic solids of
/// :func:`tetrahedron` … :func:`icosahedron`), ``P<n>`` prism, ``A<n>``
/// antiprism, ``Y<n>`` pyramid (n >= 3). Operators: ``d`` dual, ``a``
/// ambo, ``t`` truncate, ``k`` kis, ``j`` join, ``e`` expand, ``o`` ortho,
/// ``g`` gyro, ``s`` snub, ``b`` bevel, ``m`` meta, ``n`` needle, ``z`` zip,
/// ``c`` chamfer, ``u`` subdivide, ``w`` whirl, ``v`` volute, ``p``
/// propellor, ``q`` quinto, ``l`` loft, ``r`` reflect; ``t k n z l`` take a
/// number (``t5``: truncate the 5-valent vertices only, ``k3``: kis the
/// triangles only). Sources: Hart, "Conway Notation for Polyhedra";
/// polyhedronisme. See :func:`conway_operators` and docs/schemes/conway.md.
///
/// Parameters
/// ----------
/// notation : str
///     The notation; without a seed letter when ``seed`` is given.
/// seed : Mesh or None, default None
///     Any closed mesh to start from instead of a seed letter; the result
///     is ``seed.conway(notation)``, face data included.
///
/// Returns
/// -------
/// Mesh
///
/// Raises
/// ------
/// MeshError
///     A parse error naming the position and the character, no seed or two
///     seeds, a seed mesh with boundary loops, or an output beyond the
///     memory budget or 31-bit ids (checked for the whole chain first).
#[pyfunction]
#[pyo3(name = "conway", signature = (notation, seed = None))]
fn conway_fn(py: Python<'_>, notation: &str, seed: Option<PyRef<'_, PyMesh>>) -> PyResult<PyMesh> {
    match seed {
        // a seed mesh's face data (material ids …) and vertex data follow as in `Mesh.conway`
        Some(s) => s.conway(py, notation),
        None => run_interruptible(py, || conway::conway(notation, None)).map(PyMesh::wrap),
    }
}

/// The table of Conway operators.
///
/// Returns
/// -------
/// list of dict
///     One dict per operator: ``letter``, ``name``, ``method`` (the
///     ``Mesh`` method), ``definition`` (by other operators, ``""`` for a
///     primitive), ``takes_n`` (bool), ``counts`` (V', E', F' as
///     formulas in the input's V, E, F).
#[pyfunction]
fn conway_operators(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    conway::OPERATORS
        .iter()
        .map(|o| {
            let d = PyDict::new(py);
            d.set_item("letter", o.letter.to_string())?;
            d.set_item("name", o.name)?;
            d.set_item("method", o.method)?;
            d.set_item("definition", o.definition)?;
            d.set_item("takes_n", o.takes_n)?;
            d.set_item("counts", (o.counts[0], o.counts[1], o.counts[2]))?;
            Ok(d)
        })
        .collect()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(conway_fn, m)?)?;
    m.add_function(wrap_pyfunction!(conway_operators, m)?)?;
    Ok(())
}
