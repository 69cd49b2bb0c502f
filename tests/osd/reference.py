"""OpenSubdiv as a test-only reference, reached through Blender's ``bpy`` in a venv of its own.

``.ci/setup`` creates ``.venv-bpy`` with ``bpy==5.0.1`` (it pins numpy 1.26, so it stays out of
the project's venv); :func:`refine` writes the request to an ``.npz`` file, runs
``tests/osd/worker.py`` under that interpreter and reads the answer back. Blender starts in
about 1.5 s, so :func:`refine_many` sends a batch to one subprocess.

What the options mean (OpenSubdiv Sdc names; Blender's modifier settings in worker.py):

- ``scheme``: ``"catmull_clark"`` (Sdc SCHEME_CATMARK) or ``"bilinear"`` (Blender's 'SIMPLE').
  ``"loop"`` (Sdc SCHEME_LOOP) goes to the opensubdiv-petite binary (tests/osd/petite_ref.py).
- ``boundary``: ``"edge_only"`` or ``"edge_and_corner"`` (VtxBoundaryInterpolation; OpenSubdiv's
  default is edge_and_corner, Blender's UI default is edge_only).
- ``edge_sharpness``: ``{(a, b): s}``, OpenSubdiv sharpness per edge given by its two vertices;
  ``s >= 10`` (or ``math.inf``) is infinitely sharp. Blender holds a crease ``c`` in [0, 1] and
  hands OpenSubdiv ``s = c * c * 10.0f`` (``crease_to_sharpness`` in Blender's
  source/blender/blenkernel/intern/subdiv_inline.hh); worker.py inverts it, so ``s`` arrives
  exactly or one float32 ulp above (2.0 -> 2.0000002).
- ``vertex_sharpness``: ``{v: s}``, corner sharpness, same units.
- ``uvs``: (C, 2) per corner, aligned with the flattened faces; ``uv_interpolation`` is the
  FVarLinearInterpolation: ``"all"`` (FVAR_LINEAR_ALL, bilinear), ``"corners_only"``,
  ``"corners_plus1"``, ``"corners_plus2"``, ``"boundaries"``, ``"none"`` (smooth everywhere).
  Seams come from the values: corners with equal UVs at a vertex share one face-varying value
  (Blender merges UVs closer than a small limit).
- ``crease_method``: ``"uniform"`` or ``"chaikin"`` (Sdc CreasingMethod); Chaikin needs petite.
- ``backend``: ``"auto"`` (Blender, except Loop and Chaikin: petite), ``"blender"``, ``"petite"``.

Fixed by Blender, not options: the crease method is uniform (``Sdc::Options::CREASE_UNIFORM`` is
hard-coded in Blender's intern/opensubdiv/internal/topology/topology_refiner_factory.cc; the
modifier has no Chaikin setting); triangles use the Catmark rule (TRI_SUB_CATMARK); and a vertex
with exactly two edges gets the smaller of their two sharpnesses added to its own (same file,
assignComponentTags, so that a creased plane keeps its corners). OpenSubdiv alone does not do
the last: :func:`request` sends such meshes to petite (``backend="auto"``) or refuses them
(``backend="blender"``).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
WORKER = Path(__file__).with_name("worker.py")
BOUNDARIES = ("edge_only", "edge_and_corner")
UV_INTERPOLATIONS = ("all", "corners_only", "corners_plus1", "corners_plus2", "boundaries", "none")
SCHEMES = ("catmull_clark", "bilinear", "loop")
CREASE_METHODS = ("uniform", "chaikin")
BACKENDS = ("auto", "blender", "petite")
INFINITE = 10.0  # Sdc::Crease::SHARPNESS_INFINITE
TIMEOUT = 300.0


def bpy_python() -> Path:
    """The interpreter that has bpy: ``$TOPOMESH_BPY_PYTHON`` or ``<repo>/.venv-bpy/bin/python``."""
    env = os.environ.get("TOPOMESH_BPY_PYTHON")
    return Path(env) if env else ROOT / ".venv-bpy" / "bin" / "python"


_available: list[str | None] = []


def available() -> str | None:
    """None when the Blender reference works here, else the reason it does not (for pytest.skip)."""
    if not _available:
        py = bpy_python()
        reason: str | None = None
        if not py.exists():
            reason = f"OpenSubdiv reference: {py} is missing (.ci/setup installs bpy==5.0.1 there)"
        else:
            try:
                proc = subprocess.run(
                    [str(py), "-c", "import bpy, sys; sys.stdout.write(bpy.app.version_string)"],
                    capture_output=True, text=True, timeout=TIMEOUT,
                )
                if proc.returncode != 0:
                    reason = f"OpenSubdiv reference: `import bpy` fails in {py}: {proc.stderr.strip()[-300:]}"
            except (OSError, subprocess.TimeoutExpired) as exc:
                reason = f"OpenSubdiv reference: cannot run {py}: {exc}"
        _available.append(reason)
    return _available[0]


@dataclass(frozen=True)
class Refined:
    """OpenSubdiv's refined mesh: positions (float32 values as float64), faces flat, UVs per corner."""

    positions: np.ndarray
    face_sizes: np.ndarray
    face_indices: np.ndarray
    uvs: np.ndarray | None = None

    @property
    def faces(self) -> list[list[int]]:
        starts = np.concatenate([[0], np.cumsum(self.face_sizes)[:-1]]).astype(int)
        return [self.face_indices[s : s + n].tolist() for s, n in zip(starts, self.face_sizes)]

    @property
    def corner_faces(self) -> np.ndarray:
        """The face of each corner (C,), aligned with ``face_indices`` and ``uvs``."""
        return np.repeat(np.arange(len(self.face_sizes)), self.face_sizes)


def flatten_faces(faces: Any) -> tuple[np.ndarray, np.ndarray]:
    """``faces`` as (face_sizes, face_indices): a list of index sequences, or that pair already."""
    if isinstance(faces, tuple) and len(faces) == 2 and all(isinstance(a, np.ndarray) and a.ndim == 1 for a in faces):
        return np.asarray(faces[0], dtype=np.int64), np.asarray(faces[1], dtype=np.int64)
    faces = [list(map(int, f)) for f in faces]
    sizes = np.array([len(f) for f in faces], dtype=np.int64)
    return sizes, np.array([i for f in faces for i in f], dtype=np.int64)


def request(
    vertices: Any,
    faces: Any,
    levels: int,
    *,
    scheme: str = "catmull_clark",
    boundary: str = "edge_and_corner",
    edge_sharpness: Mapping[tuple[int, int], float] | None = None,
    vertex_sharpness: Mapping[int, float] | None = None,
    uvs: Any = None,
    uv_interpolation: str = "all",
    crease_method: str = "uniform",
    backend: str = "auto",
) -> dict[str, np.ndarray]:
    """Check the arguments of :func:`refine` and encode them as the worker's arrays."""
    v = np.asarray(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must be (V, 3), got {v.shape}")
    sizes, idx = flatten_faces(faces)
    if idx.size and (idx.min() < 0 or idx.max() >= len(v)):
        raise ValueError(f"face indices must be in [0, {len(v)})")
    if not (isinstance(levels, int) and 1 <= levels <= 6):
        raise ValueError(f"levels must be an int in [1, 6], got {levels!r}")
    for name, val, allowed in (("scheme", scheme, SCHEMES), ("boundary", boundary, BOUNDARIES),
                               ("uv_interpolation", uv_interpolation, UV_INTERPOLATIONS),
                               ("crease_method", crease_method, CREASE_METHODS), ("backend", backend, BACKENDS)):
        if val not in allowed:
            raise ValueError(f"{name} must be one of {allowed}, got {val!r}")
    r: dict[str, np.ndarray] = {
        "vertices": v, "face_sizes": sizes, "face_indices": idx, "levels": np.int64(levels),
        "scheme": np.str_(scheme), "boundary": np.str_(boundary), "crease_method": np.str_(crease_method),
    }
    quirk = _blender_valence_two_quirk(sizes, idx, edge_sharpness)
    if backend == "auto":
        backend = "petite" if scheme == "loop" or crease_method == "chaikin" or quirk is not None else "blender"
    elif backend == "blender" and (scheme == "loop" or crease_method == "chaikin"):
        raise ValueError("Blender has neither the Loop scheme nor Chaikin creases: use backend='petite'")
    elif backend == "blender" and quirk is not None:
        raise ValueError(f"vertex {quirk} has two edges, both sharp: Blender would add their sharpness "
                         "to the vertex's, which OpenSubdiv does not; use backend='petite'")
    r["backend"] = np.str_(backend)
    if edge_sharpness:
        pairs = np.array([tuple(map(int, k)) for k in edge_sharpness], dtype=np.int64).reshape(-1, 2)
        r["edge_pairs"] = pairs
        r["edge_sharpness"] = np.array([min(float(s), INFINITE) for s in edge_sharpness.values()])
    if vertex_sharpness:
        r["sharp_vertices"] = np.array([int(k) for k in vertex_sharpness], dtype=np.int64)
        r["vertex_sharpness"] = np.array([min(float(s), INFINITE) for s in vertex_sharpness.values()])
    if uvs is not None:
        uv = np.asarray(uvs, dtype=np.float64)
        if uv.shape != (len(idx), 2):
            raise ValueError(f"uvs must be (corners, 2) = ({len(idx)}, 2), got {uv.shape}")
        r["uvs"] = uv
        r["uv_interpolation"] = np.str_(uv_interpolation)
    return r


def _blender_valence_two_quirk(sizes: np.ndarray, idx: np.ndarray,
                               edge_sharpness: Mapping[tuple[int, int], float] | None) -> int | None:
    """A vertex with exactly two edges, both of positive sharpness, or None (see module docstring)."""
    if not edge_sharpness:
        return None
    sharp = {(min(a, b), max(a, b)) for (a, b), s in edge_sharpness.items() if s > 0}
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int)
    edges: dict[int, set[tuple[int, int]]] = {}
    for s, n in zip(starts, sizes):
        f = idx[s : s + n].tolist()
        for a, b in zip(f, f[1:] + f[:1]):
            e = (min(a, b), max(a, b))
            edges.setdefault(a, set()).add(e)
            edges.setdefault(b, set()).add(e)
    for v, es in edges.items():
        if len(es) == 2 and es <= sharp:
            return v
    return None


def _run(py: Path, script: Path, reqs: Sequence[dict[str, np.ndarray]], extra: Sequence[str] = ()) -> list[Refined]:
    tmp = Path(tempfile.mkdtemp(prefix="topomesh-osd-"))
    try:
        arrays: dict[str, Any] = {"n": np.int64(len(reqs))}
        for i, r in enumerate(reqs):
            arrays.update({f"{i}/{k}": a for k, a in r.items()})
        np.savez(tmp / "request.npz", **arrays)
        cmd = [str(py), *extra, str(script), str(tmp / "request.npz"), str(tmp / "response.npz")]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT)
        if proc.returncode != 0 or not (tmp / "response.npz").exists():
            raise RuntimeError(f"OpenSubdiv worker failed ({proc.returncode}): {proc.stderr.strip()[-2000:]}")
        with np.load(tmp / "response.npz", allow_pickle=False) as z:
            resp = {k: z[k] for k in z.files}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    out = []
    for i in range(len(reqs)):
        if f"{i}/error" in resp:
            raise RuntimeError(f"OpenSubdiv request {i}: {resp[f'{i}/error']}")
        out.append(Refined(resp[f"{i}/positions"], resp[f"{i}/face_sizes"], resp[f"{i}/face_indices"],
                           resp.get(f"{i}/uvs")))
    return out


#: wall-clock seconds of every worker run, for the test report
timings: list[tuple[int, float]] = []


def refine_many(requests: Sequence[dict[str, np.ndarray]]) -> list[Refined]:
    """Run a batch of :func:`request` encodings: Blender's in one subprocess, petite's in another."""
    results: list[Refined | None] = [None] * len(requests)
    blender = [i for i, r in enumerate(requests) if str(r["backend"]) == "blender"]
    loop = [i for i, r in enumerate(requests) if str(r["backend"]) == "petite"]
    if blender:
        reason = available()
        if reason:
            raise RuntimeError(reason)
        t = time.perf_counter()
        for i, res in zip(blender, _run(bpy_python(), WORKER, [requests[i] for i in blender], ["-I"])):
            results[i] = res
        timings.append((len(blender), time.perf_counter() - t))
    if loop:
        from tests.osd import petite_ref

        reason = petite_ref.available()
        if reason:
            raise RuntimeError(reason)
        t = time.perf_counter()
        for i, res in zip(loop, petite_ref.run([requests[i] for i in loop])):
            results[i] = res
        timings.append((len(loop), time.perf_counter() - t))
    return [r for r in results if r is not None]


def refine(vertices: Any, faces: Any, levels: int, **options: Any) -> Refined:
    """Refine ``levels`` times with OpenSubdiv (uniform refinement, not the limit surface).

    Keywords: ``scheme``, ``boundary``, ``edge_sharpness``, ``vertex_sharpness``, ``uvs``,
    ``uv_interpolation``, ``crease_method``, ``backend`` (see the module docstring). Raises
    RuntimeError when the reference is unavailable (check :func:`available` first) and
    ValueError on bad arguments.
    """
    return refine_many([request(vertices, faces, levels, **options)])[0]
