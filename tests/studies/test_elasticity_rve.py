"""studies/elasticity_rve.py --quick: its files are valid and the effective stiffnesses are consistent.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary; by hand:

  LIMSURF_CLI=build/release/cli/limsurf /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/studies

--quick is square_inclusion and rve_block, levels 0..2. Checked against what is known without the
library: the control-vertex counts of Catmull-Clark refinement counted from the OBJs; the area
fraction, the same on every level (refinement does not move the limit surface) and near pi/16 for
the disc; the Voigt, Reuss and Hashin-Shtrikman bulk bounds recomputed here from the fractions and
the plane-strain moduli, and C* within them; C* symmetric (C11 = C22 and no shear coupling for the
disc's square symmetry); the refined spaces contain the coarse ones, so every level is at most as
stiff as the one before (C*_(l-1) - C*_l positive semi-definite); the differences shrink, faster
with the creased interface (measured rate 2.8 on levels 1..2, 2.8-3.0 on 1..4) than without (1.2,
about 1 on 1..4); and the CSV, JSON and printed table agree.
"""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
STUDY = REPO / "studies" / "elasticity_rve.py"
MESHES = REPO / "data" / "meshes"
EXAMPLES = {"square_inclusion": "inclusion", "rve_block": "grain"}
LEVELS = 2
MATRIX, SECOND = (1.0, 0.3), (10.0, 0.3)
ENTRIES = [f"C{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
COLUMNS = (["example", "mesh", "level", "vertices", "faces", "seconds", "fraction"] + ENTRIES
           + ["kappa", "mu_33", "mu_d", "difference", "rate", "kappa_over_hs_lower", "c11_between_reuss_voigt",
              "voigt_margin", "reuss_margin", "within_bounds"])


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    tool = os.environ.get("LIMSURF_CLI")
    if not tool or not os.access(tool, os.X_OK):
        pytest.fail("LIMSURF_CLI must name the limsurf binary")
    out = tmp_path_factory.mktemp("elasticity_rve")
    r = subprocess.run([sys.executable, str(STUDY), tool, str(out), "--quick"], capture_output=True, text=True,
                       timeout=600, check=False)
    assert r.returncode == 0, r.stderr
    assert "| example | level | vertices | C11 |" in r.stdout
    (out / "stdout.txt").write_text(r.stdout, encoding="utf-8")
    return out


@pytest.fixture(scope="module")
def rows(outdir) -> dict[str, list[dict[str, str]]]:
    with open(outdir / "elasticity_rve.csv", newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == COLUMNS
        table = list(reader)
    by = {ex: [r for r in table if r["example"] == ex] for ex in EXAMPLES}
    assert [r["example"] for r in table] == [ex for ex in EXAMPLES for _ in range(LEVELS + 1)]
    for ex, mine in by.items():
        assert [int(r["level"]) for r in mine] == list(range(LEVELS + 1)) and mine[0]["mesh"] == f"{ex}.obj"
    return by


def f(row, key) -> float:
    v = float(row[key])
    assert math.isfinite(v), (key, row[key])
    return v


def stiffness(row) -> np.ndarray:
    return np.array([[f(row, f"C{i}{j}") for j in (1, 2, 3)] for i in (1, 2, 3)])


def plane_strain(E: float, nu: float) -> np.ndarray:
    c = E / ((1 + nu) * (1 - 2 * nu))
    return c * np.array([[1 - nu, nu, 0], [nu, 1 - nu, 0], [0, 0, (1 - 2 * nu) / 2]])


def counts(path: Path) -> tuple[int, int, int]:
    """V, E, F of an OBJ of quads."""
    faces = [[int(t.split("/")[0]) for t in line.split()[1:]]
             for line in path.read_text(encoding="utf-8").splitlines() if line.startswith("f ")]
    assert all(len(face) == 4 for face in faces)
    edges = {frozenset((a, face[(i + 1) % 4])) for face in faces for i, a in enumerate(face)}
    vertices = sum(1 for line in path.read_text(encoding="utf-8").splitlines() if line.startswith("v "))
    return vertices, len(edges), len(faces)


def test_files(outdir):
    png = outdir / "elasticity_rve.png"
    assert png.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    import matplotlib.image
    img = matplotlib.image.imread(png)
    assert (img.shape[1], img.shape[0]) == (1350, 450) and img.std() > 0.01
    assert ET.parse(outdir / "elasticity_rve.svg").getroot().tag == "{http://www.w3.org/2000/svg}svg"


def test_levels_are_catmull_clark_refinements(rows):
    for ex, mine in rows.items():
        V, E, F = counts(MESHES / f"{ex}.obj")
        for r in mine:
            assert (int(r["vertices"]), int(r["faces"])) == (V, F), (ex, r["level"])
            V, E, F = V + E + F, 2 * E + 4 * F, 4 * F  # quads: edge and face points, four children each


def test_fractions_and_bounds(rows):
    Cm, Ci = plane_strain(*MATRIX), plane_strain(*SECOND)
    km, mm = Cm[0, 0] - Cm[2, 2], Cm[2, 2]  # plane strain: kappa = lambda + mu
    ki, mi = Ci[0, 0] - Ci[2, 2], Ci[2, 2]
    for ex, mine in rows.items():
        fr = [f(r, "fraction") for r in mine]
        assert max(fr) - min(fr) < 1e-7, (ex, fr)  # the limit surface does not move with the level
        if ex == "square_inclusion":
            assert abs(fr[0] - math.pi / 16) < 0.005
        t = fr[-1]
        voigt = (1 - t) * Cm + t * Ci
        reuss = np.linalg.inv((1 - t) * np.linalg.inv(Cm) + t * np.linalg.inv(Ci))
        k_lo = km + t / (1 / (ki - km) + (1 - t) / (km + mm))
        k_hi = ki + (1 - t) / (1 / (km - ki) + t / (ki + mi))
        for r in mine:
            C = stiffness(r)
            assert np.abs(C - C.T).max() < 1e-9 * np.abs(C).max(), (ex, r["level"])
            assert np.linalg.eigvalsh(voigt - C).min() > 0 and np.linalg.eigvalsh(C - reuss).min() > 0
            kappa = 0.5 * (C[0, 0] + C[0, 1])
            assert k_lo < kappa < k_hi, (ex, r["level"], k_lo, kappa, k_hi)
            assert math.isclose(f(r, "kappa"), kappa, rel_tol=1e-12)
            assert math.isclose(f(r, "kappa_over_hs_lower"), kappa / k_lo, rel_tol=1e-6)
            assert r["within_bounds"] == "1"
            if ex == "square_inclusion":  # symmetric under the square's rotations and reflections
                assert abs(C[0, 0] - C[1, 1]) < 1e-9 and abs(C[0, 2]) < 1e-9 and abs(C[1, 2]) < 1e-9


def test_levels_converge_from_above(rows, outdir):
    summary = json.loads((outdir / "elasticity_rve.json").read_text(encoding="utf-8"))
    assert summary["levels"] == LEVELS
    for ex, mine in rows.items():
        Cs = [stiffness(r) for r in mine]
        for a, b in zip(Cs, Cs[1:]):  # nested spaces: no level stiffer than the one before
            assert np.linalg.eigvalsh(a - b).min() > -1e-9 * np.abs(b).max(), ex
        d = [np.linalg.norm(b - a) / np.linalg.norm(b) for a, b in zip(Cs, Cs[1:])]
        assert [f(r, "difference") for r in mine[1:]] == pytest.approx(d, rel=1e-9)
        assert mine[0]["difference"] == "" and mine[1]["rate"] == ""
        rate = math.log2(d[0] / d[1])
        assert math.isclose(f(mine[2], "rate"), rate, rel_tol=1e-9)
        per = summary["examples"][ex]
        assert per["differences"] == pytest.approx(d, rel=1e-9) and per["last_rate"] == pytest.approx(rate)
        if ex == "square_inclusion":  # the creased interface: measured 5.2e-4, 7.5e-5, rate 2.8
            assert d[1] < 2e-4 and rate > 2.0
        else:  # C2 across the material jump: measured 7.2e-2, 3.1e-2, rate 1.2
            assert d[1] < 0.05 and 0.5 < rate < 2.0
    table = (outdir / "stdout.txt").read_text(encoding="utf-8")
    for ex, mine in rows.items():
        assert f"| {ex} | 2 | {mine[2]['vertices']} | {f(mine[2], 'C11'):.6f} |" in table
