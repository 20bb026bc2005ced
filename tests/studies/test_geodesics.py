"""studies/geodesics.py --quick: its files are valid and the physics of SEC §4.2 holds on the quick numbers.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary; by hand:

  LIMSURF_CLI=build/release/cli/limsurf /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/studies

Checked: geodesics.{csv,json,png,svg} exist and parse (PNG signature, SVG is XML), the CSV has the documented
columns and finite errors; against the heat method with DEC on the 3-times subdivided mesh, SEC l = 3 reduces
the L2 error at least 2x against DEC on both meshes (the paper: 2.3-2.5x; measured 7.2x on genus2, 2.8x on
tri_torus); SEC converges in L to a small error (L = 1 already far below DEC); t = h_mean² on every row.
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
STUDY = REPO / "studies" / "geodesics.py"
COLUMNS = ["study", "mesh", "scheme", "method", "level", "gradient", "time_factor", "t", "reference_level",
           "l2_relative", "linf_relative", "setup_seconds", "factorisation_seconds", "solve_seconds"]


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    tool = os.environ.get("LIMSURF_CLI")
    if not tool or not os.access(tool, os.X_OK):
        pytest.fail("LIMSURF_CLI must name the limsurf binary")
    out = tmp_path_factory.mktemp("geodesics")
    r = subprocess.run([sys.executable, str(STUDY), tool, str(out), "--quick"], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    assert "| mesh | t | dec L2 |" in r.stdout
    return out


def rows(outdir: Path) -> list[dict[str, str]]:
    with open(outdir / "geodesics.csv", newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == COLUMNS
        return list(reader)


def test_files(outdir):
    assert (outdir / "geodesics.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    ET.parse(outdir / "geodesics.svg")
    data = json.loads((outdir / "geodesics.json").read_text())
    assert data["reference_level"] == 3
    for r in rows(outdir):
        assert math.isfinite(float(r["l2_relative"])) and math.isfinite(float(r["linf_relative"]))


def test_sec_beats_dec_against_the_reference(outdir):
    table = rows(outdir)
    for mesh in ("genus2.obj", "tri_torus.obj"):
        mine = {(r["method"], int(r["level"])): r for r in table if r["mesh"] == mesh}
        dec = float(mine[("dec", 0)]["l2_relative"])
        sec = [float(mine[("sec", level)]["l2_relative"]) for level in (1, 2, 3)]
        assert dec > 2.0 * sec[2], (mesh, dec, sec)
        assert sec[0] < 0.5 * dec, (mesh, dec, sec)
        assert float(mine[("sec", 3)]["linf_relative"]) < float(mine[("dec", 0)]["linf_relative"])


def test_time_step_is_the_mean_edge_length_squared(outdir):
    # genus2: every edge has length 0.5 (a voxel surface scaled 0.5), so t = 0.25 exactly.
    for r in rows(outdir):
        if r["mesh"] == "genus2.obj":
            assert float(r["t"]) == 0.25 * float(r["time_factor"])
