"""limsurf.LimitBasis: vectorised evaluation equals `limsurf eval`, weights are the evaluation,
the GIL is released, bad points are named."""
import functools
import threading
import time

import numpy as np
import pytest

import limsurf


def cli_points(result):
    faces = np.array([p["face"] for p in result["points"]])
    u = np.array([p["u"] for p in result["points"]])
    v = np.array([p["v"] for p in result["points"]])
    return faces, u, v


@pytest.mark.parametrize("name, scheme", [("genus2", "catmull-clark"), ("icosahedron", "loop"),
                                          ("cube_creases", "catmull-clark"), ("cylinder_open", "catmull-clark"),
                                          ("tetra_2", "c2g0"), ("cube", "doo-sabin")])
def test_evaluate_equals_the_cli_exactly(mesh_path, cli, name, scheme):
    theirs = cli("eval", mesh_path(name), "--scheme", scheme, "--grid", 3, "--json")
    faces, u, v = cli_points(theirs)
    basis = limsurf.LimitBasis(limsurf.read_mesh(mesh_path(name)), scheme)
    ours = basis.evaluate(faces, u, v)
    for key in ("position", "du", "dv", "duu", "duv", "dvv", "normal"):
        expected = np.array([p[key] for p in theirs["points"]], dtype=float)
        assert np.array_equal(ours[key], expected), key
    for key in ("mean_curvature", "gaussian_curvature"):
        expected = np.array([np.nan if p[key] is None else p[key] for p in theirs["points"]])
        assert np.array_equal(ours[key], expected, equal_nan=True), key
    assert np.array_equal(ours["curvature_defined"], ~np.isnan(ours["mean_curvature"]))


def test_shapes_dtypes_and_orders(mesh_path):
    basis = limsurf.LimitBasis(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark")
    n = 50
    rng = np.random.default_rng(1)
    faces = rng.integers(0, basis.num_ptex_faces, n)
    u, v = rng.random(n), rng.random(n)
    r0 = basis.evaluate(faces, u, v, order=0)
    r2 = basis.evaluate(faces, u, v, order=2)
    assert set(r0) == {"position"}
    assert r2["position"].shape == (n, 3) and r2["position"].dtype == np.float64 and r2["position"].flags.c_contiguous
    assert r2["mean_curvature"].shape == (n,) and r2["curvature_defined"].dtype == bool
    assert np.allclose(r0["position"], r2["position"], rtol=0, atol=1e-14)
    assert np.allclose(np.linalg.norm(r2["normal"], axis=1), 1.0)
    assert np.allclose(r2["k1"] + r2["k2"], 2 * r2["mean_curvature"]) and np.all(r2["k1"] >= r2["k2"])


def test_weights_applied_to_V_are_the_evaluation(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    rng = np.random.default_rng(2)
    faces = rng.integers(0, basis.num_ptex_faces, 40)
    u, v = rng.random(40), rng.random(40)
    W = basis.weights(faces, u, v, order=2)
    r = basis.evaluate(faces, u, v, order=2)
    for key in ("position", "du", "dv", "duu", "duv", "dvv"):
        assert W[key].shape == (40, mesh.num_vertices) and W[key].format == "csr"
        assert np.allclose(W[key] @ mesh.V, r[key], rtol=0, atol=1e-12), key
    assert np.allclose(W["position"].sum(axis=1), 1.0, atol=1e-14)


def test_other_control_points_and_limit_positions(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("sphere_quads"))
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    P = basis.vertex_limit_matrix()
    assert np.allclose(P @ mesh.V, basis.limit_positions())
    scaled = basis.evaluate([0, 1], [0.3, 0.7], [0.2, 0.9], order=0, X=2 * mesh.V)
    plain = basis.evaluate([0, 1], [0.3, 0.7], [0.2, 0.9], order=0)
    assert np.allclose(scaled["position"], 2 * plain["position"])


def bicubic_bspline(s, t):
    """The uniform cubic B-spline pieces (limsurf's patch_basis.h numbering: point 4 j + i at lattice
    (i - 1, j - 1)), written out here so that the patch's control net is checked independently."""
    def pieces(x):
        return np.array([(1 - x) ** 3, 3 * x ** 3 - 6 * x ** 2 + 4, -3 * x ** 3 + 3 * x ** 2 + 3 * x + 1, x ** 3]) / 6
    return np.outer(pieces(t), pieces(s)).ravel()


def expect_the_same_net_without_points(basis, face, u, v, patch):
    """points=False (LimitBasis::patch_data): the same patch and net, without 'points' and 'offset'."""
    lean = basis.patch(face, u, v, points=False)
    assert set(lean) == set(patch) - {"points", "offset"}
    assert lean["domain"] == patch["domain"] and np.array_equal(lean["vertices"], patch["vertices"])
    assert np.array_equal(lean["origin"], patch["origin"]) and np.array_equal(lean["axes"], patch["axes"])
    assert np.allclose(lean["control_points"], patch["control_points"], rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["genus2", "cube_creases"])
def test_a_patch_control_net_gives_the_surface_on_its_tile(mesh_path, name):
    mesh = limsurf.read_mesh(mesh_path(name))
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    rng = np.random.default_rng(5)
    checked = 0
    for face in range(basis.num_ptex_faces):
        for u, v in [rng.random(2), (2.0 ** -20, 0.3 * 2.0 ** -20)]:
            patch = basis.patch(face, u, v)
            assert patch is not None and patch["domain"] == "quad"
            assert patch["points"].shape == (16, len(patch["vertices"]))
            assert np.allclose(patch["points"].sum(axis=1) + patch["offset"].sum(), 1.0, rtol=0, atol=1e-12)
            net = patch["control_points"]
            assert np.allclose(net, patch["points"] @ mesh.V[patch["vertices"]] + patch["offset"] @ mesh.V[patch["vertices"]],
                               rtol=0, atol=1e-12)
            expect_the_same_net_without_points(basis, face, u, v, patch)
            # Three points of the tile: the net's B-spline against the basis.
            for s, t in [np.linalg.solve(patch["axes"], np.array([u, v]) - patch["origin"]), (0.2, 0.7), (0.9, 0.4)]:
                assert -1e-9 <= s <= 1 + 1e-9 and -1e-9 <= t <= 1 + 1e-9
                uv = patch["origin"] + patch["axes"] @ np.array([s, t])
                expected = basis.evaluate([face], [uv[0]], [uv[1]], order=0)["position"][0]
                assert np.allclose(bicubic_bspline(s, t) @ net, expected, rtol=0, atol=1e-12)
                checked += 1
    assert checked == 3 * 2 * basis.num_ptex_faces
    moved = mesh.V * 2.0 + 1.0
    assert np.allclose(basis.patch(0, 0.5, 0.5, X=moved)["control_points"],
                       basis.patch(0, 0.5, 0.5)["control_points"] * 2.0 + 1.0, rtol=0, atol=1e-12)


# patch_basis.h's numbering of the Loop patch's 12 points on the triangular lattice (i along s, j
# along t; neighbours ±(1, 0), ±(0, 1), ±(1, −1)).
BOX_SPLINE_LATTICE = [(0, -1), (1, -1), (2, -1), (-1, 0), (0, 0), (1, 0), (2, 0), (-1, 1), (0, 1), (1, 1), (-1, 2), (0, 2)]


@functools.lru_cache(maxsize=None)
def box_spline_by_subdivision(s, t, levels=4):
    """The 12 quartic box-spline weights at the dyadic point (s, t) = (i, j) / 2^levels, from Loop's
    regular rules alone: each point's impulse on the lattice is refined `levels` times (vertex 10/16
    and 1/16, edge 3/8 and 1/8) and Loop's regular limit mask (1/2 and 1/12) read at (i, j). It
    shares no formula with Stam's polynomials, which the library uses."""
    pad = 4
    grid = np.zeros((12, 2 * pad + 2, 2 * pad + 2))
    for k, (i, j) in enumerate(BOX_SPLINE_LATTICE):
        grid[k, i + pad, j + pad] = 1.0
    origin = pad

    def at(g, di, dj):  # g shifted: at(g, di, dj)[a, b] = g[a + di, b + dj], zero outside
        out = np.zeros_like(g)
        n, m = g.shape[1:]
        out[:, max(0, -di):n - max(0, di), max(0, -dj):m - max(0, dj)] = \
            g[:, max(0, di):n - max(0, -di), max(0, dj):m - max(0, -dj)]
        return out

    for _ in range(levels):
        n, m = grid.shape[1:]
        fine = np.zeros((12, 2 * n - 1, 2 * m - 1))
        ring = sum(at(grid, di, dj) for di, dj in [(1, 0), (-1, 0), (0, 1), (0, -1), (1, -1), (-1, 1)])
        fine[:, 0::2, 0::2] = 10 / 16 * grid + 1 / 16 * ring
        # Edge points of the edges along (1, 0), (0, 1) and (−1, 1) from lattice point (a, b).
        e10 = 3 / 8 * (grid + at(grid, 1, 0)) + 1 / 8 * (at(grid, 0, 1) + at(grid, 1, -1))
        e01 = 3 / 8 * (grid + at(grid, 0, 1)) + 1 / 8 * (at(grid, 1, 0) + at(grid, -1, 1))
        e11 = 3 / 8 * (at(grid, 1, 0) + at(grid, 0, 1)) + 1 / 8 * (grid + at(grid, 1, 1))
        fine[:, 1::2, 0::2] = e10[:, :-1, :]
        fine[:, 0::2, 1::2] = e01[:, :, :-1]
        fine[:, 1::2, 1::2] = e11[:, :-1, :-1]
        grid, origin = fine, 2 * origin
    a, b = origin + round(s * 2 ** levels), origin + round(t * 2 ** levels)
    assert abs(s * 2 ** levels - round(s * 2 ** levels)) < 1e-12 and abs(t * 2 ** levels - round(t * 2 ** levels)) < 1e-12
    ring = sum(grid[:, a + di, b + dj] for di, dj in [(1, 0), (-1, 0), (0, 1), (0, -1), (1, -1), (-1, 1)])
    return grid[:, a, b] / 2 + ring / 12


def test_loops_regular_weights_are_its_published_limit_mask_and_the_box_spline(mesh_path):
    """On tri_torus (every valence 6) the library's limit weights: at each control vertex Loop's
    published limit mask, 1/2 and 1/12 at each of the six neighbours (χ = 1/(3/(8β) + n) with
    β = 1/16); inside each face, non-negative, summing to 1 and equal to the box spline built by the
    helper above from Loop's refinement rules alone (its corner, the same mask, checked too)."""
    mesh = limsurf.read_mesh(mesh_path("tri_torus"))
    basis = limsurf.LimitBasis(mesh, "loop")
    P = basis.vertex_limit_matrix().toarray()
    for v in range(mesh.num_vertices):
        row = P[v]
        assert np.isclose(row[v], 0.5, rtol=0, atol=1e-15)
        others = np.delete(row, v)
        assert np.count_nonzero(np.abs(others) > 1e-15) == 6
        assert np.allclose(others[np.abs(others) > 1e-15], 1 / 12, rtol=0, atol=1e-15)
    corner = box_spline_by_subdivision(0.0, 0.0)
    ring = [0, 1, 3, 5, 7, 8]  # (0, −1), (1, −1), (−1, 0), (1, 0), (−1, 1), (0, 1)
    assert np.isclose(corner[4], 0.5, rtol=0, atol=1e-15) and np.allclose(corner[ring], 1 / 12, rtol=0, atol=1e-15)
    assert np.allclose(np.delete(corner, ring + [4]), 0.0, rtol=0, atol=1e-15)
    for face in range(0, basis.num_ptex_faces, 7):
        patch = basis.patch(face, 1 / 3, 1 / 3)
        for s, t in [(0.25, 0.5), (0.0625, 0.875), (1.0, 0.0), (0.5, 0.0)]:
            uv = patch["origin"] + patch["axes"] @ np.array([s, t])
            w = basis.weights([face], [uv[0]], [uv[1]])["position"].toarray()[0]
            assert np.isclose(w.sum(), 1.0, rtol=0, atol=1e-14) and np.all(w >= -1e-15)
            expected = np.zeros(mesh.num_vertices)
            np.add.at(expected, patch["vertices"], patch["points"].T @ box_spline_by_subdivision(s, t))
            assert np.allclose(w, expected, rtol=0, atol=1e-14)


@pytest.mark.parametrize("name", ["icosahedron", "tri_grid", "disk_ev7_tris", "tri_valence_7"])
def test_a_loop_patch_control_net_gives_the_surface_on_its_tile(mesh_path, name):
    """The 12-point net of a Loop patch, with the box spline computed from Loop's own rules (above),
    is the limit surface at dyadic points of its tile: regular faces, tiles near extraordinary
    vertices (valences 5 and 7), boundary patches, and tiles at tri_grid's corner vertices (one face)."""
    mesh = limsurf.read_mesh(mesh_path(name))
    basis = limsurf.LimitBasis(mesh, "loop")
    dyadic = [(0.25, 0.25), (0.5, 0.125), (0.1875, 0.625), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.3125, 0.6875)]
    rng = np.random.default_rng(7)
    checked = 0
    for face in range(basis.num_ptex_faces):
        for u, v in [(1 / 3, 1 / 3), tuple(rng.random(2) / 2), (2.0 ** -12, 2.0 ** -13)]:
            patch = basis.patch(face, u, v)
            assert patch is not None and patch["domain"] == "triangle"
            assert patch["points"].shape == (12, len(patch["vertices"]))
            net = patch["control_points"]
            expect_the_same_net_without_points(basis, face, u, v, patch)
            for s, t in dyadic:
                uv = patch["origin"] + patch["axes"] @ np.array([s, t])
                expected = basis.evaluate([face], [uv[0]], [uv[1]], order=0)["position"][0]
                assert np.allclose(box_spline_by_subdivision(s, t) @ net, expected, rtol=0, atol=1e-12)
                checked += 1
    assert checked == 3 * len(dyadic) * basis.num_ptex_faces


def test_patches_are_none_where_there_are_none_and_bad_points_are_named(mesh_path):
    assert limsurf.LimitBasis(limsurf.read_mesh(mesh_path("cube")), "doo-sabin").patch(0, 0.5, 0.5) is None
    basis = limsurf.LimitBasis(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark")
    extraordinary = limsurf.LimitBasis(limsurf.read_mesh(mesh_path("icosahedron")), "loop")
    assert extraordinary.patch(0, 0.0, 0.0) is None  # at a valence-5 vertex itself
    assert extraordinary.patch(0, 0.0, 0.0, points=False) is None
    assert extraordinary.patch(0, 0.25, 0.25)["domain"] == "triangle"
    with pytest.raises(limsurf.InputError, match="ptex face"):
        basis.patch(basis.num_ptex_faces, 0.5, 0.5)
    with pytest.raises(limsurf.InputError, match="outside"):
        basis.patch(0, 1.5, 0.5)


def test_evaluation_releases_the_gil_and_two_threads_agree(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    fine = limsurf.subdivide(mesh, "catmull-clark", 2)
    basis = limsurf.LimitBasis(fine, "catmull-clark")
    n = 200_000
    rng = np.random.default_rng(3)
    faces = rng.integers(0, basis.num_ptex_faces, n)
    u, v = rng.random(n), rng.random(n)
    serial = basis.evaluate(faces, u, v, order=2, threads=1)

    ticks = []
    done = threading.Event()

    def ticker():  # runs only while the evaluating thread does not hold the GIL
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    results = [None, None]

    def work(k):
        results[k] = basis.evaluate(faces, u, v, order=2, threads=1)

    t = threading.Thread(target=ticker)
    t.start()
    workers = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    start = time.perf_counter()
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    elapsed = time.perf_counter() - start
    done.set()
    t.join()
    for r in results:
        for key in serial:
            assert np.array_equal(r[key], serial[key], equal_nan=True), key
    # With the GIL held for the whole evaluation the ticker would stall; released, it ticks on.
    assert len(ticks) > 0.3 * elapsed / 0.001 * 0.5, (len(ticks), elapsed)


def test_out_reuses_the_arrays_of_an_earlier_call(mesh_path):
    basis = limsurf.LimitBasis(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark")
    rng = np.random.default_rng(3)
    faces = rng.integers(0, basis.num_ptex_faces, 500)
    first = basis.evaluate(faces, rng.random(500), rng.random(500))
    u, v = rng.random(500), rng.random(500)
    fresh = basis.evaluate(faces, u, v)
    arrays = {key: id(a) for key, a in first.items()}
    again = basis.evaluate(faces, u, v, out=first)
    assert again is not fresh and set(again) == set(fresh)
    for key in fresh:
        assert id(again[key]) == arrays[key], key  # the same array objects, filled again
        assert np.array_equal(again[key], fresh[key], equal_nan=key != "curvature_defined"), key
    # int32 faces (converted) give the same numbers as int64 (read in place)
    converted = basis.evaluate(faces.astype(np.int32), u, v)
    assert np.array_equal(converted["position"], fresh["position"])
    with pytest.raises(limsurf.InputError, match=r"out\['position'\]: expected shape \(499, 3\)"):
        basis.evaluate(faces[:499], u[:499], v[:499], out=first)
    with pytest.raises(limsurf.InputError, match=r"out\['du'\]: expected a float64 numpy array"):
        basis.evaluate(faces, u, v, out={"du": np.zeros((500, 3), dtype=np.float32)})
    with pytest.raises(limsurf.InputError, match=r"out\['position'\]: expected a writeable C-contiguous"):
        basis.evaluate(faces, u, v, out={"position": np.zeros((3, 500)).T})
    with pytest.raises(limsurf.InputError, match=r"faces: expected integers, got float64"):
        basis.evaluate(faces.astype(float), u, v)


def test_bad_points_are_named(mesh_path):
    basis = limsurf.LimitBasis(limsurf.read_mesh(mesh_path("icosahedron")), "loop")
    with pytest.raises(limsurf.InputError, match=r"point 1: \(u, v\) = \(0.75, 0.5\) is outside the triangle"):
        basis.evaluate([0, 1], [0.2, 0.75], [0.2, 0.5])
    with pytest.raises(limsurf.InputError, match=r"faces\[0\] = 20: out of range \[0, 20\)"):
        basis.evaluate([20], [0.1], [0.1])
    with pytest.raises(limsurf.InputError, match=r"faces has 2 values and v has 1"):
        basis.evaluate([0, 1], [0.1, 0.1], [0.1])
    # An unsigned index above the signed range wrapped to -1 in the message; now its value is named.
    with pytest.raises(limsurf.InputError, match=r"faces\[0\] = 18446744073709551615: out of range"):
        basis.evaluate(np.array([2**64 - 1], dtype=np.uint64), [0.1], [0.1])
    # Negative thread counts, and out= keys evaluate() does not return, are refused (they were ignored).
    with pytest.raises(limsurf.InputError, match=r"threads: expected 0 \(all cores\) or a positive count"):
        basis.evaluate([0], [0.1], [0.1], threads=-1)
    with pytest.raises(limsurf.InputError, match=r"out: unknown key 'positon'"):
        basis.evaluate([0], [0.1], [0.1], out={"positon": np.zeros((1, 3))})
    # An empty list is a float64 array in numpy: no points, not a dtype error.
    assert basis.evaluate([], [], [])["position"].shape == (0, 3)


def test_normals_of_a_surface_near_the_largest_double_are_finite(mesh_path):
    # The tangents' cross product overflowed for a surface 1e160 across: the normal was nan while
    # curvature_defined said True. The normal does not depend on the size (it is scaled exactly).
    mesh = limsurf.read_mesh(mesh_path("cube"))
    basis = limsurf.LimitBasis(mesh, "catmull-clark")
    faces, u, v = [0, 1], [0.1, 0.5], [0.2, 0.5]
    unit = basis.evaluate(faces, u, v, order=2)
    huge = basis.evaluate(faces, u, v, order=2, X=np.array(mesh.V) * 2.0**700)
    assert np.isfinite(huge["normal"]).all()
    np.testing.assert_array_equal(huge["normal"], unit["normal"])
    np.testing.assert_array_equal(huge["mean_curvature"], unit["mean_curvature"] * 2.0**-700)
    with pytest.raises(limsurf.InputError, match=r"u\[0\] = nan"):
        basis.evaluate([0], [np.nan], [0.1])
    with pytest.raises(limsurf.InputError, match="faces: expected integers"):
        basis.evaluate([0.5], [0.1], [0.1])
    # an error about an element of a mesh read from a file names the file and the element's line
    with pytest.raises(limsurf.UnsupportedError, match=r"cube\.obj:10: Loop limit evaluation: face 0 has 4 corners"):
        limsurf.LimitBasis(limsurf.read_mesh(mesh_path("cube")), "loop")


def test_points_on_faces_without_a_limit_surface_are_named(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("quad_grid"))
    basis = limsurf.LimitBasis(mesh, "catmull-clark", boundary="none")
    missing = np.nonzero(~basis.has_limit_surface())[0]
    inside = np.nonzero(basis.has_limit_surface())[0]
    assert len(missing) and len(inside)
    faces = np.concatenate([np.repeat(inside[:1], 5000), missing[:1], inside[:1], missing[:1]])
    n = len(faces)
    for threads in (1, 2, 4):  # the first bad point, whichever thread meets it
        with pytest.raises(limsurf.InputError, match=rf"^point 5000: ptex face {missing[0]} .*no limit surface"):
            basis.evaluate(faces, np.full(n, 0.5), np.full(n, 0.5), threads=threads)
    with pytest.raises(limsurf.InputError, match=r"^point 5000: "):
        basis.weights(faces, np.full(n, 0.5), np.full(n, 0.5))


def test_quadrature_samples_integrate_the_area_that_measure_reports(mesh_path):
    """The samples measure() integrates with: weights 1 per quad ptex face (1/2 per triangle), and
    Σ w |∂u x × ∂v x| over them is measure()'s area (the same samples, so to rounding)."""
    for name, scheme in [("genus2", "catmull-clark"), ("icosahedron", "loop")]:
        mesh = limsurf.read_mesh(mesh_path(name))
        basis = limsurf.LimitBasis(mesh, scheme)
        q = basis.quadrature_samples(degree=7, tiles=3)
        assert q["faces"].dtype == np.int64 and q["u"].shape == q["weights"].shape == q["faces"].shape
        per_face = np.bincount(q["faces"], weights=q["weights"], minlength=basis.num_ptex_faces)
        assert np.allclose(per_face, 1.0 if scheme == "catmull-clark" else 0.5, rtol=0, atol=1e-13)
        r = basis.evaluate(q["faces"], q["u"], q["v"], order=1, frames=False)
        area = np.sum(q["weights"] * np.linalg.norm(np.cross(r["du"], r["dv"]), axis=1))
        assert np.isclose(area, limsurf.measure(mesh, scheme, degree=7, tiles=3)["area"], rtol=1e-12, atol=0)
    with pytest.raises(limsurf.InputError, match="tile levels"):
        basis.quadrature_samples(tiles=31)
