"""studies/reverse.py --quick: its files are valid and reverse subdivision is exact and least squares.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary (test_studies.py says how
by hand). --quick is genus2 and plate_sym refined L = 1, 2 times, noise sigma = 0, 1e-8, 1e-4.
Checked: reverse.{csv,json,png,svg} exist and parse; from an exact refinement the original control
mesh comes back (its counts read here from the bundled file, its points to 1e-12 of the diagonal,
residual below 1e-12); under Gaussian noise the first level's rms residual is the noise's part
outside the range of S0, sqrt(3 (1 - n/m)) sigma, to the statistics of a few hundred samples, and
the coarse points' error is linear in sigma (log-log slope 1).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_studies import REPO, check_columns, check_images, num, study_outdir  # noqa: E402

COLUMNS = ["mesh", "levels", "sigma", "fine_vertices", "fine_faces", "coarse_vertices", "coarse_faces",
           "first_level_fine_vertices", "first_level_coarse_vertices", "residual_rms", "residual_max",
           "predicted_residual_rms", "error_max", "error_rms", "unique"]


def counts(mesh: str) -> tuple[int, int]:
    lines = (REPO / "data" / "meshes" / mesh).read_text(encoding="utf-8").splitlines()
    return sum(line.startswith("v ") for line in lines), sum(line.startswith("f ") for line in lines)


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    return study_outdir(tmp_path_factory, "reverse", "| mesh | L | sigma |")


@pytest.fixture(scope="module")
def rows(outdir):
    return check_columns(outdir / "reverse.csv", COLUMNS)


def test_reverse_files(outdir):
    check_images(outdir, "reverse", (1100, 440))


def test_an_exact_refinement_gives_the_control_mesh_back(rows):
    exact = [r for r in rows if num(r, "sigma") == 0]
    assert sorted((r["mesh"], int(r["levels"])) for r in exact) == [
        ("genus2.obj", 1), ("genus2.obj", 2), ("plate_sym.obj", 1), ("plate_sym.obj", 2)]
    for r in exact:
        vertices, faces = counts(r["mesh"])
        assert (int(r["coarse_vertices"]), int(r["coarse_faces"])) == (vertices, faces)
        assert int(r["fine_faces"]) == faces * 4 ** int(r["levels"])  # quads only: 4 children each
        assert num(r, "error_max") < 1e-12 and num(r, "residual_max") < 1e-12
        assert r["unique"] == "1"


def test_noise_is_fitted_by_least_squares(outdir, rows):
    noisy = [r for r in rows if num(r, "sigma") > 0]
    assert len(noisy) == 8
    for r in noisy:
        m, n = int(r["first_level_fine_vertices"]), int(r["first_level_coarse_vertices"])
        predicted = (3 * (1 - n / m)) ** 0.5 * num(r, "sigma")
        assert num(r, "predicted_residual_rms") == pytest.approx(predicted, rel=1e-12)
        # m - n >= 150 residual degrees of freedom per coordinate: the rms is within a few per cent.
        assert 0.85 < num(r, "residual_rms") / predicted < 1.18, (r["mesh"], r["levels"], r["sigma"])
        assert 0.2 < num(r, "error_rms") / num(r, "sigma") < 10
    summary = json.loads((outdir / "reverse.json").read_text())
    assert set(summary["cases"]) == {"genus2.obj L=1", "genus2.obj L=2", "plate_sym.obj L=1", "plate_sym.obj L=2"}
    for case in summary["cases"].values():
        assert 0.9 < case["error_slope"] < 1.1 and 0.95 < case["residual_slope"] < 1.05
        assert case["exact_error_max"] < 1e-12
