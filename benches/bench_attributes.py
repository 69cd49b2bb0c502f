"""What creases, attributes and correspondence cost on top of a plain level.

    python benches/bench_attributes.py                      # writes benches/ATTRIBUTES.md
    python benches/bench_attributes.py --baseline OTHER_PY  # also times the plain calls with another build

Inputs: the 400×250 quad torus (100,000 quads, Catmull-Clark) and the 81,920-triangle icosphere
(Loop), as in bench_subdivision.py. Each row is the median of ``--runs`` timed calls after one
warm-up, in this process, one level. "attr k" carries k float64 vertex-attribute columns; the
issue's target is at most (1 + extra output bytes / output bytes) × 1.25 of the plain call, where
the output bytes are the exported arrays (vertices 24 B, face indices 8 B per corner, face sizes
8 B per face) and the extra bytes 8·k per output vertex. ``--baseline`` runs the plain calls in a
subprocess with another interpreter (e.g. the previous release's venv) to check closed-mesh times,
alternating fresh processes of the two builds three times and keeping each one's best median.

The second table carries k = 2 columns through every scheme that carries them, two levels on the
7,200-quad torus (120×60): vertex attributes (extra bytes 16 per output vertex) and corner attributes
(16 per output corner; Catmull-Clark and Loop on their face-varying meshes, the others through the
generic corner transfer, src/schemes/corner_transfer.rs). Each call is timed in fresh processes (best
median of three), with ``--baseline`` for the other build too.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

PLAIN = """
import json, statistics, sys, time
import topomesh
torus, sphere = topomesh.torus(400, 250), topomesh.icosahedron().loop(6)
out = {}
for name, f in (("catmull_clark", lambda: torus.catmull_clark(1)), ("loop", lambda: sphere.loop(1))):
    f()
    ts = []
    for _ in range(int(sys.argv[1])):
        t = time.perf_counter(); f(); ts.append(time.perf_counter() - t)
    out[name] = statistics.median(ts)
print(json.dumps(out))
"""


CARRY = """
import json, statistics, sys, time
import numpy as np
import topomesh
m = topomesh.torus(120, 60)
fi = np.asarray(m.face_indices)
mv = m.with_attributes(vertex={"a": np.asarray(m.vertices)[:, :2].copy()})
mc = m.with_attributes(corner={"uv": np.asarray(m.vertices)[fi][:, :2].copy()})
out = {}
for name in sys.argv[2].split(","):
    levels = 1 if name in ("sierpinski", "menger") else 2
    row = {}
    for what, mesh in (("plain", m), ("vertex", mv), ("corner", mc)):
        f = lambda: getattr(mesh, name)(levels)
        r = f()
        ts = []
        for _ in range(int(sys.argv[1])):
            t = time.perf_counter(); f(); ts.append(time.perf_counter() - t)
        row[what] = statistics.median(ts)
    row["bytes"] = 24 * r.n_vertices + 8 * len(r.face_indices) + 8 * len(r.face_sizes)
    row["V"], row["C"] = r.n_vertices, len(r.face_indices)
    out[name] = row
print(json.dumps(out))
"""
CARRY_SCHEMES = "catmull_clark,loop,doo_sabin,midpoint,dual,simplest,sqrt3,honeycomb,vertex_truncation,sierpinski"


def carry_rows(py: str, runs: int) -> dict[str, dict[str, float]]:
    """Best medians over three fresh processes of ``py`` (see the module docs)."""
    best: dict[str, dict[str, float]] = {}
    for _ in range(3):
        res = subprocess.run([py, "-c", CARRY, str(runs), CARRY_SCHEMES], capture_output=True, text=True, check=True)
        for name, row in json.loads(res.stdout).items():
            b = best.setdefault(name, dict(row))
            for k in ("plain", "vertex", "corner"):
                b[k] = min(b[k], row[k])
    return best


def median_time(f, runs: int) -> float:
    f()
    ts = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--baseline", help="another Python whose topomesh times the plain calls")
    ap.add_argument("--out", default=str(HERE / "ATTRIBUTES.md"))
    a = ap.parse_args()
    import numpy as np

    import topomesh

    torus, sphere = topomesh.torus(400, 250), topomesh.icosahedron().loop(6)
    rng = np.random.default_rng(0)
    rows = []
    for scheme, m in (("catmull_clark", torus), ("loop", sphere)):
        step = getattr(m, scheme)
        out = step(1)
        out_bytes = 24 * out.n_vertices + 8 * len(out.face_indices) + 8 * len(out.face_sizes)
        plain = median_time(lambda: step(1), a.runs)
        rows.append((scheme, "plain", plain, 1.0, ""))
        for k in (1, 3, 8):
            ma = m.with_attributes(vertex={"a": rng.random((m.n_vertices, k))})
            t = median_time(lambda: getattr(ma, scheme)(1), a.runs)
            bound = (1 + 8 * k * out.n_vertices / out_bytes) * 1.25
            rows.append((scheme, f"attr {k}", t, t / plain, f"≤ {bound:.2f}: {'met' if t / plain <= bound else 'NOT met'}"))
        sharp = np.where(rng.random(m.n_edges) < 0.1, 1.5, 0.0)
        mc = m.with_creases(sharp)
        rows.append((scheme, "creases (10 % of edges, sharpness 1.5)", median_time(lambda: getattr(mc, scheme)(1), a.runs), None, ""))
        rows.append((scheme, "correspondence (S, origins)", median_time(lambda: step(1, correspondence=True), a.runs), None, ""))
        if scheme == "catmull_clark":
            from topomesh.examples import uv_cube

            uv = uv_cube().catmull_clark(6)
            rows.append((scheme, f"corner uv (another input: the UV cube ×6, {len(uv.face_sizes)} faces)", median_time(lambda: uv.catmull_clark(1), a.runs), float("nan"), ""))
    base = None
    if a.baseline:
        # alternate fresh processes of both builds, best median of three each (a shared machine drifts)
        both: dict[str, list[dict[str, float]]] = {"this": [], "base": []}
        for _ in range(3):
            for key, py in (("base", a.baseline), ("this", sys.executable)):
                res = subprocess.run([py, "-c", PLAIN, str(a.runs)], capture_output=True, text=True, check=True)
                both[key].append(json.loads(res.stdout))
        base = {s: min(r[s] for r in both["base"]) for s in both["base"][0]}
        this = {s: min(r[s] for r in both["this"]) for s in both["this"][0]}
    lines = [
        "# Creases, attributes and correspondence",
        "",
        f"`python benches/bench_attributes.py` — one level, median of {a.runs} runs after a warm-up, in one process "
        "(2 shared cores; absolute times are noisy, ratios are within one run).",
        "",
        "| scheme | call | ms | × plain | target |",
        "|---|---|---|---|---|",
    ]
    plain_t = {}
    for scheme, what, t, ratio, target in rows:
        if what == "plain":
            plain_t[scheme] = t
        r = ratio if ratio is not None else t / plain_t[scheme]
        shown = "—" if r != r else f"{r:.2f}"
        lines.append(f"| {scheme} | {what} | {1e3 * t:.1f} | {shown} | {target} |")
    if base:
        lines += ["", "Closed-mesh plain level against the baseline build, measured in the same run:", "",
                  "| scheme | this build (ms) | baseline (ms) | ratio | target ≤ 1.10 |", "|---|---|---|---|---|"]
        for s, t in base.items():
            r = this[s] / t
            lines.append(f"| {s} | {1e3 * this[s]:.1f} | {1e3 * t:.1f} | {r:.2f} | {'met' if r <= 1.10 else 'NOT met'} |")
    carried = carry_rows(sys.executable, a.runs)
    before = carry_rows(a.baseline, a.runs) if a.baseline else None
    lines += ["", "k = 2 columns carried, torus 120×60 (7,200 quads), 2 levels (Sierpinski 1); ms, best median of 3 fresh processes"
              + (", baseline = the other build in the same run" if before else "") + ":", ""]
    head = "| scheme | plain | vertex k=2 | × plain | target | corner k=2 | × plain | target |"
    if before:
        head += " baseline corner | baseline × plain |"
    lines += [head, "|" + "---|" * (head.count("|") - 1)]
    for name, r in carried.items():
        tv = (1 + 16 * r["V"] / r["bytes"]) * 1.25
        tc = (1 + 16 * r["C"] / r["bytes"]) * 1.25
        rv, rc = r["vertex"] / r["plain"], r["corner"] / r["plain"]
        row = (f"| {name} | {1e3 * r['plain']:.1f} | {1e3 * r['vertex']:.1f} | {rv:.2f} | ≤ {tv:.2f}: {'met' if rv <= tv else 'NOT met'} "
               f"| {1e3 * r['corner']:.1f} | {rc:.2f} | ≤ {tc:.2f}: {'met' if rc <= tc else 'NOT met'} |")
        if before:
            b = before[name]
            row += f" {1e3 * b['corner']:.1f} | {b['corner'] / b['plain']:.2f} |"
        lines.append(row)
    text = "\n".join(lines) + "\n"
    print(text)
    Path(a.out).write_text(text)


if __name__ == "__main__":
    sys.exit(main())
