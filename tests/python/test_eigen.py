"""The eigen-analysis of a scheme from Python (analysis/eigen_analysis.h, docs/guide/eigen.md): equal to
`limsurf eigen --json` key by key, the subdominant eigenvalues of Catmull–Clark and Loop against their
closed forms, S and the eigenvectors checked as an eigen-decomposition in numpy, the characteristic map's
samples and faces, Table 1's tuned weights, and the requests the analysis refuses."""
import math
import threading

import numpy as np
import pytest

import limsurf

SCALAR_KEYS = ("scheme", "valence", "boundary", "rings", "size", "symmetry_residual", "dominant", "subdominant",
               "subdominant_multiplicity", "subsubdominant", "subsubdominant_multiplicity")
MAP_STATISTICS = ("min_jacobian", "max_jacobian", "winding_number", "samples")


def catmull_clark_lambda(n):
    c, h = math.cos(2 * math.pi / n), math.cos(math.pi / n)
    return (5 + c + h * math.sqrt(2 * (9 + c))) / 16


def loop_lambda(n):
    return 3 / 8 + math.cos(2 * math.pi / n) / 4


CASES = [("catmull-clark", 5, []), ("catmull-clark", 3, ["--rings", "3"]), ("loop", 7, []),
         ("loop", 4, ["--boundary"]), ("catmull-clark", 4, ["--boundary"]), ("doo-sabin", 5, []), ("c2g0", 3, []),
         ("c2g0", 6, []), ("catmull-clark", 5, ["--weights", "13.4575,0.999938,0.999938"]),
         ("catmull-clark", 5, ["--rings", "1"])]


def python_call(scheme, valence, extra):
    kwargs = {}
    if "--boundary" in extra:
        kwargs["boundary"] = True
    if "--rings" in extra:
        kwargs["rings"] = int(extra[extra.index("--rings") + 1])
    if "--weights" in extra:
        kwargs["weights"] = tuple(float(w) for w in extra[extra.index("--weights") + 1].split(","))
    return limsurf.eigen_analysis(scheme, valence, **kwargs)


@pytest.mark.parametrize("scheme, valence, extra", CASES)
def test_equals_the_cli_json(cli, scheme, valence, extra):
    expected = cli("eigen", "--scheme", scheme, "--valence", valence, *extra, "--json")
    got = python_call(scheme, valence, extra)
    for key in SCALAR_KEYS:
        assert got[key] == expected[key], key
    assert got["tests"] == {name: {k: t[k] for k in ("checked", "passed", "detail")}
                            for name, t in expected["tests"].items()}
    assert len(got["eigenvalues"]) == len(expected["eigenvalues"])
    for mine, theirs in zip(got["eigenvalues"], expected["eigenvalues"]):
        assert mine["value"] == complex(theirs["value"]["re"], theirs["value"]["im"])
        for key in ("frequency", "algebraic", "geometric", "jordan_blocks"):
            assert mine[key] == theirs[key], key
    m, e = got["characteristic_map"], expected["characteristic_map"]
    assert m["evaluated"] == e["evaluated"]
    if e["evaluated"]:
        for key in MAP_STATISTICS:
            assert m[key] == e[key], key
    else:
        assert m["reason"] == e["reason"]


@pytest.mark.parametrize("n", [3, 5, 6, 7, 9, 12])
def test_subdominant_eigenvalues_are_the_closed_forms(n):
    cc = limsurf.eigen_analysis("catmull-clark", n)
    assert cc["subdominant"] == pytest.approx(catmull_clark_lambda(n), abs=1e-12)
    assert cc["dominant"] == pytest.approx(1.0, abs=1e-12)
    assert cc["size"] == 6 * n + 1 and cc["tests"]["c1"]["passed"]
    loop = limsurf.eigen_analysis("loop", n)
    assert loop["subdominant"] == pytest.approx(loop_lambda(n), abs=1e-12)
    assert loop["size"] == 3 * n + 1 and loop["tests"]["c1"]["passed"]


@pytest.mark.parametrize("scheme, valence, boundary", [("catmull-clark", 5, False), ("loop", 3, False),
                                                        ("c2g0", 3, False), ("doo-sabin", 6, False),
                                                        ("loop", 5, True)])
def test_s_and_the_eigenvectors_are_an_eigen_decomposition(scheme, valence, boundary):
    r = limsurf.eigen_analysis(scheme, valence, boundary=boundary)
    S = r["S"]
    assert S.dtype == np.float64 and S.shape == (r["size"], r["size"]) and S.flags.c_contiguous
    assert r["sector"].shape == (r["size"],) and r["sector"].dtype == np.int32
    np.testing.assert_allclose(S.sum(axis=1), 1.0, atol=1e-13)  # affine invariance: every rule sums to 1
    if not boundary:
        # Sector-major order: S commutes with the rotation that shifts every sector by one.
        sectors = r["sector"]
        n = sectors.max() + 1
        per = np.count_nonzero(sectors == 0)
        fixed = np.flatnonzero(sectors < 0)
        rotate = np.empty(r["size"], dtype=int)
        rotate[fixed] = fixed
        first = len(fixed)
        for s in range(n):
            block = np.arange(first + s * per, first + (s + 1) * per)
            rotate[block] = first + ((s + 1) % n) * per + np.arange(per)
        P = np.eye(r["size"])[rotate]
        np.testing.assert_allclose(P @ S, S @ P, atol=1e-12)
    total = 0
    for e in r["eigenvalues"]:
        V = e["eigenvectors"]
        assert V.dtype == np.complex128 and V.shape == (r["size"], e["geometric"])
        assert np.all(np.linalg.norm(V, axis=0) > 0.5)
        np.testing.assert_allclose(S @ V, e["value"] * V, atol=1e-9)
        total += e["algebraic"]
    assert total == r["size"]
    # The moduli numpy finds, in the order the analysis lists them (multiplicities expanded).
    listed = np.concatenate([[abs(e["value"])] * e["algebraic"] for e in r["eigenvalues"]])
    np.testing.assert_allclose(listed, np.sort(np.abs(np.linalg.eigvals(S)))[::-1], atol=1e-6)


def test_the_characteristic_map_is_a_mesh_of_its_samples():
    r = limsurf.eigen_analysis("loop", 5)
    m = r["characteristic_map"]
    assert m["evaluated"] and m["resolution"] == 16
    X, F = m["positions"], m["faces"]
    # (u, v) = (i, j)/16 on each of the five triangles at the vertex, face after face; 'samples' counts
    # those in the ring segment (outside the half-size triangle at the vertex), where det DΦ is checked.
    per_face = 17 * 18 // 2
    assert X.shape == (5 * per_face, 3) and np.all(X[:, 2] == 0.0)
    assert 5 * (per_face - 9 * 10 // 2) <= m["samples"] < 5 * per_face
    assert F.dtype == np.int32 and F.shape == (5 * 16 * 16, 3) and F.min() == 0 and F.max() == len(X) - 1
    # Regular (every sampled triangle of the ring segment keeps its orientation) around Φ(vertex) = 0.
    assert 0 < m["min_jacobian"] <= m["max_jacobian"] and m["winding_number"] == pytest.approx(1.0)
    assert np.abs(X[:, :2]).min(axis=0).max() < 1e-12  # the vertex's image, the origin, is a sample
    # Five rotated copies: the radii of the samples on each face are the same set.
    radii = np.linalg.norm(X[:, :2], axis=1).reshape(5, per_face)
    np.testing.assert_allclose(np.sort(radii, axis=1), np.sort(radii[:1], axis=1).repeat(5, axis=0), atol=1e-12)
    assert limsurf.eigen_analysis("catmull-clark", 5)["characteristic_map"]["faces"].shape[1] == 4


def test_table_one_weights_as_a_tuple_or_a_dict():
    cup = limsurf.eigen_analysis("catmull-clark", 5, weights=(13.4575, 0.999938, 0.999938))
    assert cup["subdominant"] == pytest.approx(0.550, abs=5e-6)  # Table 1 prints three decimals
    (w,) = limsurf.weights_for_subdominant(5, 0.585)  # the tuning's own dict W is accepted
    saddle = limsurf.eigen_analysis("catmull-clark", 5, weights=w)
    assert saddle["subdominant"] == pytest.approx(0.585, abs=1e-12)
    assert saddle["tests"]["c1"]["passed"]


def test_two_threads_analyse_at_once():
    results = {}

    def work(n):
        results[n] = limsurf.eigen_analysis("catmull-clark", n)["subdominant"]

    threads = [threading.Thread(target=work, args=(n,)) for n in (40, 41)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == {n: pytest.approx(catmull_clark_lambda(n), abs=1e-12) for n in (40, 41)}


@pytest.mark.parametrize("kwargs, message", [
    (dict(scheme="c2g0", valence=5), "valences 3 and 6"),
    (dict(scheme="loop", valence=5, weights=(1, 1, 1)), "catmull-clark only"),
    (dict(scheme="catmull-clark", valence=5, weights=(-1, 1, 1)), "alpha must be > 0"),
    (dict(scheme="catmull-clark", valence=5, weights=(1, 1)), "weights: expected (alpha, beta, gamma)"),
    (dict(scheme="catmull-clark", valence=5, weights=(1, "b", 1)), "weights[1]: expected a number"),
    (dict(scheme="catmull-clark", valence=5, weights=(1, float("nan"), 1)), "finite"),
    (dict(scheme="bilinear", valence=4), "not analysed"),
    (dict(scheme="cc", valence=4), "cc"),
    (dict(scheme="loop", valence=2), "valence 2"),
    (dict(scheme="doo-sabin", valence=5, boundary=True), "no boundary rules"),
    (dict(scheme="catmull-clark", valence=5, rings=9), "rings must be 1..8"),
])
def test_bad_requests_raise_input_error(kwargs, message):
    with pytest.raises(limsurf.InputError) as raised:
        limsurf.eigen_analysis(**kwargs)
    assert message in str(raised.value)


def test_too_few_rings_for_the_rules_is_a_numerical_error():
    with pytest.raises(limsurf.NumericalError, match="use more rings"):
        limsurf.eigen_analysis("c2g0", 3, rings=1)
