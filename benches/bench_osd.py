"""Catmull-Clark and Loop against OpenSubdiv's own C++ library, called directly (issue 19).

    python benches/bench_osd.py [--levels 1 2 3] [--runs 5]    # writes benches/OSD.md

OpenSubdiv 3.7 (Pixar), built from vendored source by the test-only ``tests/osd/petite`` binary
(``CARGO_TARGET_DIR=target-osd cargo build --release --manifest-path tests/osd/petite/Cargo.toml``;
``.ci/run`` builds it). ``osd-petite --time RUNS`` times, per mesh and after one untimed run, the
median of RUNS runs of Far's uniform refinement (``TopologyDescriptor`` + ``TopologyRefiner`` +
``RefineUniform``: the refined topology in OpenSubdiv's own tables) and of ``PrimvarRefiner``
interpolating the float32 positions through every level. Far refines on one thread. topomesh
builds its whole half-edge mesh with float64 positions; it is timed in a fresh process per case
(``RAYON_NUM_THREADS`` 1 and 2): the first call of the process, then the median of RUNS warm calls.

Inputs, as in bench_subdivision.py: the 400×250 quad torus (100,000 quads) for Catmull-Clark, the
81,920-triangle icosphere for Loop (both closed, no creases: OpenSubdiv's default
``edge_and_corner`` boundary and uniform creasing, which topomesh's defaults equal).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

WORKER = """
import json, statistics, sys, time
import topomesh
scheme, level, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
m = topomesh.torus(400, 250) if scheme == "catmull_clark" else topomesh.icosahedron().loop(6)
f = lambda: getattr(m, scheme)(level)
t = time.perf_counter(); out = f(); first = time.perf_counter() - t
ts = []
for _ in range(runs):
    t = time.perf_counter(); f(); ts.append(time.perf_counter() - t)
print(json.dumps({"first": first, "warm": statistics.median(ts), "faces": len(out.face_sizes)}))
"""


def topomesh_case(scheme: str, level: int, runs: int, threads: int) -> dict:
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    res = subprocess.run([sys.executable, "-c", WORKER, scheme, str(level), str(runs)], capture_output=True, text=True, env=env, check=True)
    return json.loads(res.stdout)


def osd_case(binary: Path, scheme: str, level: int, runs: int) -> dict:
    import numpy as np

    import topomesh
    from tests.osd.petite_ref import _encode

    m = topomesh.torus(400, 250) if scheme == "catmull_clark" else topomesh.icosahedron().loop(6)
    req = {"scheme": scheme, "levels": level, "boundary": "edge_and_corner", "vertices": np.asarray(m.vertices),
           "face_sizes": np.asarray(m.face_sizes), "face_indices": np.asarray(m.face_indices)}
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "req").write_text("1\n" + _encode(req) + "\n")
        subprocess.run([str(binary), "--time", str(runs), str(Path(d) / "req"), str(Path(d) / "resp")], check=True, timeout=3600)
        words = (Path(d) / "resp").read_text().split()
    if words[0] == "error":
        raise RuntimeError(" ".join(words))
    topo, prim, faces = float(words[0]), float(words[1]), int(words[2])
    return {"topology": topo / 1e3, "primvar": prim / 1e3, "total": (topo + prim) / 1e3, "faces": faces}


def main() -> None:
    from tests.osd.petite_ref import available, binary

    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--out", default=str(HERE / "OSD.md"))
    a = ap.parse_args()
    why = available()
    if why:
        sys.exit(why)
    load0 = os.getloadavg()[0]
    rows = []
    for scheme in ("catmull_clark", "loop"):
        for level in a.levels:
            o = osd_case(binary(), scheme, level, a.runs)
            t1 = topomesh_case(scheme, level, a.runs, 1)
            t2 = topomesh_case(scheme, level, a.runs, 2)
            assert t1["faces"] == o["faces"], (scheme, level, t1["faces"], o["faces"])
            rows.append((scheme, level, o, t1, t2))
            print(scheme, level, f"osd {o['total']*1e3:.1f} ms, topomesh 1t warm {t1['warm']*1e3:.1f} first {t1['first']*1e3:.1f}, 2t warm {t2['warm']*1e3:.1f}", flush=True)
    load1 = os.getloadavg()[0]
    lines = [
        "# Catmull-Clark and Loop against OpenSubdiv's library",
        "",
        "Written by `python benches/bench_osd.py` (see its docstring for the method). "
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}; "
        f"OpenSubdiv 3.7.0 (opensubdiv-petite 0.3.1, release build). Load average (1 min) before / after: {load0:.1f} / {load1:.1f}.",
        f"Median of {a.runs} runs after one untimed run; topomesh's first call is the first of a fresh process.",
        "`speed-up` = OpenSubdiv's time (topology + positions, one thread) / topomesh's.",
        "",
        "| scheme | input | level | output faces | OpenSubdiv topology (ms) | OpenSubdiv positions (ms) | OpenSubdiv total (ms) "
        "| topomesh 1 thread warm (ms) | first call (ms) | 2 threads warm (ms) | speed-up 1 thread warm | first call | 2 threads |",
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for scheme, level, o, t1, t2 in rows:
        inp = "torus 100k quads" if scheme == "catmull_clark" else "sphere 82k triangles"
        lines.append(
            f"| {scheme} | {inp} | {level} | {o['faces']:,} | {o['topology']*1e3:.1f} | {o['primvar']*1e3:.1f} | {o['total']*1e3:.1f} "
            f"| {t1['warm']*1e3:.1f} | {t1['first']*1e3:.1f} | {t2['warm']*1e3:.1f} "
            f"| {o['total']/t1['warm']:.1f}× | {o['total']/t1['first']:.1f}× | {o['total']/t2['warm']:.1f}× |"
        )
    text = "\n".join(lines) + "\n"
    print(text)
    Path(a.out).write_text(text)


if __name__ == "__main__":
    main()
