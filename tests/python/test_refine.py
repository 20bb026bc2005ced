"""limsurf.subdivide: the finest mesh equals the CLI's, and the sparse operators are the refinement."""
import numpy as np
import pytest

import limsurf


@pytest.mark.parametrize("name, scheme, levels", [
    ("genus2", "catmull-clark", 2), ("icosahedron", "loop", 2), ("cube_creases", "catmull-clark", 2),
    ("cube", "doo-sabin", 2), ("tetra_2", "c2g0", 1)])
def test_subdivide_equals_the_cli(mesh_path, tmp_path, cli_tool, name, scheme, levels):
    out = tmp_path / "fine.obj"  # written with 17 significant digits: exact round trips
    cli_tool("subdivide", mesh_path(name), "--scheme", scheme, "--levels", levels, "-o", out)
    theirs = limsurf.read_mesh(out)
    ours = limsurf.subdivide(limsurf.read_mesh(mesh_path(name)), scheme, levels)
    assert np.array_equal(ours.V, theirs.V), "positions must be identical, bit for bit"
    assert np.array_equal(ours.face_vertices, theirs.face_vertices)


def test_operators_reproduce_the_positions_and_commute_with_d(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    fine, ops = limsurf.subdivide(mesh, "catmull-clark", 2, forms=True)
    S0, S1, S2 = ops["S0"], ops["S1"], ops["S2"]
    assert S0.shape == (fine.num_vertices, mesh.num_vertices) and S0.format == "csr"
    assert np.allclose(S0 @ mesh.V, fine.V, rtol=0, atol=1e-13)
    assert np.allclose(S0.sum(axis=1), 1.0, atol=1e-14)  # affine invariance
    d0, d1 = limsurf.exterior_derivatives(mesh)
    d0f, d1f = limsurf.exterior_derivatives(fine)
    assert abs(S1 @ d0 - d0f @ S0).max() < 1e-13  # SEC Eq. 5: S1 d0 = d0 S0
    assert abs(S2 @ d1 - d1f @ S1).max() < 1e-13
    steps = ops["steps"]
    assert len(steps) == 2 and abs(steps[1]["S0"] @ steps[0]["S0"] - S0).max() < 1e-15


def test_subdivide_from_arrays():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    fine = limsurf.subdivide(V, F, "loop", 2)
    assert fine.num_faces == 4 * 16
    assert np.array_equal(fine.V, limsurf.subdivide(limsurf.Mesh(V, F), "loop", levels=2).V)


@pytest.mark.parametrize("name,scheme", [("icosahedron", "loop"), ("cube", "doo-sabin")])
def test_threads_give_the_same_mesh_and_operators(mesh_path, name, scheme):
    # From 1024 faces on, each step builds the child topology (the last step of topology=False: its
    # face list) on a second thread; Doo-Sabin's step too.
    mesh = limsurf.read_mesh(mesh_path(name))
    assert limsurf.subdivide(mesh, scheme, 4).num_faces >= 1024, "the last step would not take a second thread"
    one = limsurf.subdivide(mesh, scheme, 5, threads=1)
    two = limsurf.subdivide(mesh, scheme, 5, threads=2)
    assert np.array_equal(one.V, two.V) and np.array_equal(one.face_vertices, two.face_vertices)
    V, F = limsurf.subdivide(mesh, scheme, 5, topology=False, threads=2)
    assert np.array_equal(V, one.V) and len(F) == one.num_faces
    _, ops_one = limsurf.subdivide(mesh, scheme, 5, operators=True, threads=1)
    _, ops_two = limsurf.subdivide(mesh, scheme, 5, operators=True, threads=2)
    assert (ops_one["S0"] != ops_two["S0"]).nnz == 0
    with pytest.raises(limsurf.InputError, match="num_threads must be >= 0"):
        limsurf.subdivide(mesh, scheme, 1, threads=-1)


def test_topology_false_gives_the_meshs_arrays(mesh_path):
    # The finest level as (V, F) without its Topology: the same arrays as the Mesh's, for every kind
    # of face list (quads, triangles, Doo-Sabin's polygons, which come as a list).
    for name, scheme, levels in (("cube_creases", "catmull-clark", 3), ("icosahedron", "loop", 3),
                                 ("annulus", "catmull-clark", 2), ("cube", "doo-sabin", 2),
                                 ("tetra_1", "c2g0", 2)):
        mesh = limsurf.read_mesh(mesh_path(name))
        finest = limsurf.subdivide(mesh, scheme, levels, threads=1)
        V, F = limsurf.subdivide(mesh, scheme, levels, topology=False)
        assert V.dtype == np.float64 and V.shape == (finest.num_vertices, 3)
        assert np.array_equal(V, finest.V), name
        if isinstance(finest.F, list):
            assert isinstance(F, list) and len(F) == finest.num_faces
            assert all(np.array_equal(a, b) for a, b in zip(F, finest.F)), name
        else:
            assert F.dtype == np.int32 and np.array_equal(F, finest.F), name
    V, F = limsurf.subdivide(np.eye(3), [[0, 1, 2]], "loop", 1, topology=False)
    assert V.shape == (6, 3) and F.shape == (4, 3)


def test_topology_false_with_operators_gives_the_same_arrays_and_operators(mesh_path):
    # With operators, topology=False keeps no level's tables past the control mesh: the same finest
    # arrays as the Mesh's and the same operators, every one of them, bit for bit.
    for name, scheme, levels, forms in (("cube_creases", "catmull-clark", 3, False), ("cube", "catmull-clark", 2, True),
                                        ("icosahedron", "loop", 2, True), ("cube", "doo-sabin", 2, False),
                                        ("tetra_1", "c2g0", 0, False)):
        mesh = limsurf.read_mesh(mesh_path(name))
        finest, ops = limsurf.subdivide(mesh, scheme, levels, operators=True, forms=forms)
        (V, F), lean = limsurf.subdivide(mesh, scheme, levels, operators=True, forms=forms, topology=False)
        assert np.array_equal(V, finest.V), name
        if isinstance(finest.F, list):
            assert all(np.array_equal(a, b) for a, b in zip(F, finest.F)) and len(F) == finest.num_faces, name
        else:
            assert np.array_equal(F, finest.F), name
        assert sorted(lean) == sorted(ops) and len(lean["steps"]) == levels == len(ops["steps"])
        pairs = [(lean[k], ops[k]) for k in ("S0", "S1", "S2") if k in ops]
        pairs += [(a[k], b[k]) for a, b in zip(lean["steps"], ops["steps"]) for k in b]
        for got, want in pairs:
            assert got.shape == want.shape and np.array_equal(got.indptr, want.indptr), name
            assert np.array_equal(got.indices, want.indices) and np.array_equal(got.data, want.data), name
        assert np.allclose(lean["S0"] @ mesh.V, V, rtol=0, atol=1e-12)


def test_refusals_are_python_exceptions(mesh_path):
    cube = limsurf.read_mesh(mesh_path("cube"))
    with pytest.raises(limsurf.UnsupportedError, match="face"):
        limsurf.subdivide(cube, "loop", 1)
    with pytest.raises(limsurf.InputError, match="unknown scheme 'butterfly'"):
        limsurf.subdivide(cube, "butterfly", 1)
    with pytest.raises(limsurf.InputError):
        limsurf.subdivide(cube, "catmull-clark", 17)
