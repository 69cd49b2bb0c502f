"""OpenSubdiv refinement through Blender's Subdivision Surface modifier (runs inside .venv-bpy).

Usage: ``python worker.py REQUEST.npz RESPONSE.npz``. Not imported by the test suite: bpy pins
numpy 1.26 and lives in a venv of its own, so ``tests/osd/reference.py`` runs this file in a
subprocess. One request file holds a batch (``n``, then keys ``{i}/name``) so that Blender starts
once per batch:

``{i}/vertices`` (V, 3) float64, ``{i}/face_sizes`` (F,), ``{i}/face_indices`` (C,),
``{i}/levels``, ``{i}/boundary`` ('edge_only' | 'edge_and_corner'), ``{i}/scheme``
('catmull_clark' | 'bilinear'), optional ``{i}/edge_pairs`` (K, 2) + ``{i}/edge_sharpness`` (K,)
and ``{i}/sharp_vertices`` (M,) + ``{i}/vertex_sharpness`` (M,) in OpenSubdiv sharpness units,
optional ``{i}/uvs`` (C, 2) per corner + ``{i}/uv_interpolation``.

The response holds ``{i}/positions`` (V', 3) float64 (Blender's float32 values), ``{i}/face_sizes``,
``{i}/face_indices``, ``{i}/uvs`` (C', 2) when UVs were given, and ``{i}/edge_crease`` /
``{i}/vertex_crease``: the float32 Blender crease values that were set.
"""

import sys

import bpy
import numpy as np

# Blender's modifier settings -> OpenSubdiv Sdc options (Blender 5.0, blenkernel/intern/subdiv.cc:
# BKE_subdiv_vtx_boundary_interpolation_from_subsurf, BKE_subdiv_fvar_interpolation_from_uv_smooth).
# boundary_smooth 'ALL' = VTX_BOUNDARY_EDGE_ONLY, 'PRESERVE_CORNERS' = VTX_BOUNDARY_EDGE_AND_CORNER.
BOUNDARY = {"edge_only": "ALL", "edge_and_corner": "PRESERVE_CORNERS"}
UV_SMOOTH = {
    "all": "NONE",  # FVAR_LINEAR_ALL: UVs bilinear everywhere
    "corners_only": "PRESERVE_CORNERS",  # FVAR_LINEAR_CORNERS_ONLY
    "corners_plus1": "PRESERVE_CORNERS_AND_JUNCTIONS",  # FVAR_LINEAR_CORNERS_PLUS1
    "corners_plus2": "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE",  # FVAR_LINEAR_CORNERS_PLUS2
    "boundaries": "PRESERVE_BOUNDARIES",  # FVAR_LINEAR_BOUNDARIES
    "none": "SMOOTH_ALL",  # FVAR_LINEAR_NONE: UVs smooth like positions
}
SCHEME = {"catmull_clark": "CATMULL_CLARK", "bilinear": "SIMPLE"}
INFINITE = 10.0  # Sdc::Crease::SHARPNESS_INFINITE


def crease_for(sharpness):
    """Blender crease c in [0, 1] for an OpenSubdiv sharpness (infinite from 10 on).

    Blender maps crease to sharpness as ``c * c * 10.0f`` in float32 (``crease_to_sharpness`` in
    source/blender/blenkernel/intern/subdiv_inline.hh; edges and vertices alike). Of the float32
    neighbours of sqrt(s / 10) this takes the smallest whose image is >= float32(s): exact where
    one exists (1.0, 1.5, 3.0), else one ulp above (2.0 gives 2.0000002), so a sharpness that
    reaches 0 or 1 at some level does not fall short of it.
    """
    s = np.float32(min(float(sharpness), INFINITE))
    if s <= 0:
        return np.float32(0.0)
    c0 = np.float32(np.sqrt(np.float64(s) / INFINITE))
    ten = np.float32(INFINITE)
    cands = [np.float32(c0 + np.float32(k) * np.spacing(c0)) for k in range(-4, 5)]
    ok = [c for c in cands if c <= 1 and c * c * ten >= s]
    return min(ok) if ok else np.float32(1.0)


def build(req, i):
    g = lambda k: req[f"{i}/{k}"]  # noqa: E731
    verts = np.asarray(g("vertices"), dtype=np.float64)
    sizes = np.asarray(g("face_sizes"), dtype=np.int64)
    idx = np.asarray(g("face_indices"), dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    faces = [idx[s : s + n].tolist() for s, n in zip(starts, sizes)]

    me = bpy.data.meshes.new(f"req{i}")
    me.from_pydata(verts.tolist(), [], faces)
    me.update()
    if len(me.vertices) != len(verts) or len(me.polygons) != len(faces) or len(me.loops) != len(idx):
        raise ValueError(f"request {i}: Blender changed the mesh ({len(me.polygons)} faces)")

    out = {}
    if f"{i}/edge_pairs" in req:
        ev = np.empty(2 * len(me.edges), dtype=np.int32)
        me.edges.foreach_get("vertices", ev)
        lookup = {tuple(sorted(p)): e for e, p in enumerate(ev.reshape(-1, 2).tolist())}
        crease = np.zeros(len(me.edges), dtype=np.float32)
        for (a, b), s in zip(g("edge_pairs").tolist(), g("edge_sharpness").tolist()):
            key = (min(a, b), max(a, b))
            if key not in lookup:
                raise ValueError(f"request {i}: ({a}, {b}) is not an edge")
            crease[lookup[key]] = crease_for(s)
        me.attributes.new("crease_edge", "FLOAT", "EDGE").data.foreach_set("value", crease)
        out["edge_crease"] = crease
    if f"{i}/sharp_vertices" in req:
        crease = np.zeros(len(me.vertices), dtype=np.float32)
        for v, s in zip(g("sharp_vertices").tolist(), g("vertex_sharpness").tolist()):
            crease[v] = crease_for(s)
        me.attributes.new("crease_vert", "FLOAT", "POINT").data.foreach_set("value", crease)
        out["vertex_crease"] = crease
    has_uv = f"{i}/uvs" in req
    if has_uv:
        uv = me.uv_layers.new(name="UVMap")
        uv.data.foreach_set("uv", np.asarray(g("uvs"), dtype=np.float32).ravel())

    ob = bpy.data.objects.new(f"req{i}", me)
    bpy.context.scene.collection.objects.link(ob)
    md = ob.modifiers.new("subsurf", "SUBSURF")
    md.subdivision_type = SCHEME[str(g("scheme"))]
    md.levels = md.render_levels = int(g("levels"))
    md.use_limit_surface = False  # plain refinement: the level-N control points, not the limit
    md.use_creases = True
    md.boundary_smooth = BOUNDARY[str(g("boundary"))]
    if has_uv:
        md.uv_smooth = UV_SMOOTH[str(g("uv_interpolation"))]

    deps = bpy.context.evaluated_depsgraph_get()
    ev_ob = ob.evaluated_get(deps)
    res = ev_ob.to_mesh()
    co = np.empty(3 * len(res.vertices), dtype=np.float32)
    res.vertices.foreach_get("co", co)
    fs = np.empty(len(res.polygons), dtype=np.int32)
    res.polygons.foreach_get("loop_total", fs)
    fl = np.empty(len(res.polygons), dtype=np.int32)
    res.polygons.foreach_get("loop_start", fl)
    lv = np.empty(len(res.loops), dtype=np.int32)
    res.loops.foreach_get("vertex_index", lv)
    # polygons are stored in loop order in Blender 4+, but do not rely on it
    order = np.concatenate([np.arange(s, s + n) for s, n in zip(fl, fs)]) if len(fs) else np.zeros(0, int)
    out["positions"] = co.reshape(-1, 3).astype(np.float64)
    out["face_sizes"] = fs.astype(np.int64)
    out["face_indices"] = lv[order].astype(np.int64)
    if has_uv:
        uvo = np.empty(2 * len(res.loops), dtype=np.float32)
        res.uv_layers[0].data.foreach_get("uv", uvo)
        out["uvs"] = uvo.reshape(-1, 2)[order].astype(np.float64)
    ev_ob.to_mesh_clear()
    bpy.data.objects.remove(ob)
    bpy.data.meshes.remove(me)
    return out


def main(argv):
    req = dict(np.load(argv[1], allow_pickle=False))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    resp = {"n": np.int64(int(req["n"]))}
    for i in range(int(req["n"])):
        try:
            for k, v in build(req, i).items():
                resp[f"{i}/{k}"] = v
        except Exception as exc:  # reported per request; the caller raises it
            resp[f"{i}/error"] = np.str_(f"{type(exc).__name__}: {exc}")
    resp["bpy_version"] = np.str_(bpy.app.version_string)
    np.savez(argv[2], **resp)


if __name__ == "__main__":
    main(sys.argv)
