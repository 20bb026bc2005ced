"""limsurf.reverse_catmull_clark: the numbers of `limsurf reverse --json`, and the original control mesh
back after subdivide (the original file is the oracle)."""
import numpy as np
import pytest

import limsurf


def test_reverse_equals_the_cli(mesh_path, tmp_path, cli_tool, cli):
    fine_path = tmp_path / "fine.obj"
    cli_tool("subdivide", mesh_path("cube_ngons"), "--scheme", "catmull-clark", "--levels", "2", "-o", fine_path)
    theirs = cli("reverse", fine_path, "-o", tmp_path / "coarse.obj", "--json")
    coarse, info = limsurf.reverse_catmull_clark(limsurf.read_mesh(fine_path))
    assert info["levels_reversed"] == theirs["levels_reversed"] == 2
    assert info["method"] == theirs["method"]
    for ours, cli_level in zip(info["per_level"], theirs["per_level"]):
        for key in ("fine_vertices", "fine_faces", "coarse_vertices", "coarse_faces", "residual_max",
                    "residual_rms", "unique"):
            assert ours[key] == cli_level[key], key
    assert np.array_equal(coarse.V, limsurf.read_mesh(tmp_path / "coarse.obj").V)


@pytest.mark.parametrize("name", ["genus2", "cube_creases", "annulus", "tetrahedron"])
def test_subdivide_then_reverse_gives_the_original(mesh_path, name):
    original = limsurf.read_mesh(mesh_path(name))
    fine = limsurf.subdivide(original, "catmull-clark", 2)
    coarse, info = limsurf.reverse_catmull_clark(fine, 2)
    assert info["levels_reversed"] == 2
    assert np.abs(coarse.V - original.V).max() < 1e-12
    assert np.array_equal(coarse.face_offsets, original.face_offsets)
    o = original.face_offsets
    for f in range(original.num_faces):  # each face the same up to a rotation of its corners
        a = list(original.face_vertices[o[f]:o[f + 1]])
        b = list(coarse.face_vertices[o[f]:o[f + 1]])
        assert any(b[k:] + b[:k] == a for k in range(len(b))), (f, a, b)


def test_noise_shows_in_the_residual(mesh_path):
    fine = limsurf.subdivide(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark", 1)
    rng = np.random.default_rng(3)
    noisy = limsurf.Mesh(fine.V + rng.uniform(-1e-5, 1e-5, fine.V.shape), fine.F)
    _, info = limsurf.reverse_catmull_clark(noisy, 1)
    assert 1e-6 <= info["per_level"][0]["residual_max"] <= 1e-4


def test_refuses_a_triangle_naming_the_line(mesh_path):
    with pytest.raises(limsurf.InputError, match=r"single_triangle\.obj:\d+: .*quads only"):
        limsurf.reverse_catmull_clark(limsurf.read_mesh(mesh_path("single_triangle")))
