"""Where every element of a scheme's output came from.

Returned by the schemes with ``correspondence=True`` (for example
``mesh.catmull_clark(2, correspondence=True)``), composed over the levels,
so it always refers to the elements of the mesh the call started from.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

#: Origin kinds of :attr:`Correspondence.vertex_kinds` and :attr:`Correspondence.face_kinds`.
VERTEX, EDGE, FACE = 0, 1, 2


@dataclass(frozen=True, eq=False)
class Correspondence:
    """Parents, origins and the subdivision matrix of a scheme's output.

    Attributes
    ----------
    face_parents : ndarray of int64, shape (F_out,)
        For each output face (as :attr:`Mesh.face_sizes`), the input face it
        lies in. A face born from an input edge or vertex (Doo-Sabin's edge
        and vertex faces, the dual) gets the first real face of that edge or
        around that vertex, so face attributes always have a parent.
    face_kinds, face_origins : ndarray, shape (F_out,)
        The input element each output face was born from: kind
        (``VERTEX`` 0, ``EDGE`` 1, ``FACE`` 2, int8) and its index (into the
        input's vertices, :attr:`Mesh.edges` or faces, int64).
    vertex_kinds, vertex_origins : ndarray, shape (V_out,)
        The same for every output vertex: a vertex point comes from its
        vertex, an edge point from its edge, a face point from its face (the
        lowest-dimensional input element whose refinement contains it).
    """

    face_parents: npt.NDArray[np.int64]
    face_kinds: npt.NDArray[np.int8]
    face_origins: npt.NDArray[np.int64]
    vertex_kinds: npt.NDArray[np.int8]
    vertex_origins: npt.NDArray[np.int64]
    indptr: npt.NDArray[np.int64] = field(repr=False)
    indices: npt.NDArray[np.int64] = field(repr=False)
    weights: npt.NDArray[np.float64] = field(repr=False)
    shape: tuple[int, int] = (0, 0)
    #: False for a scheme whose positions are not linear in the input's
    #: (``menger``): it has no subdivision matrix, only the linear
    #: :attr:`transfer` that carried vertex attributes.
    linear: bool = True
    scheme: str = ""

    def __post_init__(self) -> None:
        for name in ("face_parents", "face_kinds", "face_origins", "vertex_kinds", "vertex_origins", "indptr", "indices", "weights"):
            getattr(self, name).flags.writeable = False

    @property
    def matrix(self) -> Any:
        """The subdivision matrix ``S`` (``scipy.sparse.csr_array``, output V × input V).

        ``S @ input.vertices`` is the output's vertices (the schemes whose
        positions are linear in the input's); apply it to a deformed input
        to re-pose the output at matrix-product speed. Duplicate entries
        are summed. Needs SciPy.

        Raises
        ------
        MeshError
            For a scheme whose positions are not linear (``menger``); its
            attribute transfer is :attr:`transfer`.
        """
        if not self.linear:
            from . import MeshError

            raise MeshError(
                f"Correspondence.matrix: {self.scheme or 'this scheme'} places points by offsets and plane intersections, "
                "so its positions are not linear in the input's and it has no subdivision matrix; "
                "Correspondence.transfer is the linear map that carried vertex attributes"
            )
        return self.transfer

    @property
    def transfer(self) -> Any:
        """The linear map that carried vertex attributes (``scipy.sparse.csr_array``, output V × input V).

        The subdivision matrix for the linear schemes; for ``menger`` each
        output vertex takes the value of the input vertex whose rule placed
        it, and each edge trisection point interpolates its edge's two ends.
        Needs SciPy.
        """
        try:
            import scipy.sparse as sp
        except ImportError as e:  # pragma: no cover - scipy is in the test extras
            raise ImportError("Correspondence.matrix needs SciPy: pip install scipy") from e
        s = sp.csr_array((self.weights.copy(), self.indices.copy(), self.indptr.copy()), shape=self.shape)
        s.sum_duplicates()
        return s

    def apply(self, values: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """``transfer @ values`` (``S @ values`` for linear schemes) without SciPy: interpolate per-vertex data of the input.

        Parameters
        ----------
        values : array of shape (V_in,) or (V_in, k)

        Returns
        -------
        ndarray of float64, shape (V_out,) or (V_out, k)
        """
        a = np.asarray(values, dtype=np.float64)
        if a.ndim not in (1, 2) or a.shape[0] != self.shape[1]:
            from . import MeshError

            raise MeshError(f"Correspondence.apply: values of shape {a.shape}, expected ({self.shape[1]},) or ({self.shape[1]}, k)")
        rows = np.repeat(np.arange(self.shape[0]), np.diff(self.indptr))
        flat = a.reshape(a.shape[0], -1)
        out = np.zeros((self.shape[0], flat.shape[1]))
        np.add.at(out, rows, self.weights[:, None] * flat[self.indices])
        return out.reshape((self.shape[0],) + a.shape[1:])
