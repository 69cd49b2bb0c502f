"""Issue 19's table: cost per output face at every level, warm and first call,
peak memory per face, against the peers, on one and two threads.

    python benches/bench_levels.py                    # the full table into benches/README.md
    python benches/bench_levels.py --schemes loop catmull_clark --levels 1 2 --no-peers --readme -
    python benches/bench_levels.py --quick --readme - # tiny inputs, printed only

Every case (scheme × input × levels × threads × tool) runs in a fresh process
(``bench_subdivision.py``'s worker): the input is built, then the *first call*
of ``iterations=levels`` in that process is timed on its own (thread pools,
lazy imports and fresh memory included), then ``--runs`` *warm* calls (median).
Inputs: the 82k-triangle icosphere (``sphere``) and the 100k-quad torus
(``torus``), every scheme on both. Columns:

* ``ns/face`` = time / output faces (warm median; first call) and ``× L1``,
  the warm ns/face as a multiple of level 1's (target ≤ 1.3 at level 4).
  ``iterations=L``'s time includes the lower levels, so even a cost per face
  that is the same at every level reads 1 + 1/4 + 1/16 + 1/64 = 1.33 here at
  level 4 for the schemes that quadruple (1.48 for √3, honeycomb and vertex
  truncation, 1.88 for simplest, 4 for dual). The table after it, *cost of
  each level's own step*, divides the last step's time,
  warm(L) − warm(L − 1) of the same run, by its faces: the target read per
  level (``--steps-from PATH`` prints it from a table already written);
  ``M faces/s`` warm (target ≥ 10 on one thread at every level).
* ``2 thr. speed-up`` = the one-thread warm time / the two-thread one
  (target ≥ 1.8 at levels ≥ 2).
* ``peak B/face`` = growth of the process's peak RSS over the built input
  during the first call (read right after it, before any warm run), per
  output face; ``× export`` = that growth over the bytes of the output's
  exported arrays (topomesh: float64 ``vertices``, int64 ``face_sizes`` and
  ``face_indices``; peers: their vertex and face arrays), target ≤ 2.
  ``× export, all runs`` = the same with the peak read after the warm runs
  too: what the allocator kept of one run's freed output while the next ran
  (glibc's heap and per-thread arenas) shows there, not in the first call.
  (Until 2026-12-05 the table gave only the latter, as ``× export``.)
* ``vs fastest peer`` = the fastest peer's warm time / topomesh's (> 1:
  topomesh is faster). Triangle-only peers (trimesh, VTK through pyvista,
  libigl) run on the sphere only; a peer whose estimated time (level-1 time ×
  growth^levels / 3) exceeds ``--budget`` seconds is skipped and named.
  ``OpenSubdiv`` is Pixar's library itself (Far's uniform refinement and
  primvar interpolation of the positions, one thread, timed inside the
  test-only ``osd-petite`` binary as ``bench_osd.py`` does; built by
  ``.ci/run``): Catmull-Clark on both inputs, Loop on the sphere. It has no
  first-call or memory figure (–), and its one-thread time stands in its
  two-thread rows too.

With ``--readme PATH`` (default ``benches/README.md``; ``-`` prints only) the
table replaces the section between ``<!-- issue19-table -->`` markers (added
at the end the first time). The machine's load average is written with it.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))  # tests.osd.petite_ref: OpenSubdiv's library as a peer
from bench_subdivision import CASES, available, run_case  # noqa: E402

SCHEMES = ["catmull_clark", "loop", "midpoint", "doo_sabin", "sqrt3", "simplest", "dual", "honeycomb", "vertex_truncation"]
TRIANGLE_ONLY = {"trimesh", "pyvista", "libigl"}
# faces per level, for the peers' time estimates
GROWTH = {"sqrt3": 3, "simplest": 2, "dual": 1, "honeycomb": 3, "vertex_truncation": 3}
MARK = ("<!-- issue19-table -->", "<!-- /issue19-table -->")


def peers(scheme: str, inp: str) -> list[str]:
    ps = [t for t in CASES[scheme][1][1:] if not (t in TRIANGLE_ONLY and inp != "sphere")]
    # OpenSubdiv's own library (Far, through the test-only osd-petite binary):
    # Catmull-Clark on both inputs, Loop on triangles
    if scheme == "catmull_clark" or (scheme == "loop" and inp == "sphere"):
        ps.append(OSD)
    return ps


OSD = "OpenSubdiv"


def osd_available() -> bool:
    from tests.osd.petite_ref import available as why_not

    return why_not() is None


def run_osd(scheme: str, inp: str, level: int, runs: int, quick: bool, cache: dict) -> dict:
    """OpenSubdiv's Far on one thread (topology + float32 positions, median of
    `runs` after one untimed run, timed inside the binary: `bench_osd.py`).
    Far has no first-call or memory figure here; its rows show them as –.
    The same figure serves the one- and two-thread rows (Far refines on one)."""
    key = (scheme, inp, level)
    if key not in cache:
        import tempfile

        import numpy as np
        from bench_subdivision import make_input
        from tests.osd.petite_ref import _encode, binary

        V, F = make_input(inp, quick)
        sizes = np.full(len(F), F.shape[1], dtype=np.int64)
        req = {"scheme": scheme, "levels": level, "boundary": "edge_and_corner", "vertices": np.asarray(V, dtype=np.float64),
               "face_sizes": sizes, "face_indices": np.asarray(F, dtype=np.int64).ravel()}
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "req").write_text("1\n" + _encode(req) + "\n")
            import subprocess

            subprocess.run([str(binary()), "--time", str(runs), str(Path(d) / "req"), str(Path(d) / "resp")], check=True, timeout=3600)
            words = (Path(d) / "resp").read_text().split()
        if words[0] == "error":
            cache[key] = {"error": " ".join(words)}
        else:
            cache[key] = {"warm": (float(words[0]) + float(words[1])) / 1e3, "faces": int(words[2])}
    return cache[key]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--schemes", nargs="*", default=SCHEMES)
    ap.add_argument("--inputs", nargs="*", default=["sphere", "torus"])
    ap.add_argument("--levels", type=int, nargs="*", default=[1, 2, 3, 4])
    ap.add_argument("--threads", type=int, nargs="*", default=[1, 2])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--budget", type=float, default=20.0, help="skip peer runs estimated above this (s)")
    ap.add_argument("--no-peers", action="store_true")
    ap.add_argument("--quick", action="store_true", help="tiny inputs")
    ap.add_argument("--readme", default=str(HERE / "README.md"), help="file to write the section into, or - to print only")
    ap.add_argument("--steps-from", help="print the per-step table from the issue-19 section of this file, run nothing")
    a = ap.parse_args()
    if a.steps_from:
        print("\n".join(step_table(rows_of_section(Path(a.steps_from).read_text()))))
        return
    load0 = os.getloadavg()
    rows = []
    osd_cache: dict = {}
    for scheme in a.schemes:
        for inp in a.inputs:
            tools = ["topomesh"] + ([] if a.no_peers else [t for t in peers(scheme, inp) if (osd_available() if t == OSD else available(t))])
            l1: dict = {}
            for th in a.threads:
                for lv in a.levels:
                    for tool in tools:
                        row = dict(scheme=scheme, input=inp, level=lv, threads=th, tool=tool)
                        if tool != "topomesh":
                            est = l1.get((tool, th))
                            est = None if est is None else est * GROWTH.get(scheme, 4) ** (lv - min(a.levels))
                            if est is not None and est > a.budget:
                                rows.append({**row, "skip": f"not run: ~{est:.0f} s per call estimated"})
                                continue
                        if tool == OSD:
                            r = run_osd(scheme, inp, lv, a.runs, a.quick, osd_cache)
                            if "error" not in r:
                                if lv == min(a.levels):
                                    l1[(tool, th)] = r["warm"]
                                rows.append({**row, "warm": r["warm"], "first": None, "faces": r["faces"], "grow": None, "grow_all": None, "export": None})
                                print(f"{scheme:17s} {inp:6s} L{lv} t{th} {tool:12s} warm {r['warm'] * 1e3:9.1f} ms (Far, one thread)", flush=True)
                                continue
                        else:
                            r = run_case(tool, scheme, inp, lv, th, a.runs, a.quick)
                        if "error" in r:
                            rows.append({**row, "skip": "error: " + r["error"][:70]})
                            continue
                        warm = statistics.median(r["times"])
                        if lv == min(a.levels):
                            l1[(tool, th)] = warm
                        row.update(warm=warm, first=r["first"], faces=r["faces"], grow=(r["first_peak_mb"] - r["base_mb"]) * 2**20,
                                   grow_all=(r["peak_mb"] - r["base_mb"]) * 2**20,
                                   export=r["export_bytes"])
                        rows.append(row)
                        print(f"{scheme:17s} {inp:6s} L{lv} t{th} {tool:12s} warm {warm * 1e3:9.1f} ms first {r['first'] * 1e3:9.1f} ms "
                              f"{r['faces']:>10,} faces {warm / r['faces'] * 1e9:7.1f} ns/face", flush=True)
    load1 = os.getloadavg()
    text = "\n".join(table(rows, a, load0, load1))
    print(text)
    if a.readme != "-":
        write_section(Path(a.readme), text)


def find(rows: list, **k):
    """The first timed row with the fields `k`, or None."""
    return next((r for r in rows if all(r.get(x) == y for x, y in k.items()) and "warm" in r), None)


def table(rows: list, a, load0, load1) -> list[str]:
    out = [
        MARK[0],
        "## Issue 19: cost per face per level, warm and first call, memory, peers",
        "",
        f"Written by `python benches/bench_levels.py {' '.join(sys.argv[1:])}`".rstrip() + " (method in its docstring). "
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}. "
        f"**Load average (1 min) before / after: {load0[0]:.1f} / {load1[0]:.1f}** (2 cores: above ~1 the figures are inflated).",
        f"Inputs: {'tiny (--quick)' if a.quick else 'icosphere 81,920 triangles (sphere), 400×250 torus 100,000 quads (torus)'}; "
        f"{a.runs} warm runs per case (median), first call timed separately, each case in a fresh process.",
        "",
        "| scheme | input | level | threads | tool | output faces | warm ms | first ms | ns/face warm | ns/face first | × L1 | M faces/s | 2 thr. speed-up | peak B/face | × export | × export, all runs | vs fastest peer |",
        "| --- | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for r in rows:
        head = f"| {r['scheme']} | {r['input']} | {r['level']} | {r['threads']} | {r['tool']} |"
        if "warm" not in r:
            out.append(head + f" – | – | – | – | – | – | – | – | – | – | – | – | {r['skip']} |")
            continue
        nf = r["faces"]
        ns = r["warm"] / nf * 1e9
        base = find(rows, scheme=r["scheme"], input=r["input"], level=min(a.levels), threads=r["threads"], tool=r["tool"])
        x1 = f"{ns / (base['warm'] / base['faces'] * 1e9):.2f}" if base else ""
        one = find(rows, scheme=r["scheme"], input=r["input"], level=r["level"], threads=1, tool=r["tool"])
        sp = f"{one['warm'] / r['warm']:.2f}×" if one and r["threads"] != 1 and r["tool"] != OSD else ""
        xe = f"{r['grow'] / r['export']:.2f}" if r["export"] else "–"
        xa = f"{r['grow_all'] / r['export']:.2f}" if r["export"] else "–"
        vs = ""
        if r["tool"] == "topomesh":
            ps = [p for p in rows if "warm" in p and p["tool"] != "topomesh" and (p["scheme"], p["input"], p["level"], p["threads"]) ==
                  (r["scheme"], r["input"], r["level"], r["threads"])]
            if ps:
                best = min(ps, key=lambda p: p["warm"])
                vs = f"{best['warm'] / r['warm']:.1f}× {best['tool']}"
        first_ms, first_ns = (f"{r['first'] * 1e3:.1f}", f"{r['first'] / nf * 1e9:.1f}") if r["first"] is not None else ("–", "–")
        grow = f"{r['grow'] / nf:.0f}" if r["grow"] is not None else "–"
        out.append(head + f" {nf:,} | {r['warm'] * 1e3:.1f} | {first_ms} | {ns:.1f} | {first_ns} | {x1} | "
                          f"{nf / r['warm'] / 1e6:.1f} | {sp} | {grow} | {xe} | {xa} | {vs} |")
    out += ["", *targets(rows, a), *step_table(rows), MARK[1]]
    return out


def step_table(rows: list) -> list[str]:
    """Cost per face of each level's own step (topomesh rows): the last
    step's time, warm(L) − warm(L − 1) of the same run, over its faces, and
    level 4's as a multiple of level 1's (the issue's ≤ 1.3)."""
    topo = {(r["scheme"], r["input"], r["threads"], r["level"]): r for r in rows if r["tool"] == "topomesh" and "warm" in r}
    keys = sorted({k[:3] for k in topo})
    if not keys:
        return []
    out = ["Cost of each level's own step (warm, ns per output face of that level; docstring):", "",
           "| scheme | input | threads | level 1 | level 2 step | level 3 step | level 4 step | level 4 step × level 1 |",
           "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    met = total = 0
    for k in keys:
        l1 = topo.get((*k, 1))
        if not l1:
            continue
        base = l1["warm"] / l1["faces"] * 1e9
        cells, last = [], None
        for lv in (2, 3, 4):
            a, b = topo.get((*k, lv)), topo.get((*k, lv - 1))
            last = (a["warm"] - b["warm"]) / a["faces"] * 1e9 if a and b else None
            cells.append(f"{last:.1f}" if last is not None else "–")
        x = f"{last / base:.2f}" if last is not None else "–"
        if last is not None:
            total += 1
            met += last / base <= 1.3
        out.append(f"| {k[0]} | {k[1]} | {k[2]} | {base:.1f} | " + " | ".join(cells) + f" | {x} |")
    out += ["", f"* level 4's own step within 1.3× of level 1 per face: {met} of {total}.", ""]
    return out


def rows_of_section(text: str) -> list[dict]:
    """The topomesh rows (scheme, input, level, threads, faces, warm) of an
    issue-19 section already written."""
    sec = text.split(MARK[0], 1)[1].split(MARK[1], 1)[0] if MARK[0] in text else text
    rows = []
    for line in sec.splitlines():
        c = [x.strip() for x in line.strip().strip("|").split("|")]
        if len(c) < 8 or c[4] != "topomesh":
            continue
        try:
            rows.append(dict(scheme=c[0], input=c[1], level=int(c[2]), threads=int(c[3]), tool="topomesh",
                             faces=int(c[5].replace(",", "")), warm=float(c[6]) / 1e3))
        except ValueError:
            continue  # a row that did not run
    return rows


def targets(rows: list, a) -> list[str]:
    """The issue's targets, met or not, from the rows above: topomesh's own
    (throughput, level 4 against level 1, two threads, memory), then the
    peer targets (midpoint ≥ 1.5× libigl, Loop ≥ 5× libigl and VTK,
    Catmull-Clark ahead of OpenSubdiv's library), each per input, level and
    thread count that both tools ran."""
    topo = [r for r in rows if r["tool"] == "topomesh" and "warm" in r]
    if not topo:
        return []
    lines = ["Targets (from the rows above):", ""]
    one = [r for r in topo if r["threads"] == 1]
    slow = [r for r in one if r["faces"] / r["warm"] < 10e6]
    lines.append(f"* ≥ 10 M faces/s on one thread at every level: {'met' if not slow else 'not met'} "
                 f"({len(one) - len(slow)} of {len(one)} rows; slowest "
                 f"{min(r['faces'] / r['warm'] / 1e6 for r in one):.1f} M/s)." if one else "* one thread: not run.")
    top = max(a.levels)
    flat = []
    for r in one:
        if r["level"] == top:
            b = next((x for x in one if (x["scheme"], x["input"], x["level"]) == (r["scheme"], r["input"], min(a.levels))), None)
            if b:
                flat.append((r["warm"] / r["faces"]) / (b["warm"] / b["faces"]))
    if flat and top > min(a.levels):
        lines.append(f"* level {top} within 1.3× of level {min(a.levels)} per face: {sum(f <= 1.3 for f in flat)} of {len(flat)} "
                     f"(worst {max(flat):.2f}×).")
    sp = []
    for r in topo:
        if r["threads"] == 2 and r["level"] >= 2:
            o = next((x for x in one if (x["scheme"], x["input"], x["level"]) == (r["scheme"], r["input"], r["level"])), None)
            if o:
                sp.append(o["warm"] / r["warm"])
    if sp:
        lines.append(f"* ≥ 1.8× on two threads at levels ≥ 2: {sum(s >= 1.8 for s in sp)} of {len(sp)} (lowest {min(sp):.2f}×).")
    mem = [r["grow"] / r["export"] for r in topo if r["export"]]
    if mem:
        lines.append(f"* peak ≤ 2× the exported arrays (first call): {sum(m <= 2 for m in mem)} of {len(mem)} (highest {max(mem):.2f}×).")
        mall = [r["grow_all"] / r["export"] for r in topo if r["export"]]
        lines.append(f"* the same with the warm runs' peak: {sum(m <= 2 for m in mall)} of {len(mall)} (highest {max(mall):.2f}×).")
    # the peer targets: topomesh's warm time against one peer's, same input, level and threads
    def warm(scheme, inp, lv, th, tool):
        r = find(rows, scheme=scheme, input=inp, level=lv, threads=th, tool=tool)
        return None if r is None else r["warm"]

    for scheme, inputs, peer, label, goal, levels in (
        ("midpoint", ["sphere"], "libigl", "libigl `upsample`", 1.5, (1, 3)),
        ("loop", ["sphere"], "libigl", "libigl", 5.0, (1, 3)),
        ("loop", ["sphere"], "pyvista", "VTK (pyvista)", 5.0, (1, 3)),
        ("catmull_clark", ["sphere", "torus"], OSD, "OpenSubdiv's library (its one-thread time)", 1.0, (1, 2, 3)),
    ):
        rs = [(inp, th, lv, p / t) for inp in inputs for th in a.threads for lv in levels if lv in a.levels
              for t, p in [(warm(scheme, inp, lv, th, "topomesh"), warm(scheme, inp, lv, th, peer))] if t and p]
        if rs:
            what = "ahead of" if goal == 1.0 else f"≥ {goal:g}×"
            desc = ", ".join(f"{inp} L{lv} {th} thr. {x:.2f}×" for inp, th, lv, x in rs)
            lines.append(f"* {scheme} {what} {label}: {sum(x > goal if goal == 1.0 else x >= goal for *_, x in rs)} of {len(rs)} ({desc}).")
    lines.append("")
    return lines


def write_section(path: Path, text: str) -> None:
    old = path.read_text() if path.exists() else ""
    if MARK[0] in old and MARK[1] in old:
        pre, rest = old.split(MARK[0], 1)
        post = rest.split(MARK[1], 1)[1]
        new = pre + text + post
    else:
        new = old.rstrip("\n") + "\n\n" + text + "\n"
    path.write_text(new)
    print("wrote", path)


if __name__ == "__main__":
    main()
