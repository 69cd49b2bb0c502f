"""Fork safety: topomesh runs its parallel work in a pool of its own
(``src/python/pool.rs``), never in rayon's global pool, whose threads a
forked child does not have (a child's ``topomesh.torus(60, 40)`` hung after
``os.fork()``, ``multiprocessing``'s default start method on Linux before
Python 3.14).

A broad workload runs in a fresh interpreter; every thread it leaves has a
name of its own (a thread that rayon's global pool started would inherit
the name of the thread that started it), and a forked child then runs the
same kinds of call to completion.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent(
    r"""
    import os, signal, sys, tempfile, warnings
    import numpy as np
    import topomesh
    from topomesh.catalog import schemes, run_entry

    warnings.simplefilter("ignore")
    tmp = tempfile.mkdtemp()

    def workload(m):
        out = [m.catmull_clark(2), m.loop(2), m.midpoint(), m.doo_sabin(), m.sqrt3(), m.dual(), m.menger()]
        for e in schemes():
            try:
                out.append(run_entry(e, m))
            except topomesh.MeshError:
                pass
        c = out[0]
        topomesh.Mesh.from_polygons(c.vertices, c.face_indices.reshape(-1, 4))
        c.triangles(); c.validate(); c.self_intersections(); c.genus; c.n_components
        for ext in ("obj", "ply", "npz"):
            p = os.path.join(tmp, f"m.{ext}")
            topomesh.save(c, p)
            topomesh.load(p)
        topomesh.menger_sponge(2); topomesh.conway("dtkC"); m.sierpinski()
        c.wall_thickness(); c.printable(0.01); m.menger(report=True); m.rind(0.05)
        # every method, with no argument and with a few small ones (face, edge and
        # corner numbers, a length), except those handing the mesh to other
        # libraries (VTK, Mesa, TBB start threads of their own)
        for name in dir(topomesh.Mesh):
            if name.startswith(("__", "_repr", "to_", "from_")) or name in ("explore", "show", "plot", "save"):
                continue
            for args in [(), (0,), (0.1,), ([0, 1],), (0, 5), (0, 1, 2, 0), ([0], 0.1)]:
                try:
                    a = getattr(topomesh.torus(12, 8), name)
                    if callable(a):
                        a(*args)
                except Exception:
                    pass
        return len(out)

    workload(topomesh.torus(40, 24))
    workload(topomesh.cube())
    # thread names: the main thread's, then one per topomesh thread, none twice
    names = []
    for t in os.listdir("/proc/self/task"):
        try:
            names.append(open(f"/proc/self/task/{t}/comm").read().strip())
        except OSError:  # a thread that ended meanwhile
            pass
    # a call's worker thread may still be ending: it is the one name allowed twice
    ours = [n for n in names if n.startswith("topomesh") and n != "topomesh-call"]
    main = open("/proc/self/comm").read().strip()
    stray = [n for n in names if n == main][1:] + [n for n in set(ours) if ours.count(n) > 1]
    assert not stray, f"threads outside topomesh's pool: {names}"
    assert any(n.startswith("topomesh-") for n in names), names

    pid = os.fork()
    if pid == 0:
        signal.alarm(120)  # a hang ends the child with SIGALRM
        try:
            workload(topomesh.torus(40, 24))
        except BaseException:
            os._exit(3)
        os._exit(0)
    _, status = os.waitpid(pid, 0)
    code = os.waitstatus_to_exitcode(status)
    assert code == 0, f"the forked child ended with {code} (-14: it hung)"
    print("ok")
    """
)


@pytest.mark.skipif(not hasattr(os, "fork") or not os.path.isdir("/proc/self/task"), reason="needs fork and /proc")
def test_parallel_work_survives_fork():
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")  # their threads would share the main name
    p = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0 and p.stdout.strip().endswith("ok"), p.stdout[-2000:] + p.stderr[-4000:]
