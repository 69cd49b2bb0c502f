"""topomesh.ifs: subdivision curves and surfaces as attractors (Schaefer, Levin, Goldman)."""

import numpy as np
import pytest
from scipy.spatial import cKDTree

import topomesh
from topomesh import ifs

P5 = np.array([[0, 0], [1, 2], [2.5, 2.2], [3.5, 0.5], [5, 1.5]], dtype=float)


def cubic_bspline_eval(p, s):
    """Exact uniform cubic B-spline at global parameters s in [0, len(p) - 3]."""
    s = np.asarray(s, dtype=float)
    j = np.minimum(np.floor(s).astype(int), len(p) - 4)
    t = (s - j)[:, None]
    b = [(1 - t) ** 3 / 6, (3 * t**3 - 6 * t**2 + 4) / 6, (-3 * t**3 + 3 * t**2 + 3 * t + 1) / 6, t**3 / 6]
    return sum(b[k] * p[j + k] for k in range(4))


def distance_to_cubic(p, x):
    """Distance from points x to the exact cubic B-spline: dense samples, then Newton on the parameter."""
    s_max = len(p) - 3
    grid = np.linspace(0, s_max, 200001)
    tree = cKDTree(cubic_bspline_eval(p, grid))
    _, idx = tree.query(x)
    s = grid[idx]
    h = 1e-6
    for _ in range(8):
        c = cubic_bspline_eval(p, s)
        d1 = (cubic_bspline_eval(p, np.clip(s + h, 0, s_max)) - cubic_bspline_eval(p, np.clip(s - h, 0, s_max))) / (2 * h)
        num = np.einsum("ij,ij->i", c - x, d1)
        den = np.einsum("ij,ij->i", d1, d1)
        s = np.clip(s - num / den, 0, s_max)
    return np.linalg.norm(cubic_bspline_eval(p, s) - x, axis=1)


def hausdorff(a, b):
    a, b = a.reshape(-1, a.shape[-1]), b.reshape(-1, b.shape[-1])
    return max(cKDTree(b).query(a)[0].max(), cKDTree(a).query(b)[0].max())


# --- construction (section 2) ------------------------------------------------------------


def test_cubic_bspline_blocks_and_lift_match_section_2_1():
    f = ifs.cubic_bspline(P5)
    assert (f.n_maps, f.dim, f.ambient_dim, f.n_components) == (2, 5, 2, 1)
    s1 = np.array([[4, 4, 0, 0, 0], [1, 6, 1, 0, 0], [0, 4, 4, 0, 0], [0, 1, 6, 1, 0], [0, 0, 4, 4, 0]]) / 8
    np.testing.assert_allclose(f.blocks[0], s1)
    np.testing.assert_allclose(f.blocks[1], np.roll(s1, 1, axis=1))
    P = f.lifted_control_points
    np.testing.assert_array_equal(P[:, :2], P5)
    np.testing.assert_array_equal(P[:, 2:], [[1, 0, 1], [0, 1, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]])
    # eq. 2 and eq. 3
    for S, M in zip(f.blocks, f.maps):
        np.testing.assert_allclose(M, np.linalg.inv(P) @ S @ P, atol=1e-12)
        np.testing.assert_allclose(M[:, -1], [0, 0, 0, 0, 1], atol=1e-12)
    np.testing.assert_allclose(f.contraction, [0.5, 0.5], atol=1e-6)
    np.testing.assert_array_equal(f.control_points, P5)


def test_not_an_affine_basis_and_not_contractive_raise():
    with pytest.raises(topomesh.MeshError, match="not an affine basis"):
        ifs.cubic_bspline([[0, 0], [1, 1], [2, 2], [3, 3], [4, 4]])
    with pytest.raises(topomesh.MeshError, match="not contractive"):
        ifs.from_subdivision(np.eye(5)[None], P5)
    with pytest.raises(topomesh.MeshError, match="sums to"):
        ifs.from_subdivision(np.full((1, 5, 5), 0.3), P5)
    with pytest.raises(topomesh.MeshError, match="do not determine any piece"):
        ifs.cubic_bspline(P5[:2])
    with pytest.raises(topomesh.MeshError):
        ifs.loop(np.zeros((18, 3)))


# --- curves are attractors ---------------------------------------------------------------


def test_cubic_bspline_attractor_lies_on_the_exact_cubic():
    f = ifs.cubic_bspline(P5)
    poly = f.polyline(12)
    assert poly.shape == (4097, 2)
    s = np.linspace(0, 2, 4097)
    assert np.abs(poly - cubic_bspline_eval(P5, s)).max() < 1e-9
    pts = f.chaos_game(20000, seed=3)
    assert distance_to_cubic(P5, pts).max() < 1e-9
    # iterating from a far-away point: the error shrinks like 2^-levels
    it = f.iterate([[7.0, -3.0, 0.4, 2.0]], 18)[:, 0]
    assert distance_to_cubic(P5, it).max() < 1e-4


def test_attractor_does_not_depend_on_the_start_set():
    f = ifs.endpoint_bspline(P5)
    from_point = f.iterate([[10.0, 10.0]], 18)
    from_triangle = f.iterate([[-5, 0], [0, 8], [3, -4]], 18)
    from_segment = f.iterate([[0, 0, 5, 5], [1, 1, -5, -5]], 18)
    assert from_point.shape == (2**18, 1, 2) and from_triangle.shape == (2**18, 3, 2)
    assert hausdorff(from_point, from_triangle) < 2e-4
    assert hausdorff(from_point, from_segment) < 2e-4
    # and iterating from the control points is subdivision (F(P) = S_i P)
    sub = f.subdivide(1)
    np.testing.assert_allclose(sub[0], f.blocks[0] @ P5, atol=1e-12)
    # end points interpolated
    poly = f.polyline(8)
    np.testing.assert_allclose(poly[[0, -1]], P5[[0, -1]], atol=1e-12)


def test_four_point_interpolates_and_reproduces_cubics():
    x = np.arange(7.0)
    cubic = lambda t: 0.1 * t**3 - 0.7 * t**2 + t + 2  # noqa: E731
    f = ifs.four_point(np.c_[x, cubic(x)])
    assert f.blocks.shape == (2, 7, 7)
    poly = f.polyline(10)
    assert np.abs(poly[:, 1] - cubic(poly[:, 0])).max() < 1e-9
    np.testing.assert_allclose(poly[:, 0], np.linspace(2, 4, 1025), atol=1e-9)
    rng = np.random.default_rng(5)
    q = rng.normal(size=(7, 2))
    poly = ifs.four_point(q).polyline(8)
    n = len(poly) - 1
    np.testing.assert_allclose(poly[[0, n // 2, n]], q[2:5], atol=1e-12)
    # chaos-game points are on the curve too: near the fine polyline
    fine = ifs.four_point(q).polyline(16)
    assert cKDTree(fine).query(ifs.four_point(q).chaos_game(5000))[0].max() < 1e-3


def test_chaikin_and_plain_subdivision_agree():
    f = ifs.chaikin(P5)
    fine = f.polyline(12)
    np.testing.assert_allclose(fine[0], (P5[0] + P5[1]) / 2, atol=1e-12)
    sub = ifs.subdivide_curve(P5, "chaikin", 10)
    assert hausdorff(sub, fine) < 0.01
    sub = ifs.subdivide_curve(P5, "cubic_bspline", 10)
    assert hausdorff(sub, ifs.cubic_bspline(P5).polyline(12)) < 0.01


def test_union_of_two_beziers():
    a = ifs.bezier([[0, 0], [1, 2], [2, 0]])
    b = ifs.bezier([[3, 0], [4, -2], [5, 1]])
    u = a.union(b)
    assert (u.n_components, u.dim) == (2, 6)
    np.testing.assert_allclose(u.polyline(6), np.stack([a.polyline(6), b.polyline(6)]), atol=1e-12)
    # Fig. 4: start from the point (2, 3/2, 1, 2, 3/2, 1)
    it = u.iterate([[2, 1.5, 1, 2, 1.5, 1]], 14)
    assert it.shape == (2, 2**14, 1, 2)
    assert hausdorff(it[0], a.polyline(12)) < 1e-3
    assert hausdorff(it[1], b.polyline(12)) < 1e-3
    assert u.chaos_game(10).shape == (2, 10, 2)


def test_curve_from_custom_rules():
    # the cubic B-spline typed as rules gives the same IFS as the named one
    f = ifs.curve(P5, [[(-1, 0.125), (0, 0.75), (1, 0.125)], [(0, 0.5), (1, 0.5)]])
    np.testing.assert_allclose(f.blocks, ifs.cubic_bspline(P5).blocks)
    # a ternary scheme: the uniform quadratic B-spline's ternary rules, mask (1, 3, 6, 7, 6, 3, 1) / 9
    rules = [[(-1, 1 / 9), (0, 7 / 9), (1, 1 / 9)], [(0, 2 / 3), (1, 1 / 3)], [(0, 1 / 3), (1, 2 / 3)]]
    t = ifs.curve(P5, rules, arity=3)
    assert t.n_maps == 3
    assert hausdorff(t.polyline(9), ifs.chaikin(P5).polyline(12)) < 1e-2


def test_chaos_game_is_seeded():
    f = ifs.cubic_bspline(P5)
    np.testing.assert_array_equal(f.chaos_game(1000, seed=4), f.chaos_game(1000, seed=4))
    assert not np.array_equal(f.chaos_game(1000, seed=4), f.chaos_game(1000, seed=5))
    only_first = f.chaos_game(50, probabilities=[1.0, 0.0])
    np.testing.assert_allclose(only_first, np.broadcast_to(f.fixed_point(0), (50, 2)), atol=1e-12)


# --- surfaces (section 3) --------------------------------------------------------------


def bumpy(xy):
    x, y = xy[:, 0], xy[:, 1]
    return np.c_[x, y, 0.3 * np.sin(1.3 * x) + 0.2 * np.cos(0.7 * y + 0.4) + 0.05 * x * y]


def test_bicubic_patch():
    g = np.array([[i, j] for j in range(4) for i in range(4)], dtype=float)
    f = ifs.bicubic(bumpy(g))
    assert f.n_maps == 4
    v, t = f.mesh(4)
    assert v.shape == (17 * 17, 3) and t.shape == (2 * 256, 3)
    # plain subdivision converges to the mesh
    sv, st = ifs.subdivide_surface(bumpy(g), "bicubic", 5)
    assert st.max() < len(sv)
    assert hausdorff(sv, v) < 0.05


def test_loop_hexagon_and_fig9_subset():
    pts = bumpy(ifs.hex_lattice(2))
    f = ifs.loop(pts)
    assert f.n_maps == 6
    v, t = f.mesh(3)
    assert v.shape == (1 + 3 * 8 * 9, 3) and t.shape == (6 * 64, 3)
    # the centre is Loop's limit position 1/2 v + 1/12 sum of neighbours
    centre = 0.5 * pts[0] + pts[1:7].sum(axis=0) / 12
    assert np.linalg.norm(v - centre, axis=1).min() < 1e-12
    # the mesh is a connected disk: Euler characteristic V - E + F = 1
    edges = {tuple(sorted(e)) for tri in t for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0]))}
    assert len(v) - len(edges) + len(t) == 1
    # subset IFS (two maps dropped): a fractal lying on the surface
    sub = f.subset([0, 2, 3, 4])
    sv, _ = sub.mesh(3)
    assert cKDTree(v).query(sv)[0].max() < 1e-9
    cg = sub.chaos_game(20000)
    assert cKDTree(f.mesh(6)[0]).query(cg)[0].max() < 0.02
    sv, _ = ifs.subdivide_surface(pts, "loop", 4)
    assert hausdorff(sv, v) < 0.1


def test_sqrt3_hexagon():
    with pytest.raises(topomesh.MeshError, match="outside the control net"):
        ifs.sqrt3(bumpy(ifs.hex_lattice(2)))
    pts = bumpy(ifs.hex_lattice(4))
    f = ifs.sqrt3(pts)
    assert f.n_maps == 19
    np.testing.assert_allclose(f.contraction, 1 / 3, atol=1e-6)
    v, t = f.mesh(2)
    assert v.shape == (1 + 3 * 9 * 10, 3) and t.shape == (6 * 81, 3)
    sv, _ = ifs.subdivide_surface(pts, "sqrt3", 3)
    assert cKDTree(sv).query(v)[0].max() < 0.05


# --- fractals with control points (section 4) ----------------------------------------------


def test_koch_dimension_and_standard_ifs():
    k = ifs.koch()
    pts = k.polyline(10)
    assert pts.shape == (4**10 + 1, 2)
    d = ifs.box_counting_dimension(pts)
    assert abs(d - np.log(4) / np.log(3)) < 0.03, d
    std = ifs.koch_standard().iterate([[0.0, 0.0]], 6)[:, 0]
    np.testing.assert_allclose(k.polyline(6)[:-1], std, atol=1e-12)
    # the standard IFS from another polygon converges to the same curve (Fig. 10, middle)
    other = ifs.koch_standard().iterate([[0.2, 0.5], [0.9, -0.3]], 9)
    assert hausdorff(other, k.polyline(9)) < 2e-3


def test_moving_a_koch_control_point_deforms_one_side_only():
    ref = ifs.koch_reference()
    base = ifs.koch(ref).polyline(7)
    half = (len(base) - 1) // 2  # first vertex of the right half (maps 3, 4)
    for idx, changed in [(0, "left"), (1, "left"), (3, "right"), (4, "right")]:
        moved = ref.copy()
        moved[idx] += [0.05, 0.1]
        m = ifs.koch(moved).polyline(7)
        left = np.abs(m[:half] - base[:half]).max()
        right = np.abs(m[half + 1 :] - base[half + 1 :]).max()
        if changed == "left":
            assert right < 1e-12 and left > 1e-2
        else:
            assert left < 1e-12 and right > 1e-2
    # the apex moves everything
    moved = ref.copy()
    moved[2] += [0.0, 0.1]
    m = ifs.koch(moved).polyline(7)
    assert np.abs(m[:half] - base[:half]).max() > 1e-2 and np.abs(m[half + 1 :] - base[half + 1 :]).max() > 1e-2


def test_gasket_rules_dimension_and_deformation():
    g = ifs.gasket()
    s1 = np.array(
        [
            [1, 0, 0, 0, 0, 0],
            [3 / 8, 3 / 4, -1 / 8, 0, 0, 0],
            [0, 1, 0, 0, 0, 0],
            [0, 1 / 2, 0, 0, 0, 1 / 2],
            [0, 0, 0, 0, 0, 1],
            [3 / 8, 0, 0, 0, -1 / 8, 3 / 4],
        ]
    )
    np.testing.assert_allclose(g.blocks[0], s1, atol=1e-12)
    pts = g.iterate([[0.3, 0.2]], 12)[:, 0]
    d = ifs.box_counting_dimension(pts)
    assert abs(d - np.log(3) / np.log(2)) < 0.03, d
    v, t = g.mesh(5)
    assert t.shape == (3**5, 3) and v.shape == ((3**6 + 3) // 2, 2)
    # moved control points: corners stay on the attractor, the shape changes
    moved = ifs.gasket_reference()
    moved[1] += [0.0, -0.2]
    moved[4] += [0.3, 0.0]
    h = ifs.gasket(moved)
    for i in range(3):
        np.testing.assert_allclose(h.fixed_point(i), moved[2 * i], atol=1e-12)
    assert hausdorff(h.chaos_game(20000), g.chaos_game(20000)) > 0.1


def test_general_constructor_from_affine_maps():
    # eq. 5 with the Koch maps and control points reproduces the koch() rules
    A = np.array([[[1 / 3, 0], [0, 1 / 3]]] * 2)
    c, s = 0.5 / 3, np.sqrt(3) / 6
    mats = np.array([A[0], [[c, -s], [s, c]], [[c, s], [-s, c]], A[0]])
    trans = np.array([[0, 0], [1 / 3, 0], [0.5, s], [2 / 3, 0]])
    f = ifs.from_affine_with_control(mats, trans, ifs.koch_reference())
    np.testing.assert_allclose(f.blocks, ifs.koch().blocks, atol=1e-12)
    # a fern-like IFS with 4 control points
    mats = np.array([[[0.5, 0], [0, 0.5]], [[0.5, 0], [0, 0.5]], [[0.5, 0], [0, 0.5]]])
    trans = np.array([[0, 0], [0.5, 0], [0, 0.5]])
    ref = np.array([[0, 0], [1, 0], [0, 1], [0.5, 0.5]])
    f = ifs.from_affine_with_control(mats, trans, ref)
    std = ifs.from_affine(mats, trans)
    assert hausdorff(f.chaos_game(20000), std.chaos_game(20000)) < 0.02
