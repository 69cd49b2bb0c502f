"""Resource safety: the memory budget, Ctrl-C, and argument hygiene (issue 14, items 3, 4, 5, 8).

Anything that could abort the interpreter runs in a subprocess, so a regression fails a test
instead of killing pytest.
"""

from __future__ import annotations

import inspect
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

import topomesh
from topomesh import Mesh, MeshError, _core, ifs

GiB = 1 << 30

# every reproducer of issue 14, item 3: each once aborted the interpreter
REPRODUCERS = [
    "topomesh.cube().catmull_clark(15)",
    "topomesh.cube().loop(15)",
    "topomesh.cube().doo_sabin(15)",
    "topomesh.cube().sqrt3(30)",
    "topomesh.tetrahedron().sierpinski(20)",
    "topomesh.cube().menger(8)",
    "topomesh.torus(10**6, 10**6)",
    # levels that do not grow never meet the memory budget: the work limit refuses them
    "topomesh.cube().dual(10**12)",
    "topomesh.cube().dual_loop(10**12)",
    "topomesh.ifs.subdivide_curve(np.random.default_rng(0).random((6, 3)), 'chaikin', 25)",
    "topomesh.ifs.subdivide_surface(np.random.default_rng(0).random((19, 3)), 'loop', 30)",
]

_CHILD = r"""
import json, resource, sys, time
import numpy as np
import topomesh
limit = int(sys.argv[1])
if limit:
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
for expr in json.loads(sys.argv[2]):
    t = time.perf_counter()
    try:
        eval(expr)
        out = "returned"
    except topomesh.MeshError as e:
        out = "MeshError: " + str(e)
    except Exception as e:
        out = type(e).__name__ + ": " + str(e)
    print(json.dumps([expr, out, time.perf_counter() - t]), flush=True)
"""


def _run_child(limit: int, exprs: list[str]) -> list[list]:
    t = time.perf_counter()
    p = subprocess.run(
        [sys.executable, "-c", _CHILD, str(limit), json.dumps(exprs)], capture_output=True, text=True, timeout=120
    )
    assert p.returncode == 0, f"child died ({p.returncode}): {p.stderr[-2000:]}"
    assert time.perf_counter() - t < 60
    return [json.loads(line) for line in p.stdout.splitlines()]


@pytest.mark.parametrize("limit", [0, 8 * GiB], ids=["no-limit", "RLIMIT_AS-8GiB"])
def test_reproducers_raise_mesh_error_within_a_second(limit):
    rows = _run_child(limit, REPRODUCERS)
    assert [r[0] for r in rows] == REPRODUCERS
    for expr, out, seconds in rows:
        assert out.startswith("MeshError: "), (expr, out)
        assert seconds < 1.0, (expr, seconds)
        call = out.split(": ")[1]
        assert call in expr, (expr, out)  # the message names the call
        if "of work" in out:
            # the iterations asked for and how many one call runs
            assert "iterations = 1000000000000" in out and "at most about" in out, out
        elif "31-bit" not in out:
            # the level, the bytes needed and the budget
            assert "needs about" in out and "memory budget" in out or "refused" in out, out


def test_cli_subdivide_past_the_budget_is_one_line(tmp_path):
    src = tmp_path / "cube.obj"
    topomesh.cube().save(src)
    t = time.perf_counter()
    p = subprocess.run(
        [sys.executable, "-m", "topomesh.cli", "subdivide", str(src), str(tmp_path / "o.obj"), "--scheme", "catmull_clark", "-n", "15"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert time.perf_counter() - t < 30
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert lines[-1].startswith("topomesh: error: catmull_clark: level ") and "memory budget" in lines[-1]
    assert "Traceback" not in p.stderr


def test_refusal_message_names_level_bytes_and_budget():
    with pytest.raises(MeshError, match=r"^catmull_clark: level \d+ of 15 needs about [\d.]+ [kMGTPE]?B, more than the memory budget of [\d.]+ [kMGTPE]?B"):
        topomesh.cube().catmull_clark(15)


def test_set_memory_budget_refuses_then_restores():
    m = topomesh.cube()
    assert topomesh.memory_budget() > 0
    try:
        topomesh.set_memory_budget(100_000)
        assert topomesh.memory_budget() == 100_000
        # a cube's level 3 (384 quads) with the builder's temporaries needs more than 100 kB
        with pytest.raises(MeshError, match=r"catmull_clark: level [345] of 5 needs about .* memory budget of 100\.0 kB"):
            m.catmull_clark(5)
        with pytest.raises(MeshError, match="torus"):
            topomesh.torus(200, 200)
        with pytest.raises(MeshError, match="nbytes = -1"):
            topomesh.set_memory_budget(-1)
    finally:
        topomesh.set_memory_budget(None)
    r = m.catmull_clark(5)
    assert r.n_faces == 6 * 4**5
    r.validate()


def test_budget_from_the_environment():
    code = "import topomesh; print(topomesh.memory_budget()); topomesh.cube().catmull_clark(6)"
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, env={**os.environ, "TOPOMESH_MEMORY_BUDGET": "1M"}
    )
    assert p.stdout.splitlines()[0] == str(1 << 20)
    assert "MeshError: catmull_clark: level" in p.stderr
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, env={**os.environ, "TOPOMESH_MEMORY_BUDGET": "lots"}
    )
    assert "TOPOMESH_MEMORY_BUDGET" in p.stderr and "MeshError" in p.stderr


def test_budget_respects_an_address_space_limit():
    code = (
        "import resource, topomesh; resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30)); "
        "print(topomesh.memory_budget())"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert 0 < int(p.stdout) < 8 * GiB


# ------------------------------------------------------------------ Ctrl-C

_SIGINT_CHILD = r"""
import os, signal, sys, time
import topomesh
caught = [0.0]
def on_sigint(sig, frame):
    caught[0] = time.perf_counter()
    raise KeyboardInterrupt
signal.signal(signal.SIGINT, on_sigint)
setup, call = sys.argv[1], sys.argv[2]
m = eval(setup)
before = (m.n_vertices, m.n_edges, m.n_faces) if m is not None else None
print("ready", flush=True)
t = time.perf_counter()
try:
    eval(call)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", time.perf_counter() - caught[0], flush=True)
    # nothing half-done: the input is intact and the next call runs
    assert m is None or (m.n_vertices, m.n_edges, m.n_faces) == before
    assert topomesh.cube().catmull_clark(2).n_faces == 96
    sys.stderr.write("KeyboardInterrupt\n")
    sys.stderr.flush()
    os._exit(0)
"""


def _interrupt_once(setup, call):
    p = subprocess.Popen([sys.executable, "-c", _SIGINT_CHILD, setup, call], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline().strip() == "ready"
        time.sleep(0.5)
        t = time.perf_counter()
        os.kill(p.pid, signal.SIGINT)
        out, err = p.communicate(timeout=30)
        exit_seconds = time.perf_counter() - t
    finally:
        p.kill()
    assert "finished" not in out, f"{call} finished within the 0.5 s before the signal: lengthen it"
    assert "KeyboardInterrupt" in err, err
    word, latency = out.split()
    assert word == "interrupted"
    return float(latency), exit_seconds


@pytest.mark.parametrize(
    "setup,call",
    [
        ("topomesh.cube()", "m.dual(2 * 10**6)"),  # many short levels
        ("topomesh.torus(2000, 2000)", "m.catmull_clark(1)"),  # one long level (16 M quads)
        # long calls (0.5-3 s each here, repeated to run 3-6 s, so the signal lands inside a call however fast the
        # machine; CI once finished a 0.5 s honeycomb before it): every phase of the scheme polls
        ("topomesh.torus(1000, 1000)", "m.loop(1)"),
        ("topomesh.torus(2000, 2000)", "m.sqrt3(2)"),
        ("topomesh.torus(1400, 1400)", "m.doo_sabin(2)"),
        ("topomesh.torus(2000, 2000)", "[m.honeycomb(1).n_faces for _ in range(8)]"),
        ("topomesh.torus(1400, 1400)", "[m.sierpinski(1).n_faces for _ in range(3)]"),
        ("topomesh.torus(200, 200)", "[m.menger(1).n_faces for _ in range(3)]"),
        ("None", "[topomesh.menger_sponge(5).n_faces for _ in range(20)]"),  # one call now takes ~0.5 s
        ("topomesh.torus(1000, 1000)", "[m.self_intersections() for _ in range(5)]"),
        ("topomesh.torus(3000, 3000)", "[topomesh.Mesh.from_flat(m.vertices, m.face_sizes, m.face_indices) for _ in range(3)]"),
    ],
    ids=["between-levels", "inside-a-level", "loop", "sqrt3", "doo_sabin", "honeycomb", "sierpinski", "menger",
         "menger_sponge", "self_intersections", "from_flat"],
)
def test_ctrl_c_stops_within_half_a_second(setup, call):
    # from the Python handler raising to the call returning. A second try when
    # the first is late: on a loaded 2-core machine one sample was measured at
    # 1.3 s where the quiet machine gives 0.03-0.4 s (most of it freeing the
    # partial output); a call that is always late still fails
    tries = [_interrupt_once(setup, call)]
    if tries[0][0] >= 0.5 or tries[0][1] >= 2.0:
        tries.append(_interrupt_once(setup, call))
    assert any(latency < 0.5 and exit_seconds < 2.0 for latency, exit_seconds in tries), tries


_CONCURRENT_CHILD = r"""
import os, signal, threading, time
import topomesh
m = topomesh.torus(300, 200)
ref = m.catmull_clark(2)
want = (ref.vertices.tobytes(), ref.face_sizes.tobytes(), ref.face_indices.tobytes())
bad, ok, stopped = [0], [0], [0]
done = threading.Event()
def other_thread():
    while not done.is_set():
        try:
            r = m.catmull_clark(2)
        except KeyboardInterrupt:
            stopped[0] += 1  # the Ctrl-C of the main thread's call stops this one too
            continue
        ok[0] += 1
        bad[0] += (r.vertices.tobytes(), r.face_sizes.tobytes(), r.face_indices.tobytes()) != want
t = threading.Thread(target=other_thread)
t.start()
big = topomesh.torus(1000, 1000)
for k in range(6):
    fired = threading.Event()
    def fire():
        os.kill(os.getpid(), signal.SIGINT)
        fired.set()
    try:
        threading.Timer(0.05 + 0.04 * k, fire).start()
        try:
            big.loop(1)  # stopped by the signal, or earlier by the flag the other thread's call still holds set
        finally:
            fired.wait()
        time.sleep(0.1)  # a signal that came after the call ended is raised here
    except KeyboardInterrupt:
        pass
done.set()
t.join()
print(bad[0], ok[0], stopped[0])
"""


def test_ctrl_c_in_one_thread_never_corrupts_another_threads_call():
    # the main thread's Ctrl-C sets the core's process-wide flag, which a
    # call running in another Python thread polls too: its loop bodies skip
    # their work and its next check must still see the flag, or it would
    # take the skipped work (columns never written) as done. The flag is now
    # cleared only once no call runs (`cancel::reset_when_idle`); before,
    # the interrupted call's binding cleared it at once. Every call of the
    # other thread either returns the reference output or an error.
    p = subprocess.run([sys.executable, "-c", _CONCURRENT_CHILD], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    bad, ok, stopped = map(int, p.stdout.split())
    # (stopped > 0: the other thread's calls were running when the flag was set)
    assert bad == 0 and ok > 0 and stopped > 0, (bad, ok, stopped)


# ----------------------------------------------------------- argument probe

BAD = {"negative": -1, "huge": 2**70, "nan": math.nan, "inf": math.inf, "1e300": 1e300, "subnormal": 1e-320}
# parameters whose valid range includes -1 (their other bad values must still be refused)
SIGNED = {("Mesh.double_stellate_misc", "height"), ("Mesh.double_stellate_misc", "curve")}


def _base_calls():
    """Valid calls of every public function and method with numeric parameters."""
    from tests.test_ops import face_at, grid_cube

    cube = topomesh.cube()
    rind = cube.rind(0.1)
    grid = grid_cube(3)
    import pyvista as pv
    import trimesh

    soup_tm = trimesh.creation.box()
    soup_pv = pv.Cube().triangulate()
    top, bottom = face_at(grid, [0, 0, 1]), face_at(grid, [0, 0, -1])
    chaikin = ifs.chaikin(np.random.default_rng(1).random((4, 2)))
    P = np.random.default_rng(2).random((6, 3))
    P2 = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 1.0], [3.0, 0.1]])
    return {
        "torus": (_core.torus, {"major": 8, "minor": 5, "major_radius": 2.0, "minor_radius": 0.5}),
        "genus_surface": (_core.genus_surface, {"g": 2}),
        "menger_sponge": (_core.menger_sponge, {"level": 1}),
        "set_memory_budget": (_core.set_memory_budget, {"nbytes": None}),
        "ifs_hex_lattice": (_core.ifs_hex_lattice, {"radius": 2}),
        "ifs_curve_subdivide": (_core.ifs_curve_subdivide, {"control_points": P, "stencils": ifs.curve_stencils("chaikin"), "levels": 2, "arity": 2}),
        "ifs_surface_subdivide": (ifs.subdivide_surface, {"control_points": np.random.default_rng(3).random((19, 3)), "scheme": "loop", "levels": 1}),
        "ifs_curve": (_core.ifs_curve, {"control_points": P2, "stencils": ifs.curve_stencils("chaikin"), "arity": 2}),
        "ifs_bspline": (_core.ifs_bspline, {"control_points": P2, "degree": 1, "knots": [0, 1, 2, 3], "pieces": [(1, 1.5), (1.5, 2)]}),
        **{
            f"Mesh.{s}": (getattr(cube, s), {"iterations": 1})
            for s in ("catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual", "sierpinski")
        },
        "Mesh.honeycomb": (cube.honeycomb, {"iterations": 1, "t": 0.5, "tension": 0.5}),
        "Mesh.vertex_truncation": (cube.vertex_truncation, {"iterations": 1, "mode": "polyhedral", "ratio": 0.3}),
        "Mesh.menger": (cube.menger, {"iterations": 1, "thickness": 0.3, "collapse_angle": 90.0, "offset": "merged"}),
        # --- TopMod remeshing and extrusions (issue 16) ---
        **{f"Mesh.{s}": (getattr(cube, s), {"iterations": 1}) for s in ("stellate_edge_removal", "linear_vertex_insertion", "root3", "dual_loop", "doo_sabin_bc")},
        "Mesh.stellate": (cube.stellate, {"iterations": 1, "offset": 0.1}),
        "Mesh.double_stellate": (cube.double_stellate, {"iterations": 1, "offset": 0.1}),
        "Mesh.double_stellate_misc": (cube.double_stellate_misc, {"iterations": 1, "height": 0.1, "curve": 0.1}),
        "Mesh.doo_sabin_bc_new": (cube.doo_sabin_bc_new, {"iterations": 1, "scale": 1.0, "length": 1.0}),
        "Mesh.wireframe_columns": (cube.wireframe_columns, {"thickness": 0.1, "segments": 4, "check_crossings": True}),
        "Mesh.corner_cutting": (cube.corner_cutting, {"iterations": 1, "alpha": 0.6}),
        "Mesh.modified_corner_cutting": (cube.modified_corner_cutting, {"iterations": 1, "thickness": 0.2}),
        "Mesh.loop_style": (cube.loop_style, {"iterations": 1, "length": 0.5}),
        **{f"Mesh.{s}": (getattr(cube, s), {"iterations": 1, "weight": 0.3, "twist": 0.2}) for s in ("root4", "dual_loop_style", "hexagon_preserving", "dual_hexagon_preserving")},
        **{f"Mesh.{s}": (getattr(cube, s), {"iterations": 1, "offset": 0.2}) for s in ("pentagonalize", "cubic_pentagonalize", "dual_pentagonalize")},
        **{f"Mesh.{s}": (getattr(cube, s), {"iterations": 1, "scale": 0.6}) for s in ("pentagon_preserving", "dual_pentagon_preserving", "dual_12_6_4", "remesh_12_6_4")},
        **{f"Mesh.{s}": (getattr(cube, s), {"iterations": 1, "thickness": 0.3}) for s in ("checkerboard", "dual_checkerboard")},
        "Mesh.dome": (cube.dome, {"iterations": 1, "length": 0.5, "scale": 0.5}),
        "Mesh.fractal": (cube.fractal, {"iterations": 1, "offset": 0.5}),
        "Mesh.subdivide_faces": (cube.subdivide_faces, {"faces": [0], "quads": True}),
        "Mesh.extrude": (cube.extrude, {"faces": [0], "kind": "cubical", "length": 0.5, "scale": 0.5, "twist": 10.0, "segments": 2, "angle": None, "lengths": None}),
        "Mesh.rind": (cube.rind, {"thickness": 0.1}),
        "Mesh.mark_creases": (cube.mark_creases, {"angle": 30.0}),
        "Mesh.printable": (cube.printable, {"min_thickness": 0.5}),
        "Mesh.subdivide_edge": (cube.subdivide_edge, {"edge": 0, "t": 0.5}),
        # a tunnel and a straight pipe through a 3 x 3 grid cube: valid calls free of crossings
        "Mesh.from_trimesh": (Mesh.from_trimesh, {"tm": soup_tm, "repair": True, "tolerance": 1e-9}),
        "Mesh.from_pyvista": (Mesh.from_pyvista, {"data": soup_pv, "repair": True, "tolerance": 1e-9}),
        "Mesh.add_handle": (grid.add_handle, {"face_a": top, "face_b": bottom, "segments": 4, "weights": (-1.0, -1.0), "pinch": 1.0, "pinch_center": 0.5, "pinch_width": 1.0, "extra_twists": 0}),
        "Mesh.insert_edge": (cube.insert_edge, {"face1": 0, "position1": 0, "face2": 0, "position2": 2}),
        "Mesh.connect_edges": (cube.connect_edges, {"face1": 0, "position1": 0, "face2": 1, "position2": 0}),
        "Mesh.create_pipe": (grid.create_pipe, {"face1": top, "position1": 0, "face2": bottom, "position2": 2}),
        "Mesh.delete_edge": (cube.delete_edge, {"edge": 0}),
        "Mesh.delete_edge_with_cleanup": (cube.delete_edge_with_cleanup, {"edge": 0}),
        "Mesh.collapse_edge": (cube.collapse_edge, {"edge": 0}),
        "Mesh.delete_vertex": (cube.create_vertex([0, 0, 5])[0].delete_vertex, {"vertex": 8}),
        "Rind.face_pair": (rind.face_pair, {"face": 0}),
        "IFS.fixed_point": (chaikin.fixed_point, {"i": 0}),
        "IFS.iterate": (chaikin.iterate, {"start": [[0.0]], "levels": 2}),
        "IFS.subdivide": (chaikin.subdivide, {"levels": 2}),
        "IFS.polyline": (chaikin.polyline, {"levels": 2}),
        "IFS.chaos_game": (chaikin.chaos_game, {"n_points": 10, "seed": 0}),
        "IFS.mesh": (ifs.loop(np.random.default_rng(4).random((19, 3))).mesh, {"levels": 1}),
        # issue 16: Conway operators
        "conway": (topomesh.conway, {"notation": "tC", "seed": None}),
        "Mesh.conway": (cube.conway, {"notation": "t"}),
        **{f"Mesh.{op}": (getattr(cube, op), {"n": 4}) for op in ("kis", "truncate", "needle", "zip", "loft")},
        "Mesh.canonicalize": (lambda **kw: cube.canonicalize(**kw)[0], {"iterations": 5, "tol": 1e-8}),
        # issue 16: tools
        "Mesh.planarize": (lambda **kw: cube.planarize(**kw)[0], {"iterations": 3, "tol": 1e-9}),
        "Mesh.spherize": (cube.spherize, {"radius": 1.5}),
        "Mesh.split_valence2_vertices": (cube.subdivide_all_edges().split_valence2_vertices, {"offset": 0.1}),
        "Mesh.subdivide_all_edges": (cube.subdivide_all_edges, {"n": 2}),
        "Mesh.wireframe": (cube.wireframe, {"thickness": 0.1, "width": 0.1, "check_crossings": True}),
        "Mesh.multi_face_handle": (cube.multi_face_handle, {"faces": [0, 1], "scale": 0.5, "extrude": 0.5, "algorithm": "convex_hull"}),
        "Mesh.rind_by_scaling": (cube.rind_by_scaling, {"scale": 0.8}),
        "Mesh.cut_vertices": (cube.cut_vertices, {"vertices": [0], "offset": 0.25}),
        "Mesh.cut_edges": (cube.cut_edges, {"edges": [0], "offset": 0.25}),
        "Mesh.cut_faces": (cube.cut_faces, {"faces": [0], "offset": 0.25}),
        # issue 19: the allocator's block cache (0 turns it off)
        "set_block_cache": (_core.set_block_cache, {"nbytes": 0}),
    }


# parameters that are not numbers (arrays, names, flags), or numbers only as a list
NOT_NUMERIC = {
    "self", "control_points", "scheme", "stencils", "knots", "pieces", "name", "mode", "progress", "absolute",
    "start", "vertices", "faces", "face_sizes", "face_indices", "close_boundaries", "boundaries", "allow_multi_edges", "path",
    "points", "point", "weights", "corners", "keep", "other", "probabilities", "return_faces", "blocks",
    "matrices", "translations", "reference", "tm", "data", "repair", "twins", "options",
    # issue 15: flags, option names and data arrays (checked in tests/test_creases.py); a
    # crease's sharpness may be inf (infinitely sharp), so it is probed there, not here
    "correspondence", "boundary", "crease_method", "corner_interpolation", "edge_sharpness", "vertex_sharpness",
    "vertex", "face", "corner", "sharpness",
    # issue 16: index lists and a point
    "edges", "center",
    # issue 17: flags of the Menger thickness reduction
    "reduce_thickness", "report",
}
# names that are numeric elsewhere but a choice of words here
NOT_NUMERIC_OF = {"Mesh.menger": {"offset"}}  # "merged" | "per_face" (checked in tests/test_menger_offset.py)


def _public_callables():
    out = {}
    for name in dir(_core):
        obj = getattr(_core, name)
        if name.startswith("_") or not callable(obj):
            continue
        if inspect.isclass(obj):
            if issubclass(obj, BaseException):
                continue
            for m in vars(obj):
                if not m.startswith("_") and callable(getattr(obj, m)):
                    out[f"{name}.{m}"] = getattr(obj, m)
        else:
            out[name] = obj
    return out


def test_probe_covers_every_public_numeric_parameter():
    base = _base_calls()
    for name, fn in _public_callables().items():
        try:
            params = [p for p in inspect.signature(fn).parameters if p not in NOT_NUMERIC | NOT_NUMERIC_OF.get(name, set())]
        except ValueError:
            continue
        if params:
            assert name in base, f"{name}{params}: add it to the argument probe"
            assert set(params) <= set(base[name][1]), (name, params)


def _probe_cases():
    for name, (fn, kw) in _base_calls().items():
        for param, value in kw.items():
            numeric = isinstance(value, (int, float)) and not isinstance(value, bool)
            if not (numeric or param == "nbytes"):
                continue
            for label, bad in BAD.items():
                yield pytest.param(name, param, bad, id=f"{name}-{param}-{label}")


@pytest.mark.parametrize("name,param,bad", list(_probe_cases()))
def test_bad_numeric_argument_is_a_named_error(name, param, bad):
    fn, kw = _base_calls()[name]
    fn(**kw)  # the base call is valid
    args = {**kw, param: bad}
    is_int_param = isinstance(kw[param], int) or kw[param] is None
    # "face1", "face_a" and "position2" may be reported as "face" and "position"
    stem = param.rstrip("12").removesuffix("_a").removesuffix("_b")
    try:
        with warnings.catch_warnings():
            if bad == 1e-320:
                # a subnormal length is positive, so in range: the degenerate
                # result may be warned about (self-intersection), not refused
                warnings.simplefilter("ignore", topomesh.GeometryWarning)
            r = fn(**args)
    except MeshError as e:
        assert stem in str(e), f"{name}({param}={bad!r}): {e}"
        # numbers written briefly: 1e300, not 301 digits (nor 2.2e-308 for "positive")
        assert len(str(e)) < 600 and not re.search(r"\d{30}", str(e)) and "e-308" not in str(e), f"{name}({param}={bad!r}): {e}"
        return
    except TypeError as e:
        # a float where an integer is required: Python's own TypeError naming the argument
        text = " ".join([str(e), *getattr(e, "__notes__", [])])
        assert is_int_param and isinstance(bad, float) and param in text, f"{name}({param}={bad!r}): {text}"
        return
    except Exception as e:  # noqa: BLE001
        pytest.fail(f"{name}({param}={bad!r}) raised {type(e).__name__}: {e}")
    # accepted: only a huge but finite length, or -1 where the documented range
    # is [-1, 1] (TopMod's signed height and curve), where the result must be valid
    signed = (name, param) in SIGNED and bad == -1
    # a subnormal is a positive number: accepted where the range is (0, x] or [0, x]
    assert signed or (not is_int_param and bad in (2**70, 1e300, 1e-320)), f"{name}({param}={bad!r}) was accepted"
    if isinstance(r, topomesh.PrintReport):
        if bad != 1e-320:
            assert not r.ok and len(r.thin_faces) == len(r.thickness)  # every wall is thinner than that
    else:
        r = r[0] if isinstance(r, tuple) else r
        (r.mesh if isinstance(r, topomesh.Rind) else r).validate()


# ------------------------------------------------------- smaller wrong answers


def test_menger_absolute_thickness_is_bounded():
    with pytest.raises(MeshError, match=r"thickness = 10 \(absolute\) is out of range; on this mesh it must be in \(0, 1"):
        topomesh.cube().menger(1, thickness=10, absolute=True)
    ok = topomesh.cube().menger(1, thickness=0.5, absolute=True)
    ok.validate()
    assert ok.volume > 0


@pytest.mark.parametrize("angle", [math.nan, math.inf, -1.0, 181.0])
def test_menger_collapse_angle_range(angle):
    with pytest.raises(MeshError, match=r"collapse_angle = .* must be a finite angle in \[0, 180\]"):
        topomesh.cube().menger(1, collapse_angle=angle, offset="merged")


def test_menger_collapse_angle_is_refused_where_it_does_not_apply():
    """The per-face construction (the default) collapses no edge: an angle
    passed with it is an error naming the construction it belongs to, not a
    silently ignored keyword; with offset="merged" it still works."""
    with pytest.raises(MeshError, match=r'collapse_angle = 120 applies to offset="merged" only'):
        topomesh.dodecahedron().menger(1, collapse_angle=120.0)
    with pytest.raises(MeshError, match=r'collapse_angle = 90 applies to offset="merged" only'):
        topomesh.cube().menger(1, 1 / 3, False, 90.0)  # positionally too
    d = topomesh.dodecahedron()
    wide = d.menger(1, collapse_angle=120.0, offset="merged")  # every dodecahedron edge (116.6°) collapses
    assert wide.n_faces < d.menger(1, offset="merged").n_faces
    assert d.menger(1, offset="merged", collapse_angle=90.0) == d.menger(1, offset="merged")


def test_peeling_every_face_is_refused():
    r = topomesh.cube().rind(0.1)
    with pytest.raises(MeshError, match="peel: selecting all 6 remaining outer faces would leave nothing"):
        r.peel(range(6))
    p = r.peel(range(5))
    p.mesh.validate()
    assert p.mesh.n_faces > 0
    with pytest.raises(MeshError, match="peel: selecting all 1 remaining"):
        p.peel([5])
    # punching them all keeps the walls: a frame of genus F - 1
    assert r.punch(range(6)).mesh.genus == 5


@pytest.mark.parametrize("call", ["from_trimesh", "printable"])
@pytest.mark.parametrize("bad", [None, 3, "cube.obj", np.zeros((4, 3))], ids=["None", "int", "str", "array"])
def test_wrong_object_is_a_named_error(call, bad):
    # a demanding user's first mistake: passing something else than the mesh
    fn = {"from_trimesh": topomesh.Mesh.from_trimesh, "printable": lambda m: topomesh.printable(m, 0.1)}[call]
    with pytest.raises(MeshError, match=rf"{call}: expected a .*, got {type(bad).__name__}"):
        fn(bad)


def _odd_meshes():
    """Meshes a demanding user hands over: every special structure the core
    holds, and geometry that breaks naive code (zero, flat, huge, tiny)."""
    c = topomesh.cube()
    v = c.vertices
    flat = v.copy()
    flat[:, 2] = 0
    ico = topomesh.icosahedron()
    return {
        "two_gon": c.insert_edge(0, 0, 0, 1)[0],
        "self_loop": c.insert_edge(0, 0, 0, 0)[0],
        "point_sphere": c.create_vertex([5.0, 5.0, 5.0])[0],
        "open": Mesh.from_polygons(v, c.face_indices.reshape(-1, 4)[1:]),
        "triangle": Mesh.from_polygons(np.eye(3), [[0, 1, 2]]),
        "all_zero": c.with_vertices(np.zeros_like(v)),
        "flat": c.with_vertices(flat),
        "huge": c.with_vertices(v * 1e300),
        "near_max": c.with_vertices(v * 1.5e308),  # centroids overflow: a MeshError, not an invalid mesh
        "tiny": c.with_vertices(v * 1e-300),
        "jittered": ico.with_vertices(ico.vertices + np.random.default_rng(0).normal(0, 0.3, (12, 3))),
        "genus2": topomesh.genus_surface(2),
        "genus2_near_max": topomesh.genus_surface(2).with_vertices(topomesh.genus_surface(2).vertices * 5e307),
    }


# display, files and peers' objects: their own tests cover them
_NOT_SWEPT = {"save", "show", "plot", "to_pyvista", "to_manifold", "to_trimesh", "explore", "widget"}


def _invalid(m: Mesh) -> str | None:
    """Why ``m`` is not a valid mesh with finite positions, or None."""
    try:
        m.validate()
    except MeshError as e:
        return str(e)
    if not np.isfinite(m.vertices).all():
        return "non-finite positions"
    return None


def test_every_method_with_its_defaults_on_odd_meshes():
    # every public attribute of Mesh that runs without arguments, on each odd
    # mesh: a valid result (meshes validate) or a MeshError, never another
    # exception, a panic (pyo3's PanicException) or an invalid mesh
    import warnings

    calls, problems = 0, []
    for mname, m in _odd_meshes().items():
        for name in dir(Mesh):
            if name.startswith("_") or name in _NOT_SWEPT:
                continue
            try:
                attr = getattr(m, name)
                if callable(attr):
                    sig = inspect.signature(attr)
                    if any(p.default is inspect.Parameter.empty and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
                           for p in sig.parameters.values()):
                        continue
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")  # warnings are answers too (crossings, dropped data)
                        r = attr()
                    calls += 1
                    r = r[0] if isinstance(r, tuple) and r and isinstance(r[0], Mesh) else r
                    if isinstance(r, Mesh):
                        # outside the MeshError below: an answer that fails validation is a problem
                        bad = _invalid(r)
                        if bad:
                            problems.append(f"{mname}.{name}: returned an invalid mesh: {bad}")
            except MeshError:
                pass
            except BaseException as e:  # noqa: BLE001 (panics derive from BaseException)
                problems.append(f"{mname}.{name}: {type(e).__name__}: {e}")
    assert not problems, "\n".join(problems)
    assert calls > 500, calls  # the sweep does call the methods


# default parameters in absolute units (TopMod's), so not scale-free by design
_ABSOLUTE_DEFAULTS = {"dome", "fractal", "modified_corner_cutting", "wireframe_columns"}


@pytest.mark.parametrize("k", [2.0**600, 2.0**-600, 1e300, 1e-300])
def test_every_method_is_scale_free_at_extreme_coordinates(k):
    # coordinates near float64's ends are valid input: squared lengths and
    # cross products overflow past ~1e154 and underflow below ~1e-154, which
    # once gave NaN apices (kis and the seven operators built on it), lost
    # normals and misleading errors. Every method with its defaults gives the
    # scaled answer (canonicalize the same answer: it normalizes the size),
    # or a MeshError that names the coordinates (menger), never NaN or a
    # silently different shape.
    import warnings

    ico = topomesh.icosahedron()
    meshes = {"cube": topomesh.cube(), "genus2": topomesh.genus_surface(2),
              "jittered": ico.with_vertices(ico.vertices + np.random.default_rng(0).normal(0, 0.3, (12, 3)))}
    problems, compared = [], 0
    for mname, m in meshes.items():
        big = m.with_vertices(m.vertices * k)
        for name in dir(Mesh):
            if name.startswith("_") or name in _NOT_SWEPT or name in _ABSOLUTE_DEFAULTS:
                continue
            attr = getattr(m, name)
            if not callable(attr) or any(p.default is inspect.Parameter.empty and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
                                         for p in inspect.signature(attr).parameters.values()):
                continue
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    want = attr()
                except MeshError:
                    continue
                want = want[0] if isinstance(want, tuple) and want and isinstance(want[0], Mesh) else want
                if not isinstance(want, Mesh):
                    continue
                try:
                    got = getattr(big, name)()
                except MeshError as e:
                    if not (name == "menger" and "coordinates reach" in str(e)):
                        problems.append(f"{mname}.{name} ×{k:g}: MeshError {e}")
                    continue
            got = got[0] if isinstance(got, tuple) else got
            if got.n_vertices != want.n_vertices or not np.array_equal(got.face_indices, want.face_indices):
                problems.append(f"{mname}.{name} ×{k:g}: different connectivity")
                continue
            g = got.vertices if name == "canonicalize" else got.vertices / k
            err = np.abs(g - want.vertices).max() / max(np.abs(want.vertices).max(), 1e-300)
            compared += 1
            if not err < 1e-9:
                problems.append(f"{mname}.{name} ×{k:g}: relative error {err:.3g}")
    assert not problems, "\n".join(problems)
    assert compared > 150, compared


def _typical_arguments(m: Mesh) -> dict:
    """Plausible arguments for the methods that need some, on ``m``."""
    nf, ne = m.n_faces, m.n_edges
    conway = "d a t k j e o g s b m n z c u w v p q l r dtk t5 k3".split()
    return {
        "add_handle": [dict(face_a=0, face_b=min(2, nf - 1))],
        "collapse_edge": [dict(edge=0), dict(edge=ne - 1)],
        "conway": [dict(notation=s) for s in conway],
        "create_face_manifold": [dict(points=[[0, 0, 0], [1, 0, 0], [0, 1, 0]])],
        "create_vertex": [dict(point=[1, 2, 3])],
        "cut_edges": [dict(edges=[0])], "cut_faces": [dict(faces=[0])], "cut_vertices": [dict(vertices=[0])],
        "delete_edge": [dict(edge=0)], "delete_edge_with_cleanup": [dict(edge=0)], "delete_vertex": [dict(vertex=0)],
        "extrude": [dict(faces=[0]), dict(faces=list(range(nf)))],
        "multi_face_handle": [dict(faces=list(range(min(3, nf))))],
        "printable": [dict(min_thickness=0.1)],
        "rind": [dict(thickness=0.1)], "rind_by_scaling": [dict(scale=0.5)],
        "subdivide_edge": [dict(edge=0)], "subdivide_faces": [dict(faces=[0])],
        "wireframe": [dict(thickness=0.1), dict(thickness=0.05, width=0.2)],
    }


def test_methods_with_required_arguments_on_odd_meshes():
    # the methods the defaults sweep skips, with typical arguments: a valid
    # mesh with finite positions or a MeshError, nothing else
    import warnings

    calls, problems = 0, []
    for mname, m in _odd_meshes().items():
        for name, kws in _typical_arguments(m).items():
            for kw in kws:
                try:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        r = getattr(m, name)(**kw)
                except MeshError:
                    continue
                except BaseException as e:  # noqa: BLE001
                    problems.append(f"{mname}.{name}({kw}): {type(e).__name__}: {e}")
                    continue
                calls += 1
                for x in r if isinstance(r, tuple) else (r,):
                    bad = _invalid(x) if isinstance(x, Mesh) else None
                    if bad:
                        problems.append(f"{mname}.{name}({kw}): returned an invalid mesh: {bad}")
    assert not problems, "\n".join(problems)
    assert calls > 150, calls


@pytest.mark.parametrize("k", [1e300, 1e100, 1e-100, 1e-300])
def test_convex_hull_at_extreme_coordinates(k):
    # 50 random points times 1e100 used to panic (the predicates' products
    # overflowed), times 1e-300 to be called collinear (they underflowed)
    p = np.random.default_rng(1).normal(size=(50, 3))
    want, got = topomesh.convex_hull(p), topomesh.convex_hull(p * k)
    assert np.array_equal(got.face_indices, want.face_indices)
    assert np.array_equal(got.vertices, want.vertices * k)  # the given points, exactly


def test_convex_hull_of_far_clusters_is_an_error_not_a_panic():
    # three clusters of unit size 1e17 apart: the coplanar merging folded the
    # hull into too few polygons and an unwrap panicked; a handle extruded
    # 1e10 from a unit cube's faces reached the same hull
    p = np.array([[0, 0, 1e17], [1, 0, 1e17], [0, 1, 1e17], [1, 1, 1e17], [0, 0, -1e17], [1, 0, -1e17],
                  [1e17, 0, 0], [1e17, 1, 0], [1e17, 1, 1]], float)
    # since the hull's visibility became strict (no face re-fanned per
    # coplanar point) these merge into seven polygons: a closed hull at the
    # documented tolerance (1e-9 of the extent, here 2e8, far above the
    # clusters' unit size), or the error saying the merging went too far
    try:
        h = topomesh.convex_hull(p)
    except MeshError as e:
        assert "too few to bound a volume" in str(e)
    else:
        h.validate()
        assert h.is_closed and h.genus == 0 and len(h.face_sizes) >= 4 and (h.face_sizes >= 3).all()
    with pytest.raises(MeshError, match="multi_face_handle"):
        topomesh.cube().multi_face_handle([0, 1, 2], extrude=1e10)


@pytest.mark.parametrize("bad", [[], [0, 0], "abc", [1, 2, 3, 4]])
def test_points_of_the_wrong_length_name_the_parameter(bad):
    # pyo3's own conversion said "expected a sequence of length 3" as a ValueError
    with pytest.raises(MeshError, match="create_vertex: point must be three real numbers"):
        topomesh.cube().create_vertex(bad)
    with pytest.raises(MeshError, match="spherize: center must be three real numbers"):
        topomesh.cube().spherize(center=bad)


def test_budget_refuses_the_dense_stencils_of_a_large_face():
    """Stencils over an n-gon hold about n² terms for Catmull-Clark, Loop,
    Doo-Sabin and honeycomb: a level that needs them (corner data through
    the generic transfer on an open mesh, a subdivision matrix) is refused
    before it is built when they would not fit (an open mesh's 32,000-gon
    would take about 33 GB), while the same level without them runs, and
    so do Doo-Sabin and honeycomb with corner data: they write a large
    face's corners without its rows."""
    p = topomesh.conway("P2000")
    sizes, idx = p.face_sizes, p.face_indices
    starts = np.concatenate([[0], np.cumsum(sizes)])
    cap = int(np.flatnonzero(sizes == 2000)[0])
    m = topomesh.Mesh.from_polygons(p.vertices, [idx[starts[f]:starts[f + 1]] for f in range(p.n_faces) if f != cap])
    assert m.n_holes == 1 and m.face_sizes.max() == 2000
    c = int(m.face_sizes.sum())
    uv = m.with_attributes(corner={"uv": np.arange(2 * c, dtype=float).reshape(c, 2)})
    try:
        topomesh.set_memory_budget(64 << 20)
        assert m.honeycomb().n_faces > 0  # positions only: no stencils
        with pytest.raises(MeshError, match=r"honeycomb: its stencils .* about 4000000 terms over face \d+ of 2000 corners .* memory budget"):
            m.honeycomb(correspondence=True)
        # corner data: Doo-Sabin and honeycomb write the large face's
        # corners themselves, without its rows
        for s in ("doo_sabin", "honeycomb"):
            out = getattr(uv, s)()
            assert out.corner_attributes["uv"].shape == (out.face_sizes.sum(), 2)
        # Loop's corner data go through its face-varying mesh, whose level
        # needs no stencils; its matrix does (3 terms per pair)
        with pytest.raises(MeshError, match=r"loop: its stencils .* about 12000000 terms"):
            m.loop(correspondence=True)
        with pytest.raises(MeshError, match=r"catmull_clark: its stencils .* about 8000000 terms"):
            m.catmull_clark(correspondence=True)
        # the dual's rows over a face are linear in its size: not refused
        d = uv.dual()
        assert d.corner_attributes["uv"].shape == (d.face_sizes.sum(), 2)
    finally:
        topomesh.set_memory_budget(None)
    r = m.honeycomb(correspondence=True)
    assert r[1].matrix.nnz > 2000**2
