"""Cost against face size: every catalog entry, and the tools and schemes
around it, on meshes with a few very large faces (Conway's prism ``Pn``,
antiprism ``An`` and pyramid ``Yn``: two n-gons, or one, beside small faces),
at two sizes n. A row whose time grows by more than 8x for 4x the size
(and takes over 50 ms) is flagged ``<<<``: its cost is quadratic in a face's
size somewhere (issue 16's sweep of 2026-12-06 found the closest-edge
handle, its cleanup, the local crossing check, crossing reports without a
limit, and the open Doo-Sabin and Catmull-Clark rows this way; its second
pass the fans of large convex faces and of high-valence vertices in the
crossing scan, the tools' Builder at such vertices, Menger's planar split,
and corner attributes through open Doo-Sabin and honeycomb).

    python benches/bench_large_faces.py [--sizes 2000 8000] [--seeds P A Y] [--only NAME]

One call per row (the large rows take seconds); times are wall times of
the Python call on one machine, so compare the two columns of a row, not
rows. Open rows remove one n-gon (a hole of n sides beside a real n-gon).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import topomesh
from topomesh import MeshError


def open_of(m: topomesh.Mesh, n: int) -> topomesh.Mesh:
    """``m`` without its first n-gon: a hole of n sides."""
    f = int(np.flatnonzero(m.face_sizes == n)[0])
    idx, sizes = m.face_indices, m.face_sizes
    starts = np.concatenate([[0], np.cumsum(sizes)])
    return topomesh.Mesh.from_polygons(m.vertices, [idx[starts[i]:starts[i + 1]] for i in range(m.n_faces) if i != f])


def big(m: topomesh.Mesh, n: int) -> list[int]:
    return [int(i) for i in np.flatnonzero(m.face_sizes == n)]


def rows():
    """(name, call(mesh, n)) for every catalog entry and the extra calls."""
    out = []
    for e in topomesh.catalog():
        if e["method"] == "dome":
            continue  # 58 faces per edge: its size, not its faces, decides
        params = e.get("params") or {}
        kw = {k: v for k, v in params.items() if v is not None and not isinstance(v, list)}
        takes_faces = "faces" in params

        def call(m, n, e=e, kw=kw, takes_faces=takes_faces):
            k = dict(kw)
            if takes_faces:
                k["faces"] = big(m, n)[:2]
            return getattr(m, e["method"])(**k)

        out.append((e["name"], call))
    out += [
        ("triangulate", lambda m, n: m.triangulate()),
        ("planarize", lambda m, n: m.planarize()),
        ("cut_faces", lambda m, n: m.cut_faces([0])),
        ("convex_hull of the vertices", lambda m, n: topomesh.convex_hull(m.vertices)),
        ("self_intersections", lambda m, n: m.self_intersections()),
        ("wall_thickness", lambda m, n: m.wall_thickness()),
        ("add_handle", lambda m, n: m.add_handle(0, m.n_faces - 1)),
        ("menger (merged)", lambda m, n: m.menger(offset="merged")),
        ("save + load OBJ", lambda m, n: _round_trip(m)),
    ]
    for s in ["catmull_clark", "doo_sabin", "loop", "sqrt3", "dual", "honeycomb"]:
        out.append((f"open {s}", lambda m, n, s=s: getattr(open_of(m, n), s)()))
        out.append((f"open {s} + corner attribute", lambda m, n, s=s: getattr(with_corners(open_of(m, n)), s)()))
    return out


def with_corners(m: topomesh.Mesh) -> topomesh.Mesh:
    """``m`` with one corner attribute of two columns (a value per corner: seams everywhere)."""
    c = int(m.face_sizes.sum())
    return m.with_attributes(corner={"uv": np.arange(2 * c, dtype=float).reshape(c, 2)})


def _round_trip(m):
    import os
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        p = os.path.join(d, "m.obj")
        m.save(p)
        return topomesh.load(p)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs=2, default=[2000, 8000])
    ap.add_argument("--seeds", nargs="+", default=["P", "A", "Y"])
    ap.add_argument("--only", help="rows whose name contains this")
    a = ap.parse_args(argv)
    warnings.simplefilter("ignore", topomesh.GeometryWarning)
    print(f"| seed | row | n = {a.sizes[0]} (ms) | n = {a.sizes[1]} (ms) | ratio | result |")
    print("| --- | --- | ---: | ---: | ---: | --- |")
    for seed in a.seeds:
        meshes = [topomesh.conway(f"{seed}{n}") for n in a.sizes]
        for name, call in rows():
            if a.only and a.only not in name:
                continue
            times = []
            for n, m in zip(a.sizes, meshes):
                t = time.perf_counter()
                try:
                    call(m, n)
                    result = "ok"
                except MeshError as err:
                    result = "MeshError: " + str(err)[:50]
                times.append((time.perf_counter() - t, result))
            ratio = times[1][0] / max(times[0][0], 1e-4)
            flag = " <<<" if ratio > 8 and times[1][0] > 0.05 else ""
            print(f"| {seed} | {name} | {times[0][0] * 1e3:.1f} | {times[1][0] * 1e3:.1f} | {ratio:.1f}{flag} | {times[1][1]} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
