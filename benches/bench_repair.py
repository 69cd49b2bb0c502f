"""Repair benchmark: a ~1.3M-triangle soup (an icosphere with every triangle
carrying its own three corners, as STL stores it), plain and with 10 % of the
triangles flipped, through ``topomesh.repair`` and through trimesh's
``Trimesh(..., process=True)`` + ``trimesh.repair.fix_normals``; and a binary
STL of it read by ``topomesh.stl.read_stl`` + ``Mesh.from_polygons`` and by
``trimesh.load``.

    python benches/bench_repair.py [--subdivisions 8] [--repeat 3]

trimesh's ``fix_normals`` needs ``networkx`` (pip install networkx).

Writes benches/REPAIR.md. Times are medians of ``--repeat`` runs in this
process, all cases in the same run (so on the same machine load).
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import trimesh

import topomesh
from topomesh.stl import read_stl


def timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--subdivisions", type=int, default=8)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    s = trimesh.creation.icosphere(subdivisions=args.subdivisions)
    v = s.vertices[s.faces].reshape(-1, 3)
    f = np.arange(len(v)).reshape(-1, 3)
    rng = np.random.default_rng(1)
    flipped = f.copy()
    sel = rng.random(len(f)) < 0.1
    flipped[sel] = flipped[sel, ::-1]
    n = len(f)

    def topo(faces):
        return lambda: topomesh.repair(v, faces)

    def tri(faces):
        def run():
            tm = trimesh.Trimesh(v, faces, process=True)
            trimesh.repair.fix_normals(tm)
            return tm

        return run

    rows = []
    for label, faces in [("soup", f), ("soup, 10 % flipped", flipped)]:
        t_topo, (m, r) = timed(topo(faces), args.repeat)
        t_tri, tm = timed(tri(faces), args.repeat)
        rows.append(
            (
                label,
                t_topo,
                t_tri,
                f"V={m.n_vertices} F={m.n_faces} genus={m.genus} volume={m.volume:.6f}; "
                f"flipped {r.faces_flipped} faces, {r.components_flipped} components",
                f"V={len(tm.vertices)} F={len(tm.faces)} watertight={tm.is_watertight} "
                f"winding={tm.is_winding_consistent} volume={tm.volume:.6f}",
            )
        )
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "sphere.stl"
        path.write_bytes(trimesh.Trimesh(s.vertices, s.faces, process=False).export(file_type="stl"))

        def topo_stl():
            vv, tt = read_stl(path)
            return topomesh.Mesh.from_polygons(vv, tt)

        t_topo, m = timed(topo_stl, args.repeat)
        t_tri, tm = timed(lambda: trimesh.load(path), args.repeat)
        rows.append(
            (
                f"binary STL read ({path.stat().st_size / 1e6:.0f} MB)",
                t_topo,
                t_tri,
                f"read_stl + from_polygons: V={m.n_vertices} F={m.n_faces} genus={m.genus}",
                f"trimesh.load: V={len(tm.vertices)} F={len(tm.faces)} watertight={tm.is_watertight}",
            )
        )
    load = os.getloadavg()[0]
    lines = [
        "# Repair benchmark",
        "",
        f"Written by `python benches/bench_repair.py --subdivisions {args.subdivisions} --repeat {args.repeat}`: "
        f"an icosphere of {n:,} triangles as a soup ({3 * n:,} corners, {len(s.vertices):,} distinct points). "
        "topomesh: `topomesh.repair(vertices, faces)` (weld, degenerate and duplicate faces, orientation, pinches; "
        "building the `Mesh` included). trimesh: `Trimesh(vertices, faces, process=True)` "
        "(merge vertices) + `trimesh.repair.fix_normals`. Medians in seconds, one process, "
        f"{os.cpu_count()} cores, load average {load:.1f} when written.",
        "",
        "| input | topomesh (s) | trimesh (s) | trimesh / topomesh | topomesh result | trimesh result |",
        "|---|---|---|---|---|---|",
    ]
    for label, a, b, ra, rb in rows:
        lines.append(f"| {label} | {a:.2f} | {b:.2f} | {b / a:.1f}× | {ra} | {rb} |")
    out = Path(__file__).with_name("REPAIR.md")
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
