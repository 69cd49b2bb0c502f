"""Benchmarks for topomesh.ifs: chaos-game throughput and deterministic iteration.

Run:  python benches/bench_ifs.py [--out benches/IFS.md]
Single-threaded (the chaos game and iteration run on one core). Best of 3 runs.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

from topomesh import ifs


def best(fn, repeat=3):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return min(ts), out


def bumpy(xy):
    x, y = xy[:, 0], xy[:, 1]
    return np.c_[x, y, 0.5 * np.sin(1.3 * x) * np.cos(0.9 * y) + 0.1 * x * y]


def cases():
    P5 = np.array([[0, 0], [1, 2], [2.5, 2.2], [3.5, 0.5], [5, 1.5]], float)
    R7 = np.array([[0, 0], [1, 1.5], [2, 0.2], [3, 2], [4, 0.5], [5, 1.8], [6, 0]], float)
    grid = np.array([[i, j] for j in range(4) for i in range(4)], float)
    return [
        ("cubic B-spline (5 pts)", ifs.cubic_bspline(P5)),
        ("four-point (7 pts)", ifs.four_point(R7)),
        ("Koch (5 pts)", ifs.koch()),
        ("gasket (6 pts)", ifs.gasket()),
        ("union of 2 Béziers", ifs.bezier(P5[:3]).union(ifs.bezier(P5[2:]))),
        ("bicubic (16 pts)", ifs.bicubic(bumpy(grid))),
        ("Loop hexagon (19 pts)", ifs.loop(bumpy(ifs.hex_lattice(2)))),
        ("sqrt3 hexagon (61 pts)", ifs.sqrt3(bumpy(ifs.hex_lattice(4)))),
    ]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    lines = [
        "# topomesh.ifs benchmarks",
        "",
        f"Machine: {platform.machine()}, {platform.python_implementation()} {platform.python_version()}; "
        "one core; best of 3; `python benches/bench_ifs.py`.",
        "",
        "## Chaos game (points per second, one core)",
        "",
        "| IFS | maps | reduced dim | points | time | points/s |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name, f in cases():
        n = 10_000_000 if f.dim <= 8 else (2_000_000 if f.dim <= 20 else 500_000)
        t, _ = best(lambda: f.chaos_game(n, seed=1))
        lines.append(f"| {name} | {f.n_maps} | {f.dim - f.n_components} | {n:,} | {t * 1e3:.0f} ms | {n / t:.3g} |")
        print(lines[-1], flush=True)
    lines += [
        "",
        "## Deterministic iteration to about 10^6 points",
        "",
        "`X_{k+1} = F(X_k)` from one start point (all words of length `levels`), and `polyline` / `mesh`.",
        "",
        "| IFS | call | output | time | points/s |",
        "|---|---|---:|---:|---:|",
    ]
    runs = [
        ("cubic B-spline", ifs.cubic_bspline(np.array([[0, 0], [1, 2], [2.5, 2.2], [3.5, 0.5], [5, 1.5]], float)), "iterate", 20),
        ("cubic B-spline", None, "polyline", 20),
        ("Koch", ifs.koch(), "iterate", 10),
        ("gasket", ifs.gasket(), "iterate", 13),
        ("Loop hexagon", ifs.loop(bumpy(ifs.hex_lattice(2))), "mesh", 9),
        ("bicubic", ifs.bicubic(bumpy(np.array([[i, j] for j in range(4) for i in range(4)], float))), "mesh", 10),
        ("sqrt3 hexagon", ifs.sqrt3(bumpy(ifs.hex_lattice(4))), "mesh", 5),
    ]
    prev = None
    for name, f, call, lev in runs:
        f = f or prev
        prev = f
        if call == "iterate":
            t, out = best(lambda: f.iterate([[0.3, 0.2]], lev))
            n = out.shape[0]
            desc = f"`iterate(point, {lev})`"
            size = f"{n:,} points"
        elif call == "polyline":
            t, out = best(lambda: f.polyline(lev))
            n = len(out)
            desc = f"`polyline({lev})`"
            size = f"{n:,} points"
        else:
            t, (v, tri) = best(lambda: f.mesh(lev))
            n = len(v)
            desc = f"`mesh({lev})`"
            size = f"{len(v):,} vertices, {len(tri):,} triangles"
        lines.append(f"| {name} | {desc} | {size} | {t * 1e3:.0f} ms | {n / t:.3g} |")
        print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    if a.out:
        with open(a.out, "w") as fh:
            fh.write(text)


if __name__ == "__main__":
    main()
