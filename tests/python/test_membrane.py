"""limsurf.shape_functionals and limsurf.minimize_membrane equal to `limsurf membrane --json` (the same
numbers on the same input, with either Hessian), their gradients and limsurf.shape_hessian's matrices
against finite differences and the homogeneity identities, limsurf.ShapeEvaluator equal to the functions
to the bit, the iteration callback, and their errors (membrane/, apps/membrane.h, docs/guide/membrane.md)."""
import math
import threading

import numpy as np
import pytest

import limsurf

VALUE_KEYS = ("area", "volume", "mean_curvature", "willmore", "gaussian", "harmonic", "reduced_volume",
              "reduced_mean_curvature", "volume_is_exact", "samples")
NAMES = ("area", "volume", "mean_curvature", "willmore", "gaussian", "harmonic")
A0 = 4 * math.pi


@pytest.mark.parametrize("name, scheme", [("tetra_2", "c2g0"), ("icosahedron", "loop"),
                                          ("sphere_quads", "catmull-clark")])
def test_shape_functionals_equal_the_cli(mesh_path, cli, name, scheme):
    theirs = cli("membrane", mesh_path(name), "--scheme", scheme, "--evaluate-only", "--spontaneous-curvature", 0.25,
                 "--json")
    mesh = limsurf.read_mesh(mesh_path(name))
    ours = limsurf.shape_functionals(mesh, scheme, spontaneous_curvature=0.25)
    for key in VALUE_KEYS + ("helfrich",):
        assert ours[key] == theirs[key], key
    from_arrays = limsurf.shape_functionals(mesh.V, mesh.F, scheme, gradients=False)
    assert from_arrays["willmore"] == ours["willmore"] and "gradient" not in from_arrays
    for g in ours["gradient"].values():
        assert g.shape == (mesh.num_vertices, 3) and g.dtype == np.float64


def test_gradients_match_finite_differences_and_the_identities(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("icosahedron"))
    X = mesh.V.copy()
    rng = np.random.default_rng(17)
    X += 0.05 * rng.standard_normal(X.shape)  # off the symmetric shape, where gradients are generic
    f = limsurf.shape_functionals(mesh, "loop", X=X)
    g = f["gradient"]
    # Homogeneity (Euler): ∇A·X = 2A, ∇V·X = 3V, ∇M·X = M, ∇W·X = 0.
    for name, degree in (("area", 2), ("volume", 3), ("mean_curvature", 1)):
        assert np.sum(g[name] * X) == pytest.approx(degree * f[name], rel=1e-10), name
    assert abs(np.sum(g["willmore"] * X)) < 1e-9 * f["willmore"] * np.abs(X).max()
    # Translations leave every functional unchanged: the gradient rows sum to zero.
    for name in NAMES:
        assert np.abs(g[name].sum(axis=0)).max() < 1e-9 * np.abs(g[name]).max(), name
    # Central differences of W in a few coordinates: error O(h²) of the discrete functional.
    h = 1e-5
    for (i, k) in ((0, 0), (5, 1), (11, 2)):
        Xp, Xm = X.copy(), X.copy()
        Xp[i, k] += h
        Xm[i, k] -= h
        fd = (limsurf.shape_functionals(mesh, "loop", X=Xp, gradients=False)["willmore"]
              - limsurf.shape_functionals(mesh, "loop", X=Xm, gradients=False)["willmore"]) / (2 * h)
        assert fd == pytest.approx(g["willmore"][i, k], rel=1e-6, abs=1e-8 * np.abs(g["willmore"]).max())


def test_sum_factorisation_is_the_dense_path_to_rounding(mesh_path):
    # genus2 refined once: regular Catmull–Clark faces next to valence-3 and -5 corners.
    V, F = limsurf.subdivide(limsurf.read_mesh(mesh_path("genus2")), "catmull-clark", 1, topology=False)
    F = np.asarray(F)
    valence = np.bincount(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 3]], F[:, [3, 0]]]).ravel(),
                          minlength=len(V)) // 2
    regular_faces = int(np.all(valence[F] == 4, axis=1).sum())
    assert 0 < regular_faces < len(F)
    rng = np.random.default_rng(5)
    X = V + 0.02 * rng.standard_normal(V.shape)
    fast = limsurf.shape_functionals(V, F, "catmull-clark", X=X)
    dense = limsurf.shape_functionals(V, F, "catmull-clark", X=X, sum_factorisation=False)
    assert fast["sum_factorised_elements"] == regular_faces and dense["sum_factorised_elements"] == 0
    for name in NAMES:
        assert fast[name] == pytest.approx(dense[name], rel=1e-13, abs=1e-13), name
        scale = max(np.abs(dense["gradient"][name]).max(), 1.0)
        assert np.abs(fast["gradient"][name] - dense["gradient"][name]).max() <= 1e-13 * scale, name
    loop = limsurf.shape_functionals(limsurf.read_mesh(mesh_path("icosahedron")), "loop", gradients=False)
    assert loop["sum_factorised_elements"] == 0
    # A solve reports the count as `limsurf membrane --json` does, and takes the switch too: the same
    # first steps to rounding (a few iterations, before rounding can steer the paths apart).
    solves = [limsurf.minimize_membrane(V, F, "catmull-clark", area=4 * np.pi, reduced_volume=0.95, max_iterations=3,
                                        sum_factorisation=flag) for flag in (True, False)]
    assert [s["sum_factorised_elements"] for s in solves] == [regular_faces, 0]
    assert solves[0]["willmore"] == pytest.approx(solves[1]["willmore"], rel=1e-9)


@pytest.mark.parametrize("name, scheme, levels", [("tetra_3", "c2g0", 0), ("icosahedron", "loop", 1),
                                                  ("genus2", "catmull-clark", 1)])
def test_a_shape_evaluator_is_the_functions_to_the_bit(mesh_path, name, scheme, levels):
    mesh = limsurf.subdivide(limsurf.read_mesh(mesh_path(name)), scheme, levels) if levels else \
        limsurf.read_mesh(mesh_path(name))
    evaluator = limsurf.ShapeEvaluator(mesh, scheme)
    assert evaluator.scheme == scheme and evaluator.num_vertices == mesh.num_vertices
    rng = np.random.default_rng(41)
    for X in (None, mesh.V + 0.01 * rng.standard_normal(mesh.V.shape), 1.5 * mesh.V):
        ours = evaluator.evaluate(X, spontaneous_curvature=0.5)
        theirs = limsurf.shape_functionals(mesh, scheme, X=X, spontaneous_curvature=0.5)
        assert set(ours) == set(theirs)
        for key in VALUE_KEYS + ("helfrich", "sum_factorised_elements"):
            assert ours[key] == theirs[key], key
        for key, g in theirs["gradient"].items():
            assert np.array_equal(ours["gradient"][key], g), key
    assert evaluator.num_samples == ours["samples"] and evaluator.volume_is_exact == ours["volume_is_exact"]
    assert evaluator.sum_factorised_elements == ours["sum_factorised_elements"]
    assert (evaluator.sum_factorised_elements > 0) == (scheme == "catmull-clark")
    assert "gradient" not in evaluator.evaluate(gradients=False)
    weights = {"willmore": 1.0, "area": -0.5}
    H = evaluator.hessian(weights, X=1.5 * mesh.V)
    H_function = limsurf.shape_hessian(mesh, scheme, weights, X=1.5 * mesh.V)
    assert (H != H_function).nnz == 0 and H.nnz == H_function.nnz
    assert evaluator.self_intersections() == limsurf.self_intersections(mesh, scheme)
    same = limsurf.ShapeEvaluator(mesh.V, mesh.F, scheme).evaluate(gradients=False)
    assert same["willmore"] == evaluator.evaluate(gradients=False)["willmore"]


def test_a_shape_evaluator_serves_threads_and_refuses_bad_input(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("icosahedron"))
    evaluator = limsurf.ShapeEvaluator(mesh, "loop", threads=1)
    X = [mesh.V * (1 + 0.1 * k) for k in range(4)]
    results = [None] * 4

    def work(k):
        results[k] = evaluator.evaluate(X[k])["willmore"]

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [evaluator.evaluate(x)["willmore"] for x in X]  # W is scale-invariant: all equal
    assert max(results) - min(results) <= 1e-12 * results[0]
    with pytest.raises(limsurf.InputError, match="X"):
        evaluator.evaluate(mesh.V[:-1])
    with pytest.raises(limsurf.InputError, match="X"):
        evaluator.evaluate(np.full_like(mesh.V, np.nan))
    with pytest.raises(limsurf.InputError, match="spontaneous_curvature"):
        evaluator.evaluate(spontaneous_curvature=float("inf"))
    with pytest.raises(limsurf.InputError, match="coefficients"):
        evaluator.hessian({"bending": 1.0})
    with pytest.raises(limsurf.InputError, match="threads"):
        limsurf.ShapeEvaluator(mesh, "loop", threads=-1)
    with pytest.raises(limsurf.InputError, match="closed surface"):
        limsurf.ShapeEvaluator(limsurf.read_mesh(mesh_path("plate_sym")), "catmull-clark")
    with pytest.raises(limsurf.UnsupportedError):
        limsurf.ShapeEvaluator(limsurf.read_mesh(mesh_path("cube")), "doo-sabin")


def test_shape_hessian_matches_the_gradients_and_the_identities(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("icosahedron"))
    X = mesh.V + 0.05 * np.random.default_rng(23).standard_normal(mesh.V.shape)
    weights = {"willmore": 1.0, "area": 0.5, "mean_curvature": -0.25}
    H = limsurf.shape_hessian(mesh, "loop", weights, X=X)
    assert H.shape == (3 * mesh.num_vertices, 3 * mesh.num_vertices) and (H != H.T).nnz == 0
    # Rows and columns 3 v + c: X.reshape(-1) is in that order. H D against central differences of the
    # gradients of the same combination.
    D = np.random.default_rng(29).standard_normal(X.shape)
    h = 1e-5

    def gradient(Y):
        g = limsurf.shape_functionals(mesh, "loop", X=Y)["gradient"]
        return sum(w * g[name] for name, w in weights.items()).reshape(-1)

    central = (gradient(X + h * D) - gradient(X - h * D)) / (2 * h)
    HD = H @ D.reshape(-1)
    assert np.linalg.norm(HD - central) <= 1e-6 * np.linalg.norm(HD)
    # Euler: ∇A is homogeneous of degree 1, so H_A X = ∇A; ∇W of degree −1: H_W X = −∇W.
    g = limsurf.shape_functionals(mesh, "loop", X=X)["gradient"]
    for name, factor in (("area", 1.0), ("willmore", -1.0)):
        HX = limsurf.shape_hessian(mesh, "loop", {name: 1.0}, X=X) @ X.reshape(-1)
        assert np.linalg.norm(HX - factor * g[name].reshape(-1)) <= 1e-8 * np.linalg.norm(HX), name
    # Arrays instead of a Mesh; the pattern is the faces', whatever the weights.
    same = limsurf.shape_hessian(mesh.V, mesh.F, "loop", weights, X=X)
    assert (same != H).nnz == 0
    assert limsurf.shape_hessian(mesh, "loop", {}).nnz == H.nnz


def test_exact_hessians_equal_the_cli(mesh_path, cli, tmp_path):
    theirs = cli("membrane", mesh_path("octahedron"), "--scheme", "loop", "--area", repr(A0), "--reduced-volume", 0.9,
                 "--hessian", "exact", "--objective-tolerance", 0, "-o", tmp_path / "exact.obj", "--json")
    ours = limsurf.minimize_membrane(limsurf.read_mesh(mesh_path("octahedron")), "loop", area=A0, reduced_volume=0.9,
                                     hessian="exact", objective_tolerance=0)
    assert ours["converged"] and ours["status"].startswith("solved") and ours["hessian"] == "exact"
    for key in set(theirs) - {"seconds", "output"}:
        assert ours[key] == theirs[key], key
    # BFGS for the shape, Newton steps for (3.12): each stage's JSON says which.
    theirs = cli("membrane", mesh_path("octahedron"), "--scheme", "loop", "--area", repr(A0), "--reduced-volume", 0.9,
                 "--regularize-harmonic", 0.05, "--regularization-hessian", "exact", "-o", tmp_path / "mixed.obj",
                 "--json")
    ours = limsurf.minimize_membrane(limsurf.read_mesh(mesh_path("octahedron")), "loop", area=A0, reduced_volume=0.9,
                                     regularize_harmonic=0.05, regularization_hessian="exact")
    assert ours["hessian"] == "limited-memory" and ours["regularization"]["hessian"] == "exact"
    for key in set(theirs) - {"seconds", "output", "regularization"}:
        assert ours[key] == theirs[key], key
    for key in set(theirs["regularization"]) - {"seconds"}:
        assert ours["regularization"][key] == theirs["regularization"][key], key


def test_minimize_membrane_equals_the_cli(mesh_path, cli, tmp_path):
    out = tmp_path / "prolate.obj"
    theirs = cli("membrane", mesh_path("octahedron"), "--scheme", "loop", "--area", repr(A0), "--reduced-volume", 0.9,
                 "--max-iterations", 300, "-o", out, "--json")
    ours = limsurf.minimize_membrane(limsurf.read_mesh(mesh_path("octahedron")), "loop", area=A0, reduced_volume=0.9,
                                     max_iterations=300)
    assert ours["converged"] and theirs["converged"]
    for key in set(theirs) - {"seconds", "output"}:
        assert ours[key] == theirs[key], key
    assert ours["max_relative_residual"] <= 1e-8
    assert ours["reduced_volume"] == pytest.approx(0.9, abs=1e-8)
    # The positions are those the CLI wrote (shortest round-trip digits in the OBJ).
    assert np.array_equal(ours["positions"], limsurf.read_mesh(out).V)


def test_self_intersections_equal_the_cli(mesh_path, cli, tmp_path):
    mesh = limsurf.read_mesh(mesh_path("icosahedron"))
    X = mesh.V.copy()
    X[0] = -3.0 * X[0] + 0.3 * X[5]  # pulled through the middle: the Loop surface crosses itself
    pulled = tmp_path / "pulled.obj"
    limsurf.write_mesh(pulled, mesh.with_positions(X))
    for path, expected in ((mesh_path("icosahedron"), False), (pulled, True)):
        theirs = cli("membrane", path, "--scheme", "loop", "--evaluate-only", "--intersection-resolution", 7,
                     "--json")["self_intersection"]
        ours = limsurf.self_intersections(limsurf.read_mesh(path), "loop", resolution=7)
        assert ours == theirs and ours["intersects"] == expected
    # Other positions for the same faces, and arrays instead of a Mesh.
    assert limsurf.self_intersections(mesh, "loop", X=X, resolution=7) == ours
    assert limsurf.self_intersections(mesh.V, mesh.F, "loop", X=X, resolution=7) == ours
    with pytest.raises(limsurf.InputError, match="resolution"):
        limsurf.self_intersections(mesh, "loop", resolution=300)


def test_callback_sees_every_iteration_and_can_stop_the_solve(mesh_path):
    mesh = limsurf.read_mesh(mesh_path("icosahedron"))
    seen = []
    done = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.8, max_iterations=50,
                                     callback=lambda it: seen.append(it))
    # Numbered in order; the regular iteration leaving Ipopt's restoration phase repeats its last number.
    assert seen[0]["iteration"] == 0
    for before, it in zip(seen, seen[1:]):
        leaving_restoration = before["restoration"] and not it["restoration"]
        assert it["iteration"] == before["iteration"] + (0 if leaving_restoration else 1)
    assert all(it["stage"] == "shape" for it in seen)
    assert set(seen[0]) == {"stage", "iteration", "objective", "constraint_violation", "dual_infeasibility", "step",
                            "restoration", "watchdog"}
    assert done["iterations"] <= len(seen)
    stopped = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.8,
                                        callback=lambda it: it["iteration"] < 3)
    assert not stopped["converged"] and stopped["iterations"] <= 4
    assert np.isfinite(stopped["positions"]).all()
    assert stopped["projected"] is False  # a stop asked for returns the last iterate as it is
    # Cut short by max_iterations instead, the points returned hold the constraints when it could project:
    # after 3 iterations every iterate is still more than 0.1 (relative) away, beyond what is projected, so
    # the last one comes back as it is; after 20 some came near enough. (Where the iterates go depends on
    # the gradients' last bits; the premise is checked, so that a new path fails here and not obscurely.)
    path = []
    far = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.8, max_iterations=3,
                                    callback=lambda it: path.append(it["constraint_violation"]))
    assert min(path) > 0.1, f"the premise: no iterate near the constraints ({path})"
    assert not far["converged"] and far["projected"] is False and far["max_relative_residual"] > 0.1
    short = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.8, max_iterations=20)
    assert not short["converged"] and short["projected"] is True
    assert short["max_relative_residual"] <= 1e-9 and "projected onto the constraints" in short["status"]

    def fail(it):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.8, callback=fail)


def test_continuation_equals_the_cli_and_stops_when_asked(mesh_path, cli, tmp_path):
    mesh = limsurf.read_mesh(mesh_path("octahedron"))
    stages = []
    ours = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.9, continuation_steps=3,
                                     callback=lambda it: stages.append(it["stage"]))
    theirs = cli("membrane", mesh_path("octahedron"), "--scheme", "loop", "--area", repr(A0), "--reduced-volume", 0.9,
                 "--continuation", 3, "-o", tmp_path / "continued.obj", "--json")
    assert ours["converged"] and len(ours["continuation"]) == 2
    for key in set(theirs) - {"seconds", "output", "continuation"}:
        assert ours[key] == theirs[key], key
    for step, cli_step in zip(ours["continuation"], theirs["continuation"]):
        assert {k: v for k, v in step.items() if k != "seconds"} == {k: v for k, v in cli_step.items() if k != "seconds"}
    v_start = limsurf.shape_functionals(mesh, "loop", gradients=False)["reduced_volume"]
    for k, step in enumerate(ours["continuation"], start=1):
        assert step["targets"]["reduced_volume"] == pytest.approx(v_start + (0.9 - v_start) * k / 3, abs=1e-12)
    assert stages[0] == "continuation" and stages[-1] == "shape"
    assert stages.count("shape") >= ours["iterations"] + 1  # iterations 0 … n
    # A stop asked for in a step stops the whole solve, and the callback is not called again.
    calls = []
    starts = []  # the continuation's iterations 0: one per step (restoration continues the numbering)

    def stop_in_the_second_step(it):
        calls.append(it["stage"])
        if it["stage"] == "continuation" and it["iteration"] == 0:
            starts.append(len(calls))
        return not (len(starts) == 2 and it["iteration"] >= 2)

    stopped = limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.9, continuation_steps=3,
                                        callback=stop_in_the_second_step)
    assert not stopped["converged"] and stopped["status"] == "stopped by the caller"
    assert len(stopped["continuation"]) == 2 and stopped["continuation"][1]["status"] == "stopped by the caller"
    assert calls[-1] == "continuation" and "shape" not in calls
    with pytest.raises(limsurf.InputError, match="continuation steps = 0"):
        limsurf.minimize_membrane(mesh, "loop", area=A0, reduced_volume=0.9, continuation_steps=0)


def test_regularization_reports_both_stages(mesh_path):
    stages = []
    r = limsurf.minimize_membrane(limsurf.read_mesh(mesh_path("octahedron")), "loop", area=A0, reduced_volume=0.9,
                                  reduced_mean_curvature=1.06, regularize_harmonic=0.05,
                                  callback=lambda it: stages.append(it["stage"]))
    assert r["converged"] and r["regularization"]["converged"]
    assert stages[0] == "shape" and stages[-1] == "regularization" and stages == sorted(stages, key=stages.index)
    reg = r["regularization"]
    assert reg["targets"]["willmore_bound"] == r["willmore"] + 0.05
    assert reg["willmore"] <= reg["targets"]["willmore_bound"] * (1 + 1e-8)
    assert reg["harmonic"] < r["harmonic"]
    # 'positions' are the last stage's: evaluated again they give its functionals.
    again = limsurf.shape_functionals(limsurf.read_mesh(mesh_path("octahedron")), "loop", X=r["positions"],
                                      gradients=False)
    assert again["harmonic"] == reg["harmonic"] and again["willmore"] == reg["willmore"]


def test_errors(mesh_path):
    sphere = limsurf.read_mesh(mesh_path("tetra_1"))
    with pytest.raises(limsurf.InputError, match="reduced volume"):
        limsurf.minimize_membrane(sphere, "c2g0", area=A0, reduced_volume=1.2)
    with pytest.raises(limsurf.InputError, match="area"):
        limsurf.minimize_membrane(sphere, "c2g0", area=-1.0, reduced_volume=0.9)
    with pytest.raises(limsurf.InputError, match="exactly one"):
        limsurf.minimize_membrane(sphere, "c2g0", area=A0, volume=3.0, reduced_volume=0.9)
    with pytest.raises(limsurf.InputError, match="closed surface"):
        limsurf.shape_functionals(limsurf.read_mesh(mesh_path("cylinder_open")), "catmull-clark")
    with pytest.raises(limsurf.UnsupportedError):
        limsurf.shape_functionals(limsurf.read_mesh(mesh_path("cube")), "doo-sabin")
    with pytest.raises(limsurf.InputError):
        limsurf.shape_functionals(sphere, "c2g0", X=np.zeros((3, 3)))
    with pytest.raises(limsurf.InputError, match="hessian: 'limited-memory' or 'exact'"):
        limsurf.minimize_membrane(sphere, "c2g0", area=A0, reduced_volume=0.9, hessian="newton")
    with pytest.raises(limsurf.InputError, match="regularization_hessian needs regularize_harmonic"):
        limsurf.minimize_membrane(sphere, "c2g0", area=A0, reduced_volume=0.9, regularization_hessian="exact")
    with pytest.raises(limsurf.InputError, match="regularization_hessian: 'limited-memory' or 'exact'"):
        limsurf.minimize_membrane(sphere, "c2g0", area=A0, reduced_volume=0.9, regularize_harmonic=0.1,
                                  regularization_hessian="newton")
    with pytest.raises(limsurf.InputError, match="'wilmore' is not a shape functional"):
        limsurf.shape_hessian(sphere, "c2g0", {"wilmore": 1.0})
    with pytest.raises(limsurf.InputError, match="must be finite"):
        limsurf.shape_hessian(sphere, "c2g0", {"willmore": math.inf})
    with pytest.raises(limsurf.InputError):
        limsurf.shape_hessian(sphere, "c2g0", {"willmore": 1.0}, X=np.zeros((3, 3)))
