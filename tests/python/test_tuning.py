"""The IGA-tuned Catmull–Clark weights from Python (analysis/weight_tuning.h, docs/guide/tune.md): Table 1 of
iga-tuned-catmull-clark-weights through the closed form, Catmull–Clark's subdominant eigenvalue against its
textbook formula, the regular B-spline's exact quadratics, the search against the paper's optima and equal to
`limsurf tune --json`, the cup–saddle decomposition on planted quadratics (superposition, rigid motions), and
the errors."""
import math

import numpy as np
import pytest

import limsurf

W_KEYS = ("lambda", "alpha", "beta", "gamma", "constraint", "lambda3", "lambda4")
W_ERROR_KEYS = W_KEYS + ("cup_error", "saddle_error")
CURVE_COLUMNS = ("lambda", "alpha", "beta", "gamma", "lambda3", "lambda4", "cup_error", "saddle_error")


def catmull_clark_lambda(n):
    """The subdominant eigenvalue of Catmull–Clark at valence n (Doo–Sabin's analysis; Stam 1998)."""
    c, h = math.cos(2 * math.pi / n), math.cos(math.pi / n)
    return (5 + c + h * math.sqrt(2 * (9 + c))) / 16


# --- closed forms -------------------------------------------------------------------------------------------

@pytest.mark.parametrize("lam, alpha, beta, beta_tol", [(0.550, 13.4575, 0.999938, 5e-7),
                                                         (0.585, 13.9851, 0.824885, 1e-6)])
def test_table_1_through_the_closed_form(lam, alpha, beta, beta_tol):
    candidates = limsurf.weights_for_subdominant(5, lam)
    assert len(candidates) == 1
    w = candidates[0]
    assert set(w) == set(W_KEYS)
    assert w["constraint"] == "relaxed" and w["lambda"] == lam
    assert abs(w["alpha"] - alpha) < 5e-5
    assert abs(w["beta"] - beta) < beta_tol and w["gamma"] == w["beta"]
    # The other path: the one-ring spectrum of those weights has λ₁ = λ and λ₃ = λ² (31).
    spectrum = limsurf.one_ring_spectrum(5, w["alpha"], w["beta"], w["gamma"])
    assert spectrum["lambda"] == pytest.approx(lam, abs=1e-12)
    assert spectrum["lambda3"] == pytest.approx(lam**2, abs=1e-12)
    assert spectrum["constraint"] == "none"


@pytest.mark.parametrize("n", [3, 5, 6, 8])
def test_catmull_clark_lambda_is_feasible_and_textbook(n):
    spectrum = limsurf.one_ring_spectrum(n)  # alpha None: Catmull–Clark's n(n − 2), β = γ = 1
    assert spectrum["alpha"] == n * (n - 2) and spectrum["beta"] == spectrum["gamma"] == 1.0
    assert spectrum["lambda"] == pytest.approx(catmull_clark_lambda(n), abs=1e-12)
    low, high = limsurf.feasible_subdominant_range(n)
    assert low < spectrum["lambda"] < high


def test_feasible_range_at_valence_5():
    low, high = limsurf.feasible_subdominant_range(5)
    assert low < catmull_clark_lambda(5) < high
    assert catmull_clark_lambda(5) == pytest.approx(0.54999, abs=1e-5)
    assert (low, high) == pytest.approx((0.319875, 0.822464), abs=1e-6)
    # The ends are where a weight meets its bound: α → 0 at the low end, β = γ → 0 at the high end.
    (at_low,) = limsurf.weights_for_subdominant(5, low)
    (at_high,) = limsurf.weights_for_subdominant(5, high)
    assert at_low["alpha"] < 1e-6 < at_low["beta"] and at_high["beta"] < 1e-6 < at_high["alpha"]


def test_the_regular_witness_reproduces_quadratics():
    # The bicubic B-spline (valence 4, weights 8, 1, 1) reproduces every quadratic: both errors vanish.
    errors = limsurf.quadratic_shape_errors(4, 8.0, 1.0, 1.0)
    assert errors["cup"] < 1e-10 and errors["saddle"] < 1e-10
    assert limsurf.quadratic_shape_errors(4) == errors
    # Valence 5 does not: Catmull–Clark's errors are far from zero, and the options reach the library.
    classical = limsurf.quadratic_shape_errors(5)
    assert classical["cup"] > 0.1 and classical["saddle"] > 0.1
    other = limsurf.quadratic_shape_errors(5, quadrature=3, tile_levels=8, poisson_ratio=0.2)
    assert other["cup"] != classical["cup"] and other["cup"] == pytest.approx(classical["cup"], rel=0.05)


# --- the search ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("shape, optimum", [("cup", 0.550), ("saddle", 0.585)])
def test_tune_finds_the_papers_optima(shape, optimum):
    result = limsurf.tune_weights(5, shape, samples=21)
    other = "saddle" if shape == "cup" else "cup"
    tuned, classical = result["tuned"], result["classical"]
    assert abs(tuned["lambda"] - optimum) < 5e-4
    assert set(tuned) == set(W_ERROR_KEYS) and set(classical) == set(W_ERROR_KEYS)
    assert tuned[f"{shape}_error"] < classical[f"{shape}_error"]
    assert tuned[f"{other}_error"] <= classical[f"{other}_error"] + 1e-12
    assert result["protection_binds"]  # the paper's optima are where the other error meets Catmull–Clark's
    assert result["unconstrained"][f"{shape}_error"] < tuned[f"{shape}_error"]
    assert classical["constraint"] == "none" and classical["alpha"] == 15.0
    curve = result["curve"]
    for column in CURVE_COLUMNS:
        assert isinstance(curve[column], np.ndarray) and curve[column].dtype == np.float64
        assert curve[column].shape == (21,)
    assert len(curve["constraint"]) == 21
    assert np.all(np.diff(curve["lambda"]) > 0)
    assert (curve["lambda"][0], curve["lambda"][-1]) == tuple(result["search_range"]) == tuple(result["feasible_range"])
    # The curve's errors are those of quadratic_shape_errors at its weights.
    i = 10
    errors = limsurf.quadratic_shape_errors(5, curve["alpha"][i], curve["beta"][i], curve["gamma"][i])
    assert errors == {"cup": curve["cup_error"][i], "saddle": curve["saddle_error"][i]}


def test_tuned_vertex_weights_are_table_1():
    cup = limsurf.tuned_vertex_weights(5, "cup")
    assert cup["lambda"] == 0.55 and abs(cup["alpha"] - 13.4575) < 5e-5 and abs(cup["beta"] - 0.999938) < 5e-7
    assert {"cup": cup["cup_error"], "saddle": cup["saddle_error"]} == limsurf.quadratic_shape_errors(
        5, cup["alpha"], cup["beta"], cup["gamma"])


def curve_rows(curve):
    """The columns of tune_weights' curve as the CLI's list of W."""
    n = len(curve["constraint"])
    return [{key: curve[key][i] for key in W_ERROR_KEYS} for i in range(n)]


def assert_equal_to_cli(ours, theirs):
    for key in ("valence", "shape", "quadrature_points", "tile_levels", "poisson_ratio", "protect_other_shape",
                "protection_binds"):
        assert ours[key] == theirs[key], key
    for key in ("feasible_range", "search_range"):
        assert list(ours[key]) == theirs[key], key
    for key in ("tuned", "unconstrained", "classical"):
        assert ours[key] == theirs[key], key
    assert curve_rows(ours["curve"]) == theirs["curve"]
    assert set(theirs) - set(ours) == {"command", "time_seconds"}


def test_tune_equals_the_cli(cli):
    theirs = cli("tune", "--valence", 5, "--shape", "cup", "--samples", 21, "--json")
    assert_equal_to_cli(limsurf.tune_weights(5, "cup", samples=21), theirs)


def test_tune_options_equal_the_cli(cli):
    theirs = cli("tune", "--valence", 6, "--shape", "saddle", "--quadrature", 3, "--tile-levels", 8,
                 "--poisson-ratio", 0.25, "--lambda-range", "0.55,0.65", "--samples", 11, "--no-protect", "--json")
    ours = limsurf.tune_weights(6, "saddle", quadrature=3, tile_levels=8, poisson_ratio=0.25,
                                lambda_range=(0.55, 0.65), samples=11, protect=False)
    assert_equal_to_cli(ours, theirs)
    assert not ours["protection_binds"] and ours["tuned"] == ours["unconstrained"]
    assert tuple(ours["search_range"]) == (0.55, 0.65)
    # threads share each evaluation's faces: the same numbers on one thread
    one = limsurf.tune_weights(6, "saddle", quadrature=3, tile_levels=8, poisson_ratio=0.25,
                               lambda_range=(0.55, 0.65), samples=11, protect=False, threads=1)
    assert_equal_to_cli(one, theirs)


def test_errors_do_not_depend_on_the_thread_count():
    for valence in (5, 9):
        one = limsurf.quadratic_shape_errors(valence, threads=1)
        assert limsurf.quadratic_shape_errors(valence, threads=2) == one
        assert limsurf.quadratic_shape_errors(valence) == one
    assert limsurf.tuned_vertex_weights(5, threads=1) == limsurf.tuned_vertex_weights(5, threads=2)
    with pytest.raises(limsurf.InputError, match="thread count"):
        limsurf.quadratic_shape_errors(5, threads=-2)


def test_weights_at_a_lambda_equal_the_cli(cli):
    theirs = cli("tune", "--valence", 5, "--lambda", 0.55, "--json")
    ours = limsurf.weights_for_subdominant(5, 0.55)
    assert len(theirs["candidates"]) == len(ours)
    for w, c in zip(ours, theirs["candidates"]):
        errors = limsurf.quadratic_shape_errors(5, w["alpha"], w["beta"], w["gamma"])
        assert dict(w, cup_error=errors["cup"], saddle_error=errors["saddle"]) == c
    assert list(limsurf.feasible_subdominant_range(5)) == theirs["feasible_range"]


# --- the cup–saddle decomposition ---------------------------------------------------------------------------

def assert_same_parts(a, b, rel=1e-12):
    """Two decompose_shapes lists agree: the same vertices and verdicts, numbers to @p rel of the largest k."""
    assert [p["vertex"] for p in a] == [p["vertex"] for p in b]
    for p, q in zip(a, b):
        scale = max(abs(p["k3"]), abs(p["k4"]), abs(p["k5"]))
        assert p["valence"] == q["valence"] and p["cup_dominates"] == q["cup_dominates"]
        for k in ("k3", "k4", "k5"):
            assert p[k] == pytest.approx(q[k], abs=rel * scale), k
        assert p["ratio"] == pytest.approx(q["ratio"], rel=1e-6)
        assert np.allclose(p["normal"], q["normal"], atol=1e-12)


def planted(mesh, c3=0.0, c4=0.0, c5=0.0):
    """P = (x, y, c3 (x² + y²) + c4 (x² − y²) + c5 2xy) over the mesh's own x, y."""
    x, y = mesh.V[:, 0], mesh.V[:, 1]
    return np.c_[x, y, c3 * (x * x + y * y) + c4 * (x * x - y * y) + c5 * 2 * x * y]


def test_verdicts_on_planted_quadratics(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("quad_valence_5"))  # closed; its two poles have valence 5
    for c3 in (0.7, -1.3):
        parts = limsurf.decompose_shapes(mesh, planted(mesh, c3=c3))
        assert [p["vertex"] for p in parts] == [0, 1] and all(p["valence"] == 5 for p in parts)
        for p in parts:
            assert p["cup_dominates"] and p["ratio"] > 1
            assert abs(p["k3"]) > 1e6 * max(abs(p["k4"]), abs(p["k5"]))
    for p in limsurf.decompose_shapes(mesh, planted(mesh, c4=1.0)):
        assert not p["cup_dominates"] and p["ratio"] < 1
    # Arrays in, as from a mesh; P None decomposes the mesh's own positions (a sphere: cups).
    assert_same_parts(limsurf.decompose_shapes(mesh.V, mesh.F, planted(mesh, c3=0.7)),
                      limsurf.decompose_shapes(mesh, planted(mesh, c3=0.7)), rel=0.0)
    assert all(p["cup_dominates"] for p in limsurf.decompose_shapes(mesh))
    assert limsurf.decompose_shapes(mesh, min_valence=6) == []


def test_a_flat_vertex_has_no_ratio(mesh_path):
    # A plane (the flat plate itself, then tilted and far from the origin) is no shape: before, R was inf on
    # the flat plate and 5 to 53 on the tilted one (rounding read as a verdict).
    mesh = limsurf.read_mesh(mesh_path("plate_ev35"))
    x, y = mesh.V[:, 0], mesh.V[:, 1]
    for P in (mesh.V, np.c_[x + 1e4, y - 3e3, 0.1 * x + 0.3 * y + 2e3]):
        parts = limsurf.decompose_shapes(mesh, P)
        assert len(parts) == 4
        for p in parts:
            assert not p["has_quadratic_part"] and not p["cup_dominates"] and np.isnan(p["ratio"])
            assert p["k3"] == p["k4"] == p["k5"] == 0.0
    # A faint cup on the same tilted plane is seen (2e-9 against a floor of 2e-15 × 1e4).
    parts = limsurf.decompose_shapes(mesh, np.c_[x + 1e4, y - 3e3, 0.1 * x + 0.3 * y + 2e3 + 2e-9 * (x * x + y * y)])
    assert all(p["has_quadratic_part"] and p["cup_dominates"] for p in parts)


def test_superposition_and_the_ratio(mesh_path):
    # The disk's one-ring is a regular pentagon: the cup has no frequency-2 part and the saddles no frequency-0
    # part, so the coefficients of a sum are those of its terms.
    mesh = limsurf.read_mesh(mesh_path("disk_ev5_quads"))
    (cup,) = limsurf.decompose_shapes(mesh, planted(mesh, c3=1.0))
    (saddle,) = limsurf.decompose_shapes(mesh, planted(mesh, c4=1.0))
    (twist,) = limsurf.decompose_shapes(mesh, planted(mesh, c5=1.0))
    (mix,) = limsurf.decompose_shapes(mesh, planted(mesh, c3=1.0, c4=0.3, c5=0.1), poisson_ratio=0.25)
    scale = abs(cup["k3"])
    assert mix["k3"] == pytest.approx(cup["k3"], abs=1e-12 * scale)
    assert mix["k4"] == pytest.approx(0.3 * saddle["k4"], abs=1e-12 * scale)
    assert mix["k5"] == pytest.approx(0.1 * twist["k5"], abs=1e-12 * scale)
    assert abs(saddle["k4"]) == pytest.approx(abs(twist["k5"]), rel=1e-9)  # 2xy is x² − y² turned by π/4
    expected = mix["k3"] ** 2 / (mix["k4"] ** 2 + mix["k5"] ** 2) * (1 + 0.25) / (1 - 0.25)
    assert mix["ratio"] == pytest.approx(expected, rel=1e-12) and mix["cup_dominates"]
    # A saddle turned in the plane keeps its size k4² + k5².
    for phi in (0.3, 1.1, 2.0):
        (turned,) = limsurf.decompose_shapes(mesh, planted(mesh, c4=math.cos(2 * phi), c5=math.sin(2 * phi)))
        assert math.hypot(turned["k4"], turned["k5"]) == pytest.approx(abs(saddle["k4"]), rel=1e-9)
        assert not turned["cup_dominates"]


def test_limit_point_and_tangents_are_the_limit_surfaces(mesh_path):
    # Any control points (here the disk moved at random, out of the plane too): 'position' is the
    # limit surface at the vertex, as LimitBasis evaluates it at the corner of a face, and each face's
    # derivative along its edge out of the vertex is s (cos θ_j tangent1 + sin θ_j tangent2), with one
    # s and θ_j = 2πj/5 (the characteristic map takes the j-th spoke to that angle).
    mesh = limsurf.read_mesh(mesh_path("disk_ev5_quads"))
    P = np.asarray(mesh.V) + 0.05 * np.random.default_rng(7).standard_normal(np.asarray(mesh.V).shape)
    (d,) = limsurf.decompose_shapes(mesh, P)
    F = np.asarray(mesh.F)
    faces = np.flatnonzero(F[:, 0] == d["vertex"])  # the vertex is every one of its faces' first corner
    assert len(faces) == 5
    W = limsurf.LimitBasis(mesh, "catmull-clark").weights(faces, np.zeros(5), np.zeros(5), order=1)
    assert np.allclose(W["position"] @ P, d["position"], rtol=0, atol=1e-13)
    assert d["tangents"].shape == (2, 3) and d["position"].shape == (3,)
    T = d["tangents"].T
    du = W["du"] @ P
    coefficients = np.linalg.lstsq(T, du.T, rcond=None)[0].T
    assert np.allclose(coefficients @ T.T, du, rtol=0, atol=1e-12 * np.abs(du).max())
    z = coefficients[:, 0] + 1j * coefficients[:, 1]
    assert np.allclose(np.abs(z), np.abs(z[0]), rtol=1e-10)
    turn = np.angle(z[1:] / z[:-1])
    assert np.allclose(np.abs(turn), 2 * math.pi / 5, rtol=0, atol=1e-10) and len(set(np.sign(turn))) == 1


def test_rigid_motions_leave_the_decomposition(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("disk_ev5_quads"))
    P = planted(mesh, c3=1.0, c4=0.5, c5=-0.2)
    (before,) = limsurf.decompose_shapes(mesh, P)
    rng = np.random.default_rng(18)
    for _ in range(3):
        Q, R = np.linalg.qr(rng.standard_normal((3, 3)))
        Q *= np.sign(np.diag(R))
        if np.linalg.det(Q) < 0:
            Q[:, 0] = -Q[:, 0]
        moved = P @ Q.T + rng.standard_normal(3)
        (after,) = limsurf.decompose_shapes(mesh, moved)
        assert after["ratio"] == pytest.approx(before["ratio"], rel=1e-9)
        for k in ("k3", "k4", "k5"):
            assert after[k] == pytest.approx(before[k], abs=1e-9 * abs(before["k3"])), k
        assert np.allclose(after["normal"], Q @ before["normal"], atol=1e-9)
        assert np.allclose(after["position"], Q @ before["position"] + (moved - P @ Q.T)[0], atol=1e-9)
        assert np.allclose(after["tangents"], before["tangents"] @ Q.T, atol=1e-9)
        assert after["normal"].shape == (3,) and after["normal"].dtype == np.float64
    # The other orientation of the faces flips the normal (and k3 with it) and turns the ξ frame: the sizes stay.
    (flipped,) = limsurf.decompose_shapes(mesh.V, np.asarray(mesh.F)[:, ::-1], P)
    assert np.allclose(flipped["normal"], -before["normal"], atol=1e-12)
    assert flipped["k3"] == pytest.approx(-before["k3"], rel=1e-12)
    assert math.hypot(flipped["k4"], flipped["k5"]) == pytest.approx(math.hypot(before["k4"], before["k5"]), rel=1e-12)
    assert flipped["ratio"] == pytest.approx(before["ratio"], rel=1e-12)


def test_weights_forms_agree(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("disk_ev5_quads"))
    P = planted(mesh, c3=1.0, c4=0.5)
    cup = limsurf.tuned_vertex_weights(5, "cup")
    by_dict = limsurf.decompose_shapes(mesh, P, weights={"valence": {5: cup}})
    by_tuple = limsurf.decompose_shapes(mesh, P, weights={"valence": {5: (cup["alpha"], cup["beta"], cup["gamma"])}})
    by_vertex = limsurf.decompose_shapes(mesh, P, weights={"vertex": {0: cup}})
    assert_same_parts(by_dict, by_tuple, rel=0.0)
    assert_same_parts(by_dict, by_vertex, rel=0.0)
    by_preset = limsurf.decompose_shapes(mesh, P, weights="cup")  # Table 1's printed digits
    assert by_preset[0]["k3"] == pytest.approx(by_dict[0]["k3"], rel=1e-5)
    classical = limsurf.decompose_shapes(mesh, P)
    assert_same_parts(classical, limsurf.decompose_shapes(mesh, P, weights="catmull-clark"), rel=0.0)
    assert by_dict[0]["k3"] != classical[0]["k3"]  # the weights change the eigenvectors


# --- errors -------------------------------------------------------------------------------------------------

def test_bad_input_raises_input_error(mesh_path):
    with pytest.raises(limsurf.InputError, match="valence 4"):
        limsurf.feasible_subdominant_range(4)
    with pytest.raises(limsurf.InputError):
        limsurf.feasible_subdominant_range(2)
    with pytest.raises(limsurf.InputError, match="outside the feasible range"):
        limsurf.weights_for_subdominant(5, 0.9)
    with pytest.raises(limsurf.InputError):
        limsurf.weights_for_subdominant(4, 0.5)
    with pytest.raises(limsurf.InputError, match="not inside the feasible range"):
        limsurf.tune_weights(5, lambda_range=(0.2, 0.6))
    with pytest.raises(limsurf.InputError, match="shape"):
        limsurf.tune_weights(5, "bowl")
    with pytest.raises(limsurf.InputError, match="samples"):
        limsurf.tune_weights(5, samples=2)
    with pytest.raises(limsurf.InputError, match="thread count"):
        limsurf.tune_weights(5, samples=3, threads=-1)
    with pytest.raises(limsurf.InputError, match="quadrature"):
        limsurf.quadratic_shape_errors(5, quadrature=11)
    with pytest.raises(limsurf.InputError):
        limsurf.quadratic_shape_errors(4, 7.0)  # tuned weights at the regular valence
    with pytest.raises(limsurf.InputError):
        limsurf.one_ring_spectrum(5, -1.0)
    mesh = limsurf.read_mesh(mesh_path("quad_valence_5"))
    with pytest.raises(limsurf.InputError, match="rows"):
        limsurf.decompose_shapes(mesh, np.zeros((3, 3)))
    with pytest.raises(limsurf.InputError):
        limsurf.decompose_shapes(mesh, np.full((17, 3), np.nan))
    w = limsurf.weights_for_subdominant(5, 0.55)[0]
    with pytest.raises(limsurf.InputError, match="vertex 2"):  # vertex 2 is in vertex 0's one-ring
        limsurf.decompose_shapes(mesh, weights={"vertex": {0: w, 2: w}})
    for bad in ({"vertex": {0: (1.0, 2.0)}}, {"valence": {5: (13.0, "a", 1.0)}}, {"foo": {}}, 3,
                {"valence": {5: (math.nan, 1.0, 1.0)}}, {"valence": {5: (-1.0, 1.0, 1.0)}}, {"valence": {2: w}},
                {"valence": {5: {"alpha": 13.0}}}):
        with pytest.raises(limsurf.InputError, match="weights|valence"):
            limsurf.decompose_shapes(mesh, weights=bad)


def test_plate_with_tuned_weights_equals_the_cli(cli, mesh_path):
    """limsurf.plate(tuned='auto') gives `limsurf plate --tuned auto --json`'s numbers: the cup pass, the
    ratio R per vertex and the choice it makes, and the second pass's errors."""
    path = mesh_path("plate_ev35.obj")
    theirs = cli("plate", path, "--levels", 1, "--load", "sinusoidal", "--tuned", "auto", "--json")
    ours = limsurf.plate(limsurf.read_mesh(path), "catmull-clark", "sinusoidal", levels=1, tuned="auto")
    assert ours["tuned"] == theirs["tuned"] == "auto"
    for a, b in zip(ours["levels"], theirs["levels"]):
        assert a["navier"]["l2_relative_error"] == pytest.approx(b["navier"]["l2_relative_error"], rel=1e-12)
        assert a["first_pass"]["navier"]["energy_relative_error"] == pytest.approx(
            b["first_pass"]["navier"]["energy_relative_error"], rel=1e-12)
        assert len(a["tuned_vertices"]) == len(b["tuned_vertices"]) == 4
        for u, v in zip(a["tuned_vertices"], b["tuned_vertices"]):
            assert (u["vertex"], u["valence"], u["shape"]) == (v["vertex"], v["valence"], v["shape"])
            assert u["decomposition"]["ratio"] == pytest.approx(v["decomposition"]["ratio"], rel=1e-12)
            for key in ("position", "tangents"):
                assert np.allclose(u["decomposition"][key], np.array(v["decomposition"][key]), rtol=1e-12, atol=1e-15)
            # the choice follows the ratio (38): cup where R >= 1
            assert u["shape"] == ("cup" if u["decomposition"]["ratio"] >= 1 else "saddle")
    with pytest.raises(limsurf.InputError):
        limsurf.plate(limsurf.read_mesh(path), "catmull-clark", "uniform", tuned="bowl")


def test_plate_deciding_once_equals_the_cli(cli, mesh_path):
    """decide_level=K is `limsurf plate --decide-level K`: level K's cup pass chooses for every level."""
    path = mesh_path("plate_flip.obj")
    theirs = cli("plate", path, "--levels", 1, "--load", "sinusoidal", "--tuned", "auto", "--decide-level", 2, "--json")
    ours = limsurf.plate(limsurf.read_mesh(path), "catmull-clark", "sinusoidal", levels=1, tuned="auto",
                         decide_level=2)
    assert ours["decide_level"] == theirs["decide_level"] == 2
    for a, b in zip(ours["levels"], theirs["levels"]):
        assert "first_pass" not in a and "first_pass" not in b  # level 2 is not among those reported
        assert a["navier"]["l2_relative_error"] == pytest.approx(b["navier"]["l2_relative_error"], rel=1e-12)
        assert [(u["vertex"], u["shape"]) for u in a["tuned_vertices"]] == \
            [(v["vertex"], v["shape"]) for v in b["tuned_vertices"]] == [(7, "cup"), (15, "saddle")]
        for u, v in zip(a["tuned_vertices"], b["tuned_vertices"]):
            assert u["decomposition"]["ratio"] == pytest.approx(v["decomposition"]["ratio"], rel=1e-12)
    with pytest.raises(limsurf.InputError, match="auto"):
        limsurf.plate(limsurf.read_mesh(path), "catmull-clark", "sinusoidal", tuned="cup", decide_level=2)
