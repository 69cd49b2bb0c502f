"""Test-only OpenSubdiv reference (tests/osd/reference.py) and the helpers that match its output.

``available()`` says why the reference cannot run here (or None); ``refine()`` / ``refine_many()``
refine with OpenSubdiv; ``match_points``, ``same_points``, ``match_faces`` and ``match_corners``
compare up to element order; ``tests.osd.fixtures`` holds the reference meshes.
"""

from tests.osd.match import assert_same_mesh, match_corners, match_faces, match_points, same_points
from tests.osd.reference import Refined, available, refine, refine_many, request

__all__ = [
    "Refined", "assert_same_mesh", "available", "match_corners", "match_faces", "match_points", "refine", "refine_many",
    "request", "same_points",
]
