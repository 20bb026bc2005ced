"""The Canham problem by limsurf against Surface Evolver, the independent peer (label `peer`).

min W = ∫H² dA s.t. A = 4π, V = v0·4π/3 at v0 = 0.8 (prolate branch, the minimum there: Seifert,
Berndl & Lipowsky 1991). limsurf (`limsurf membrane --json`, Ipopt) from data/meshes/tetra_3.obj (C2g0, 130
control vertices) and from the level-2 icosphere (Loop, 162), both stretched into the prolate spheroid of
reduced volume v0; Evolver (evolver_canham.py: the icosphere of level K, star_perp_sq_mean_curvature,
hard area and volume) at K = 2 and 3, its O(h²) discretisation error removed by Richardson extrapolation
(4 W3 − W2)/3. That extrapolation is itself good to ~3e-4 relative at v0 = 0.8 (against the K = 3, 4
extrapolation, studies/membranes.py: 1.388054 vs 1.387631 ×4π), so the 1e-3 tolerance is 3x Evolver's own
error (measured: C2g0 tetra_3 1.387442, Loop 1.387749 ×4π, 4.4e-4 and 2.2e-4 off). Checked: limsurf converged, its area and volume residuals below 1e-8 relative, W within 1e-3 relative
of Evolver's, and the shape prolate and axisymmetric (shell inertia moments of the limit surface, from
--field-output: I2 = I3 within 1e-3, I1 < 0.6 I2), as is Evolver's (vertex cloud, within 1e-2).

Evolver is an optional peer: the test SKIPS when `evolver` is not on PATH. It FAILS when LIMSURF_CLI does not
name the limsurf binary (ctest sets it). About 50 s in the ci (RelWithDebInfo) build (Evolver ~10 s; the two limsurf solves,
at most 1000 Ipopt iterations each, side by side). v0 = 0.9 is left to the study (another minute).
"""

from __future__ import annotations

import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(REPO / "studies"))
import membranes  # noqa: E402  (studies/membranes.py: initial guesses, limit-surface inertia)

AREA = 4.0 * math.pi
EVOLVER = shutil.which("evolver")

pytestmark = pytest.mark.skipif(EVOLVER is None, reason="Surface Evolver (`evolver`, Debian package evolver-nox) "
                                                        "is not installed: the peer comparison is skipped")


@pytest.fixture(scope="module")
def cli() -> str:
    tool = os.environ.get("LIMSURF_CLI")
    if not tool or not os.access(tool, os.X_OK):
        pytest.fail("LIMSURF_CLI must name the limsurf binary (ctest sets it)")
    return tool


def evolver(v0: float, level: int) -> dict:
    r = subprocess.run([sys.executable, str(HERE / "evolver_canham.py"), "--reduced-volume", repr(v0), "--area",
                        repr(AREA), "--refine", str(level), "--initial", "prolate", "--tolerance", "1e-9",
                        "--evolver", EVOLVER], capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


V0 = 0.8
SCHEMES = [("c2g0", "tetra_3.obj"), ("loop", "icosphere_2")]


@pytest.fixture(scope="module")
def peer() -> dict:
    coarse, fine = evolver(V0, 2), evolver(V0, 3)
    for run in (coarse, fine):
        assert run["converged"]
        assert run["area"] == pytest.approx(AREA, rel=1e-9)
        assert run["reduced_volume"] == pytest.approx(V0, rel=1e-9)
        i1, i2, i3 = run["inertia_moments"]
        assert i3 - i2 < 1e-2 * i3 and i1 < 0.6 * i2, run["inertia_moments"]  # prolate, axisymmetric
    # O(h²): the finer level is closer, by a factor near 4 (measured 3.5 at v0 = 0.8, K = 2, 3, 4).
    assert fine["W"] < coarse["W"]
    extrapolated = (4.0 * fine["W"] - coarse["W"]) / 3.0
    assert 1.0 < extrapolated / (4.0 * math.pi) < 1.5  # above the sphere's 4π, below two spheres' 8π
    return {"W": extrapolated, "coarse": coarse, "fine": fine}


@pytest.fixture(scope="module")
def limsurf_runs(cli, tmp_path_factory) -> dict:
    """Both schemes' solves side by side (two cores: ~40 s)."""
    work = tmp_path_factory.mktemp("canham")

    def solve(scheme: str, mesh: str) -> dict:
        source = REPO / "data" / "meshes" / mesh if mesh.endswith(".obj") else \
            membranes.icosphere_obj(work / f"{mesh}.obj", 2)
        return membranes.run_limsurf(cli, work, scheme, mesh, source, V0, "prolate", max_iterations=1000)

    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {scheme: pool.submit(solve, scheme, mesh) for scheme, mesh in SCHEMES}
        return {scheme: f.result() for scheme, f in futures.items()}


@pytest.mark.parametrize("scheme", [s for s, _ in SCHEMES])
def test_limsurf_matches_evolver(limsurf_runs, peer, scheme):
    run = limsurf_runs[scheme]
    assert run["converged"], {k: run[k] for k in ("W_over_4pi", "iterations", "seconds")}
    assert abs(run["area_residual"]) < 1e-8 * AREA
    assert abs(run["volume_residual"]) < 1e-8 * V0 * AREA / 3.0
    assert run["W"] == pytest.approx(peer["W"], rel=1e-3), (run["W_over_4pi"], peer["W"] / (4.0 * math.pi))
    moments = [run["inertia_1"], run["inertia_2"], run["inertia_3"]]
    assert moments[2] - moments[1] < 1e-3 * moments[2], moments
    assert moments[0] < 0.6 * moments[1], moments
    assert membranes.shape_class(moments, 1e-3) == "prolate"
