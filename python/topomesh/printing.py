"""Printability: is a mesh ready for a 3D printer?

:func:`printable` (also :meth:`Mesh.printable`) runs three checks on the
triangles a printer would get (:meth:`Mesh.triangulate`, as written to STL
and 3MF by :func:`topomesh.io.save`):

* **watertight**: no boundary loops (hole faces), every triangle side meets
  exactly one opposite side, and the triangles around every vertex form one
  fan (self-loops, one- and two-gons and vertices repeated in a face pinch
  the triangle mesh: sheets that touch at a point, which print as a zero
  width joint or not at all);
* **no self-intersections**: the exact crossing check of
  :meth:`Mesh.self_intersections` (``src/geometry/crossing/``), reported as
  face pairs;
* **walls at least** ``min_thickness``: :meth:`Mesh.wall_thickness` casts a
  ray from every triangle's centroid along the inward normal
  (``src/geometry/thickness.rs``); faces whose wall is thinner are listed.

Face indices are the mesh's face ids, as in :attr:`Mesh.face_centroids` and
``Mesh.triangles(return_faces=True)`` (the rows of :attr:`Mesh.face_sizes`
when the mesh has no hole faces).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from topomesh._core import Mesh, MeshError

__all__ = ["PrintReport", "printable"]


@dataclass(frozen=True, repr=False, eq=False)
class PrintReport:
    """What :func:`printable` found. ``ok`` is True when the mesh is
    watertight, free of self-intersections and nowhere thinner than
    ``min_thickness``.

    Attributes
    ----------
    ok : bool
    min_thickness : float
        The threshold checked.
    watertight : bool
        No boundary loops, every triangle side paired with one opposite
        side, no pinched vertex.
    open_boundaries : int
        Boundary loops (hole faces) of the mesh.
    unpaired_sides : int
        Triangle sides without exactly one opposite side.
    pinched_vertices : int
        Vertices where triangle fans touch at a point (counted when every
        side is paired).
    self_intersections : int64 array (K, 2)
        Face pairs ``(f, g)``, ``f <= g``, sorted, with triangles that cross
        (``f == g``: a face's own triangles cross).
    n_crossing_triangle_pairs : int
        Crossing triangle pairs behind them (the count of
        :meth:`Mesh.self_intersections`).
    thin_faces : int64 array
        Faces whose wall thickness is below ``min_thickness``, ascending.
    min_thickness_found : float
        The smallest wall thickness measured (``inf`` if every ray left the
        surface, NaN if there was no triangle).
    thinnest_face : int or None
        A face where it was measured.
    thickness : float64 array (F,)
        :meth:`Mesh.wall_thickness`.
    """

    ok: bool
    min_thickness: float
    watertight: bool
    open_boundaries: int
    unpaired_sides: int
    pinched_vertices: int
    self_intersections: npt.NDArray[np.int64] = field(repr=False)
    n_crossing_triangle_pairs: int
    thin_faces: npt.NDArray[np.int64] = field(repr=False)
    min_thickness_found: float
    thinnest_face: int | None
    thickness: npt.NDArray[np.float64] = field(repr=False)

    @property
    def n_self_intersections(self) -> int:
        """Face pairs in :attr:`self_intersections`."""
        return len(self.self_intersections)

    def __repr__(self) -> str:
        return (
            f"PrintReport(ok={self.ok}, min_thickness={self.min_thickness:g}, watertight={self.watertight}, "
            f"self_intersections={self.n_self_intersections}, thin_faces={len(self.thin_faces)}, "
            f"min_thickness_found={self.min_thickness_found:.6g})"
        )

    def __str__(self) -> str:
        def faces(a: np.ndarray, k: int = 8) -> str:
            shown = ", ".join(str(x) for x in a[:k].tolist())
            return shown + (f", ... ({len(a) - k} more)" if len(a) > k else "")

        verdict = "printable" if self.ok else "NOT printable"
        lines = [f"{verdict} with walls of at least {self.min_thickness:g}"]
        if self.watertight:
            lines.append("  closed: yes (watertight triangles)")
        else:
            lines.append(
                f"  closed: NO ({self.open_boundaries} boundary loops, {self.unpaired_sides} triangle sides without one "
                f"opposite side, {self.pinched_vertices} pinched vertices)"
            )
        if self.n_self_intersections:
            pairs = ", ".join(f"{f}-{g}" for f, g in self.self_intersections[:6].tolist())
            more = f", ... ({self.n_self_intersections - 6} more)" if self.n_self_intersections > 6 else ""
            lines.append(
                f"  self-intersections: {self.n_self_intersections} face pairs "
                f"({self.n_crossing_triangle_pairs} triangle pairs): {pairs}{more}"
            )
        else:
            lines.append("  self-intersections: none")
        where = f" (face {self.thinnest_face})" if self.thinnest_face is not None else ""
        lines.append(f"  thinnest wall: {self.min_thickness_found:.6g}{where}")
        if len(self.thin_faces):
            lines.append(f"  thin faces (< {self.min_thickness:g}): {len(self.thin_faces)}: {faces(self.thin_faces)}")
        else:
            lines.append(f"  thin faces (< {self.min_thickness:g}): none")
        return "\n".join(lines)


def printable(mesh: Mesh, min_thickness: float) -> PrintReport:
    """Check ``mesh`` for 3D printing with walls of at least ``min_thickness``.

    Parameters
    ----------
    mesh : Mesh
    min_thickness : float
        The thinnest wall the printer makes, in the mesh's units (STL has
        none; 3MF files say millimetres); finite and > 0.

    Returns
    -------
    PrintReport
        See the module docs; ``print(report)`` gives a summary.

    Raises
    ------
    MeshError
        ``min_thickness`` not a finite number > 0.

    Examples
    --------
    >>> import topomesh
    >>> r = topomesh.menger_sponge(2).printable(0.25)   # cells of 2/9
    >>> r.ok, len(r.thin_faces) > 0
    (False, True)
    """
    if not isinstance(mesh, Mesh):
        raise MeshError(f"printable: expected a topomesh.Mesh, got {type(mesh).__name__}")
    try:
        t = float(min_thickness)
    except (TypeError, ValueError):
        raise MeshError(f"printable: min_thickness = {min_thickness!r} must be a finite number > 0") from None
    if not (math.isfinite(t) and t > 0):
        raise MeshError(f"printable: min_thickness = {t} is out of range; it must be a finite number > 0")
    thickness, tri_pairs, tri_face, (sides, pinched) = mesh._print_check()
    thickness.flags.writeable = False
    if len(tri_pairs):
        fp = np.sort(tri_face[tri_pairs], axis=1)
        face_pairs = np.unique(fp, axis=0)
    else:
        face_pairs = np.zeros((0, 2), dtype=np.int64)
    measured = ~np.isnan(thickness)
    thin = np.flatnonzero(measured & (thickness < t)).astype(np.int64)
    if measured.any():
        k = int(np.nanargmin(thickness))
        found, thinnest = float(thickness[k]), k
    else:
        found, thinnest = math.nan, None
    holes = mesh.n_holes
    watertight = sides == 0 and pinched == 0 and holes == 0
    return PrintReport(
        ok=bool(watertight and len(face_pairs) == 0 and len(thin) == 0),
        min_thickness=t,
        watertight=watertight,
        open_boundaries=holes,
        unpaired_sides=sides,
        pinched_vertices=pinched,
        self_intersections=face_pairs,
        n_crossing_triangle_pairs=len(tri_pairs),
        thin_faces=thin,
        min_thickness_found=found,
        thinnest_face=thinnest,
        thickness=thickness,
    )
