"""The gallery: every mesh topomesh can make, written out with a render and
a table of what topomesh, trimesh and manifold3d say about it.

``topomesh gallery OUTDIR`` writes ``OUTDIR/<name>.obj`` (``.ply`` where OBJ cannot
store the mesh), ``OUTDIR/<name>.png``
and ``OUTDIR/summary.md`` (plus ``summary.csv``). Entries come from
:func:`entries`; a scheme shows up here by adding its builder there.
"""

from __future__ import annotations

import csv
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterator

import numpy as np

import topomesh
from topomesh import Mesh


@dataclass(frozen=True)
class Entry:
    name: str
    title: str
    build: Callable[[], Mesh]
    #: zero-length features (self-loops at a point) make the raw geometry
    #: pinched; the peers are then asked about this smoothed realization
    realize: Callable[[Mesh], Mesh] | None = None
    #: per-face (or per-vertex) values the render is coloured by
    color: Callable[[Mesh], np.ndarray] | None = None


def _menger(m, k: int, offset: str = "per_face"):
    """``m.menger(iterations=k, offset=offset)`` with the thickness-reduction
    notice silenced (the reduction is the expected path for some entries, and
    the per-face construction's depth is bounded at sharp edges; other
    warnings pass)."""
    import warnings

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=r"menger: .*the thickness was reduced", category=topomesh.GeometryWarning)
        return m.menger(iterations=k, offset=offset)


def entries() -> Iterator[Entry]:
    """Every gallery entry, in display order."""
    solids = {
        "tetrahedron": topomesh.tetrahedron,
        "cube": topomesh.cube,
        "octahedron": topomesh.octahedron,
        "dodecahedron": topomesh.dodecahedron,
        "icosahedron": topomesh.icosahedron,
    }
    for name, make in solids.items():
        yield Entry(name, name.capitalize(), make)
    yield Entry("torus", "Quad torus 24×12", lambda: topomesh.torus(24, 12))
    for g in (2, 3, 5):
        yield Entry(f"genus{g}", f"Genus-{g} slab tunnelled with InsertEdge", lambda g=g: topomesh.genus_surface(g))
    yield from _extra_entries(solids)
    yield from _catalog_entries()


def _extra_entries(solids: dict[str, Callable[[], Mesh]]) -> Iterator[Entry]:
    from topomesh import examples, modeling

    # smoothing and refinement schemes (issue 6)
    for scheme in ("catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual"):
        yield Entry(
            f"cube_{scheme}",
            f"Cube, {scheme.replace('_', '-')} ×3",
            lambda s=scheme: getattr(topomesh.cube(), s)(iterations=3),
        )
    for name in ("cube", "dodecahedron"):
        yield Entry(f"{name}_honeycomb", f"{name.capitalize()}, honeycomb ×2", lambda n=name: solids[n]().honeycomb(iterations=2))
    for name in ("tetrahedron", "cube", "dodecahedron"):
        yield Entry(
            f"{name}_truncation",
            f"{name.capitalize()}, Chaikin vertex truncation ×3",
            lambda n=name: solids[n]().vertex_truncation(iterations=3),
        )
    # high-genus fractals (issue 4); Sierpinski output is checked after
    # Doo-Sabin opens its zero-length self-loops
    for name in ("tetrahedron", "cube", "octahedron"):
        yield Entry(
            f"{name}_sierpinski",
            f"Sierpinski {name} ×3",
            lambda n=name: solids[n]().sierpinski(iterations=3),
            realize=lambda m: m.doo_sabin(iterations=2),
        )
        yield Entry(
            f"{name}_sierpinski_doo_sabin",
            f"Sierpinski {name} ×2, doo-sabin ×2",
            lambda n=name: solids[n]().sierpinski(iterations=2).doo_sabin(iterations=2),
        )
    # inputs with star, concave, planar and saddle vertices (Sierpinski paper, section 5)
    for make, what in (
        (examples.star_prism, "star vertex, non-convex face"),
        (examples.dented_cube, "concave and star vertices"),
        (examples.planar_vertex_box, "planar vertices"),
        (examples.monkey_saddle, "saddle vertex"),
    ):
        yield Entry(
            f"{make.__name__}_sierpinski_doo_sabin",
            f"{make.__name__.replace('_', ' ').capitalize()} ({what}): Sierpinski ×2, Doo-Sabin ×2",
            lambda make=make: make().sierpinski(iterations=2).doo_sabin(iterations=2),
        )
    for level in (1, 2, 3):
        yield Entry(f"menger_sponge_{level}", f"Classic Menger sponge, level {level}", lambda k=level: topomesh.menger_sponge(k))
    # iterations that are free of self-intersections (tests/test_fractal.py, tests/test_menger_offset.py)
    for name, k in (("cube", 3), ("tetrahedron", 3), ("octahedron", 3), ("dodecahedron", 3)):
        yield Entry(f"{name}_menger", f"Generalized Menger {name} ×{k}", lambda n=name, k=k: _menger(solids[n](), k))
    # the dissertation's merged construction (VII.4: collapsed edges, the chapter's counts)
    yield Entry("tetrahedron_menger_merged", "Generalized Menger tetrahedron ×3, the dissertation's merged corners",
                lambda: _menger(solids["tetrahedron"](), 3, offset="merged"))
    # handles and rinds (issue 3)
    yield Entry("cup", "The dissertation's cup (Fig. 65): rind body + curved handle", modeling.cup)
    yield Entry("arch_cube_3", "Genus-3 cube: three curved handles", lambda: modeling.arch_cube(3))
    yield Entry("twisted_handle", "Twisted handle", lambda: modeling.arch_cube(1, twist=1))
    yield Entry("triangle_hexagon_handle", "Handle from a triangle to a hexagon", modeling.triangle_hexagon_handle)
    yield Entry("peeled_rind_sphere", "Peeled rind sphere", modeling.peeled_rind_sphere)
    yield from _real_mesh_entries()


def _real_mesh_entries() -> Iterator[Entry]:
    """Open meshes, creases, UVs and correspondence (notebooks/05_real_meshes)."""
    from topomesh import examples

    for mode in ("edge_and_corner", "edge_only"):
        yield Entry(f"terrain_catmull_clark_{mode}", f"Open terrain, Catmull-Clark ×3, boundary={mode}", lambda m=mode: examples.terrain().catmull_clark(3, boundary=m))
    yield Entry("terrain_loop", "Open terrain, Loop ×3", lambda: examples.terrain().loop(3))

    def creased(s: float) -> Mesh:
        c = topomesh.cube()
        top = {tuple(e): s for e in c.edges if (c.vertices[e, 2] > 0).all()}
        return c.with_creases(top).catmull_clark(4)

    for s, label in ((0.0, "0"), (1.0, "1"), (2.0, "2"), (float("inf"), "inf")):
        yield Entry(f"creased_cube_{label}", f"Cube, top edges of sharpness {label}, Catmull-Clark ×4", lambda s=s: creased(s))
    yield Entry(
        "uv_cube_checker",
        "Checkerboard UVs with seams through Catmull-Clark ×4",
        lambda: examples.uv_cube().catmull_clark(4, corner_interpolation="boundaries"),
        color=examples.checker,
    )

    # OpenSubdiv's face-varying modes that pin the UV corners and junctions, and seams through a scheme
    # without face-varying rules (the generic corner transfer: no value crosses a seam)
    for mode in ("corners_plus1", "corners_plus2"):
        yield Entry(
            f"uv_cube_checker_{mode}",
            f"Checkerboard UVs with seams through Catmull-Clark ×4, corner_interpolation={mode}",
            lambda m=mode: examples.uv_cube().catmull_clark(4, corner_interpolation=m),
            color=examples.checker,
        )
    yield Entry("uv_cube_checker_doo_sabin", "Checkerboard UVs with seams through Doo-Sabin ×4", lambda: examples.uv_cube().doo_sabin(4), color=examples.checker)

    def parents() -> Mesh:
        t = topomesh.torus(8, 6)
        return t.with_attributes(face={"parent": np.arange(len(t.face_sizes))}).catmull_clark(3)

    yield Entry("torus_parents", "Torus, Catmull-Clark ×3, coloured by parent face", parents, color=lambda m: m.face_attributes["parent"] % 7)

    def reposed() -> Mesh:
        t = topomesh.torus(8, 6)
        fine, corr = t.catmull_clark(3, correspondence=True)
        v = t.vertices.copy()
        ang = 1.2 * v[:, 1]
        v[:, 0], v[:, 2] = np.cos(ang) * t.vertices[:, 0] - np.sin(ang) * t.vertices[:, 2], np.sin(ang) * t.vertices[:, 0] + np.cos(ang) * t.vertices[:, 2]
        return fine.with_vertices(corr.matrix @ v)

    yield Entry("torus_reposed", "Torus ×3 re-posed through the subdivision matrix S", reposed)


def _catalog_entries() -> Iterator[Entry]:
    """One entry per row of ``topomesh.catalog()`` beyond the papers' schemes
    (shown above): TopMod's remeshing menu on the cube, its high-genus tools on
    the genus-2 slab, Conway's operators on the dodecahedron, each with its
    catalog defaults (:func:`topomesh.catalog.run_entry`)."""
    import re
    import warnings

    from topomesh.catalog import run_entry

    seeds = {"topmod": ("Cube", topomesh.cube), "tool": ("Genus-2 slab", lambda: topomesh.genus_surface(2)), "conway": ("Dodecahedron", topomesh.dodecahedron)}

    def build(e: dict[str, object], make: Callable[[], Mesh]) -> Mesh:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", topomesh.GeometryWarning)  # column joints may cross on genus 2 (issue 16)
            return run_entry(e, make())

    for family, (label, make) in seeds.items():
        for e in topomesh.catalog(family):
            slug = re.sub(r"[^a-z0-9]+", "_", str(e["name"]).lower()).strip("_")
            what = f"{e['name']} ({e['letter']})" if "letter" in e else str(e["name"])
            yield Entry(f"{family}_{slug}", f"{label}, {what}", lambda e=e, make=make: build(e, make))


@dataclass(frozen=True)
class Picture:
    """A gallery image that is not a closed mesh (IFS attractors)."""

    name: str
    title: str
    draw: Callable[[Path], None]


def pictures() -> Iterator[Picture]:
    """Attractors of subdivision schemes (attractors paper), drawn with matplotlib."""
    from topomesh import ifs

    def plot(path: Path, title: str, curves: list[tuple[np.ndarray, str]], points: np.ndarray | None = None) -> None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4), dpi=100)
        for xy, style in curves:
            ax.plot(xy[:, 0], xy[:, 1], style, lw=1, ms=3)
        if points is not None:
            ax.plot(points[:, 0], points[:, 1], ",", color="#4d3319")
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=10)
        ax.axis("off")
        fig.savefig(path, bbox_inches="tight")
        plt.close(fig)

    ctrl = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.5], [6.0, 1.5], [7.0, 0.0]])

    def bspline(path: Path) -> None:
        f = ifs.cubic_bspline(ctrl)
        plot(path, "Cubic B-spline as an IFS: attractor vs control polygon", [(ctrl, "o--"), (f.polyline(10), "-")])

    def koch(path: Path) -> None:
        pts = ifs.koch_reference().copy()
        moved = pts.copy()
        moved[2, 1] += 0.25
        plot(
            path,
            "Koch curve from 5 control points; apex moved (orange)",
            [(ifs.koch(pts).polyline(7), "-"), (ifs.koch(moved).polyline(7), "-"), (moved, "o")],
        )

    def gasket(path: Path) -> None:
        f = ifs.gasket()
        plot(path, "Sierpinski gasket: chaos game, 200k points", [(ifs.gasket_reference(), "o")], f.chaos_game(200_000))

    yield Picture("ifs_cubic_bspline", "Cubic B-spline attractor", bspline)
    yield Picture("ifs_koch", "Koch curve with control points", koch)
    yield Picture("ifs_gasket", "Sierpinski gasket (chaos game)", gasket)


def peer_summary(mesh: Mesh) -> dict[str, object]:
    """Counts by topomesh, and genus/closedness by trimesh and manifold3d
    (whichever is installed). Never raises: a peer's failure is reported."""
    row: dict[str, object] = {
        "V": mesh.n_vertices,
        "E": mesh.n_edges,
        "F": mesh.n_faces,
        "genus": mesh.genus,
        "components": mesh.n_components,
        "self_loops": mesh.n_self_loops,
    }
    verts, tris, _ = mesh.triangulate()
    try:
        import trimesh

        tm = trimesh.Trimesh(verts, tris, process=False)
        row["trimesh_watertight"] = bool(tm.is_watertight)
        # trimesh's χ counts no boundary: the loops it sees (pieces of its
        # once-used edges) give the genus of the capped surface, as topomesh's
        pairs, count = np.unique(np.asarray(tm.edges_sorted), axis=0, return_counts=True)
        rim = pairs[count == 1]
        loops = len(trimesh.graph.connected_components(rim, min_len=1)) if len(rim) else 0
        row["trimesh_genus"] = int(mesh.n_components - (tm.euler_number + loops) // 2)
    except Exception as e:  # pragma: no cover - reported, not raised
        row["trimesh_watertight"] = f"error: {type(e).__name__}"
        row["trimesh_genus"] = ""
    try:
        import manifold3d as m3d

        man = m3d.Manifold(m3d.Mesh(vert_properties=verts.astype(np.float32), tri_verts=tris.astype(np.uint32)))
        ok = man.status() == m3d.Error.NoError
        row["manifold_status"] = str(man.status()).split(".")[-1]
        # manifold3d's genus is 1 − χ/2 of the whole mesh; add back the components
        row["manifold_genus"] = int(man.genus()) + mesh.n_components - 1 if ok else ""
    except Exception as e:  # pragma: no cover
        row["manifold_status"] = f"error: {type(e).__name__}"
        row["manifold_genus"] = ""
    return row


def render(mesh: Mesh, path: Path, title: str = "", color_by: np.ndarray | None = None) -> None:
    """Render ``mesh`` off-screen to a PNG (:mod:`topomesh.viz`: polygon
    edges below 20k faces, the camera fitted to the mesh)."""
    from topomesh import viz

    png = viz.render_png(mesh, [viz.title_text(mesh, title)], window_size=(640, 480), edges=None, color_by=color_by)
    Path(path).write_bytes(png)


def run(outdir: str | os.PathLike[str], only: list[str] | None = None, progress: bool = True, images: bool = True) -> list[dict[str, object]]:
    """Build every entry (or those named in ``only``), write mesh + PNG, and
    the summary table. Returns the table rows."""
    from tqdm.auto import tqdm

    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    todo = [e for e in entries() if not only or e.name in only]
    if only:
        unknown = sorted(set(only) - {e.name for e in todo} - {p.name for p in pictures()})
        if unknown:
            raise topomesh.MeshError(f"unknown gallery entries: {', '.join(unknown)}")
    rows = []
    for e in tqdm(todo, desc="gallery", unit="mesh", disable=not progress):
        m = e.build()
        m.validate()
        try:
            m.save(out / f"{e.name}.obj")
        except topomesh.MeshError:
            # two-gons between one pair of vertices (Doo-Sabin BC): OBJ's polygon
            # list cannot pair them back; PLY stores the corner twins
            m.save(out / f"{e.name}.ply")
        if images:
            render(m, out / f"{e.name}.png", e.title, e.color(m).astype(float) if e.color else None)
        checked = e.realize(m) if e.realize else m
        row: dict[str, object] = {"name": e.name, "title": e.title}
        row.update(peer_summary(m))
        if e.realize:
            peers = peer_summary(checked)
            row.update({k: f"{v} (smoothed)" for k, v in peers.items() if k.startswith(("trimesh", "manifold"))})
        rows.append(row)
    pics = [p for p in pictures() if not only or p.name in only] if images else []
    for p in tqdm(pics, desc="pictures", unit="image", disable=not progress):
        p.draw(out / f"{p.name}.png")
    _write_tables(out, rows, pics)
    return rows


def _write_tables(out: Path, rows: list[dict[str, object]], pics: list[Picture]) -> None:
    cols = ["name", "V", "E", "F", "genus", "components", "self_loops", "trimesh_watertight", "trimesh_genus", "manifold_status", "manifold_genus"]
    with open(out / "summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    lines = [
        "# topomesh gallery",
        "",
        "Counts and genus by topomesh; watertightness and genus by trimesh and manifold3d on the triangulated mesh. "
        "Entries with zero-length self-loops (Sierpinski) are checked by the peers after two smoothing steps (one leaves each loop as two coincident edges), marked (smoothed).",
        "",
        "| " + " | ".join(cols) + " | render |",
        "|" + "---|" * (len(cols) + 1),
    ]
    for r in rows:
        lines.append("| " + " | ".join(str(r.get(c, "")) for c in cols) + f" | ![]({r['name']}.png) |")
    if pics:
        lines += ["", "## Attractors of subdivision schemes", ""]
        lines += [f"- {p.title}: ![]({p.name}.png)" for p in pics]
    (out / "summary.md").write_text("\n".join(lines) + "\n")
