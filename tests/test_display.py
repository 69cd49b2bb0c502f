"""Display: Mesh.plot, the Jupyter rich display and topomesh.explore, all
headless (off-screen pyvista; widgets driven by setting their values)."""

from __future__ import annotations

import builtins
import html.parser
import io
import os

import numpy as np
import pytest

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
pv = pytest.importorskip("pyvista")
PIL = pytest.importorskip("PIL.Image")

import topomesh  # noqa: E402
from topomesh import viz  # noqa: E402

PNG = b"\x89PNG\r\n\x1a\n"


def pixels(png: bytes) -> np.ndarray:
    return np.asarray(PIL.open(io.BytesIO(png)).convert("RGB")).astype(int)


def object_rows(img: np.ndarray) -> float:
    """Fraction of the image height between the first and last row holding
    a pixel unlike the background (the corner pixel)."""
    bg = img[0, 0]
    rows = np.nonzero((np.abs(img - bg).sum(axis=2) > 30).any(axis=1))[0]
    return 0.0 if not len(rows) else (rows[-1] - rows[0] + 1) / img.shape[0]


class _Tags(html.parser.HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.stack: list[str] = []
        self.text: list[str] = []
        self.ok = True

    def handle_starttag(self, tag, attrs):
        if tag not in ("img", "br"):
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        pass

    def handle_endtag(self, tag):
        if not self.stack or self.stack.pop() != tag:
            self.ok = False

    def handle_data(self, data):
        self.text.append(data)


# ------------------------------------------------------------- rich display


def test_repr_html_counts_and_structure():
    m = topomesh.genus_surface(2)
    h = m._repr_html_()
    p = _Tags()
    p.feed(h)
    assert p.ok and not p.stack, "unbalanced tags"
    text = "".join(p.text)
    assert f"{m.n_vertices}, {m.n_edges}, {m.n_faces}" in text
    assert str(m.euler_characteristic) in text and "genus" in text and f"{m.genus} (1 component" in text
    assert "boundaries" in text and "bounding box" in text
    # histograms are shown as "size: count"
    k, n = next(iter(m.face_size_histogram.items()))
    assert f"{k}: {n}" in text
    assert "data:image/png;base64," in h  # small mesh: an inline render


def test_repr_html_escapes_and_skips_render_when_large(monkeypatch):
    m = topomesh.cube()
    # the caption is the repr: force markup into it to check it is escaped
    monkeypatch.setattr(viz, "_safe_repr", lambda mesh: "<b>&x</b>")
    h = m._repr_html_()
    assert "&lt;b&gt;&amp;x&lt;/b&gt;" in h and "<b>&x</b>" not in h
    monkeypatch.setattr(viz, "HTML_RENDER_MAX_FACES", 3)
    assert "data:image/png" not in m._repr_html_()


def test_repr_html_never_raises(monkeypatch):
    def boom(mesh, *a, **k):
        raise RuntimeError("no GPU")

    monkeypatch.setattr(viz.Renderer, "render", boom)
    monkeypatch.setattr(viz, "_CAN_RENDER", None)
    h = topomesh.torus(8, 4)._repr_html_()
    assert "genus" in h and "data:image/png" not in h
    assert viz._CAN_RENDER is False  # not tried again
    assert topomesh.torus(8, 4)._repr_png_() is None


def test_repr_png_is_png():
    data = topomesh.dodecahedron()._repr_png_()
    assert isinstance(data, bytes) and data.startswith(PNG)
    img = pixels(data)
    assert img.shape[:2] == (240, 320) and object_rows(img) > 0.6


def test_repr_png_none_without_renderer(monkeypatch):
    monkeypatch.setattr(viz, "_CAN_RENDER", False)
    assert topomesh.cube()._repr_png_() is None


# ------------------------------------------------------------------- plot


@pytest.mark.parametrize(
    "make",
    [topomesh.cube, lambda: topomesh.torus(24, 12), lambda: topomesh.tetrahedron().sierpinski(3)],
    ids=["cube", "torus", "sierpinski"],
)
def test_plot_screenshot_frames_the_object(tmp_path, make):
    path = tmp_path / "m.png"
    out = make().plot(screenshot=path, title=False, window_size=(400, 300))
    data = path.read_bytes()
    assert data.startswith(PNG)
    img = pixels(data)
    assert img.shape[:2] == (300, 400)
    assert object_rows(img) > 0.6
    # the returned static image is the same render
    assert getattr(out, "data", out) == data


def test_plot_with_title_keeps_object_framed(tmp_path):
    path = tmp_path / "t.png"
    topomesh.cube().plot(screenshot=path, window_size=(400, 300))
    img = pixels(path.read_bytes())
    assert object_rows(img) > 0.6


def test_gallery_render_uses_the_fitted_camera(tmp_path):
    from topomesh import gallery

    gallery.render(topomesh.cube().catmull_clark(2), tmp_path / "g.png", "Cube")
    img = pixels((tmp_path / "g.png").read_bytes())
    bg = img[0, 0]
    rows = np.nonzero((np.abs(img - bg).sum(axis=2) > 30).any(axis=1))[0]
    # the lower third is no longer empty
    assert rows[-1] > 0.9 * img.shape[0]


@pytest.mark.parametrize("color_by", ["face_size", "valence", "component", "faces", "verts"])
def test_plot_color_options(tmp_path, color_by):
    m = topomesh.cube().catmull_clark(1)
    value = {"faces": np.arange(len(m.face_sizes)), "verts": m.vertices[:, 2]}.get(color_by, color_by)
    plain = pixels(m.plot(screenshot=tmp_path / "a.png", off_screen=True).data)
    coloured = pixels(m.plot(color_by=value, screenshot=tmp_path / "b.png", edges=False).data)
    assert coloured.shape == plain.shape and np.abs(coloured - plain).sum() > 0


def test_color_by_values():
    m = topomesh.cube()
    assert list(viz.scalars(m, "face_size")[0]) == [4] * 6
    assert list(viz.valences(m)) == [3] * 8
    two = topomesh.cube().create_vertex([0, 0, 5])[0]  # a point-sphere: a second component
    comp, where, _ = viz.scalars(two, "component")
    assert where == "cell" and sorted(set(comp)) == [0, 1] and (comp == 1).sum() == 1


@pytest.mark.parametrize(
    "options, word",
    [
        ({"color_by": "curvature"}, "color_by"),
        ({"color_by": np.zeros(5)}, "color_by"),
        ({"color_by": [np.nan] * 6}, "color_by"),
        ({"window_size": (0, 10)}, "window_size"),
        ({"window_size": "big"}, "window_size"),
        ({"edges": "yes"}, "edges"),
        ({"title": 3}, "title"),
        ({"view": (0, 0, 0)}, "view"),
        ({"colour": "red"}, "colour"),
    ],
)
def test_plot_bad_options_raise_mesh_error(options, word):
    with pytest.raises(topomesh.MeshError, match=word):
        topomesh.cube().plot(off_screen=True, **options)


def test_plot_in_notebook_falls_back_to_static_png(monkeypatch):
    from IPython.display import Image

    monkeypatch.setattr(viz, "in_kernel", lambda: True)
    monkeypatch.setattr(pv.global_theme, "jupyter_backend", "static")
    shown = []
    monkeypatch.setattr("IPython.display.display", lambda obj: shown.append(obj))
    out = topomesh.cube().plot(off_screen=False)
    # displayed once, where the call is, not again as the cell's value
    assert out is None and len(shown) == 1 and isinstance(shown[0], Image) and shown[0].data.startswith(PNG)


def test_live_backend_failure_falls_back(monkeypatch):
    monkeypatch.setattr(viz, "in_kernel", lambda: True)
    # the setter itself refuses "trame" when trame is missing; its field does not
    monkeypatch.setattr(pv.global_theme, "_jupyter_backend", "trame")

    def no_trame(*a, **k):
        raise ImportError("trame is not installed")

    monkeypatch.setattr(pv.Plotter, "show", no_trame)
    shown = []
    monkeypatch.setattr("IPython.display.display", lambda obj: shown.append(obj))
    assert topomesh.cube().plot(off_screen=False) is None
    assert len(shown) == 1 and shown[0].data.startswith(PNG)


def test_plot_does_not_modify_the_mesh(tmp_path):
    m = topomesh.torus(8, 4)
    before = m.vertices.copy()
    m.plot(screenshot=tmp_path / "x.png", color_by="valence")
    assert np.array_equal(m.vertices, before) and m == topomesh.torus(8, 4)


# ---------------------------------------------------------------- explore

ipywidgets = pytest.importorskip("ipywidgets")


def test_explore_slider_changes_mesh_and_image():
    ex = topomesh.explore(topomesh.dodecahedron(), "honeycomb", t=(0.1, 0.9, 0.1))
    assert set(ex.widgets) >= {"scheme", "iterations", "t"}
    m0, png0 = ex.mesh, ex.png
    assert png0.startswith(PNG) and ex.image.value == png0
    assert (m0.n_vertices, m0.n_faces) == (2 * 30, 12 + 20)
    ex.widgets["t"].value = 0.3
    assert ex.mesh.n_faces == m0.n_faces and not np.allclose(ex.mesh.vertices, m0.vertices)
    assert ex.png != png0 and ex.image.value == ex.png
    ex.widgets["iterations"].value = 2
    assert ex.mesh.n_faces == m0.n_faces + m0.n_vertices
    assert len(ex.timings) == 3 and all(t["render"] > 0 for t in ex.timings)
    ex.close()


def test_explore_scheme_dropdown_swaps_parameters():
    ex = topomesh.explore(topomesh.cube(), "catmull_clark")
    assert ex.mesh.n_faces == 24 and "t" not in ex.widgets
    png = ex.png
    ex.widgets["scheme"].value = "vertex_truncation"
    assert set(ex.widgets) >= {"mode", "ratio"}
    assert ex.mesh.face_size_histogram == {3: 8, 8: 6}
    ex.widgets["mode"].value = "polyhedral"
    ex.widgets["ratio"].value = 0.5
    assert ex.mesh.n_vertices == 12  # the cuboctahedron: V' = E
    assert ex.png != png
    ex.widgets["scheme"].value = "doo_sabin"
    assert "ratio" not in ex.widgets and ex.mesh.n_faces == 6 + 12 + 8
    ex.close()


def test_explore_input_dropdown_and_bad_values():
    ex = topomesh.explore({"cube": topomesh.cube(), "torus": topomesh.torus(8, 4)}, "loop", iterations=1)
    assert ex.mesh.genus == 0
    ex.widgets["input"].value = "torus"
    # Loop fans each of the 32 quads around its centroid first: 4 triangles, then 4 each
    assert ex.mesh.genus == 1 and ex.mesh.n_faces == 4 * 4 * 32
    ex.close()
    # a value the scheme refuses keeps the last output and says why
    ex = topomesh.explore(topomesh.cube(), "menger", iterations=1, thickness=(0.1, 0.6, 0.1))
    good = ex.mesh
    ex.widgets["thickness"].value = 0.5
    assert ex.mesh is good and "thickness" in ex.status.value
    ex.close()


def test_explore_menger_construction_dropdown():
    """The Menger panel offers both constructions; collapse_angle, which only
    the merged one reads, gets no slider unless a range is passed."""
    ex = topomesh.explore(topomesh.tetrahedron(), "menger", iterations=1)
    assert "collapse_angle" not in ex.widgets and ex.mesh.n_faces == 46  # per-face corners, the default
    ex.widgets["offset"].value = "merged"
    assert ex.mesh.n_faces == 36  # the dissertation's collapses (VII.4)
    ex.close()


def test_explore_compare_two_values_side_by_side():
    ex = topomesh.explore(topomesh.dodecahedron(), "honeycomb", compare={"t": 0.2}, window_size=(600, 300))
    left, right = ex.meshes
    assert left.n_faces == right.n_faces and not np.allclose(left.vertices, right.vertices)
    assert pixels(ex.png).shape[:2] == (300, 600)
    png = ex.png
    ex.panels[1].widgets["t"].value = 0.5
    assert np.allclose(ex.meshes[1].vertices, ex.meshes[0].vertices) and ex.png != png
    ex.close()
    ex = topomesh.explore(topomesh.cube(), "catmull_clark", compare="doo_sabin")
    assert [m.n_faces for m in ex.meshes] == [24, 26]
    ex.close()


@pytest.mark.parametrize(
    "kw, word",
    [
        ({"scheme": "rind"}, "scheme"),
        ({"scheme": "honeycomb", "q": (0, 1)}, "'q'"),
        ({"scheme": "honeycomb", "t": (0.9, 0.1)}, "t = "),
        ({"scheme": "honeycomb", "t": (0.1, 0.9, 2.0)}, "step"),
        ({"scheme": "loop", "compare": "nope"}, "compare"),
        ({"scheme": "loop", "color_by": [1, 2]}, "color_by"),
        ({"scheme": "loop", "iterations": -1}, "iterations"),
    ],
)
def test_explore_bad_arguments(kw, word):
    with pytest.raises(topomesh.MeshError, match=word):
        topomesh.explore(topomesh.cube(), **kw)


def test_explore_without_ipywidgets(monkeypatch):
    real = builtins.__import__

    def no_widgets(name, *a, **k):
        if name == "ipywidgets" or name.startswith("ipywidgets."):
            raise ImportError("no ipywidgets")
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_widgets)
    ex = topomesh.explore(topomesh.cube(), "catmull_clark", iterations=(0, 2))
    assert ex.widgets == {} and not ex.interactive
    assert ex.mesh.n_faces == 6 * 4 * 4  # the last of the row: 2 iterations
    img = pixels(ex.png)
    assert img.shape[:2] == (300, 3 * 320)  # input, 1 and 2 iterations
