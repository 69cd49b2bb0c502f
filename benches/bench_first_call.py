"""First call against warm calls under the allocator's huge-page settings
(issue 19): one fresh process per row, the settings alternated round by round.

    python benches/bench_first_call.py [--rounds 4] [--scheme catmull_clark] [--input torus|sphere]

Each process runs the scheme with ``RAYON_NUM_THREADS=1`` on the 400×250
torus (100k quads) or on trimesh's 82k-triangle icosphere (subdivisions=6,
as ``bench_levels.py`` builds it, trimesh imported): level 3 twice (first
and second call), level 2 once then three more times (median), level 1
seven times (median). Settings: the default (no advice), the advice on
blocks of 4–64 MiB (``TOPOMESH_HUGE_PAGES=1``) and on every block
(``TOPOMESH_HUGE_PAGES_MAX=100G`` too). Prints one line per process; the
tables in benches/README.md ("The advice capped at 64 MiB", "The advice off
by default") were written from its output.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys

CHILD = r"""
import os, statistics, sys, time, numpy as np, topomesh
if sys.argv[2] == "sphere":
    import trimesh
    s = trimesh.creation.icosphere(subdivisions=6)
    t = topomesh.Mesh.from_polygons(np.asarray(s.vertices, dtype=np.float64), np.asarray(s.faces, dtype=np.int64))
else:
    t = topomesh.torus(400, 250)
run = getattr(t, sys.argv[1])
def tm(n):
    t0 = time.perf_counter(); run(n); return 1e3 * (time.perf_counter() - t0)
a = tm(3); b = tm(3)
c = tm(2); d = statistics.median([tm(2) for _ in range(3)])
e = statistics.median([tm(1) for _ in range(7)])
print(f"L3 first {a:.0f} second {b:.0f} | L2 first {c:.0f} warm {d:.0f} | L1 warm {e:.1f} | load {os.getloadavg()[0]:.1f}")
"""

SETTINGS = {
    "default (no advice)": {},
    "advice on 4-64 MiB": {"TOPOMESH_HUGE_PAGES": "1"},
    "advice on every block": {"TOPOMESH_HUGE_PAGES": "1", "TOPOMESH_HUGE_PAGES_MAX": "100G"},
}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--scheme", default="catmull_clark")
    ap.add_argument("--input", choices=["torus", "sphere"], default="torus")
    a = ap.parse_args()
    for r in range(a.rounds):
        for name, env in SETTINGS.items():
            e = {k: v for k, v in os.environ.items() if not k.startswith("TOPOMESH_HUGE")}
            e.update(env, RAYON_NUM_THREADS="1")
            out = subprocess.run([sys.executable, "-c", CHILD, a.scheme, a.input], env=e, capture_output=True, text=True, check=True)
            print(f"round {r + 1} | {a.scheme} {a.input} | {name}: {out.stdout.strip()}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
