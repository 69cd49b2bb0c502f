"""STL reading (ASCII and binary) into welded vertices and triangles.

STL stores every triangle with its own three corners; :func:`read_stl`
welds corners with exactly equal coordinates (the same float written
twice), which is what every STL writer produces for a shared vertex. For
near-coincident corners, orientation or non-manifold fixes, pass the result
through :func:`topomesh.repair`."""

from __future__ import annotations

import os
import re

import numpy as np
import numpy.typing as npt

from topomesh._core import Mesh, MeshError

# binary layout: 80-byte header, uint32 count, then per triangle a normal,
# three vertices (float32 x 3 each) and a 2-byte attribute count
_RECORD = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
_VERTEX = re.compile(rb"^[ \t]*vertex[ \t]+(\S+)[ \t]+(\S+)[ \t]+(\S+)[ \t]*\r?$", re.MULTILINE)


def read_stl(path: str | os.PathLike[str]) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Read an STL file.

    Binary when the file is exactly ``84 + 50·n`` bytes for the triangle
    count ``n`` in its header; otherwise ASCII (it must start with ``solid``).

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    vertices : float64 array (V, 3)
        Distinct corner positions, in order of first appearance.
    triangles : int64 array (T, 3)
        Corner indices, in file order (orientation as stored).

    Raises
    ------
    MeshError
        Naming the path (and for ASCII the line): unreadable file, truncated
        binary data, an ASCII file that is not STL, a malformed ``vertex``
        line, a facet without exactly three vertices, a non-finite coordinate.
    """
    name = os.fspath(path)
    try:
        with open(name, "rb") as fh:
            data = fh.read()
    except OSError as e:
        raise MeshError(f"{name}: cannot read STL file ({e.strerror or e})") from e
    if len(data) >= 84:
        n = int.from_bytes(data[80:84], "little")
        if len(data) == 84 + 50 * n:
            corners = np.frombuffer(data, dtype=_RECORD, count=n, offset=84)["corners"].reshape(-1, 3)
            return _weld(name, corners.astype(np.float64), None)
    if not data.lstrip().lower().startswith(b"solid"):
        raise MeshError(
            f"{name}: not an STL file: neither binary ({len(data)} bytes is not 84 + 50 x the triangle count"
            " in the header) nor ASCII (does not start with 'solid')"
        )
    return _read_ascii(name, data)


def _line_of(data: bytes, offset: int) -> int:
    return data.count(b"\n", 0, offset) + 1


def _read_ascii(name: str, data: bytes) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    matches = list(_VERTEX.finditer(data))
    # every line that starts with "vertex" must have matched the pattern
    n_vertex_lines = len(re.findall(rb"^[ \t]*vertex\b", data, re.MULTILINE))
    if n_vertex_lines != len(matches):
        starts = {m.start() for m in matches}
        for m in re.finditer(rb"^[ \t]*vertex\b.*$", data, re.MULTILINE):
            if m.start() not in starts:
                text = m.group().decode(errors="replace").strip()
                raise MeshError(f"{name}: line {_line_of(data, m.start())}: malformed vertex line {text!r} (expected 'vertex x y z')")
    try:
        corners = np.array([m.groups() for m in matches], dtype=np.float64).reshape(-1, 3)
    except ValueError:
        for m in matches:
            try:
                [float(x) for x in m.groups()]
            except ValueError:
                text = m.group().decode(errors="replace").strip()
                raise MeshError(f"{name}: line {_line_of(data, m.start())}: vertex coordinates {text!r} are not numbers") from None
        raise
    # three vertices per facet: count them between facet ... endfacet
    facets = [m.start() for m in re.finditer(rb"^[ \t]*endfacet\b", data, re.MULTILINE)]
    if len(corners) != 3 * len(facets):
        # find the first facet with a wrong count
        pos = np.array([m.start() for m in matches])
        prev = 0
        for k, end in enumerate(facets):
            cnt = int(np.count_nonzero((pos >= prev) & (pos < end)))
            if cnt != 3:
                raise MeshError(f"{name}: line {_line_of(data, end)}: facet {k} has {cnt} vertices, STL facets have 3")
            prev = end
        raise MeshError(f"{name}: {len(corners)} vertex lines for {len(facets)} facets (3 per facet expected)")
    lines = None
    if not np.isfinite(corners).all():
        bad = int(np.flatnonzero(~np.isfinite(corners).all(axis=1))[0])
        lines = _line_of(data, matches[bad].start())
    return _weld(name, corners, lines)


def _weld(name: str, corners: npt.NDArray[np.float64], bad_line: int | None) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    finite = np.isfinite(corners).all(axis=1)
    if not finite.all():
        where = f"line {bad_line}" if bad_line is not None else f"triangle {int(np.flatnonzero(~finite)[0]) // 3}"
        raise MeshError(f"{name}: {where}: non-finite vertex coordinate")
    # the core's exact weld (a parallel hash sort; -0.0 and 0.0 are the same
    # point), numbering distinct points in order of first appearance
    uniq, index = Mesh._weld(corners, 0.0)
    return uniq, index.reshape(-1, 3)
