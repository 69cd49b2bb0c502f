"""Subdivision curves and surfaces as attractors of iterated function systems.

Schaefer, Levin, Goldman, *Subdivision Schemes and Attractors* (SGP 2005).
A stationary subdivision scheme with control points ``P`` and square
subdivision blocks ``S_i`` is the IFS ``f_i(X) = X P^-1 S_i P`` (eq. 2) in a
lifted homogeneous space; its attractor is the subdivision limit, whatever
compact set the iteration starts from. The blocks are derived from each
scheme's rules (stencils), never typed in.

Curves::

    from topomesh import ifs
    f = ifs.cubic_bspline([[0, 0], [1, 2], [2.5, 2.2], [3.5, 0.5], [5, 1.5]])
    f.polyline(10)              # (1025, 2) ordered points on the curve
    f.iterate([[7, -3]], 12)    # images of a start point, (4096, 1, 2)
    f.chaos_game(10**6)         # (1000000, 2)

Surfaces (regular case) return meshes: ``ifs.loop(points).mesh(4)``.
Fractals with control points (section 4): :func:`koch`, :func:`gasket`,
:func:`from_affine_with_control`.

All constructors return an :class:`IFS`; invalid input (not an affine basis,
a non-contractive map, wrong point counts) raises :class:`topomesh.MeshError`.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import numpy.typing as npt

from topomesh._core import (
    IFS,
    ifs_bezier,
    ifs_bspline,
    ifs_curve,
    ifs_curve_stencils,
    ifs_curve_subdivide,
    ifs_from_affine,
    ifs_from_affine_with_control,
    ifs_from_subdivision,
    ifs_gasket,
    ifs_gasket_reference,
    ifs_hex_lattice,
    ifs_koch,
    ifs_koch_reference,
    ifs_koch_standard,
    ifs_surface,
    ifs_surface_subdivide,
)

__all__ = [
    "IFS",
    "bezier",
    "bicubic",
    "box_counting_dimension",
    "bspline",
    "chaikin",
    "cubic_bspline",
    "curve",
    "curve_stencils",
    "endpoint_bspline",
    "four_point",
    "from_affine",
    "from_affine_with_control",
    "from_subdivision",
    "gasket",
    "gasket_reference",
    "hex_lattice",
    "koch",
    "koch_reference",
    "koch_standard",
    "loop",
    "sqrt3",
    "subdivide_curve",
    "subdivide_surface",
]

from_subdivision = ifs_from_subdivision
from_affine = ifs_from_affine
from_affine_with_control = ifs_from_affine_with_control
bezier = ifs_bezier
bspline = ifs_bspline
hex_lattice = ifs_hex_lattice
koch_standard = ifs_koch_standard


def curve_stencils(scheme: str) -> list[list[tuple[int, float]]]:
    """Stencils of ``"cubic_bspline"`` (eq. 4), ``"four_point"`` or ``"chaikin"``.

    ``stencils[r]`` lists ``(offset, weight)``: ``p'[2 i + r] = sum w p[i + offset]``.
    """
    return ifs_curve_stencils(scheme)


def curve(
    control_points: npt.ArrayLike,
    stencils: Sequence[Sequence[tuple[int, float]]],
    arity: int = 2,
    name: str = "curve",
) -> IFS:
    """IFS of any uniform stationary curve scheme given by its rules.

    The ``arity`` blocks are the self-similar sub-polygons of the refined
    polygon, found from the stencils' support and centroids.
    """
    return ifs_curve(control_points, [list(s) for s in stencils], arity, name)


def cubic_bspline(control_points: npt.ArrayLike) -> IFS:
    """Uniform cubic B-spline (eq. 4); 5 points give the paper's two 5x5 blocks."""
    return ifs_curve(control_points, ifs_curve_stencils("cubic_bspline"), 2, "cubic_bspline")


def four_point(control_points: npt.ArrayLike) -> IFS:
    """Interpolatory four-point scheme (section 2.3); 7 points give 7x7 blocks."""
    return ifs_curve(control_points, ifs_curve_stencils("four_point"), 2, "four_point")


def chaikin(control_points: npt.ArrayLike) -> IFS:
    """Chaikin's corner cutting (quadratic B-spline)."""
    return ifs_curve(control_points, ifs_curve_stencils("chaikin"), 2, "chaikin")


def endpoint_bspline(control_points: npt.ArrayLike) -> IFS:
    """End-point interpolating cubic B-spline, knots ``0,0,0,1,2,2,2`` (5 points, section 2.1)."""
    return ifs_bspline(control_points, 3, [0, 0, 0, 1, 2, 2, 2], [(0, 1), (1, 2)], "endpoint_bspline")


def subdivide_curve(control_points: npt.ArrayLike, scheme: str, levels: int) -> np.ndarray:
    """Plain subdivision of an open control polygon with a named scheme's rules."""
    return ifs_curve_subdivide(control_points, ifs_curve_stencils(scheme), levels, 2)


def bicubic(control_points: npt.ArrayLike) -> IFS:
    """Bicubic B-spline patch from a 4x4 grid (index ``4 j + i``), 4 maps (section 3.1)."""
    return ifs_surface(control_points, "bicubic")


def loop(control_points: npt.ArrayLike) -> IFS:
    """Three-direction quartic box spline (Loop, regular) on a hexagon, 6 maps (section 3.2).

    ``control_points``: 19 points, one per site of :func:`hex_lattice` ``(2)``, same order.
    """
    return ifs_surface(control_points, "loop")


def sqrt3(control_points: npt.ArrayLike) -> IFS:
    """Kobbelt's sqrt(3) on a hexagon, two steps per level, 19 maps (section 3.3).

    ``control_points``: 61 points on :func:`hex_lattice` ``(4)`` (the two-step stencils reach that far).
    """
    return ifs_surface(control_points, "sqrt3")


def subdivide_surface(control_points: npt.ArrayLike, scheme: str, levels: int) -> tuple[np.ndarray, np.ndarray]:
    """Plain subdivision of a ``"bicubic"``, ``"loop"`` or ``"sqrt3"`` net: ``(points, triangles)``."""
    return ifs_surface_subdivide(control_points, scheme, levels)


def koch_reference() -> np.ndarray:
    """The five natural Koch control points (ends, thirds, apex), ``(5, 2)``."""
    return ifs_koch_reference()


def gasket_reference() -> np.ndarray:
    """The six gasket control points (corners at even indices, edge midpoints between), ``(6, 2)``."""
    return ifs_gasket_reference()


def koch(control_points: npt.ArrayLike | None = None) -> IFS:
    """Koch curve with control points (section 4.1); the reference points by default."""
    return ifs_koch(koch_reference() if control_points is None else control_points)


def gasket(control_points: npt.ArrayLike | None = None) -> IFS:
    """Sierpinski gasket with six control points (section 4.2); reference points by default."""
    return ifs_gasket(gasket_reference() if control_points is None else control_points)


def box_counting_dimension(
    points: npt.ArrayLike, sizes: Sequence[float] | None = None, n_offsets: int = 8, seed: int = 0
) -> float:
    """Box-counting dimension of a point set.

    Counts occupied boxes ``N(eps)`` for each box size (relative to the
    largest bounding-box extent; default ``2**-3 .. 2**-9``), averaged over
    ``n_offsets`` random grid offsets (aligned grids over-count self-similar
    sets), and returns the least-squares slope of ``log N`` against ``log 1/eps``.
    """
    p = np.asarray(points, dtype=np.float64)
    p = p.reshape(-1, p.shape[-1])
    p = p - p.min(axis=0)
    ext = float(p.max())
    if sizes is None:
        sizes = [2.0**-k for k in range(3, 10)]
    rng = np.random.default_rng(seed)
    counts = []
    for s in sizes:
        c = []
        for o in rng.random((n_offsets, p.shape[1])):
            cells = np.floor(p / (s * ext) + o).astype(np.int64)
            key = np.zeros(len(cells), dtype=np.int64)
            for j in range(cells.shape[1]):
                key = key * (int(cells[:, j].max()) + 1) + cells[:, j]
            c.append(len(np.unique(key)))
        counts.append(np.mean(c))
    slope = np.polyfit(np.log(1.0 / np.asarray(sizes)), np.log(counts), 1)[0]
    return float(slope)
