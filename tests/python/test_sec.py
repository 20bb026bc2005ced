"""SEC operators as scipy matrices (exact identities) and limsurf.poisson equal to `limsurf poisson`."""
import numpy as np
import pytest

import limsurf


def test_exterior_derivatives_and_operators(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    d0, d1 = limsurf.exterior_derivatives(mesh)
    assert d0.shape == (mesh.num_edges, mesh.num_vertices) and d1.shape == (mesh.num_faces, mesh.num_edges)
    assert (d1 @ d0).count_nonzero() == 0
    assert np.array_equal(d0[np.arange(mesh.num_edges), mesh.edges[:, 1]].A1, np.ones(mesh.num_edges))
    ops = limsurf.operators(mesh, "catmull-clark", method="sec", level=2)
    L, M0 = ops["laplacian"], ops["M0"]
    assert abs(L - L.T).max() < 1e-12 and abs(M0 - M0.T).max() < 1e-14
    assert np.abs(L @ np.ones(mesh.num_vertices)).max() < 1e-12
    assert abs(L - d0.T @ ops["M1"] @ d0).max() < 1e-12
    assert abs(ops["divergence"] - d0.T @ ops["M1"]).max() < 1e-12


def test_inner_products_sum_to_the_area(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    area = limsurf.measure(mesh, "catmull-clark")["area"]
    ip = limsurf.inner_products(mesh, "catmull-clark", method="sec", level=4)
    ones = np.ones(mesh.num_vertices)
    assert abs(ones @ ip["M0"] @ ones - area) / area < 2e-3   # M0 integrates 1 to the level-4 area
    lumped = limsurf.inner_products(mesh, "catmull-clark", method="sec", level=4, lumped=True)
    assert np.allclose(lumped["M0"].diagonal(), ip["M0"] @ ones, rtol=1e-12)  # lumping is diag(M 1) (SEC §3.5)


@pytest.mark.parametrize("name, scheme, method", [("genus2", "catmull-clark", "sec"), ("icosahedron", "loop", "dec"),
                                                  ("cylinder_open", "catmull-clark", "iga"),
                                                  ("sphere_tris", "loop", "secsnap")])
def test_poisson_equals_the_cli(mesh_path, cli, name, scheme, method):
    # A polynomial f: the formula parser and numpy then compute bit-identical values.
    theirs = cli("poisson", mesh_path(name), "--scheme", scheme, "--method", method, "--rhs", "x*y + z",
                 "--boundary-value", "x", "--reference-level", 2, "--json")
    ours = limsurf.poisson(limsurf.read_mesh(mesh_path(name)), scheme, lambda P: P[:, 0] * P[:, 1] + P[:, 2],
                           method=method, boundary_values=lambda P: P[:, 0], reference_level=2)
    for key in ("method", "level", "vertices", "closed", "solver", "residual", "mean_removed", "u_min", "u_max",
                "quadrature", "reference"):
        assert ours[key] == theirs[key], key
    assert ours["u"].shape == (ours["vertices"],) and ours["u"].min() == theirs["u_min"]


def test_poisson_with_vertex_values_and_errors(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("sphere_quads"))
    f = mesh.V[:, 2].copy()
    r = limsurf.poisson(mesh, "catmull-clark", f, method="dec")
    assert r["closed"] and abs(r["mean_removed"]) < 1e-12
    # −Δu = z on the unit sphere has u = z/2: the discrete one is close on this coarse sphere
    assert np.corrcoef(r["u"], f)[0, 1] > 0.99
    with pytest.raises(limsurf.InputError, match=rf"^rhs: expected {mesh.num_vertices} values, got 3"):
        limsurf.poisson(mesh, "catmull-clark", [1.0, 2.0, 3.0])
    with pytest.raises(limsurf.InputError, match=r"rhs\(P\) result: expected"):
        limsurf.poisson(mesh, "catmull-clark", lambda P: np.ones(3))
    with pytest.raises(ZeroDivisionError):  # a Python error in the callback propagates as itself
        limsurf.poisson(mesh, "catmull-clark", lambda P: 1 / 0)
    with pytest.raises(limsurf.InputError, match="unknown method .fem."):
        limsurf.poisson(mesh, "catmull-clark", f, method="fem")


def test_poisson_threads_do_not_change_the_solution(mesh_path):
    mesh = limsurf.subdivide(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark", 2)
    one = limsurf.poisson(mesh, "catmull-clark", lambda P: P[:, 0], method="sec", threads=1)
    two = limsurf.poisson(mesh, "catmull-clark", lambda P: P[:, 0], method="sec", threads=2)
    assert np.array_equal(one["u"], two["u"])
    with pytest.raises(limsurf.InputError, match="threads must be >= 0"):
        limsurf.poisson(mesh, "catmull-clark", lambda P: P[:, 0], threads=-1)
