"""Core benchmark: construction, validate(), genus, triangulation and export on
a ~1.3M-triangle icosphere, side by side with trimesh and manifold3d.

    python benches/bench_core.py [--subdivisions 8] [--repeat 5]

Writes benches/CORE.md. Times are medians of ``--repeat`` runs in this process;
peak memory is the max RSS of a fresh subprocess doing only that case, minus the
RSS of the same subprocess before the case (so the interpreter and the input
arrays are not counted).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def sphere(subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    import trimesh

    s = trimesh.creation.icosphere(subdivisions=subdivisions)
    return np.asarray(s.vertices), np.asarray(s.faces, dtype=np.int64)


def case_fns(v: np.ndarray, f: np.ndarray):
    import manifold3d as m3d
    import trimesh

    import topomesh

    def topo_build_validate_genus():
        m = topomesh.Mesh.from_polygons(v, f)
        m.validate()
        return m.genus

    def topo_build_genus():
        return topomesh.Mesh.from_polygons(v, f).genus

    m = topomesh.Mesh.from_polygons(v, f)

    def topo_triangles():
        return m.triangles()

    def topo_export():
        return m.vertices, m.face_sizes, m.face_indices

    def trimesh_euler_watertight():
        t = trimesh.Trimesh(vertices=v, faces=f, process=False)
        return t.euler_number, t.is_watertight

    v32, f32 = v.astype(np.float32), f.astype(np.uint32)

    def manifold_build_genus():
        return m3d.Manifold(m3d.Mesh(vert_properties=v32, tri_verts=f32)).genus()

    return {
        "topomesh: from_polygons + validate + genus": topo_build_validate_genus,
        "topomesh: from_polygons + genus": topo_build_genus,
        "topomesh: triangles()": topo_triangles,
        "topomesh: export (vertices, face_sizes, face_indices)": topo_export,
        "trimesh: Trimesh + euler_number + is_watertight": trimesh_euler_watertight,
        "manifold3d: Manifold + genus()": manifold_build_genus,
    }


def rss_kib() -> int:
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return 0


def child(name: str, subdivisions: int) -> None:
    v, f = sphere(subdivisions)
    fns = case_fns(v, f)
    import resource  # noqa: F401  (keeps imports out of the measured window)

    before = rss_kib()
    fns[name]()
    print(json.dumps({"peak_kib": rss_kib() - before}))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--subdivisions", type=int, default=8)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--child", default=None)
    a = ap.parse_args()
    if a.child:
        child(a.child, a.subdivisions)
        return
    v, f = sphere(a.subdivisions)
    nf = len(f)
    fns = case_fns(v, f)
    rows = []
    for name, fn in fns.items():
        fn()  # warm-up
        ts = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            fn()
            ts.append(time.perf_counter() - t0)
        med = statistics.median(ts)
        out = subprocess.run(
            [sys.executable, __file__, "--child", name, "--subdivisions", str(a.subdivisions)],
            capture_output=True, text=True, check=True,
        )
        peak = json.loads(out.stdout.strip().splitlines()[-1])["peak_kib"] * 1024
        rows.append((name, med, peak))
        print(f"{name:58s} {med * 1e3:9.1f} ms  peak +{peak / 2**20:8.1f} MiB  {peak / nf:7.1f} B/face", flush=True)
    t = {n: s for n, s, _ in rows}
    ours = t["topomesh: from_polygons + validate + genus"]
    lines = [
        "# Core benchmark",
        "",
        f"Icosphere, {len(v):,} vertices, {nf:,} triangles; median of {a.repeat} runs; {os.cpu_count()} cores; "
        f"peak = extra max-RSS of a fresh process running only that case.",
        "",
        "| case | median ms | peak extra MiB | bytes / face |",
        "|---|---:|---:|---:|",
    ]
    lines += [f"| {n} | {s * 1e3:.1f} | {p / 2**20:.1f} | {p / nf:.0f} |" for n, s, p in rows]
    lines += [
        "",
        "Ratios (peer time / topomesh construction + validate + genus, same run):",
        "",
        f"- trimesh Trimesh + euler_number + is_watertight: **{t['trimesh: Trimesh + euler_number + is_watertight'] / ours:.1f}×**",
        f"- manifold3d Manifold + genus(): **{t['manifold3d: Manifold + genus()'] / ours:.1f}×**",
        "",
    ]
    Path(__file__).with_name("CORE.md").write_text("\n".join(lines))
    print("\n".join(lines[-5:]))


if __name__ == "__main__":
    main()
