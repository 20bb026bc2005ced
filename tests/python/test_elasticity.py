"""limsurf.elasticity: the numbers of `limsurf elasticity --json` on the bundled block with grains, the
patch test of a homogeneous cell against the analytic plane strain and plane stress matrices (written
out here), the fields, and refusals of bad input."""
import numpy as np
import pytest

import limsurf

SEED_F = np.array([[1.0, 0.05], [0.05, 1.0]])


def analytic_C(E, nu, plane_stress):
    if plane_stress:
        return E / (1 - nu * nu) * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])
    return E / ((1 + nu) * (1 - 2 * nu)) * np.array([[1 - nu, nu, 0], [nu, 1 - nu, 0], [0, 0, (1 - 2 * nu) / 2]])


def voigt_strain(F):
    return np.array([F[0, 0] - 1, F[1, 1] - 1, F[0, 1] + F[1, 0]])


def grain_materials(path):
    """face_material for `--material grain:10,0.3`: -1 (E, nu) for the matrix, 0 for the grains."""
    mesh, groups, names = limsurf.read_mesh(path, groups=True)
    return mesh, np.where(groups == names.index("grain"), 0, -1)


def test_same_numbers_as_the_cli(mesh_path, cli):
    path = mesh_path("rve_block")
    mesh, face_material = grain_materials(path)
    r = limsurf.elasticity(mesh, face_material=face_material, materials=[(10.0, 0.3)], levels=1)
    j = cli("elasticity", path, "--material", "grain:10,0.3", "--levels", "1", "--json")
    assert r["boundary"] == j["boundary"] == "periodic"
    assert r["model"] == j["model"] == "strain"
    assert [m["faces"] for m in r["materials"]] == [m["faces"] for m in j["materials"]]
    assert len(r["levels"]) == len(j["levels"]) == 2
    for a, b in zip(r["levels"], j["levels"]):
        assert a["vertices"] == b["vertices"]
        np.testing.assert_allclose(a["homogenised_stress"], b["homogenised_stress"], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(a["effective_stiffness"], b["effective_stiffness"], rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(a["material_area"], b["material_area"], rtol=1e-13)
        assert a["u"].shape == (a["vertices"], 2)
    np.testing.assert_allclose(r["bounds"]["voigt"], j["bounds"]["voigt"], rtol=1e-13)
    np.testing.assert_allclose(r["bounds"]["reuss"], j["bounds"]["reuss"], rtol=1e-13)
    np.testing.assert_allclose(r["bounds"]["bulk_hashin_shtrikman"], j["bounds"]["bulk_hashin_shtrikman"], rtol=1e-13)
    C = r["effective_stiffness"]
    assert C.shape == (3, 3)
    assert np.linalg.norm(C - C.T) < 1e-8 * np.linalg.norm(C)
    assert np.linalg.eigvalsh((C + C.T) / 2).min() > 0
    # The same through the arrays V, F.
    again = limsurf.elasticity(mesh.V, mesh.F, face_material=face_material, materials=[(10.0, 0.3)],
                               effective_stiffness=False)
    np.testing.assert_allclose(again["levels"][0]["homogenised_stress"], r["levels"][0]["homogenised_stress"],
                               rtol=1e-12, atol=1e-15)
    assert again["effective_stiffness"] is None


@pytest.mark.parametrize("plane_stress", [False, True])
@pytest.mark.parametrize("F", [SEED_F, np.array([[1.01, 0.02], [0.0, 0.99]]), np.array([[1.01, 0.02], [0.0, 1.0]])])
def test_patch_test(mesh_path, plane_stress, F):
    mesh = limsurf.read_mesh(mesh_path("rve_block"))
    r = limsurf.elasticity(mesh, E=2.5, nu=0.3, plane_stress=plane_stress, macro_deformation=F)
    C = analytic_C(2.5, 0.3, plane_stress)
    level = r["levels"][0]
    np.testing.assert_allclose(level["homogenised_stress"], C @ voigt_strain(F), rtol=0, atol=1e-10)
    np.testing.assert_allclose(r["effective_stiffness"], C, rtol=0, atol=1e-10 * np.linalg.norm(C))
    # ũ = 0: the control values are (Fᵐ − I) X, to the rounding of a solve with the block's condition number.
    np.testing.assert_allclose(r["u"], mesh.V[:, :2] @ (F - np.eye(2)).T, rtol=0, atol=1e-8)


def test_fields(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("quad_grid"))
    F = np.array([[1.01, 0.02], [0.0, 1.0]])
    r = limsurf.elasticity(mesh, macro_deformation=F, plane_stress=True, resolution=3)
    fields = r["fields"]
    n = fields["positions"].shape[0]
    assert fields["displacement"].shape == (n, 2)
    assert fields["stress"].shape == (n, 3)
    assert fields["triangles"].max() < n
    # A homogeneous cell: the stress is C ε everywhere, von Mises of plane stress from it.
    s = analytic_C(1.0, 0.3, True) @ voigt_strain(F)
    np.testing.assert_allclose(fields["stress"], np.tile(s, (n, 1)), rtol=0, atol=1e-10)
    vm = np.sqrt(s[0] ** 2 - s[0] * s[1] + s[1] ** 2 + 3 * s[2] ** 2)
    np.testing.assert_allclose(fields["von_mises"], vm, rtol=1e-9)
    np.testing.assert_allclose(fields["displacement"], fields["positions"][:, :2] @ (F - np.eye(2)).T, atol=1e-10)


def test_threads_do_not_change_the_numbers_or_the_fields(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("rve_block"))
    face_material = np.where(np.arange(mesh.num_faces) % 2 == 0, -1, 0).astype(np.int32)  # -1: E, nu
    runs = [limsurf.elasticity(mesh, face_material=face_material, materials=[(10.0, 0.3)], levels=1, resolution=4,
                               threads=threads) for threads in (1, 2)]
    assert np.array_equal(runs[0]["levels"][-1]["homogenised_stress"], runs[1]["levels"][-1]["homogenised_stress"])
    for key in ("effective_stiffness", "u"):
        assert np.array_equal(runs[0][key], runs[1][key]), key
    for key in ("displacement", "strain", "stress", "von_mises"):
        assert np.array_equal(runs[0]["fields"][key], runs[1]["fields"][key]), key
    with pytest.raises(limsurf.InputError, match="threads"):
        limsurf.elasticity(mesh, threads=-1)


def test_loaded_strip_balances_its_traction(mesh_path):
    # v = (x + 1, 0) vanishes on the clamped left side of [-1, 1]²: mean σ_xx = t_x exactly.
    mesh = limsurf.read_mesh(mesh_path("quad_grid"))
    r = limsurf.elasticity(mesh, boundary="loaded", clamp=["left"], tractions=[("right", (0.1, 0.0))])
    assert r["cell"] is None and r["macro_deformation"] is None
    assert r["levels"][0]["homogenised_stress"][0] == pytest.approx(0.1, abs=1e-9)


def test_bad_input_raises(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("rve_block"))
    with pytest.raises(limsurf.InputError, match="nu"):
        limsurf.elasticity(mesh, nu=0.5)
    with pytest.raises(limsurf.InputError):
        limsurf.elasticity(mesh, E=0.0)
    with pytest.raises(limsurf.InputError, match="face_material"):
        limsurf.elasticity(mesh, face_material=np.zeros(3, dtype=np.int32), materials=[(1.0, 0.3)])
    with pytest.raises(limsurf.InputError, match="face_material"):
        limsurf.elasticity(mesh, face_material=np.full(mesh.num_faces, 2), materials=[(1.0, 0.3)])
    with pytest.raises(limsurf.InputError, match="macro_deformation"):
        limsurf.elasticity(mesh, macro_deformation=[1.0, 0.0, 0.0])
    with pytest.raises(limsurf.InputError):
        limsurf.elasticity(mesh, boundary="loaded")
    with pytest.raises(limsurf.InputError, match="boundary"):
        limsurf.elasticity(mesh, boundary="sliding")
    with pytest.raises(limsurf.InputError):
        limsurf.elasticity(limsurf.read_mesh(mesh_path("cube")))
    with pytest.raises(limsurf.InputError, match="materials"):
        limsurf.elasticity(mesh, face_material=np.zeros(mesh.num_faces, dtype=np.int32), materials=[(1.0, 0.6)])
