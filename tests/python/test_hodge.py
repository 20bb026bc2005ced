"""limsurf.hodge_decomposition and limsurf.harmonic_basis against `limsurf hodge --json` (the same numbers,
exactly), the parts' identities checked with the operators of limsurf.operators (an independent assembly of
d0, d1 and M1), and the harmonic dimension 2g."""
import numpy as np
import pytest

import limsurf


@pytest.mark.parametrize("name, scheme, method", [("genus2", "catmull-clark", "sec"), ("torus_4x5", "loop", "dec"),
                                                  ("annulus", "catmull-clark", "secsnap")])
def test_hodge_equals_the_cli(mesh_path, cli, name, scheme, method):
    sec = method.startswith("sec")  # only sec and secsnap take a level: both sides refuse it with dec
    theirs = cli("hodge", mesh_path(name), "--scheme", scheme, "--method", method, *(("--level", 2) if sec else ()),
                 "--random", 5, "--reference-level", 1, "--json")
    mesh = limsurf.read_mesh(mesh_path(name))
    level = 2 if sec else None
    ours = limsurf.hodge_decomposition(mesh, scheme, random=5, method=method, level=level, reference_level=1)
    for key in theirs:
        assert ours[key] == theirs[key], key
    # The identities, with the operators assembled by limsurf.operators.
    ops = limsurf.operators(mesh, scheme, method=method, level=level)
    d0, d1, M1 = ops["d0"], ops["d1"], ops["M1"]
    w, a, c, h = ours["w"], ours["exact"], ours["coexact"], ours["harmonic"]
    scale = w @ (M1 @ w)
    assert np.abs(a + c + h - w).max() <= 1e-14 * np.abs(w).max()
    for x, y in ((a, c), (a, h), (c, h)):
        assert abs(x @ (M1 @ y)) < 1e-12 * scale
    assert np.abs(d1 @ h).max() < 1e-11 * np.abs(d1 @ w).max()
    assert np.abs(d0.T @ (M1 @ h)).max() < 1e-11 * np.abs(d0.T @ (M1 @ w)).max()
    assert np.abs(a - d0 @ ours["alpha"]).max() < 1e-14 * np.abs(w).max() * 10


def test_harmonic_basis(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    b = limsurf.harmonic_basis(mesh, "catmull-clark", method="sec", level=2)
    assert b["dimension"] == b["expected"] == 4 and b["gap"] > 1e6
    M1 = limsurf.inner_products(mesh, "catmull-clark", method="sec", level=2)["M1"]
    F = b["forms"]
    assert np.abs(F.T @ (M1 @ F) - np.eye(4)).max() < 1e-12
    sphere = limsurf.harmonic_basis(limsurf.read_mesh(mesh_path("icosahedron")), "loop", method="dec")
    assert sphere["dimension"] == 0 and sphere["forms"].shape == (30, 0)


def test_errors(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    with pytest.raises(limsurf.InputError, match="exactly one of w"):
        limsurf.hodge_decomposition(mesh, "catmull-clark")
    with pytest.raises(limsurf.InputError, match="w: expected 100 values"):
        limsurf.hodge_decomposition(mesh, "catmull-clark", [1.0])
