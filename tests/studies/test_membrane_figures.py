"""studies/membrane_figures.py --quick: its files are valid, and on F_tetra,2 the Helfrich problem of Fig. 11
(v0 = 0.5, m0 = 1.05, A0 = 4π) gives one Willmore energy from three initial guesses, and the regularisation
(3.12) of Fig. 12 (ε = 0.003) lowers the harmonic energy with W at most ε above W0.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary; by hand:

  LIMSURF_CLI=build/release/cli/limsurf /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/studies

Measured (quick, the round and perturbed starts in 5 continuation steps, 15 runs whose C2g0 weights were perturbed
by an ulp): every start converged to an embedded shape, W/4π 2.246078 … 2.246426 (the paper: 4 significant digits,
on F_tetra,3); (3.12) lowered E by 3.3-9.8 % with W + 3.0e-3. The full run (F_tetra,3 and F_tetra,4, the stomatocyte
and Fig. 7) is in studies/results and docs/VERIFICATION.md.
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

import pytest

REPO = Path(__file__).resolve().parents[2]
STUDY = REPO / "studies" / "membrane_figures.py"
AREA = 4.0 * math.pi
COLUMNS = ["study", "case", "scheme", "mesh", "vertices", "initial", "reduced_volume", "reduced_mean_curvature",
           "epsilon", "W", "W_over_4pi", "harmonic", "reduced_volume_reached", "reduced_mean_curvature_reached",
           "regularized_W", "regularized_harmonic", "self_intersecting", "intersecting_pairs",
           "intersection_resolution", "converged", "iterations", "seconds", "continuation_steps"]


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    tool = os.environ.get("LIMSURF_CLI")
    if not tool or not os.access(tool, os.X_OK):
        pytest.fail("LIMSURF_CLI must name the limsurf binary")
    out = tmp_path_factory.mktemp("membrane_figures")
    r = subprocess.run([sys.executable, str(STUDY), tool, str(out), "--quick"], capture_output=True, text=True,
                       timeout=600, env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    assert r.returncode == 0, r.stderr
    assert "| case | scheme | mesh | start |" in r.stdout
    return out


def rows(outdir: Path) -> list[dict[str, str]]:
    with open(outdir / "membrane_figures.csv", newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == COLUMNS
        return list(reader)


def test_files(outdir):
    assert (outdir / "membrane_figures.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    assert "<dc:date>" not in (outdir / "membrane_figures.svg").read_text(encoding="utf-8")
    ET.parse(outdir / "membrane_figures.svg")
    data = json.loads((outdir / "membrane_figures.json").read_text())
    assert data["area"] == AREA
    assert rows(outdir)


def test_fig11_every_start_reaches_one_willmore_energy(outdir):
    fig11 = [r for r in rows(outdir) if r["case"] == "fig11"]
    assert sorted(r["initial"] for r in fig11) == ["perturbed1", "prolate", "round"]
    for r in fig11:
        assert r["converged"] == "True", r
        assert float(r["reduced_volume_reached"]) == pytest.approx(0.5, abs=1e-6)
        assert float(r["reduced_mean_curvature_reached"]) == pytest.approx(1.05, abs=1e-6)
        assert float(r["harmonic"]) >= 2.0 * AREA * (1.0 - 1e-9)  # E >= 2A, = 2A only for a conformal map
        assert r["self_intersecting"] == "False"
    ws = [float(r["W"]) for r in fig11]
    # The paper's claim: the Willmore energies agree in their first 4 significant digits, i.e. W/4π within one
    # unit of the fourth (1e-3 at W/4π ≈ 2.25). F_tetra,2 has several local minima that close together: runs
    # whose gradients differed only in their last bits ended at W/4π 2.246080 … 2.246741 (relative spread up
    # to 2.9e-4; docs/membrane.md, "Tests that ride on the last bits"), so a tighter bound would test rounding.
    assert 2.2 < min(ws) / AREA < 2.3  # a shape far from the sphere (W/4π = 1)
    unit = 10.0 ** (math.floor(math.log10(min(ws) / AREA)) - 3)
    assert (max(ws) - min(ws)) / AREA < unit, ws
    summary = json.loads((outdir / "membrane_figures.json").read_text())["fig11"]
    assert summary["relative_spread"] == pytest.approx((max(ws) - min(ws)) / min(ws), rel=1e-9)


def test_fig12_regularisation_lowers_the_harmonic_energy_within_epsilon(outdir):
    s = json.loads((outdir / "membrane_figures.json").read_text())["fig12"]
    assert s["epsilon"] == 0.003 and s["converged"]
    assert s["W_rise"] <= 0.003 + 1e-7 * s["W0"]  # W <= W0 + ε, the constraint's tolerance
    # The drop depends on which of F_tetra,2's nearby minima the Helfrich stage reached (runs with rounding-
    # perturbed gradients: 3.3 % from W/4π 2.246316, 3.5 % from 2.246323, 4.0-4.3 % from 2.246208, 4.4 % from
    # 2.246078, 5.6 % from 2.246393, 9.8 % from 2.246155; the same with Newton steps, which reach the KKT point).
    assert s["harmonic_drop_relative"] > 0.025, s
    assert s["harmonic_after"] >= 2.0 * AREA * (1.0 - 1e-9)
