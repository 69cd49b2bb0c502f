"""Runs the fuzz targets (tests/fuzz.py, tests/fuzz_catalog.py) in subprocesses, so that an abort
is a failure and not the end of the test session. The case counts come
from TOPOMESH_FUZZ_CASES (default 100000, split over two processes) and
TOPOMESH_FUZZ_CATALOG_CASES (default 20000)."""

from __future__ import annotations

import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_fuzz_target_finds_no_failure():
    cases = int(os.environ.get("TOPOMESH_FUZZ_CASES", "100000"))
    half = (cases + 1) // 2

    def one(seed: int) -> subprocess.CompletedProcess:
        return subprocess.run(
            [sys.executable, "-m", "tests.fuzz", "--cases", str(half), "--seed", str(seed)],
            cwd=ROOT, capture_output=True, text=True, timeout=1800,
        )

    with ThreadPoolExecutor(2) as pool:
        runs = list(pool.map(one, (0, 1)))
    for r in runs:
        # a negative return code is a signal (SIGABRT from an allocation failure, SIGSEGV)
        assert r.returncode == 0, f"exit {r.returncode}\n{r.stdout[-4000:]}\n{r.stderr[-4000:]}"
        assert f"{half} cases" in r.stdout and " 0 failures" in r.stdout, r.stdout


def test_catalog_fuzz_target_finds_no_failure():
    """tests/fuzz_catalog.py: every catalog entry on random meshes with random
    arguments (TOPOMESH_FUZZ_CATALOG_CASES, default 20000, about 20 s)."""
    cases = int(os.environ.get("TOPOMESH_FUZZ_CATALOG_CASES", "20000"))
    r = subprocess.run([sys.executable, "-m", "tests.fuzz_catalog", "--cases", str(cases), "--seed", "0"],
                       cwd=ROOT, capture_output=True, text=True, timeout=1800)
    # a negative return code is a signal (an abort, a segmentation fault)
    assert r.returncode == 0, f"exit {r.returncode}\n{r.stdout[-4000:]}\n{r.stderr[-4000:]}"
    assert f"{cases} cases" in r.stdout and " 0 failures" in r.stdout, r.stdout
    # the run is no stub: it checked outputs, and counts against the catalog
    checked = int(r.stdout.split(" outputs checked (")[0].split(", ")[-1])
    counted = int(r.stdout.split(" outputs checked (")[1].split(" ")[0])
    assert checked > cases // 4 and counted > cases // 4, r.stdout
