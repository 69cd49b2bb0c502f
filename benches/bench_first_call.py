"""First call against warm calls under the allocator's huge-page settings
(issue 19): one fresh process per row, the settings alternated round by round.

    python benches/bench_first_call.py [--rounds 4]

Each process runs Catmull-Clark on the 400×250 torus (100k quads) with
``RAYON_NUM_THREADS=1``: level 3 twice (first and second call), level 2 once
then three more times (median), level 1 seven times (median). Settings:
the default (advice on blocks of 4–64 MiB), the advice on every block
(``TOPOMESH_HUGE_PAGES_MAX=100G``) and no advice (``TOPOMESH_HUGE_PAGES=0``).
Prints one line per process; the table in benches/README.md ("The advice
capped at 64 MiB") was written from its output.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys

CHILD = r"""
import os, statistics, time, topomesh
t = topomesh.torus(400, 250)
def tm(f):
    t0 = time.perf_counter(); f(); return 1e3 * (time.perf_counter() - t0)
a = tm(lambda: t.catmull_clark(3)); b = tm(lambda: t.catmull_clark(3))
c = tm(lambda: t.catmull_clark(2)); d = statistics.median([tm(lambda: t.catmull_clark(2)) for _ in range(3)])
e = statistics.median([tm(lambda: t.catmull_clark(1)) for _ in range(7)])
print(f"L3 first {a:.0f} second {b:.0f} | L2 first {c:.0f} warm {d:.0f} | L1 warm {e:.1f} | load {os.getloadavg()[0]:.1f}")
"""

SETTINGS = {
    "default (4-64 MiB)": {},
    "every block": {"TOPOMESH_HUGE_PAGES_MAX": "100G"},
    "no advice": {"TOPOMESH_HUGE_PAGES": "0"},
}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=4)
    a = ap.parse_args()
    for r in range(a.rounds):
        for name, env in SETTINGS.items():
            e = {k: v for k, v in os.environ.items() if not k.startswith("TOPOMESH_HUGE")}
            e.update(env, RAYON_NUM_THREADS="1")
            out = subprocess.run([sys.executable, "-c", CHILD], env=e, capture_output=True, text=True, check=True)
            print(f"round {r + 1} | {name}: {out.stdout.strip()}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
