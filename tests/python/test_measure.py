"""limsurf.measure, limsurf.volume and limsurf.polyhedral_volumes equal `limsurf measure` / `limsurf volume`; the volume gradient
is exact (finite differences, homogeneity)."""
import numpy as np
import pytest

import limsurf


@pytest.mark.parametrize("name, scheme", [("genus2", "catmull-clark"), ("icosahedron", "loop"),
                                          ("cylinder_open", "catmull-clark")])
def test_measure_equals_the_cli(mesh_path, cli, name, scheme):
    theirs = cli("measure", mesh_path(name), "--scheme", scheme, "--json")
    ours = limsurf.measure(limsurf.read_mesh(mesh_path(name)), scheme)
    assert ours["closed"] == theirs["closed"]
    assert ours["area"] == theirs["area"]
    assert list(ours["surface_centroid"]) == theirs["surface_centroid"]
    assert ours["error_estimate"] == theirs["error_estimate"]
    if theirs["closed"]:
        assert ours["volume"] == theirs["volume"]
        assert list(ours["centroid"]) == theirs["centroid"]
        assert ours["inertia"].tolist() == theirs["inertia"]
    else:
        assert ours["volume"] is None and ours["inertia"] is None


@pytest.mark.parametrize("name, scheme", [("genus2", "catmull-clark"), ("icosahedron", "loop"), ("cube", "doo-sabin")])
def test_volume_equals_the_cli(mesh_path, cli, name, scheme):
    theirs = cli("volume", mesh_path(name), "--scheme", scheme, "--json")
    assert limsurf.volume(limsurf.read_mesh(mesh_path(name)), scheme) == theirs["volume"]


@pytest.mark.parametrize("name, scheme", [("genus2", "catmull-clark"), ("icosahedron", "loop"), ("cube", "doo-sabin")])
def test_polyhedral_volumes_equal_the_cli_and_approach_the_exact_volume(mesh_path, cli, name, scheme):
    theirs = cli("volume", mesh_path(name), "--scheme", scheme, "--levels", "4", "--json")
    mesh = limsurf.read_mesh(mesh_path(name))
    ours = limsurf.polyhedral_volumes(mesh, scheme, levels=4)
    assert [(l["level"], l["faces"], l["volume"]) for l in ours] == [
        (l["level"], l["faces"], l["volume"]) for l in theirs["polyhedral"]]
    errors = [abs(l["volume"] - theirs["volume"]) for l in ours]
    assert all(b < a for a, b in zip(errors, errors[1:]))  # closer at every level
    # A face budget ends the list early; a negative level count is refused.
    assert len(limsurf.polyhedral_volumes(mesh, scheme, levels=4, max_faces=4 * mesh.num_faces)) <= 2
    with pytest.raises(limsurf.InputError):
        limsurf.polyhedral_volumes(mesh, scheme, levels=-1)


def test_volume_gradient_is_exact(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    V0, G = limsurf.volume(mesh, "catmull-clark", gradient=True)
    assert G.shape == mesh.V.shape
    assert np.isclose(np.sum(G * mesh.V), 3 * V0, rtol=1e-12)  # homogeneous of degree 3
    assert np.allclose(G.sum(axis=0), 0, atol=1e-12 * abs(V0))  # translation invariant
    rng = np.random.default_rng(4)
    D = rng.standard_normal(mesh.V.shape)
    h = 1e-6
    plus = limsurf.volume(mesh, "catmull-clark", X=mesh.V + h * D)
    minus = limsurf.volume(mesh, "catmull-clark", X=mesh.V - h * D)
    assert np.isclose((plus - minus) / (2 * h), np.sum(G * D), rtol=1e-7)


def test_open_meshes_have_no_volume(mesh_path):
    with pytest.raises(limsurf.InputError, match="boundary"):
        limsurf.volume(limsurf.read_mesh(mesh_path("cylinder_open")), "catmull-clark")
