"""topomesh: orientable 2-manifold polygon meshes of any genus, closed or open.

A Rust core (``topomesh._core``) with NumPy in and out. Start with a
primitive or your own arrays::

    import topomesh
    m = topomesh.cube()
    m.genus, m.n_faces
    tm = m.to_trimesh()
"""

from topomesh._core import (
    GeometryWarning,
    Mesh,
    MeshError,
    Rind,
    conway,
    conway_operators,
    cube,
    dodecahedron,
    genus_surface,
    icosahedron,
    memory_budget,
    menger_sponge,
    octahedron,
    set_memory_budget,
    tetrahedron,
    torus,
)
from topomesh.io import load, save  # noqa: E402
from topomesh.printing import PrintReport, printable  # noqa: E402
from topomesh._repair import RepairReport, repair  # noqa: E402
from topomesh import _interop, ifs  # noqa: E402
from topomesh.explore import explore  # noqa: E402
from topomesh.correspondence import Correspondence  # noqa: E402
from topomesh.catalog import catalog, schemes  # noqa: E402
from topomesh._core import convex_hull, dual_convex_hull  # noqa: E402
from topomesh._core import block_cache, set_block_cache  # noqa: E402  (issue 19)

__all__ = [
    "Correspondence",
    "GeometryWarning",
    "Mesh",
    "MeshError",
    "PrintReport",
    "RepairReport",
    "Rind",
    "block_cache",
    "catalog",
    "conway",
    "conway_operators",
    "cube",
    "dodecahedron",
    "explore",
    "genus_surface",
    "ifs",
    "icosahedron",
    "load",
    "memory_budget",
    "menger_sponge",
    "octahedron",
    "printable",
    "repair",
    "save",
    "schemes",
    "set_block_cache",
    "set_memory_budget",
    "tetrahedron",
    "torus",
    "convex_hull",
    "dual_convex_hull",
]
__version__ = "0.1.0"
