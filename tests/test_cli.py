"""The command line and the gallery, run in-process."""

from __future__ import annotations

import csv
import os
import re
from pathlib import Path

import pytest

import topomesh
from topomesh import cli, gallery


def test_info_reports_topology_and_peers(tmp_path, capsys):
    p = tmp_path / "g2.obj"
    topomesh.genus_surface(2).save(p)
    assert cli.main(["info", str(p)]) == 0
    out = capsys.readouterr().out
    assert "genus=2" in out
    assert re.search(r"trimesh\s+watertight=True genus=2", out)
    assert re.search(r"manifold3d\s+status=NoError genus=2", out)


def test_convert_between_formats(tmp_path):
    src, dst = tmp_path / "t.off", tmp_path / "t.ply"
    topomesh.torus(6, 4).save(src)
    assert cli.main(["convert", str(src), str(dst)]) == 0
    assert topomesh.load(dst) == topomesh.load(src)


def test_errors_are_one_line_with_status_2(tmp_path, capsys):
    assert cli.main(["info", str(tmp_path / "nope.obj")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("topomesh: error:") and "no such file" in err
    assert cli.main(["subdivide", str(tmp_path / "a.obj"), str(tmp_path / "b.obj"), "--scheme", "bogus"]) == 2
    assert "unknown scheme 'bogus'" in capsys.readouterr().err


def test_gallery_writes_meshes_renders_and_table(tmp_path):
    names = ["cube", "genus3"]
    rows = gallery.run(tmp_path, only=names, progress=False)
    assert [r["name"] for r in rows] == names
    for n in names:
        assert topomesh.load(tmp_path / f"{n}.obj").genus == (3 if n == "genus3" else 0)
        png = tmp_path / f"{n}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 5000
    with open(tmp_path / "summary.csv") as f:
        table = list(csv.DictReader(f))
    g3 = next(r for r in table if r["name"] == "genus3")
    assert (g3["genus"], g3["trimesh_genus"], g3["manifold_genus"], g3["trimesh_watertight"]) == ("3", "3", "3", "True")
    assert "| genus3 |" in (tmp_path / "summary.md").read_text()


def test_gallery_rejects_unknown_entries(tmp_path):
    with pytest.raises(topomesh.MeshError, match="unknown gallery entries: nope"):
        gallery.run(tmp_path, only=["nope"], progress=False)


def test_every_gallery_entry_builds_a_valid_mesh():
    # building (not rendering) every entry keeps the gallery honest as schemes are added
    for e in gallery.entries():
        m = e.build()
        m.validate()
        assert m.n_faces > 0, e.name


def test_readme_example_runs(tmp_path, monkeypatch):
    text = (Path(__file__).parent.parent / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})


def test_gallery_draws_attractor_pictures(tmp_path):
    gallery.run(tmp_path, only=["ifs_koch", "ifs_gasket"], progress=False)
    for n in ("ifs_koch", "ifs_gasket"):
        png = tmp_path / f"{n}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 5000
    assert "![](ifs_koch.png)" in (tmp_path / "summary.md").read_text()


@pytest.mark.parametrize(
    "args,check",
    [
        (["subdivide", "--scheme", "catmull_clark", "-n", "2"], lambda m: m.n_faces == 6 * 16 and m.genus == 0),
        (["subdivide", "--scheme", "honeycomb", "-n", "1"], lambda m: m.n_faces == 6 + 8),
        (["sierpinski", "-n", "2"], lambda m: m.genus == topomesh.cube().sierpinski(2).genus),
        (["menger", "-n", "1", "--thickness", "0.25"], lambda m: m.genus == 5),
    ],
)
def test_scheme_commands(tmp_path, capsys, args, check):
    src, dst = tmp_path / "cube.obj", tmp_path / "out.ply"
    topomesh.cube().save(src)
    cmd, rest = args[0], args[1:]
    assert cli.main([cmd, str(src), str(dst), *rest]) == 0
    assert check(topomesh.load(dst, allow_multi_edges=True))
