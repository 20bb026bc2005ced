"""limsurf.design_vector_field and limsurf.one_form_vectors against `limsurf vector-field --json` (the same
numbers, exactly), a constant field on a plane reproduced exactly, and clear errors."""
import numpy as np
import pytest

import limsurf


def test_design_equals_the_cli(mesh_path, cli, tmp_path):
    saved = tmp_path / "w.txt"
    theirs = cli("vector-field", mesh_path("genus2"), "--scheme", "catmull-clark", "--method", "sec", "--level", 2,
                 "--source", "0:1", "--sink", "30:1", "--vorticity", "7:0.5:1e4", "--stroke", "0,1:0.3",
                 "--reference-level", 2, "--save-one-form", saved, "--json")
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    ours = limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], sinks=[(30, 1.0)],
                                       vortices=[(7, 0.5, 1e4)], strokes=[([0, 1], 0.3)], method="sec", level=2,
                                       reference_level=2)
    for key in ("scheme", "method", "level", "vertices", "edges", "faces", "closed", "genus", "solver",
                "vertex_mass", "solver_steps", "energy",
                "w_norm", "max_residual", "source_imbalance", "vorticity_imbalance", "constraints", "warnings",
                "samples", "reference"):
        assert ours[key] == theirs[key], key
    assert np.array_equal(ours["w"], np.loadtxt(saved))
    v = ours["vectors"]
    assert v["points"].shape == v["vectors"].shape == (800, 3)
    assert np.abs(np.einsum("ij,ij->i", v["vectors"], v["normals"])).max() < 1e-12  # tangent


def test_lumped_vertex_mass_equals_the_cli(mesh_path, cli):
    theirs = cli("vector-field", mesh_path("genus2"), "--scheme", "catmull-clark", "--level", 2, "--source", "0:1",
                 "--sink", "30:1", "--vertex-mass", "lumped", "--json")
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    ours = limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], sinks=[(30, 1.0)], level=2,
                                       vertex_mass="lumped")
    exact = limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], sinks=[(30, 1.0)], level=2)
    assert ours["vertex_mass"] == theirs["vertex_mass"] == "lumped"
    assert ours["solver_steps"] == theirs["solver_steps"] == 0
    assert ours["energy"] == theirs["energy"]
    # The exact M0⁻¹ bounds the lumped one from above (M0 <= diag(M0 1)): a larger energy at the minimiser.
    assert exact["solver_steps"] > 0 and exact["energy"] > ours["energy"]


def test_constant_field_on_a_plane(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("tri_grid"))
    d0, _ = limsurf.exterior_derivatives(mesh)
    c = np.array([0.25, -1.5, 0.0])
    r = limsurf.one_form_vectors(mesh, "loop", d0 @ (mesh.V @ c), level=3)
    assert np.abs(r["vectors"] - c).max() < 1e-12
    assert r["fit_residual"] < 1e-12


def test_errors(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("genus2"))
    with pytest.raises(limsurf.InputError, match="unknown vertex_mass 'diagonal'"):
        limsurf.design_vector_field(mesh, "catmull-clark", sources=[(0, 1.0)], vertex_mass="diagonal")
    with pytest.raises(limsurf.InputError, match="vertex 48 is out of range"):
        limsurf.design_vector_field(mesh, "catmull-clark", sources=[(48, 1.0)])
    with pytest.raises(limsurf.InputError, match="at least one constraint"):
        limsurf.design_vector_field(mesh, "catmull-clark")
    with pytest.raises(limsurf.InputError, match="not joined by an edge"):
        limsurf.design_vector_field(mesh, "catmull-clark", strokes=[([0, 40], 1.0)])
    with pytest.raises(limsurf.InputError, match="w: expected 100 values"):
        limsurf.one_form_vectors(mesh, "catmull-clark", [1.0, 2.0])
