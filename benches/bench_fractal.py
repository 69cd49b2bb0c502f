"""Fractal benchmark: Sierpinski iterations of the cube, the classic Menger
sponge, the generalized Menger sponge (when present).

    python benches/bench_fractal.py [--repeat 3]

Writes benches/FRACTAL.md. Times are medians of ``--repeat`` runs in this
process; peak memory is the max RSS of a fresh subprocess running only that
case minus its RSS just before the case (interpreter and inputs not counted).
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

import topomesh


def cases() -> dict:
    """name -> (prepare() -> state, run(state) -> Mesh)."""
    out = {
        "sierpinski(cube, 8): all 8 iterations": (topomesh.cube, lambda c: c.sierpinski(8)),
        "sierpinski(cube, 8): last iteration only": (lambda: topomesh.cube().sierpinski(7), lambda m: m.sierpinski()),
        "sierpinski(cube, 10): last iteration only": (lambda: topomesh.cube().sierpinski(9), lambda m: m.sierpinski()),
        "menger_sponge(5)": (lambda: 5, topomesh.menger_sponge),
    }
    if hasattr(topomesh.Mesh, "menger"):
        out["menger(cube, 4)"] = (topomesh.cube, lambda c: c.menger(4))
        out["menger(cube, 4): last iteration only"] = (lambda: topomesh.cube().menger(3), lambda m: m.menger())
        out["menger(dodecahedron, 4)"] = (topomesh.dodecahedron, lambda c: c.menger(4))
        # issue 17: the last iteration with and without the thickness reduction
        # (src/schemes/menger/mod.rs, "Thickness reduction"), same run
        for name, k in [("cube", 4), ("tetrahedron", 4), ("dodecahedron", 3)]:
            prep = (lambda name=name, k=k: _quiet(lambda: getattr(topomesh, name)().menger(k - 1)))
            out[f"menger({name}, {k}): last iteration, reduce_thickness=False"] = (
                prep, lambda m: _quiet(lambda: m.menger(reduce_thickness=False)))
            out[f"menger({name}, {k}): last iteration, reduced (default)"] = (prep, lambda m: _quiet(m.menger))
    return out


def _quiet(f):
    """f() with GeometryWarning silenced (the crossing iterations warn)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topomesh.GeometryWarning)
        return f()


def vm_hwm_kib() -> int:
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return 0


def child(name: str) -> None:
    prep, run = cases()[name]
    state = prep()
    before = vm_hwm_kib()
    m = run(state)
    print(json.dumps({"peak_kib": vm_hwm_kib() - before, "faces": m.n_faces}))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--child", default=None)
    ap.add_argument("--only", default=None, help="run the cases whose name contains this; their table goes "
                    "into FRACTAL.md's section of that name (the main table is left as it is)")
    a = ap.parse_args()
    if a.child:
        child(a.child)
        return
    rows = []
    for name, (prep, run) in cases().items():
        if a.only and a.only not in name:
            continue
        state = prep()
        ts = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            m = run(state)
            ts.append(time.perf_counter() - t0)
            nf, ne, g = m.n_faces, m.n_edges, m.genus
            del m
        med = statistics.median(ts)
        out = subprocess.run([sys.executable, __file__, "--child", name], capture_output=True, text=True, check=True)
        peak = json.loads(out.stdout.strip().splitlines()[-1])["peak_kib"] * 1024
        rows.append((name, nf, ne, g, med, peak))
        print(f"{name:45s} F={nf:>10,} {med:8.3f} s {nf / med / 1e6:7.2f} M faces/s  peak +{peak / 2**20:8.1f} MiB "
              f"{peak / nf:6.0f} B/face", flush=True)
    lines = [
        "# Fractal benchmark",
        "",
        f"Median of {a.repeat} runs, {os.cpu_count()} cores (shared with other jobs). Faces/s = output faces / wall time "
        "of the whole case. Peak = extra max-RSS of a fresh process running only that case (its input excluded), "
        "per output face.",
        "",
        "| case | output faces | edges | genus | median s | M faces / s | peak extra MiB | bytes / face |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    lines += [
        f"| {n} | {nf:,} | {ne:,} | {g:,} | {s:.3f} | {nf / s / 1e6:.2f} | {p / 2**20:.0f} | {p / nf:.0f} |"
        for n, nf, ne, g, s, p in rows
    ]
    if a.only:
        section(a.only, lines[len(lines) - len(rows) - 2:], a.repeat)
        return
    lines += [
        "",
        "Sierpinski iteration 8 of the cube is small (524,288 faces); iteration 10 (8.4 M faces) is shown as",
        "well. Iteration 11 (33.6 M faces, 67 M edges) would also fit in 24 GiB at the measured bytes/face.",
        "The classic sponge's level 5 has 20^5 = 3.2 M kept cells out of 27^5 = 14.3 M; the builder scans",
        "every cell, so its time is linear in 27^n while the output grows as 20^n.",
        "The generalized Menger sponge builds polygons and pairs them with `from_polygons` (bucketed by vertex),",
        "so it is near-linear rather than a one-pass twin builder. Its crossing check (module docs of",
        "src/schemes/menger/mod.rs: every input vertex's triangles tested pairwise, crossing vertices rebuilt",
        "fully collapsed) is most of its time: 0.058 s for the cube's fourth iteration and 0.57 s for the",
        "dodecahedron's (1.68 M faces, before full collapses merged faces) without it.",
        "",
    ]
    Path(__file__).with_name("FRACTAL.md").write_text("\n".join(lines))
    print("\n".join(lines))


def section(only: str, table: list[str], repeat: int) -> None:
    """Replace (or append) FRACTAL.md's section for the ``--only`` cases."""
    path = Path(__file__).with_name("FRACTAL.md")
    text = path.read_text()
    head = f"## Cases matching `{only}`"
    body = [head, "", f"Median of {repeat} runs, same run for every row; columns as above.", "", *table, ""]
    if head in text:
        start = text.index(head)
        end = text.find("\n## ", start + len(head))
        text = text[:start] + "\n".join(body) + (text[end + 1:] if end >= 0 else "")
    else:
        text = text.rstrip("\n") + "\n\n" + "\n".join(body)
    path.write_text(text)
    print("\n".join(body))


if __name__ == "__main__":
    main()
