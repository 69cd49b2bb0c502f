"""Issue 19: cost per output face at every level (the flat-cost target).

    python benches/bench_levels.py [--levels 1 2 3 4] [--threads 1 2] [--runs 3]
                                   [--schemes catmull_clark loop] [--label after]

Runs ``bench_subdivision.py``'s worker (a fresh process per case: input,
one untimed call, then ``--runs`` timed calls of ``iterations=levels``) for
topomesh only, and prints ns per output face (the minimum and the median of
the runs), output faces per second, peak RSS per output face, and the ratio
of each level's ns/face to level 1's. The CPU column is the process CPU
time (all threads): on a shared machine it leaves out the time the
process waited for a core. Catmull-Clark runs on the 100k-quad
torus, Loop and the others on their inputs in ``bench_subdivision.py``.
Point ``PYTHONPATH`` at another build of the package to measure it instead.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_subdivision import CASES, THREAD_VARS  # noqa: E402


def run(scheme: str, levels: int, threads: int, runs: int) -> dict:
    env = dict(os.environ)
    for k in THREAD_VARS:
        env[k] = str(threads)
    inp = CASES[scheme][0]
    cmd = [sys.executable, str(HERE / "bench_subdivision.py"), "--worker", "--tool", "topomesh", "--scheme", scheme,
           "--input", inp, "--levels", str(levels), "--runs", str(runs)]
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=3600)
    if p.returncode != 0:
        raise RuntimeError(p.stderr.strip().splitlines()[-1])
    return json.loads([ln for ln in p.stdout.splitlines() if ln.startswith("{")][-1])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, nargs="*", default=[1, 2, 3, 4])
    ap.add_argument("--threads", type=int, nargs="*", default=[1, 2])
    ap.add_argument("--schemes", nargs="*", default=["catmull_clark", "loop"])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--label", default="")
    a = ap.parse_args()
    print(f"| {a.label} scheme | threads | level | faces | ms (min) | ns/face (min) | ns/face (median) | CPU ns/face (min) | M faces/s | × level 1 | peak B/face |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for scheme in a.schemes:
        for th in a.threads:
            first = None
            for lv in a.levels:
                r = run(scheme, lv, th, a.runs)
                nf = r["faces"]
                tmin, tmed = min(r["times"]), statistics.median(r["times"])
                ns = tmin / nf * 1e9
                first = first or ns
                peak = (r["peak_mb"] - r["base_mb"]) * 2**20 / nf
                cpu = min(r["cpu"]) / nf * 1e9
                print(f"| {scheme} | {th} | {lv} | {nf:,} | {tmin * 1e3:.1f} | {ns:.1f} | {tmed / nf * 1e9:.1f} | {cpu:.1f} | "
                      f"{nf / tmin / 1e6:.1f} | {ns / first:.2f} | {peak:.0f} |", flush=True)


if __name__ == "__main__":
    main()
