"""topomesh.catalog(): every entry runs, and its stated counts hold on real meshes."""

from __future__ import annotations

import json
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import topomesh as tm
from topomesh import MeshError

MESHES = {"cube": tm.cube, "icosahedron": tm.icosahedron, "torus": lambda: tm.torus(6, 4), "genus2": lambda: tm.genus_surface(2)}


def _counts(m: tm.Mesh) -> dict[str, int]:
    return {"V": m.n_vertices, "E": m.n_edges, "F": len(m.face_sizes), "H": 2 * m.n_edges}


def _evaluable(formula: str) -> bool:
    return re.fullmatch(r"\d*[VEFH](?:[+-]\d*[VEFH])*", formula) is not None


def test_every_entry_names_a_method() -> None:
    entries = tm.catalog()
    assert {e["family"] for e in entries} == {"scheme", "topmod", "tool", "conway"}
    for e in entries:
        assert callable(getattr(tm.Mesh, e["method"], None)), e
    # names are unique within a family
    for fam in ("scheme", "topmod", "tool", "conway"):
        names = [e["name"] for e in tm.catalog(fam)]
        assert len(names) == len(set(names))


@pytest.mark.parametrize("mesh", sorted(MESHES))
def test_stated_counts_hold(mesh: str) -> None:
    m = MESHES[mesh]()
    before = _counts(m)
    checked = 0
    bad = []
    for e in tm.catalog():
        if e["family"] == "tool" or not all(_evaluable(e[k]) for k in "VEF") or e["method"] in ("subdivide_faces", "extrude"):
            continue
        # the formulas are for the plain rule; a conway "t" with n, etc. takes no argument here
        out = getattr(m, e["method"])()
        got = _counts(out)
        tri = bool((m.face_sizes == 3).all())
        if e.get("input") == ("no triangles" if tri else "triangles") or (e.get("input") == "no triangles" and (m.face_sizes == 3).any()):
            continue  # counts stated for another kind of input
        want = {k: eval(re.sub(r"(\d)([VEFH])", r"\1*\2", e[k]), {}, dict(before)) for k in "VEF"}
        if (got["V"], got["E"], got["F"]) != (want["V"], want["E"], want["F"]):
            bad.append((e["name"], mesh, (got["V"], got["E"], got["F"]), want))
        checked += 1
    assert not bad
    assert checked >= 30


def test_topmod_entries_are_the_docs_list() -> None:
    page = (Path(__file__).resolve().parents[1] / "docs" / "schemes" / "topmod.md").read_text()
    block = page.split("## Machine-readable list", 1)[1].split("```json", 1)[1].split("```", 1)[0]
    docs = json.loads(block)
    ours = [{k: v for k, v in e.items() if k != "family"} for e in tm.catalog("topmod")]
    assert ours == docs


def test_family_filter_and_error() -> None:
    assert all(e["family"] == "conway" for e in tm.catalog("conway"))
    with pytest.raises(MeshError, match=r"^catalog: family = 'x'; expected one of"):
        tm.catalog("x")


def _counts_by_valence(m: tm.Mesh) -> dict[str, int]:
    vh = m.valence_histogram
    return {**_counts(m), "V1": vh.get(1, 0), "V2": vh.get(2, 0), "V3": sum(c for k, c in vh.items() if k >= 3)}


@pytest.mark.parametrize("make", [tm.cube, tm.dodecahedron, lambda: tm.cube().subdivide_all_edges(1)])
def test_tool_entries(make) -> None:
    # each tool runs with its catalog params; stated formulas hold (V1, V2, V3: vertices of valence 1, 2, >= 3)
    m = make()
    before = _counts_by_valence(m)
    checked = 0
    for e in tm.catalog("tool"):
        params = dict(e["params"])
        if "faces" in params:
            centroids = m.face_centroids
            # two opposite faces facing away from each other have no hub; take three around a corner
            params["faces"] = [int(i) for i in np.argsort(-centroids @ np.array([1.0, 0.9, 0.8]))[:3]]
        if e["method"] == "multi_face_handle" and params.get("algorithm") == "convex_hull":
            continue  # its hub needs faces looking at one point (tests/test_tools.py)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", tm.GeometryWarning)
            out = getattr(m, e["method"])(**params)
        out.validate()
        got = _counts(out)
        for k in "VEF":
            if "see" not in e[k]:
                want = eval(re.sub(r"(\d)([VEFH(])", r"\1*\2", e[k]), {}, dict(before))
                assert got[k] == want, (e["name"], k)
                checked += 1
    assert checked >= 7


def test_schemes_table_and_run_entry() -> None:
    # schemes() is the catalog; run_entry runs every row on a cube and a genus-2 surface with its defaults
    from topomesh.catalog import default_selection, run_entry

    assert tm.schemes() == tm.catalog() and tm.schemes("conway") == tm.catalog("conway")
    for m in (tm.cube(), tm.genus_surface(2)):
        for e in tm.schemes():
            if "faces" in e.get("params", {}):
                sel = default_selection(e, m)
                assert len(set(sel)) == len(sel) >= 2
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", tm.GeometryWarning)
                out = run_entry(e, m)
            assert isinstance(out, tm.Mesh), e["name"]
            out.validate()
            if e["family"] in ("topmod", "conway") and e["method"] not in ("subdivide_faces", "extrude"):
                assert out.genus == m.genus, e["name"]
    # explicit parameters win over the defaults
    c = tm.cube()
    assert run_entry(tm.catalog("topmod")[0], c, offset=0.5).vertices.max() == pytest.approx(c.vertices.max() + 0.5)


@pytest.mark.parametrize("bad", [float("nan"), -1e300, 1e300, float("-inf")])
def test_out_of_range_arguments_are_named_briefly(bad: float) -> None:
    """Every numeric parameter of every entry, given a value out of any range:
    a MeshError that names the call (not a step inside a composition, such as
    remesh_12_6_4's dual 12.6.4) and the parameter, with numbers written
    briefly (1e300, not 301 digits; a positive range as (0, x], not from
    2.2250738585072014e-308)."""
    m = tm.cube()
    checked = 0
    for e in tm.catalog():
        for name, default in (e.get("params") or {}).items():
            if isinstance(default, bool) or not isinstance(default, float):
                continue
            kw = {name: bad}
            if "faces" in e["params"]:
                kw["faces"] = [0, 2]
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", tm.GeometryWarning)
                    getattr(m, e["method"])(**kw)
            except MeshError as err:
                msg = str(err)
                assert msg.startswith(e["method"]) and name in msg, msg
                assert len(msg) < 400 and not re.search(r"\d{20}", msg) and "e-308" not in msg, msg
                checked += 1
                continue
            # a huge value some entries accept (a handle's scale, a wireframe's thickness: warned about)
            assert bad == 1e300, f"{e['method']}({name}={bad}) was accepted"
    assert checked >= (30 if bad == 1e300 else 35), checked
