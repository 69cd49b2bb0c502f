"""File benchmark: OBJ load and save of 1M-face meshes, topomesh against
trimesh (``trimesh.load(..., process=False)``) and meshio in the same run,
plus topomesh's lossless ``.npz`` and ``.ply``.

    python benches/bench_io.py [--repeat 3]

Writes benches/IO.md. Times are medians of ``--repeat`` runs in this process.
Every reader reads the same file, written by topomesh (17 significant digits,
so the files are as large as exact float64 text needs). topomesh's load is the
whole path to a validated mesh (parse, then ``Mesh.from_flat``); its parse
alone is given too. trimesh triangulates the quads on load.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def median_time(fn, repeat: int) -> float:
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(Path(__file__).with_name("IO.md")))
    a = ap.parse_args()

    import meshio
    import trimesh

    import topomesh
    from topomesh._core import _read_obj

    quads = topomesh.torus(1000, 1000)  # 1M quads
    t = topomesh.torus(1000, 500)
    tris = topomesh.Mesh.from_polygons(t.vertices, t.triangles())  # 1M triangles
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for label, m in (("1M quads (torus 1000×1000)", quads), ("1M triangles (torus 1000×500)", tris)):
            p = os.path.join(d, "m.obj")
            m.save(p)
            size = os.path.getsize(p) / 2**20
            tm = trimesh.load(p, process=False)
            mm = meshio.read(p)
            q = os.path.join(d, "peer.obj")
            r = {
                "topomesh load": median_time(lambda: topomesh.load(p), a.repeat),
                "topomesh parse only": median_time(lambda: _read_obj(p), a.repeat),
                "trimesh load": median_time(lambda: trimesh.load(p, process=False), a.repeat),
                "meshio read": median_time(lambda: meshio.read(p), a.repeat),
                "topomesh save": median_time(lambda: m.save(p), a.repeat),
                "trimesh export": median_time(lambda: tm.export(q), a.repeat),
                "meshio write": median_time(lambda: meshio.write(q, mm), a.repeat),
            }
            for ext in (".npz", ".ply"):
                f = os.path.join(d, "m" + ext)
                r[f"topomesh save {ext}"] = median_time(lambda: m.save(f), a.repeat)
                r[f"topomesh load {ext}"] = median_time(lambda: topomesh.load(f), a.repeat)
            rows.append((label, size, r))
            print(label, {k: round(v, 3) for k, v in r.items()}, file=sys.stderr)

    lines = [
        "# OBJ load and save, 1M faces",
        "",
        "`python benches/bench_io.py` (medians of %d runs, one process, 2 cores). The OBJ file is written by" % a.repeat,
        "topomesh (exact float64: 17 significant digits). topomesh load = parse + `Mesh.from_flat` (validated mesh);",
        "trimesh = `trimesh.load(path, process=False)` (triangulates quads), meshio = `meshio.read`.",
        "Ratios are peer time / topomesh time (> 1: topomesh is faster).",
        "",
    ]
    for label, size, r in rows:
        tl, ts = r["topomesh load"], r["topomesh save"]
        lines += [
            f"## {label}, OBJ {size:.0f} MiB",
            "",
            "| operation | time (s) | ratio |",
            "|---|---:|---:|",
            f"| topomesh load | {tl:.3f} | 1 |",
            f"| topomesh parse only (`_read_obj`) | {r['topomesh parse only']:.3f} | |",
            f"| trimesh load | {r['trimesh load']:.3f} | {r['trimesh load'] / tl:.1f} |",
            f"| meshio read | {r['meshio read']:.3f} | {r['meshio read'] / tl:.1f} |",
            f"| topomesh save | {ts:.3f} | 1 |",
            f"| trimesh export | {r['trimesh export']:.3f} | {r['trimesh export'] / ts:.1f} |",
            f"| meshio write | {r['meshio write']:.3f} | {r['meshio write'] / ts:.1f} |",
            f"| topomesh save / load .npz (lossless) | {r['topomesh save .npz']:.3f} / {r['topomesh load .npz']:.3f} | |",
            f"| topomesh save / load .ply (lossless) | {r['topomesh save .ply']:.3f} / {r['topomesh load .ply']:.3f} | |",
            "",
        ]
    Path(a.out).write_text("\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
