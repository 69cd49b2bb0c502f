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

/// A number as error messages show it: as written (`0.5`, `-1`, `1000`)
/// between 1e-5 and 1e16 in magnitude, else in exponent form (`1e300`,
/// `2.2250738585072014e-308`), where the plain form has hundreds of digits.
pub(crate) fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `[lo, hi]` as an error message gives an argument's range: the smallest
/// positive float as the lower bound reads `(0, hi]`. (The Python layer's
/// argument checks use it; the core only tests it.)
#[cfg_attr(not(feature = "python"), allow(dead_code))]
pub(crate) fn range(lo: f64, hi: f64) -> String {
    if lo == f64::MIN_POSITIVE { format!("(0, {}]", num(hi)) } else { format!("[{}, {}]", num(lo), num(hi)) }
}

#[cfg(test)]
mod tests {
    use super::{num, range};

    #[test]
    fn numbers_in_messages_stay_short() {
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(-1.0), "-1");
        assert_eq!(num(1e15), "1000000000000000");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(-2.5e-300), "-2.5e-300");
        assert_eq!(num(f64::MIN_POSITIVE), "2.2250738585072014e-308");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::NEG_INFINITY), "-inf");
        assert_eq!(num(0.0), "0");
        assert!(num(f64::MAX).len() < 30, "{}", num(f64::MAX));
        assert_eq!(range(f64::MIN_POSITIVE, 1e15), "(0, 1000000000000000]");
        assert_eq!(range(0.0, 1.0), "[0, 1]");
        assert_eq!(range(-1e300, f64::MAX), "[-1e300, 1.7976931348623157e308]");
    }
}
