//! The one error type of the core. Every fallible public function returns
//! `Result<_, MeshError>`; the Python layer maps it to `topomesh.MeshError`
//! (a `ValueError`). Messages name the offending element (face, vertex, edge).

use std::fmt;

/// Everything that can go wrong in topomesh, with the element it concerns.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshError {
    /// A face refers to a vertex index outside `0..n_vertices`.
    IndexOutOfRange { face: usize, position: usize, index: i64, n_vertices: usize },
    /// A face with no vertices.
    EmptyFace { face: usize },
    /// An edge used by more than two face sides.
    NonManifoldEdge { a: usize, b: usize, faces: Vec<usize> },
    /// Two faces traverse a shared edge in the same direction.
    InconsistentOrientation { a: usize, b: usize, face1: usize, face2: usize },
    /// The faces around a vertex do not form one disk (a pinch or a fan of several umbrellas).
    NonManifoldVertex { vertex: usize },
    /// An edge with a face on one side only, and open meshes were refused.
    Boundary { a: usize, b: usize, face: usize },
    /// A coordinate is NaN or infinite.
    NonFinite { vertex: usize },
    /// An argument is malformed (shape, dtype, range, unknown option).
    InvalidArgument(String),
    /// An operator's precondition does not hold (e.g. DeleteVertex on a vertex with edges).
    Precondition(String),
    /// `validate()` found a broken structural invariant.
    Invariant(String),
    /// Reading or writing a file failed.
    Io(String),
    /// A call would need more memory than the budget (`crate::budget`) allows,
    /// or a large allocation failed; the message names the call, level and bytes.
    Memory(String),
    /// The call was cancelled through `crate::cancel` (Ctrl-C in Python).
    Interrupted,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use MeshError::*;
        match self {
            IndexOutOfRange { face, position, index, n_vertices } => write!(
                f,
                "face {face}: vertex index {index} at position {position} is out of range (mesh has {n_vertices} vertices)"
            ),
            EmptyFace { face } => write!(f, "face {face} is empty"),
            NonManifoldEdge { a, b, faces } => write!(
                f,
                "edge ({a}, {b}) is used by {} face sides (faces {:?}); a manifold edge has exactly two",
                faces.len(),
                faces
            ),
            InconsistentOrientation { a, b, face1, face2 } => write!(
                f,
                "faces {face1} and {face2} are inconsistently oriented: both traverse edge ({a}, {b}) in the same direction"
            ),
            NonManifoldVertex { vertex } => write!(
                f,
                "vertex {vertex} is non-manifold: its faces do not form a single disk around it"
            ),
            Boundary { a, b, face } => write!(
                f,
                "edge ({a}, {b}) of face {face} is a boundary edge (no face on its other side) and open meshes were refused \
                 (boundaries=\"refuse\" or close_boundaries=False); the default boundaries=\"keep\" keeps the mesh open"
            ),
            NonFinite { vertex } => write!(f, "vertex {vertex} has a NaN or infinite coordinate"),
            InvalidArgument(m) | Precondition(m) | Invariant(m) | Io(m) | Memory(m) => f.write_str(m),
            Interrupted => f.write_str("interrupted"),
        }
    }
}

impl std::error::Error for MeshError {}

pub type Result<T> = std::result::Result<T, MeshError>;
