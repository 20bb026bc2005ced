"""studies/spectra.py --quick: its files are valid and the spectra are those of the literature.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary (test_studies.py says how
by hand). --quick is valences 3..8. Checked: spectra.{csv,json,png,svg} exist and parse; the
subdominant eigenvalue of Catmull-Clark (Doo and Sabin 1978) and Loop (Loop 1987) is the closed form
written here, independently of the study's own, and Doo-Sabin's is 1/2; Catmull-Clark and Loop are C1
at every valence (Reif's test: regular, injective characteristic maps); the curvature verdicts
are the classical ones: Catmull-Clark bounded at 3 and 4 only, Loop at 4, 5, 6 only, (17) at the
regular valences only; C2g0 passes (17) at 3 and 6 (c2g0-sphere-scheme-biomembranes §2.2); Table 1's
weights give its lambda; each verdict follows from the numbers in the same row.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_studies import check_columns, check_images, num, study_outdir  # noqa: E402

COLUMNS = ["scheme", "valence", "weights", "rings", "size", "lambda", "closed_form", "lambda_multiplicity",
           "next", "next_multiplicity", "lambda_squared", "next_over_lambda_squared", "c1_spectrum", "c1",
           "bounded_curvature", "c2_necessary", "min_jacobian", "max_jacobian", "winding_number"]
VALENCES = list(range(3, 9))


def catmull_clark(n):
    c = math.cos(2 * math.pi / n)
    return (5 + c + math.cos(math.pi / n) * math.sqrt(2 * (9 + c))) / 16


def loop(n):
    return 3 / 8 + math.cos(2 * math.pi / n) / 4


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    return study_outdir(tmp_path_factory, "spectra", "| scheme | valence | weights | lambda |")


@pytest.fixture(scope="module")
def rows(outdir):
    return check_columns(outdir / "spectra.csv", COLUMNS)


def test_spectra_files(outdir):
    check_images(outdir, "spectra", (1200, 700))


def by(rows, scheme, weights=""):
    return {int(r["valence"]): r for r in rows if r["scheme"] == scheme and r["weights"] == weights}


def test_subdominant_eigenvalues_are_the_closed_forms(rows):
    cc, lp, ds = by(rows, "catmull-clark"), by(rows, "loop"), by(rows, "doo-sabin")
    assert sorted(cc) == sorted(lp) == sorted(ds) == VALENCES
    for n in VALENCES:
        assert num(cc[n], "lambda") == pytest.approx(catmull_clark(n), abs=1e-12)
        assert num(lp[n], "lambda") == pytest.approx(loop(n), abs=1e-12)
        assert num(ds[n], "lambda") == pytest.approx(0.5, abs=1e-12)
        assert int(cc[n]["size"]) == 6 * n + 1 and int(lp[n]["size"]) == 3 * n + 1
        assert int(cc[n]["lambda_multiplicity"]) == 2 and int(lp[n]["lambda_multiplicity"]) == 2


def test_the_verdicts_are_the_classical_ones(rows):
    cc, lp = by(rows, "catmull-clark"), by(rows, "loop")
    for n in VALENCES:
        for r in (cc[n], lp[n]):
            # Reif's test: C1 at every valence, the map regular (det DΦ > 0) and injective (winding 1).
            assert r["c1"] == "yes" and num(r, "min_jacobian") > 0 and num(r, "winding_number") == pytest.approx(1)
            # Bounded curvature is "next <= lambda^2" (equal where the eigenvalue is not defective).
            ratio = num(r, "next_over_lambda_squared")
            assert ratio == pytest.approx(num(r, "next") / num(r, "lambda") ** 2, rel=1e-12)
            assert (r["bounded_curvature"] == "yes") == (ratio <= 1 + 1e-9), (r["scheme"], n)
    assert [n for n in VALENCES if cc[n]["bounded_curvature"] == "yes"] == [3, 4]
    assert [n for n in VALENCES if lp[n]["bounded_curvature"] == "yes"] == [4, 5, 6]
    assert [n for n in VALENCES if cc[n]["c2_necessary"] == "yes"] == [4]
    assert [n for n in VALENCES if lp[n]["c2_necessary"] == "yes"] == [6]
    c2g0 = by(rows, "c2g0")
    assert sorted(c2g0) == [3, 6] and all(r["c2_necessary"] == "yes" and r["c1"] == "yes" for r in c2g0.values())
    assert num(c2g0[3], "lambda") == pytest.approx(0.25, abs=1e-12)  # §2.1: 1, 1/4 ×2, 1/16 ×3
    assert num(c2g0[3], "next") == pytest.approx(1 / 16, abs=1e-12) and int(c2g0[3]["next_multiplicity"]) == 3


def test_table_one_and_the_summary(outdir, rows):
    cup, saddle = by(rows, "catmull-clark", "cup")[5], by(rows, "catmull-clark", "saddle")[5]
    assert num(cup, "lambda") == pytest.approx(0.550, abs=5e-6)  # Table 1 prints six digits of the weights
    assert num(saddle, "lambda") == pytest.approx(0.585, abs=5e-6)
    assert cup["c1"] == saddle["c1"] == "yes"
    summary = json.loads((outdir / "spectra.json").read_text())
    assert summary["valences"] == VALENCES
    for scheme in ("catmull-clark", "loop", "doo-sabin"):
        assert summary["schemes"][scheme]["max_difference_from_closed_form"] < 1e-12
    assert summary["schemes"]["loop"]["bounded_curvature"] == [4, 5, 6]
    assert summary["table1"]["cup"] == num(cup, "lambda")
