"""The validation harness: topomesh's own topology against two peers.

``assert_agrees_with_peers(mesh)`` triangulates the mesh and asserts that

* trimesh (``process=False``) sees it watertight and winding-consistent, with
  the same Euler characteristic and number of connected pieces, and
* manifold3d accepts it (status ``NoError``) without splitting any vertex
  (a split means a geometric pinch), with genus 1 − χ/2 summed over the
  whole mesh, i.e. ``mesh.genus − (components − 1)``, and the same volume.

Zero-length features (Sierpinski self-loops) are pinches to both peers:
validate a realization that opens them (one smoothing step), as STACK.md notes.
"""

from __future__ import annotations

import numpy as np
import trimesh
import manifold3d as m3d

import topomesh


# the five Platonic solids by name, the corpus every scheme's tests start from
PLATONIC = {
    "tetrahedron": topomesh.tetrahedron,
    "cube": topomesh.cube,
    "octahedron": topomesh.octahedron,
    "dodecahedron": topomesh.dodecahedron,
    "icosahedron": topomesh.icosahedron,
}


def peer_report(mesh: topomesh.Mesh) -> dict:
    """What trimesh and manifold3d say about ``mesh`` (triangulated)."""
    verts, tris, _ = mesh.triangulate()
    tm = trimesh.Trimesh(vertices=verts, faces=tris, process=False)
    labels = trimesh.graph.connected_components(tm.face_adjacency, nodes=np.arange(len(tris)), min_len=1)
    man = m3d.Manifold(m3d.Mesh(vert_properties=verts.astype(np.float32), tri_verts=tris.astype(np.uint32)))
    return {
        "trimesh_watertight": bool(tm.is_watertight),
        "trimesh_winding": bool(tm.is_winding_consistent),
        "trimesh_euler": int(tm.euler_number),
        "trimesh_components": len(labels),
        "trimesh_volume": float(tm.volume),
        "manifold_status": man.status(),
        "manifold_genus": int(man.genus()),
        "manifold_vertices": int(man.num_vert()),
        "triangulation_vertices": len(verts),
        "manifold_volume": float(man.volume()),
    }


def assert_agrees_with_peers(
    mesh: topomesh.Mesh, expect_genus: int | None = None, exact_vertices: bool = True, planar: bool = True
) -> dict:
    """Assert trimesh and manifold3d agree with topomesh on closedness, χ,
    components and genus. Returns the peer report.

    ``exact_vertices=False`` lets manifold3d merge coincident points (meshes
    that keep zero-length edges, such as a truncated zero-length self-loop).
    ``planar=False`` is for meshes with non-planar faces (Doo-Sabin output,
    truncations of 4-valent vertices): topomesh's volume (a fan per face) then
    differs from the triangulation's, so the two peers' volumes are compared
    with each other instead. Every other check applies either way."""
    mesh.validate()
    assert mesh.n_holes == 0, "holes are left out of exports: the peers would see an open mesh"
    if expect_genus is not None:
        assert mesh.genus == expect_genus, f"topomesh genus {mesh.genus} != expected {expect_genus}"
    r = peer_report(mesh)
    where = repr(mesh)
    assert r["trimesh_watertight"], f"trimesh: not watertight ({where})"
    assert r["trimesh_winding"], f"trimesh: winding inconsistent ({where})"
    assert r["trimesh_euler"] == mesh.euler_characteristic, f"trimesh χ {r['trimesh_euler']} ({where})"
    assert r["trimesh_components"] == mesh.n_components, f"trimesh components {r['trimesh_components']} ({where})"
    assert r["manifold_status"] == m3d.Error.NoError, f"manifold3d: {r['manifold_status']} ({where})"
    assert not exact_vertices or r["manifold_vertices"] == r["triangulation_vertices"], (
        f"manifold3d split vertices ({r['manifold_vertices']} != {r['triangulation_vertices']}): a geometric pinch ({where})"
    )
    assert r["manifold_genus"] == mesh.genus - (mesh.n_components - 1), f"manifold3d genus {r['manifold_genus']} ({where})"
    vol = mesh.volume
    assert vol > 0, f"non-positive volume {vol}: faces not oriented outward ({where})"
    if not planar:
        vol = r["trimesh_volume"]
    else:
        assert abs(r["trimesh_volume"] - vol) <= 1e-9 * max(1.0, abs(vol)), f"trimesh volume {r['trimesh_volume']} vs {vol}"
    assert abs(r["manifold_volume"] - vol) <= 1e-4 * max(1.0, abs(vol)), f"manifold3d volume {r['manifold_volume']} vs {vol}"
    return r
