"""limsurf.geodesic_distance equal to `limsurf geodesic --json`, limsurf.HeatGeodesics for repeated
queries (the same numbers as one-off calls), and its errors (SEC §4.2, apps/geodesics.h)."""
import numpy as np
import pytest

import limsurf

KEYS = ("scheme", "method", "level", "quadrature", "gradient", "gradient_level", "vertices", "closed", "sources",
        "time_factor", "t", "mean_edge_length", "max_edge_length", "distance_min", "distance_max", "limit_distance_min",
        "limit_distance_max", "source_values", "reference")


@pytest.mark.parametrize("name, scheme, method, sources", [("genus2", "catmull-clark", "sec", [0]),
                                                           ("tri_torus", "loop", "dec", [3, 20]),
                                                           ("quad_grid", "catmull-clark", "secsnap", [12]),
                                                           ("tri_torus", "loop", "iga", [3])])
def test_geodesic_distance_equals_the_cli(mesh_path, cli, name, scheme, method, sources):
    args = ["geodesic", mesh_path(name), "--scheme", scheme, "--method", method, "--reference-level", 2,
            "--time-factor", 2, "--json"]
    for s in sources:
        args += ["--source", s]
    theirs = cli(*args)
    ours = limsurf.geodesic_distance(limsurf.read_mesh(mesh_path(name)), scheme, sources, method=method,
                                     reference_level=2, time_factor=2.0)
    for key in KEYS:
        assert ours[key] == theirs[key], key
    assert ours["distance"].shape == (ours["vertices"],) and ours["distance"].max() == theirs["distance_max"]


def test_prefactorised_queries_match_one_off_calls(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    heat = limsurf.HeatGeodesics(mesh, "catmull-clark", method="sec", level=2)
    assert heat.time_step == pytest.approx(heat.mean_edge_length ** 2, rel=1e-15)
    assert heat.gradient == "subdivided" and heat.gradient_level == 2  # auto below level 3
    assert heat.setup_seconds >= 0 and heat.factorisation_seconds >= 0
    for sources in (5, [5, 30]):
        once = limsurf.geodesic_distance(mesh, "catmull-clark", sources, method="sec", level=2)["distance"]
        assert np.array_equal(heat.distance(sources), once)
    d = heat.distance(7)
    assert abs(heat.source_values(d, 7)[0]) < 0.3 * heat.mean_edge_length
    dec = limsurf.HeatGeodesics(mesh, "catmull-clark", method="dec")
    assert dec.distance([7])[7] == 0.0 and dec.gradient_level == 0 and dec.gradient == "control"
    subdivided = limsurf.HeatGeodesics(mesh, "catmull-clark", level=2, gradient_level=1)
    assert subdivided.gradient == "subdivided" and subdivided.gradient_level == 1
    explicit = limsurf.HeatGeodesics(mesh, "catmull-clark", level=2, gradient="subdivided", gradient_level=1)
    assert np.array_equal(explicit.distance(7), subdivided.distance(7))
    limit = limsurf.HeatGeodesics(mesh, "catmull-clark", gradient="limit")
    assert limit.gradient == "limit" and limit.gradient_level is None
    finer = limsurf.HeatGeodesics(mesh, "catmull-clark", gradient="limit", gradient_degree=6)
    coarse = limit.distance(7)
    assert not np.array_equal(finer.distance(7), coarse)
    assert np.allclose(finer.distance(7), coarse, atol=0.03 * coarse.max())


def test_distances_batches_source_sets(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("quad_grid"))  # open: the Neumann/Dirichlet average too
    heat = limsurf.HeatGeodesics(mesh, "catmull-clark")
    sets = [12, [0, 24], 7]
    batch = heat.distances(sets)
    assert batch.shape == (len(mesh.V), 3)
    for k, sources in enumerate(sets):
        single = heat.distance(sources)
        assert np.allclose(batch[:, k], single, rtol=0, atol=1e-12 * np.abs(single).max())
    assert heat.distances([]).shape == (len(mesh.V), 0)
    n = len(mesh.V)
    with pytest.raises(limsurf.InputError, match=rf"^source_sets\[1\]\[1\] = 99: out of range \[0, {n}\)"):
        heat.distances([3, [4, 99]])
    # A negative index names the mesh's range too (it was [0, 2147483647), the conversion's bound).
    with pytest.raises(limsurf.InputError, match=rf"^source_sets\[0\]\[0\] = -1: out of range \[0, {n}\)"):
        heat.distances([-1])
    with pytest.raises(limsurf.InputError, match=rf"^sources\[0\] = -2: out of range \[0, {n}\)"):
        heat.distance(-2)


def test_errors(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    with pytest.raises(limsurf.InputError, match=r"^sources\[1\] = 48: out of range \[0, 48\)"):
        limsurf.geodesic_distance(mesh, "catmull-clark", [1, 48])
    with pytest.raises(limsurf.InputError, match=r"^sources\[0\] = -3: out of range \[0, 48\)"):
        limsurf.geodesic_distance(mesh, "catmull-clark", -3)
    with pytest.raises(limsurf.InputError, match="no source vertex"):
        limsurf.HeatGeodesics(mesh, "catmull-clark", method="dec").distance([])
    with pytest.raises(limsurf.InputError, match="connected components"):
        limsurf.geodesic_distance(limsurf.read_mesh(mesh_path("tetra_and_cube")), "catmull-clark", 0)
    with pytest.raises(limsurf.InputError, match="time factor"):
        limsurf.HeatGeodesics(mesh, "catmull-clark", time_factor=-1.0)
    with pytest.raises(limsurf.InputError, match="subdivided gradient only"):
        limsurf.HeatGeodesics(mesh, "catmull-clark", gradient="limit", gradient_level=1)
    with pytest.raises(limsurf.InputError, match="unknown heat gradient"):
        limsurf.HeatGeodesics(mesh, "catmull-clark", gradient="faces")
    with pytest.raises(limsurf.InputError, match=r"^sources: expected integers, got dtype <U4"):
        limsurf.geodesic_distance(mesh, "catmull-clark", "zero")
    with pytest.raises(limsurf.InputError, match=r"^sources: expected a vector, got 2 dimensions"):
        limsurf.geodesic_distance(mesh, "catmull-clark", [[0, 1]])
