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
import threading
import time
from pathlib import Path

# before NumPy loads: OpenBLAS's threads spin for a while after any BLAS call
# (trimesh's export makes some) and took a core from the next timed read, which
# then ran 5-10x slower whichever library it was (perf: blas_thread_server)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402


def settle() -> None:
    """Waits (untimed) for the threads on which topomesh's saves release the
    files they replaced (``io._release_in_background``), so that they take no
    core from the next timed call."""
    for th in threading.enumerate():
        if th.name == "topomesh-release":
            th.join()


def median_time(fn, repeat: int) -> float:
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
        settle()
    return statistics.median(ts)


def interleaved(t):
    """``t``'s quads with every other one split into two triangles: face sizes
    change at every face, the worst case of PLY's variable-length records."""
    import topomesh

    q = t.face_indices.reshape(-1, 4)
    split = np.arange(len(q)) % 2 == 0
    sizes = np.where(split, 3, 4).repeat(np.where(split, 2, 1))
    tri = q[split][:, [0, 1, 2, 0, 2, 3]]
    # the flat index list in face order: 6 indices per split quad, 4 per kept one
    width = np.where(split, 6, 4)
    starts = np.cumsum(width) - width
    out = np.empty(int(width.sum()), dtype=np.int64)
    out[starts[split][:, None] + np.arange(6)] = tri
    out[starts[~split][:, None] + np.arange(4)] = q[~split]
    return topomesh.Mesh.from_flat(t.vertices, sizes, out)


def peer_time(fn, repeat: int) -> float:
    """A peer's median time, NaN when it cannot read the file (trimesh refuses
    binary PLY faces of mixed sizes: "PLY is unexpected length")."""
    try:
        return median_time(fn, repeat)
    except Exception:
        return float("nan")


def ply_only(repeat: int) -> int:
    """Issue 19's PLY check on 1M triangles: topomesh's save and parse and
    trimesh's export and load, interleaved in one process (each round runs
    both sides), so the machine's load hits them alike; prints medians and
    ratios. Writes and reads run in separate rounds, with ``os.sync()``
    between: a read right after a write of 36 MiB shared the two cores with
    the kernel's writeback of it and ran 2-10x slower, whichever library
    read (trimesh's load too)."""
    import trimesh

    import topomesh
    from topomesh._ply import _read_ply

    t = topomesh.torus(1000, 500)
    m = topomesh.Mesh.from_polygons(t.vertices, t.triangles())
    m.face_indices, m.corner_twins  # exports computed once, as after any first access
    tm = trimesh.Trimesh(m.vertices, m.face_indices.reshape(-1, 3), process=False)
    res: dict = {k: [] for k in ("save", "save+release", "export", "parse", "load", "parse peer", "topomesh load", "trimesh load ours")}
    with tempfile.TemporaryDirectory() as d:
        f, g = os.path.join(d, "m.ply"), os.path.join(d, "peer.ply")
        m.save(f), tm.export(g)
        rounds = [(("save", lambda: m.save(f)), ("export", lambda: tm.export(g)))]
        rounds.append((("parse", lambda: _read_ply(f)), ("load", lambda: trimesh.load(g, process=False)),
                       # the same file for both readers: trimesh's (float32, triangles, no twins)
                       ("parse peer", lambda: _read_ply(g)),
                       # the whole load to a validated half-edge mesh, and trimesh reading topomesh's file
                       ("topomesh load", lambda: topomesh.load(f)), ("trimesh load ours", lambda: trimesh.load(f, process=False))))
        for ops in rounds:
            for _ in range(repeat):
                for k, fn in ops:
                    t0 = time.perf_counter()
                    fn()
                    res[k].append(time.perf_counter() - t0)
                    # a save over the file releases the old one on a thread of its own
                    # (io._release_in_background): waited for, untimed, so that it does not
                    # take a core from the next timed call; "save+release" counts it
                    settle()
                    if k == "save":
                        res["save+release"].append(time.perf_counter() - t0)
            os.sync()
        sizes = os.path.getsize(f) / 2**20, os.path.getsize(g) / 2**20
    med = {k: statistics.median(v) for k, v in res.items()}
    print(f"| 1M triangles | topomesh save {med['save'] * 1e3:.1f} ms (with the old file's release "
          f"{med['save+release'] * 1e3:.1f} ms) | trimesh export {med['export'] * 1e3:.1f} ms | "
          f"{med['export'] / med['save']:.2f}× ({med['export'] / med['save+release']:.2f}×) | topomesh parse {med['parse'] * 1e3:.1f} ms | trimesh load {med['load'] * 1e3:.1f} ms | "
          f"{med['load'] / med['parse']:.2f}× | topomesh parse of trimesh's file {med['parse peer'] * 1e3:.1f} ms | "
          f"{med['load'] / med['parse peer']:.2f}× | topomesh.load (validated mesh) {med['topomesh load'] * 1e3:.1f} ms | "
          f"trimesh load of topomesh's file {med['trimesh load ours'] * 1e3:.1f} ms | "
          f"files {sizes[0]:.0f} / {sizes[1]:.0f} MiB | load avg {os.getloadavg()[0]:.1f} |")
    return 0


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(Path(__file__).with_name("IO.md")))
    ap.add_argument("--ply-only", action="store_true", help="only issue 19's PLY check (1M triangles, against trimesh), printed")
    a = ap.parse_args()
    if a.ply_only:
        return ply_only(a.repeat)

    import meshio
    import trimesh

    import topomesh
    from topomesh._core import _read_obj
    from topomesh._ply import _read_ply

    quads = topomesh.torus(1000, 1000)  # 1M quads
    t = topomesh.torus(1000, 500)
    tris = topomesh.Mesh.from_polygons(t.vertices, t.triangles())  # 1M triangles
    mixed = interleaved(topomesh.torus(1000, 700))
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for label, m in (("1M quads (torus 1000×1000)", quads), ("1M triangles (torus 1000×500)", tris),
                         ("1.05M mixed faces (torus 1000×700, every other quad split: 350k quads and 700k triangles interleaved)", mixed)):
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
            # PLY against trimesh (binary both ways): trimesh reads topomesh's file (it skips the
            # corner_twins list) and writes its own, which topomesh then reads without twins
            f = os.path.join(d, "m.ply")
            g = os.path.join(d, "peer.ply")
            r["topomesh parse only .ply"] = median_time(lambda: _read_ply(f), a.repeat)
            r["trimesh load .ply"] = peer_time(lambda: trimesh.load(f, process=False), a.repeat)
            # a like-for-like "usable mesh": trimesh's edge topology (what watertight, Euler and genus need)
            r["trimesh load .ply + topology"] = peer_time(
                lambda: trimesh.load(f, process=False).is_watertight, a.repeat)
            r["trimesh export .ply"] = median_time(lambda: tm.export(g), a.repeat)
            r["topomesh load peer .ply"] = median_time(lambda: topomesh.load(g), a.repeat)
            rows.append((label, size, r))
            print(label, {k: round(v, 3) for k, v in r.items()}, file=sys.stderr)

    lines = [
        "# OBJ and PLY load and save, 1M faces",
        "",
        "`python benches/bench_io.py` (medians of %d runs, one process, 2 cores). The OBJ file is written by" % a.repeat,
        "topomesh (exact float64: 17 significant digits). topomesh load = parse + `Mesh.from_flat` (validated mesh);",
        "trimesh = `trimesh.load(path, process=False)` (triangulates quads), meshio = `meshio.read`.",
        "Ratios are peer time / topomesh time (> 1: topomesh is faster); the PLY ratios compare with topomesh's",
        "lossless .ply row (trimesh's binary PLY holds the triangulated faces, float32 positions).",
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
            f"| topomesh parse only .ply (`_read_ply`, arrays before the mesh is built) | {r['topomesh parse only .ply']:.3f} | |",
            f"| trimesh load of that .ply (arrays) | {r['trimesh load .ply']:.3f} | {r['trimesh load .ply'] / r['topomesh parse only .ply']:.1f} vs parse |",
            f"| trimesh load of that .ply + `is_watertight` (edge topology) | {r['trimesh load .ply + topology']:.3f} | {r['trimesh load .ply + topology'] / r['topomesh load .ply']:.1f} vs load |",
            f"| trimesh export .ply | {r['trimesh export .ply']:.3f} | {r['trimesh export .ply'] / r['topomesh save .ply']:.1f} |",
            f"| topomesh load of trimesh's .ply (no twins) | {r['topomesh load peer .ply']:.3f} | |",
            "",
        ]
    Path(a.out).write_text("\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
