"""Catalog benchmark (issue 16): every row of ``topomesh.catalog()``, one
level on a ~100k-face input, one thread, in output faces per second against
the issue's target of 10 M output faces/s.

    python benches/bench_catalog.py                    # writes benches/CATALOG.md and benches/catalog.json
    python benches/bench_catalog.py --baseline OLD.json  # adds OLD's figures as the "before" column
    python benches/bench_catalog.py --quick            # a 4k-face input, prints only
    python benches/bench_catalog.py --only ROW ...     # those rows (family/name), prints only

Input: the 400×250 quad torus (100,000 quads, the input of bench_subdivision.py);
rows that need another kind of input say so (dome makes 56 faces per input
edge: it runs on a 100×50 torus, 5,000 quads, for an output of the same size as
the others'). Rows that take a face selection run on
``topomesh.catalog.default_selection`` (three faces, or two for the handles),
made once before the timed calls, so their time is a copy of the input plus a
few faces (and the handles' crossing report): they are listed, but their
faces/s measure the copy. The wireframe tools run with ``thickness`` a
tenth of the shortest edge (their defaults are lengths for a unit solid), and
are timed twice: as called by default, with the crossing report that warns of
self-intersection, and with ``check_crossings=False`` (the tool alone). The process sets RAYON_NUM_THREADS=1 before
topomesh is imported (and OPENBLAS_NUM_THREADS=1). Each row: one untimed warm-up call, then the median of
``--runs`` timed calls (one for rows whose warm-up takes over 2 s) of ``topomesh.catalog.run_entry``. ``vs CC`` is the
row's faces/s over Catmull-Clark's (the fastest builder of the package,
bench_subdivision.py) on the big input, timed between the row's own calls: a
ratio that the machine's load (shared by several jobs) changes much less than
the raw figures. ``M corners/s`` counts output corners (half-edges) instead of
faces, and ``corners vs CC`` divides it by Catmull-Clark's (whose output is
quads: four corners a face): a scheme whose faces are hexagons writes 1.5×
the corners of one whose faces are quads for the same face count. The
speed-up column divides the two runs' ``vs CC``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
import warnings
from pathlib import Path

os.environ["RAYON_NUM_THREADS"] = "1"  # before topomesh (and its rayon pool) is loaded
# OpenBLAS threads spin after a NumPy call: on a 2-core machine they took the
# second core from the timed calls
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

HERE = Path(__file__).resolve().parent
TARGET = 10.0  # M output faces/s (issue 16)
NOTES = "<!-- notes: kept by bench_catalog.py when it rewrites the table above -->"


def inputs(quick: bool):
    import topomesh

    big = topomesh.torus(80, 50) if quick else topomesh.torus(400, 250)
    small = topomesh.torus(20, 10) if quick else topomesh.torus(100, 50)
    return big, small


def overrides(entry, mesh) -> dict:
    """The wireframe tools' defaults are absolute lengths for a unit solid:
    on the fine torus they would overlap their neighbours (a
    self-intersecting output, whose crossing report then dominates the
    time); scale them to the shortest edge instead. Rows that take a face
    selection get ``default_selection`` made here, untimed."""
    import numpy as np
    from topomesh.catalog import default_selection

    kw: dict = {}
    p = entry.get("params", {})
    if "faces" in p and not p["faces"]:
        # the selection is made once, outside the timed calls (as a user
        # holding a selection would): run_entry would otherwise time the
        # centroids and the argsort that pick it
        kw["faces"] = default_selection(entry, mesh)
        if entry["method"] == "multi_face_handle" and p.get("algorithm") == "convex_hull":
            kw.update(scale=0.5, extrude=-0.25)  # as run_entry sets them with its own selection
    if entry["method"] in ("wireframe", "wireframe_columns"):
        v, e = mesh.vertices, mesh.edges
        shortest = float(np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).min())
        kw["thickness"] = 0.1 * shortest
    return kw


# Rows also timed without their optional crossing report (a variant row
# below the default one): the tool alone, what a caller who checks the
# output another way (or knows it is clear) pays.
UNCHECKED = {"wireframe", "wireframe_columns"}


def time_row(entry, mesh, runs: int, ref, extra: dict | None = None) -> tuple[float, int, int, float]:
    """Median time, output faces and output corners of the row, and the
    median faces/s of the reference (Catmull-Clark on the big input) timed
    between its calls."""
    from topomesh.catalog import run_entry

    kw = overrides(entry, mesh) | (extra or {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        out = run_entry(entry, mesh, **kw)  # warm-up
        slow = time.perf_counter() - t0 > 2.0
        ts, rs = [], []
        for _ in range(1 if slow else runs):  # rows over 2 s: one timed call
            rs.append(ref())
            t = time.perf_counter()
            out = run_entry(entry, mesh, **kw)
            ts.append(time.perf_counter() - t)
    return statistics.median(ts), len(out.face_sizes), int(out.face_sizes.sum()), statistics.median(rs)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--baseline", type=Path, help="catalog.json of an earlier run: its M faces/s become the 'before' column")
    ap.add_argument("--only", nargs="*", help="row names (family/name) to run")
    ap.add_argument("--json", type=Path, default=HERE / "catalog.json")
    args = ap.parse_args()

    import topomesh

    big, small = inputs(args.quick)

    def ref() -> float:
        t = time.perf_counter()
        out = big.catmull_clark()
        return len(out.face_sizes) / (time.perf_counter() - t) / 1e6

    ref()
    rows = []
    t_all = time.perf_counter()
    load0 = os.getloadavg()[0]
    for e in topomesh.catalog():
        key = f"{e['family']}/{e['name']}"
        if args.only and key not in args.only:
            continue
        mesh = small if e["method"] == "dome" else big
        variants = [(key, None)]
        if e["method"] in UNCHECKED:
            variants.append((f"{key} (check_crossings=False)", {"check_crossings": False}))
        for name, extra in variants:
            try:
                t, nf, nc, cc = time_row(e, mesh, args.runs, ref, extra)
                rows.append({"row": name, "method": e["method"], "input_faces": mesh.n_faces, "ms": 1e3 * t, "faces": nf, "mfs": nf / t / 1e6,
                             "corners": nc, "mcs": nc / t / 1e6, "cc_mfs": cc})
            except Exception as ex:  # reported in the table, not raised
                rows.append({"row": name, "method": e["method"], "input_faces": mesh.n_faces, "error": f"{type(ex).__name__}: {ex}"[:120]})
            r = rows[-1]
            print(f"{name:45s} " + (f"{r['ms']:9.1f} ms {r['faces']:>10,} faces {r['mfs']:6.2f} M/s, {r['mcs']:6.1f} M corners/s (CC {r['cc_mfs']:5.2f} M faces/s)"
                                    if "ms" in r else r["error"]), flush=True)
    total = time.perf_counter() - t_all
    load1 = os.getloadavg()[0]
    if args.quick or args.only:
        return  # a partial run does not rewrite the table
    args.json.write_text(json.dumps({"rows": rows, "load": [load0, load1]}, indent=1))
    write_table(rows, args.baseline, total, (load0, load1))


def write_table(rows, baseline: Path | None, total: float, load: tuple[float, float]) -> None:
    import topomesh

    before = {}
    if baseline is not None:
        before = {r["row"]: r for r in json.loads(baseline.read_text())["rows"] if "mfs" in r}
    cc = next((r["mfs"] for r in rows if r["row"] == "scheme/Catmull-Clark" and "mfs" in r), None)

    def ref_of(r, whole_run_cc):
        # the Catmull-Clark calls timed between the row's own (older runs: the CC row)
        return r.get("cc_mfs") or whole_run_cc
    cc_before = before.get("scheme/Catmull-Clark", {}).get("mfs")
    ok = [r for r in rows if "mfs" in r]
    met = [r for r in ok if r["mfs"] >= TARGET]

    def corners_vs(r):
        # Catmull-Clark's output is all quads: 4 corners per face
        return r["mcs"] / (4 * ref_of(r, cc)) if "mcs" in r else None
    per_corner = [(corners_vs(r), r["row"]) for r in ok if "mcs" in r]
    lines = [
        "# Catalog benchmark",
        "",
        "Written by `python benches/bench_catalog.py` (see its docstring for the method).",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, topomesh {topomesh.__version__}; "
        f"RAYON_NUM_THREADS=1. Load average (1 min) before / after: {load[0]:.1f} / {load[1]:.1f} (a shared machine: "
        "single figures are noisy, `vs CC` less so).",
        "Input: 400×250 quad torus (100,000 quads); dome on a 100×50 torus (5,000 quads). One level, median of 5 calls.",
        f"Target (issue 16): ≥ {TARGET:.0f} M output faces/s. Met by {len(met)} of {len(ok)} rows. Total run {total:.0f} s.",
        "Per output corner (half-edge), against Catmull-Clark's (4 per face) timed beside the row: `corners vs CC`; the lowest five: "
        + ", ".join(f"{n} {v:.2f}" for v, n in sorted(per_corner)[:5]) + ".",
        "",
        "| row | input faces | output faces | ms | M faces/s | vs CC | M corners/s | corners vs CC |"
        + (" before: M faces/s | before: vs CC | speed-up |" if before else ""),
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |" + (" ---: | ---: | ---: |" if before else ""),
    ]
    for r in rows:
        if "mfs" not in r:
            lines.append(f"| {r['row']} | {r['input_faces']:,} | – | – | – | – | – | – |" + (" | | |" if before else "") + f" error: {r['error']}")
            continue
        vs = r["mfs"] / ref_of(r, cc)
        cv = corners_vs(r)
        line = (f"| {r['row']} | {r['input_faces']:,} | {r['faces']:,} | {r['ms']:.1f} | {r['mfs']:.2f} | {vs:.2f} | "
                + (f"{r['mcs']:.1f} | {cv:.2f} |" if cv is not None else "– | – |"))
        if before:
            b = before.get(r["row"])
            if b and cc_before:
                bvs = b["mfs"] / ref_of(b, cc_before)
                line += f" {b['mfs']:.2f} | {bvs:.2f} | {vs / bvs:.2f}× |"
            else:
                line += " | | |"
        lines.append(line)
    # hand-written notes below the marker survive a new run
    path = HERE / "CATALOG.md"
    old = path.read_text() if path.exists() else ""
    notes = old[old.index(NOTES):] if NOTES in old else NOTES + "\n"
    path.write_text("\n".join(lines) + "\n\n" + notes)
    print(f"wrote {HERE / 'CATALOG.md'}", file=sys.stderr)


if __name__ == "__main__":
    main()
