"""Issue 19 benchmark: the output-time Menger sponge against a plain NumPy
voxel-boundary construction of the same faces, and the allocator's block
cache (warm and first-call times, with and without it).

    python benches/bench_perf.py [--repeat 5] [--fresh 5]

Prints a Markdown section for benches/README.md. Sponge: both tools run
alternately in one process, ``--repeat`` times per level; medians and the
min–max spread are reported, and the ratio is NumPy's median over
topomesh's. Cache: every first-call figure is a fresh process (import,
input, then one timed call); warm figures are the median of ``--repeat``
calls after one untimed call in one process. Peak RSS is read from the
fresh processes (``ru_maxrss``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np


def numpy_sponge(level: int):
    """(vertices, quads) of the level-`level` sponge: kept cells from the digit
    rule, exposed squares by comparing each cell with its 6 neighbours, vertex
    ids through a grid-sized lookup table."""
    n = 3**level
    t = np.arange(n)
    ones = np.zeros(n, np.int64)
    for k in range(level):
        ones |= ((t // 3**k) % 3 == 1).astype(np.int64) << k
    a, b, c = ones[:, None, None], ones[None, :, None], ones[None, None, :]
    kept = ((a & b) | (b & c) | (a & c)) == 0
    pad = np.pad(kept, 1)
    g = n + 1
    quads = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for sign in (-1, 1):
            sl = [slice(1, -1)] * 3
            sl[axis] = slice(1 + sign, n + 1 + sign)
            p = [q.astype(np.int64) for q in np.nonzero(kept & ~pad[tuple(sl)])]
            if sign == 1:
                p[axis] = p[axis] + 1
            base = (p[0] * g + p[1]) * g + p[2]
            du, dv = g ** (2 - u), g ** (2 - v)
            order = [0, du, du + dv, dv] if sign == 1 else [0, dv, du + dv, du]
            quads.append(base[:, None] + np.array(order)[None, :])
    quads = np.concatenate(quads)
    used = np.zeros(g**3, bool)
    used[quads.ravel()] = True
    ids = np.cumsum(used) - 1
    gv = np.nonzero(used)[0]
    verts = np.stack([gv // (g * g), (gv // g) % g, gv % g], 1) * (2.0 / n) - 1.0
    return verts, ids[quads]


def sponge(repeat: int) -> list[str]:
    import topomesh

    rows = ["| level | faces | topomesh (ms) | spread | NumPy voxels (ms) | spread | NumPy / topomesh | target ≥ 5× |",
            "| ---: | ---: | ---: | --- | ---: | --- | ---: | --- |"]
    for level in (3, 4, 5):
        a, b = [], []
        for _ in range(repeat):
            t = time.perf_counter()
            m = topomesh.menger_sponge(level)
            a.append(time.perf_counter() - t)
            del m
            t = time.perf_counter()
            r = numpy_sponge(level)
            b.append(time.perf_counter() - t)
            nf = len(r[1])
            del r
        ma, mb = statistics.median(a), statistics.median(b)
        rows.append(f"| {level} | {nf:,} | {ma * 1e3:.1f} | {min(a) * 1e3:.1f}–{max(a) * 1e3:.1f} | {mb * 1e3:.1f} | "
                    f"{min(b) * 1e3:.1f}–{max(b) * 1e3:.1f} | {mb / ma:.2f}× | {'met' if mb / ma >= 5 else 'not met'} |")
    return rows


CHILD = r"""
import json, resource, sys, time
import topomesh
case, warm, repeat = sys.argv[1], sys.argv[2] == "1", int(sys.argv[3])
if case == "loop":
    import trimesh
    s = trimesh.creation.icosphere(subdivisions=6)
    m = topomesh.Mesh.from_polygons(s.vertices, s.faces)
    run = lambda: m.loop(1)
elif case == "catmull_clark":
    m = topomesh.torus(400, 250)
    run = lambda: m.catmull_clark(1)
else:
    run = lambda: topomesh.menger_sponge(4)
times = []
if warm:
    run()
    for _ in range(repeat):
        t = time.perf_counter(); r = run(); times.append(time.perf_counter() - t); del r
else:
    t = time.perf_counter(); r = run(); times.append(time.perf_counter() - t); del r
print(json.dumps({"t": times, "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "held": topomesh.block_cache()[1]}))
"""


def cache(repeat: int, fresh: int) -> list[str]:
    rows = ["| case | block cache | first call, fresh process (ms) | spread | warm (ms) | spread | held after (MB) | peak RSS (MB) |",
            "| --- | --- | ---: | --- | ---: | --- | ---: | ---: |"]
    for case in ("loop", "catmull_clark", "menger_sponge"):
        for env in ("0", "256M"):
            e = {**os.environ, "TOPOMESH_BLOCK_CACHE": env}

            def go(warm: bool):
                out = subprocess.run([sys.executable, "-c", CHILD, case, "1" if warm else "0", str(repeat)],
                                     env=e, capture_output=True, text=True, check=True)
                return json.loads(out.stdout)

            first = [go(False) for _ in range(fresh)]
            ft = [r["t"][0] for r in first]
            w = go(True)
            wt = w["t"]
            label = {"loop": "loop L1, sphere 82k", "catmull_clark": "catmull_clark L1, torus 100k", "menger_sponge": "menger_sponge(4)"}[case]
            rows.append(f"| {label} | {'off (default)' if env == '0' else env} | {statistics.median(ft) * 1e3:.1f} | "
                        f"{min(ft) * 1e3:.1f}–{max(ft) * 1e3:.1f} | {statistics.median(wt) * 1e3:.1f} | "
                        f"{min(wt) * 1e3:.1f}–{max(wt) * 1e3:.1f} | {w['held'] / 2**20:.0f} | "
                        f"{statistics.median(r['rss'] for r in first):.0f} |")
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--fresh", type=int, default=5)
    ap.add_argument("--only", choices=["sponge", "cache"])
    args = ap.parse_args()
    load0 = os.getloadavg()[0]
    out = []
    if args.only != "cache":
        out += sponge(args.repeat) + [""]
    if args.only != "sponge":
        out += cache(args.repeat, args.fresh) + [""]
    out.append(f"Load average (1 min) before / after: {load0:.1f} / {os.getloadavg()[0]:.1f}.")
    print("\n".join(out))


if __name__ == "__main__":
    main()
