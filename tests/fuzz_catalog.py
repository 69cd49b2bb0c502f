"""The catalog's fuzz target (issue 16): every entry of ``topomesh.catalog()``
called on seeded random meshes with random arguments, its output checked.

The core fuzz target (``tests/fuzz.py``) drives the operators and the ten
smoothing schemes; this one drives the rest of the catalog (TopMod's
remeshing menu, extrusions, the high-genus tools, Conway's operators) the way
a user exploring it in a notebook would, on inputs the curated tests do not
hold together: ``tests.fuzz``'s random bases (Platonic solids jittered out of
plane, tori, genus surfaces, random polygon input) after up to two random
operators (self-loops, two-gons, multi-edges, point-spheres, pipes), and the
open test meshes. Arguments are drawn from each entry's own defaults: the
default, edge values (0, 1, -1, tiny, huge), NaN and infinities for floats,
negative and huge integers, face lists with ids out of range. For every call
it asserts:

* nothing but ``MeshError`` is raised (no panic, no other exception type),
* the input is unchanged (its pickle is byte-identical),
* the output validates and round-trips (``tests.fuzz.check_mesh``),
* on a connected closed input (not a point-sphere) called with iterations=1 and the arguments the
  entry's counts are stated for, ``V'``, ``E'`` and ``F'`` are what the
  catalog's formula says (those written in V, E, F and H = 2E; Loop's on
  all-triangle inputs only, midpoint's on inputs without triangles, as the
  entries' ``input`` field says).

Run by hand: ``python -m tests.fuzz_catalog --cases 200000 --seed 1``;
``tests/test_fuzz.py`` runs it in a subprocess, so an abort is a failure.
"""

from __future__ import annotations

import argparse
import pickle
import re
import sys
import time
import traceback
import warnings

import numpy as np

import topomesh
from tests import open_meshes
from tests.fuzz import _base, _op, check_mesh
from topomesh import Mesh, MeshError

ENTRIES = topomesh.catalog()
# formulas in V, E, F, H alone, e.g. "V+2E", "F + V"
_EVALUABLE = re.compile(r"\d*[VEFH](?:[+-]\d*[VEFH])*")
# parameters whose value changes the counts the catalog states (its formulas
# are for the default): the n of t5, k3 …, the columns' segments
_COUNT_PARAMS = {"n", "segments"}
_KINDS = ("cubical", "doo_sabin", "dodecahedral", "icosahedral", "octahedral", "stellate", "double_stellate", "dome",
          "no such kind")


def _number(rng: np.random.Generator, default):
    """A value for a numeric parameter with this default."""
    k = int(rng.integers(0, 10))
    if k < 3:
        return default
    if isinstance(default, bool):
        return bool(rng.integers(2))
    if isinstance(default, int):
        return int(rng.choice([-2, -1, 0, 1, 2, 3, 5, 8, 10**9]))
    if k == 3:
        return float("nan")
    if k == 4:
        return float(rng.choice([np.inf, -np.inf]))
    if k == 5:
        return float(rng.choice([0.0, 1.0, -1.0, 1e12, -1e-12, 0.5]))
    return float(rng.normal(0, 1.5))


def _arguments(rng: np.random.Generator, m: Mesh, entry: dict) -> dict:
    kw = {}
    for name, default in (entry.get("params") or {}).items():
        if name == "faces":
            nf = m.n_faces
            kw[name] = [int(x) for x in rng.integers(-1, nf + 1, int(rng.integers(0, 4)))] if nf else []
        elif name == "kind":
            kw[name] = str(rng.choice(_KINDS))
        elif name == "algorithm":
            kw[name] = default  # the two algorithms are two entries
        elif name in ("lengths", "angle"):
            continue  # extrude's per-face sequences and angle: covered by tests/test_topmod.py
        elif default is None:
            if rng.random() < 0.4:
                kw[name] = _number(rng, 1.0)
        elif isinstance(default, (int, float)):
            kw[name] = _number(rng, default)
    if entry.get("letter") and rng.random() < 0.3 and entry["method"] in ("truncate", "kis", "needle", "zip", "loft"):
        kw["n"] = int(rng.choice([-1, 0, 1, 2, 3, 4, 5, 6]))
    sig = getattr(getattr(m, entry["method"]), "__text_signature__", "") or ""
    if "iterations" in sig and rng.random() < 0.2:
        kw["iterations"] = int(rng.choice([0, 2, -1]))
    return kw


def _base_mesh(rng: np.random.Generator) -> Mesh:
    if rng.random() < 0.2:
        names = sorted(open_meshes.EXPECTED)
        return open_meshes.mesh(names[int(rng.integers(len(names)))])
    m = _base(rng)
    for _ in range(int(rng.integers(0, 3))):
        try:
            m = _op(rng, m)
        except MeshError:
            pass
    return m


def stated_counts_differ(m: Mesh, out: Mesh, entry: dict, kw: dict) -> str | None:
    """Which of V', E', F' differs from the entry's formula: None when all
    agree, "" when no formula applies to this call."""
    # (a connected mesh without edges is a point-sphere, carried unchanged)
    defaults = entry.get("params") or {}
    if kw.get("iterations", 1) != 1 or any(kw[k] != defaults.get(k) for k in _COUNT_PARAMS & kw.keys()):
        return ""
    if m.n_holes or m.n_components != 1 or m.n_edges == 0:
        return ""
    sizes = m.face_sizes
    need = entry.get("input")
    if (need == "triangles" and (sizes != 3).any()) or (need == "no triangles" and (sizes == 3).any()):
        return ""
    c = {"V": m.n_vertices, "E": m.n_edges, "F": m.n_faces, "H": 2 * m.n_edges}
    if not any(_EVALUABLE.fullmatch(entry[k].replace(" ", "")) for k in "VEF"):
        return ""
    got = {"V": out.n_vertices, "E": out.n_edges, "F": out.n_faces}
    for key in "VEF":
        f = entry[key].replace(" ", "")
        if not _EVALUABLE.fullmatch(f):
            continue
        want = sum((-1 if t.startswith("-") else 1) * int(t.lstrip("+-")[:-1] or 1) * c[t[-1]]
                   for t in re.findall(r"[+-]?\d*[VEFH]", f))
        if want != got[key]:
            return f"{key}' = {got[key]}, the catalog's {f} = {want}"
    return None


def run(cases: int, seed: int, start: int = 0) -> tuple[dict, list]:
    st = {"cases": 0, "outputs": 0, "rejected": 0, "counted": 0}
    failures = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topomesh.GeometryWarning)
        for case in range(start, start + cases):
            st["cases"] += 1
            rng = np.random.default_rng([seed, case])
            try:
                m = _base_mesh(rng)
            except MeshError:
                st["rejected"] += 1
                continue
            if m.n_faces > 300:  # the dome's 58 faces per edge, three levels deep, stay small
                continue
            entry = ENTRIES[int(rng.integers(len(ENTRIES)))]
            kw = _arguments(rng, m, entry)
            before = pickle.dumps(m)
            try:
                out = getattr(m, entry["method"])(**kw)
                out = out[0] if isinstance(out, tuple) else out
                assert pickle.dumps(m) == before, "the input was modified"
                check_mesh(out)
                st["outputs"] += 1
                bad = stated_counts_differ(m, out, entry, kw)
                st["counted"] += bad is None
                assert not bad, bad
            except MeshError:
                st["rejected"] += 1
            except (Exception, BaseException) as e:  # noqa: B036 - a PanicException is a BaseException
                if isinstance(e, KeyboardInterrupt):
                    raise
                failures.append((case, f"{entry['method']}({kw}) on {m!r}: {type(e).__name__}: {e}\n"
                                       f"{traceback.format_exc(limit=3)}"))
    return st, failures


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=20_000)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--start", type=int, default=0, help="first case number (to rerun a range)")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    st, failures = run(a.cases, a.seed, a.start)
    print(f"{st['cases']} cases, {st['outputs']} outputs checked ({st['counted']} against the stated counts), "
          f"{st['rejected']} MeshError rejections, {len(failures)} failures, {time.perf_counter() - t0:.1f} s")
    for case, msg in failures[:20]:
        print(f"case {case} (seed {a.seed}): {msg}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
