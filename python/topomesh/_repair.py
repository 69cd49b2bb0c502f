"""The repair path for polygon soups and sloppy meshes: :func:`repair` and
its :class:`RepairReport`. The work is done in the Rust core
(``src/repair/``); this module only shapes the result."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, Sequence

import numpy.typing as npt

from topomesh._core import Mesh, MeshError

# the counts, in the order the steps run, with how __str__ names them
_STEPS = {
    "vertices_merged": "vertices merged",
    "degenerate_faces_dropped": "degenerate faces dropped",
    "duplicate_faces_dropped": "duplicate faces dropped",
    "non_manifold_edges_split": "non-manifold edges split (faces beyond the first consistent pair detached)",
    "faces_flipped": "faces flipped to agree with their component",
    "components_flipped": "closed components flipped outward",
    "non_orientable_edges_cut": "edges cut to orient a non-orientable piece",
    "pinched_vertices_split": "pinched vertices split (extra vertices made)",
    "unreferenced_vertices_removed": "unreferenced vertices removed",
    "boundary_loops": "boundary loops left",
}


@dataclass(frozen=True)
class RepairReport:
    """What :func:`repair` changed, step by step.

    Attributes
    ----------
    tolerance : float
        The absolute merge tolerance used.
    vertices_merged : int
        Input vertices merged into an earlier one (input V minus merged V).
    degenerate_faces_dropped : int
        Faces with fewer than three distinct corners, or thinner than the
        tolerance (zero area when it is 0).
    duplicate_faces_dropped : int
        Faces repeating an earlier one (same vertex cycle up to rotation and direction).
    non_manifold_edges_split : int
        Edges that had more than two faces: faces beyond the consistently
        oriented pairs were detached from them (their vertices split).
    faces_flipped : int
        Faces reversed to agree with the majority of their component.
    components_flipped : int
        Closed components reversed because their signed volume was negative.
    non_orientable_edges_cut : int
        Edges cut where two faces could not be oriented alike (Möbius bands).
    pinched_vertices_split : int
        Extra vertices made to give every umbrella (fan of faces) its own vertex.
    unreferenced_vertices_removed : int
        Vertices (after merging) that no remaining face uses.
    boundary_loops : int
        Boundary loops in the result (kept open, as hole faces).
    """

    tolerance: float
    vertices_merged: int = 0
    degenerate_faces_dropped: int = 0
    duplicate_faces_dropped: int = 0
    non_manifold_edges_split: int = 0
    faces_flipped: int = 0
    components_flipped: int = 0
    non_orientable_edges_cut: int = 0
    pinched_vertices_split: int = 0
    unreferenced_vertices_removed: int = 0
    boundary_loops: int = 0

    @property
    def changed(self) -> bool:
        """Whether any step changed the input (boundary loops are not a change)."""
        return any(getattr(self, f.name) for f in fields(self) if f.name not in ("tolerance", "boundary_loops"))

    def __str__(self) -> str:
        lines = [f"{getattr(self, k)} {label}" for k, label in _STEPS.items() if getattr(self, k)]
        head = f"repair (tolerance {self.tolerance:.3g}): " + ("changed" if self.changed else "nothing to change")
        return "\n".join([head, *("  " + line for line in lines)])


def _report(counts: dict[str, Any]) -> RepairReport:
    return RepairReport(**counts)


def _tolerance(tolerance: Any) -> float | None:
    """``tolerance`` as a float (range checked by the core), or a MeshError naming it."""
    if tolerance is None:
        return None
    try:
        return float(tolerance)
    except (TypeError, ValueError):
        raise MeshError(f"repair: tolerance = {tolerance!r} is not a number (expected a finite float >= 0 or None)") from None


def repair(
    vertices: npt.ArrayLike,
    faces: Sequence[Sequence[int]] | npt.ArrayLike,
    *,
    tolerance: float | None = None,
    close_boundaries: bool | None = None,
    boundaries: str = "keep",
) -> tuple[Mesh, RepairReport]:
    """Repair a polygon soup or a sloppy mesh and build it.

    In order: merge vertices within ``tolerance``; drop degenerate faces
    (fewer than three distinct corners, or thinner than the tolerance) and
    duplicate faces (same cycle up to rotation and direction); on edges with
    more than two faces keep the consistently oriented pairs (in face order)
    and detach the rest; orient every face-connected component consistently
    (the majority of its faces wins) and outward (closed components with
    negative signed volume are reversed); split pinched vertices into one
    vertex per fan of faces; remove unreferenced vertices. Linear (one sort).

    Parameters
    ----------
    vertices : array_like, shape (V, 3)
        Real coordinates (converted to float64). Not modified.
    faces : sequence of sequences of int, or int array of shape (F, k)
        As for :meth:`Mesh.from_polygons`; orientation need not be consistent.
    tolerance : float, optional
        Merge distance (Euclidean). Default ``1e-9`` times the bounding-box
        diagonal; ``0`` merges exactly equal positions only. A face whose
        height is below it is degenerate.
    close_boundaries : bool or None, default None
        Legacy spelling of ``boundaries``: ``True`` keeps (the default),
        ``False`` refuses.
    boundaries : {"keep", "refuse"}, default "keep"
        ``"keep"``: boundary loops left after the repair stay open (stored as
        hole faces, counted in ``report.boundary_loops``); ``"refuse"``: a
        remaining boundary raises :class:`MeshError` naming an edge.

    Returns
    -------
    mesh : Mesh
        Vertices in the input order of their lowest merged vertex (split
        copies at the end), faces in input order (reversed ones reversed).
    report : RepairReport
        What each step changed; ``print(report)`` lists the non-zero counts.

    Raises
    ------
    MeshError
        Index out of range, empty face, non-finite coordinate, negative or
        non-finite ``tolerance``, an unknown ``boundaries`` value, or (when
        boundaries are refused) a boundary left.
    """
    mesh, counts = Mesh._repair(vertices, faces, _tolerance(tolerance), close_boundaries, boundaries)
    return mesh, _report(counts)


def repair_flat(
    vertices: npt.ArrayLike,
    face_sizes: npt.ArrayLike,
    face_indices: npt.ArrayLike,
    *,
    tolerance: float | None = None,
    close_boundaries: bool | None = None,
    boundaries: str = "keep",
) -> tuple[Mesh, RepairReport]:
    """:func:`repair` on faces given as ``face_sizes`` (F,) and flat ``face_indices``."""
    kw = (_tolerance(tolerance), close_boundaries, boundaries)
    mesh, counts = Mesh._repair_flat(vertices, face_sizes, face_indices, *kw)
    return mesh, _report(counts)
