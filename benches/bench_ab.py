"""Old build against new build of the same scheme, alternating in one run.

    python benches/bench_ab.py --old DIR --new DIR [--schemes simplest]
        [--inputs torus sphere] [--levels 1 2 3] [--threads 1 2] [--runs 5] [--rounds 2]

``DIR`` holds a ``topomesh`` package (a copy of ``python/topomesh`` with the
``_core*.so`` of one release build); each case runs as
``bench_subdivision.py``'s worker (fresh process, input built, one untimed
call, then ``--runs`` timed calls of ``iterations=level``) with
``PYTHONPATH=DIR``. Per case the two builds alternate ``--rounds`` times
(old, new, old, new, ...), so a change of machine load hits both alike. The
table gives the median wall and CPU time over all runs of each build and
the ratio new / old of the medians (< 1: the new build is faster), and the
median of each process's first call (fresh memory, no allocator reuse).

Before timing, both builds export every case's output (positions, face
sizes and indices, corner twins) and the SHA-256 of the exports must agree:
the port is only worth timing if the output is bit-identical.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_subdivision import THREAD_VARS, run_case  # noqa: E402

DIGEST = """
import hashlib, sys
import numpy as np
sys.path.insert(0, {here!r})
from bench_subdivision import make_input
import topomesh
V, F = make_input({inp!r}, False)
m = topomesh.Mesh.from_polygons(V, F)
r = getattr(m, {scheme!r})(iterations={levels})
h = hashlib.sha256()
for a in (r.vertices, r.face_sizes, r.face_indices, r.corner_twins):
    h.update(np.ascontiguousarray(a).tobytes())
print(h.hexdigest())
"""


def with_build(d: Path, threads: int) -> None:
    os.environ["PYTHONPATH"] = str(d)
    for k in THREAD_VARS:
        os.environ[k] = str(threads)


def digest(d: Path, scheme: str, inp: str, levels: int) -> str:
    env = dict(os.environ, PYTHONPATH=str(d))
    code = DIGEST.format(here=str(HERE), inp=inp, scheme=scheme, levels=levels)
    p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=3600)
    if p.returncode != 0:
        raise RuntimeError(p.stderr.strip().splitlines()[-1])
    return p.stdout.strip()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", type=Path, required=True)
    ap.add_argument("--new", type=Path, required=True)
    ap.add_argument("--schemes", nargs="*", default=["simplest"])
    ap.add_argument("--inputs", nargs="*", default=["torus", "sphere"])
    ap.add_argument("--levels", type=int, nargs="*", default=[1, 2, 3])
    ap.add_argument("--threads", type=int, nargs="*", default=[1, 2])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--no-check", action="store_true", help="skip the output comparison")
    a = ap.parse_args()
    for d in (a.old, a.new):
        if not (d / "topomesh").is_dir():
            sys.exit(f"{d} has no topomesh package")
    if not a.no_check:
        for scheme in a.schemes:
            for inp in a.inputs:
                for lv in a.levels:
                    ho, hn = digest(a.old, scheme, inp, lv), digest(a.new, scheme, inp, lv)
                    if ho != hn:
                        sys.exit(f"{scheme} {inp} L{lv}: outputs differ between the builds ({ho[:12]} vs {hn[:12]})")
                    print(f"# {scheme} {inp} L{lv}: outputs identical ({hn[:12]})", flush=True)
    print(f"# load average before: {os.getloadavg()[0]:.2f}", flush=True)
    print("| scheme | input | level | threads | output faces | old ms (median) | new ms (median) | new / old | "
          "old CPU ms | new CPU ms | CPU new / old | old first ms | new first ms | first new / old |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    saved = dict(os.environ)
    for scheme in a.schemes:
        for inp in a.inputs:
            for lv in a.levels:
                for th in a.threads:
                    t = {"old": [], "new": []}
                    c = {"old": [], "new": []}
                    fc = {"old": [], "new": []}  # each process's first call
                    faces = None
                    for _ in range(a.rounds):
                        for name, d in (("old", a.old), ("new", a.new)):
                            with_build(d, th)
                            r = run_case("topomesh", scheme, inp, lv, th, a.runs, False)
                            os.environ.clear()
                            os.environ.update(saved)
                            if "error" in r:
                                sys.exit(f"{name} {scheme} {inp} L{lv}: {r['error']}")
                            t[name] += r["times"]
                            c[name] += r["cpu"]
                            fc[name].append(r["first"])
                            faces = r["faces"]
                    mo, mn = statistics.median(t["old"]) * 1e3, statistics.median(t["new"]) * 1e3
                    co, cn = statistics.median(c["old"]) * 1e3, statistics.median(c["new"]) * 1e3
                    fo, fn = statistics.median(fc["old"]) * 1e3, statistics.median(fc["new"]) * 1e3
                    print(f"| {scheme} | {inp} | {lv} | {th} | {faces:,} | {mo:.1f} | {mn:.1f} | {mn / mo:.2f} | "
                          f"{co:.1f} | {cn:.1f} | {cn / co:.2f} | {fo:.1f} | {fn:.1f} | {fn / fo:.2f} |", flush=True)
    print(f"# load average after: {os.getloadavg()[0]:.2f}", flush=True)


if __name__ == "__main__":
    main()
