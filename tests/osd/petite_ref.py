"""OpenSubdiv through the opensubdiv-petite crate (tests/osd/petite): Loop, and Chaikin creases.

Blender has no Loop scheme and hard-codes the uniform crease method, so this small binary (not
part of the topomesh workspace, not built by .ci/setup) covers the rest of OpenSubdiv's
options on positions: ``scheme`` loop / catmull_clark / bilinear, ``boundary``, edge and vertex
sharpness (OpenSubdiv units, passed through unchanged), ``crease_method`` uniform / chaikin.
The crate gives no way to declare face-varying channels, so UVs are Blender's alone.

Build once: ``CARGO_TARGET_DIR=target-osd cargo build --release --manifest-path
tests/osd/petite/Cargo.toml`` (clean: 196 s of CPU, 294 s wall on 2 shared cores; OpenSubdiv's
C++ via cmake, then bindgen, which needs libclang and the clang headers: Debian's cmake,
libclang1-14 and libclang-common-14-dev).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path
from typing import Sequence

import numpy as np

from tests.osd.reference import ROOT, TIMEOUT, Refined

BUILD = "CARGO_TARGET_DIR=target-osd cargo build --release --manifest-path tests/osd/petite/Cargo.toml"


def binary() -> Path:
    """``$TOPOMESH_OSD_PETITE`` or ``<repo>/target-osd/release/osd-petite``."""
    env = os.environ.get("TOPOMESH_OSD_PETITE")
    return Path(env) if env else ROOT / "target-osd" / "release" / "osd-petite"


def available() -> str | None:
    """None when the petite binary is built, else why not (for pytest.skip)."""
    if not binary().exists():
        return f"opensubdiv-petite reference not built ({binary()} is missing): run `{BUILD}`"
    return None


def _encode(r: dict[str, np.ndarray]) -> str:
    if "uvs" in r:
        raise ValueError("the opensubdiv-petite reference has no face-varying data: UVs go to Blender")
    v, sizes, idx = r["vertices"], r["face_sizes"], r["face_indices"]
    pairs = r.get("edge_pairs", np.zeros((0, 2), dtype=np.int64))
    es = r.get("edge_sharpness", np.zeros(0))
    cv = r.get("sharp_vertices", np.zeros(0, dtype=np.int64))
    cs = r.get("vertex_sharpness", np.zeros(0))
    lines = [f"{r['scheme']} {int(r['levels'])} {r['boundary']} {r.get('crease_method', 'uniform')} "
             f"{len(v)} {len(sizes)} {len(pairs)} {len(cv)}"]
    # float32 is what OpenSubdiv computes in; repr of a float32 round-trips
    lines += [" ".join(repr(float(np.float32(x))) for x in p) for p in v]
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int)
    lines += [" ".join(map(str, [n, *idx[s : s + n].tolist()])) for s, n in zip(starts, sizes)]
    lines += [f"{a} {b} {float(s)!r}" for (a, b), s in zip(pairs.tolist(), es.tolist())]
    lines += [f"{a} {float(s)!r}" for a, s in zip(cv.tolist(), cs.tolist())]
    return "\n".join(lines)


def run(requests: Sequence[dict[str, np.ndarray]]) -> list[Refined]:
    """Refine a batch of ``tests.osd.reference.request`` encodings with the petite binary."""
    tmp = Path(tempfile.mkdtemp(prefix="topomesh-petite-"))
    try:
        (tmp / "request.txt").write_text(f"{len(requests)}\n" + "\n".join(_encode(r) for r in requests) + "\n")
        proc = subprocess.run([str(binary()), str(tmp / "request.txt"), str(tmp / "response.txt")],
                              capture_output=True, text=True, timeout=TIMEOUT)
        if proc.returncode != 0:
            raise RuntimeError(f"osd-petite failed ({proc.returncode}): {proc.stderr.strip()[-2000:]}")
        lines = (tmp / "response.txt").read_text().splitlines()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    out, k = [], 0
    for i in range(len(requests)):
        if k >= len(lines) or lines[k].startswith("error"):
            raise RuntimeError(f"osd-petite request {i}: {lines[k] if k < len(lines) else 'no answer'}")
        nv, nf = map(int, lines[k].split())
        pos = np.array([lines[k + 1 + j].split() for j in range(nv)], dtype=np.float64).reshape(nv, 3)
        faces = [list(map(int, lines[k + 1 + nv + j].split())) for j in range(nf)]
        k += 1 + nv + nf
        sizes = np.array([f[0] for f in faces], dtype=np.int64)
        idx = np.array([i for f in faces for i in f[1:]], dtype=np.int64)
        out.append(Refined(pos, sizes, idx, None))
    return out
