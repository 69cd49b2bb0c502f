"""The ``topomesh`` command line.

    topomesh gallery OUTDIR              every built-in mesh: OBJ + PNG + summary table
    topomesh info FILE                   counts, genus, watertight per trimesh and manifold3d
    topomesh convert IN OUT              between NPZ, PLY, OBJ, OFF, STL (binary) and 3MF
    topomesh subdivide IN OUT --scheme S -n K   S: a scheme, a TopMod remeshing or a Conway operator (method names);
                                         -n is also spelled --iterations
    topomesh sierpinski IN OUT -n K
    topomesh menger IN OUT -n K [--thickness D] [--offset per_face|merged]

Every command that reads a file takes ``--boundaries {keep,refuse}``, ``--allow-multi-edges``
and ``--repair`` (passed to :func:`topomesh.load`): open meshes are read and kept open unless
``--boundaries refuse``; ``--close-boundaries`` (keep, the default) is accepted for old scripts. Errors are one line on stderr, never a
traceback: bad input (``MeshError``) exits with status 2, Ctrl-C with 130, a file or other
failure with 1. The output path is checked (extension, writable directory) before any work. Warnings (``GeometryWarning``, e.g. an STL that is not closed) are one line too.
"""

from __future__ import annotations

import argparse
import re
import sys
import warnings
from typing import Sequence

import topomesh
from topomesh import Mesh, MeshError

SCHEMES: tuple[str, ...] = ("catmull_clark", "doo_sabin", "loop", "sqrt3", "simplest", "midpoint", "dual", "honeycomb", "vertex_truncation")
#: every remeshing of the catalog runs as a whole-mesh level too: TopMod's menu
#: (but the selection tools) and Conway's operators (one level per -n)
_ONE_LEVEL = tuple(e["method"] for e in topomesh.catalog("conway"))
_REMESHING = [e["method"] for e in topomesh.catalog("topmod") if e["method"] not in ("subdivide_faces", "extrude")]
SCHEMES += tuple(m for m in dict.fromkeys(_REMESHING + list(_ONE_LEVEL)) if m not in SCHEMES)


def _iterate(mesh: Mesh, method: str, n: int, **kw: object) -> Mesh:
    """Run a scheme ``n`` times with a progress bar."""
    fn = getattr(mesh, method)
    try:
        return fn(iterations=n, progress=True, **kw)
    except TypeError:
        # a scheme without its own progress option: one bar step per level
        from tqdm.auto import tqdm

        for _ in tqdm(range(n), desc=method, unit="level"):
            step = getattr(mesh, method)
            # Conway's operators are one level each and take no iterations
            mesh = step(**kw) if method in _ONE_LEVEL else step(iterations=1, **kw)
        return mesh


# core messages suggest Python keywords; the CLI names its own flags
_HINTS = {
    "close_boundaries": "--close-boundaries",
    "boundaries": "--boundaries",
    "allow_multi_edges": "--allow-multi-edges",
    "repair": "--repair",
    "iterations": "-n",
    "thickness": "--thickness",
}


def _cli_message(msg: str) -> str:
    """``pass close_boundaries=True`` → ``pass --close-boundaries``, and so on."""
    msg = re.sub(r'(?<![-\w])boundaries\s*=\s*"(\w+)"', r"--boundaries \1", msg)
    msg = re.sub(r"(?<![-\w])close_boundaries\s*=\s*False\b", "--boundaries refuse", msg)
    for kw, flag in _HINTS.items():
        msg = re.sub(rf"(?<![-\w]){kw}\s*=\s*True\b", flag, msg)
        msg = re.sub(rf"(?<![-\w]){kw}\b", flag, msg)
    return msg.replace("(--boundaries refuse or --boundaries refuse)", "(--boundaries refuse)")


def _load(a: argparse.Namespace, path: str) -> Mesh:
    """``topomesh.load`` with the construction flags of the command line."""
    return topomesh.load(
        path, close_boundaries=a.close_boundaries, allow_multi_edges=a.allow_multi_edges, repair=a.repair,
        boundaries=a.boundaries,
    )


def cmd_info(a: argparse.Namespace) -> int:
    from topomesh.gallery import peer_summary

    m = _load(a, a.file)
    row = peer_summary(m)
    print(f"{a.file}: {m!r}")
    print(f"  Euler characteristic  {m.euler_characteristic}")
    print(f"  component genera      {m.component_genera}")
    print(f"  boundary loops        {m.n_boundary_loops}" + ("" if m.is_closed else f" (per component {m.component_boundary_loops})"))
    print(f"  self-loops            {m.n_self_loops}")
    print(f"  face sizes            {m.face_size_histogram}")
    print(f"  valences              {m.valence_histogram}")
    print(f"  trimesh               watertight={row['trimesh_watertight']} genus={row['trimesh_genus']}")
    print(f"  manifold3d            status={row['manifold_status']} genus={row['manifold_genus']}")
    return 0


def _output(path: str) -> str:
    """The output path, checked before the work: a long subdivision must not
    end in "unsupported extension" or "no such directory"."""
    from topomesh.io import check_writable

    check_writable(path)
    return path


def cmd_convert(a: argparse.Namespace) -> int:
    out = _output(a.output)
    _load(a, a.input).save(out)
    return 0


def cmd_gallery(a: argparse.Namespace) -> int:
    from topomesh import gallery

    rows = gallery.run(a.outdir, only=a.only or None, images=not a.no_images)
    print(f"wrote {len(rows)} meshes and summary.md to {a.outdir}")
    return 0


def cmd_subdivide(a: argparse.Namespace) -> int:
    if a.scheme not in SCHEMES:
        raise MeshError(f"unknown scheme {a.scheme!r}; available: {', '.join(SCHEMES)}")
    out = _output(a.output)
    _iterate(_load(a, a.input), a.scheme, a.n).save(out)
    return 0


def cmd_sierpinski(a: argparse.Namespace) -> int:
    out = _output(a.output)
    _iterate(_load(a, a.input), "sierpinski", a.n).save(out)
    return 0


def cmd_menger(a: argparse.Namespace) -> int:
    kw = {} if a.thickness is None else {"thickness": a.thickness}
    out = _output(a.output)
    _iterate(_load(a, a.input), "menger", a.n, offset=a.offset, **kw).save(out)
    return 0


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="topomesh", description="Manifold polygon meshes of any genus.")
    p.add_argument("--version", action="version", version=f"topomesh {topomesh.__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    reads = argparse.ArgumentParser(add_help=False)
    reads.add_argument(
        "--boundaries", choices=("keep", "refuse"), default="keep",
        help="keep open meshes open (default) or refuse them with an error naming a boundary edge",
    )
    reads.add_argument(
        "--close-boundaries", action="store_true", default=None,
        help="old spelling of --boundaries keep (the default): accept open meshes",
    )
    reads.add_argument("--allow-multi-edges", action="store_true", help="accept several edges between the same two vertices")
    reads.add_argument("--repair", action="store_true", help="repair sloppy input while loading (merge, orient, split pinches)")
    g = sub.add_parser("gallery", help="write every built-in mesh with a render and a summary table")
    g.add_argument("outdir")
    g.add_argument("--only", nargs="*", help="entry names to build (default: all)")
    g.add_argument("--no-images", action="store_true", help="skip the PNG renders")
    g.set_defaults(func=cmd_gallery)
    i = sub.add_parser("info", parents=[reads], help="counts, genus and peer checks of a mesh file")
    i.add_argument("file")
    i.set_defaults(func=cmd_info)
    c = sub.add_parser(
        "convert",
        parents=[reads],
        help="convert between NPZ, PLY, OBJ, OFF, STL and 3MF (by extension)",
        description="Convert a mesh file; the extensions choose the formats. NPZ and PLY keep every mesh, OBJ and "
        "OFF its polygons, STL (binary, float32) and 3MF (through trimesh: pip install 'topomesh[print]') its "
        "triangles. Reads ASCII or binary STL.",
    )
    c.add_argument("input")
    c.add_argument("output")
    c.set_defaults(func=cmd_convert)
    s = sub.add_parser("subdivide", parents=[reads], help="apply a subdivision scheme")
    s.add_argument("input")
    s.add_argument("output")
    s.add_argument("--scheme", required=True, help=f"one of: {', '.join(SCHEMES)}")
    # --iterations: the Python keyword, for users coming from the API
    s.add_argument("-n", "--iterations", dest="n", type=int, default=1, help="iterations (default 1)")
    s.set_defaults(func=cmd_subdivide)
    si = sub.add_parser("sierpinski", parents=[reads], help="Sierpinski subdivision (high genus)")
    si.add_argument("input")
    si.add_argument("output")
    si.add_argument("-n", "--iterations", dest="n", type=int, default=1, help="iterations (default 1)")
    si.set_defaults(func=cmd_sierpinski)
    me = sub.add_parser("menger", parents=[reads], help="generalized Menger sponge")
    me.add_argument("input")
    me.add_argument("output")
    me.add_argument("-n", "--iterations", dest="n", type=int, default=1, help="iterations (default 1)")
    me.add_argument("--thickness", type=float, default=None)
    me.add_argument("--offset", choices=["per_face", "merged"], default="per_face",
                    help="inner surface construction (Mesh.menger's offset): per_face (default) is crossing-free on "
                         "every measured case; merged is the dissertation's construction and counts (VII.4)")
    me.set_defaults(func=cmd_menger)
    return p


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ANN001
    print(f"topomesh: warning: {_cli_message(str(message))}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (argparse exits 2 itself on bad usage)."""
    args = parser().parse_args(argv)
    try:
        with warnings.catch_warnings():
            # a warning (e.g. an STL that is not closed) is one line too
            warnings.showwarning = _show_warning
            return int(args.func(args))
    except MeshError as e:
        print(f"topomesh: error: {_cli_message(str(e))}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("topomesh: interrupted", file=sys.stderr)
        return 130
    except OSError as e:
        where = f": {e.filename}" if getattr(e, "filename", None) else ""
        print(f"topomesh: error: {e.strerror or e}{where}", file=sys.stderr)
        return 1
    except Exception as e:  # noqa: BLE001 - the CLI never shows a traceback
        print(f"topomesh: error: {type(e).__name__}: {_cli_message(str(e))}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
