"""The study scripts (studies/*.py) run with --quick: their files are valid and their numbers right.

Run by ctest (`studies.plots`, tests/studies/CMakeLists.txt) with LIMSURF_CLI naming the limsurf
binary; by hand:

  LIMSURF_CLI=build/release/cli/limsurf /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/studies

Each study is run once into a temporary directory; the tests check that the PNG and SVG exist and
parse (PNG signature, matplotlib reads a non-empty image of the fixed figure size; the SVG is XML
without a date), that the CSV has the documented columns and finite numbers, and that the physics
of the study holds on the quick numbers, so a wrong number fails a test, not only a missing file.
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
STUDIES = REPO / "studies"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

# Generous: sanitizer builds run the CLI 5-20x slower.
TIMEOUT_S = 600


def cli() -> str:
    path = os.environ.get("LIMSURF_CLI")
    if not path:
        pytest.fail("LIMSURF_CLI is not set: it must name the limsurf binary")
    if not os.access(path, os.X_OK):
        pytest.fail(f"LIMSURF_CLI={path} is not an executable")
    return path


def run_study(name: str, outdir: Path, *extra: str) -> str:
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    r = subprocess.run([sys.executable, str(STUDIES / f"{name}.py"), cli(), str(outdir), "--quick", *extra],
                       capture_output=True, text=True, timeout=TIMEOUT_S, env=env, check=False)
    assert r.returncode == 0, f"{name}.py --quick failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r.stdout


def study_outdir(tmp_path_factory, name: str, table_header: str) -> Path:
    """The study run once with --quick into a temporary directory; its printed table starts with table_header."""
    out = tmp_path_factory.mktemp(name)
    assert table_header in run_study(name, out)
    return out


def read_csv(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        return list(reader.fieldnames or []), rows


def num(row: dict[str, str], key: str) -> float:
    v = float(row[key])
    assert math.isfinite(v), f"{key} = {row[key]} is not finite"
    return v


def check_images(outdir: Path, name: str, size_px: tuple[int, int]) -> None:
    """NAME.png: PNG signature, readable by matplotlib, width x height = size_px; NAME.svg: XML."""
    import matplotlib.image

    png = outdir / f"{name}.png"
    svg = outdir / f"{name}.svg"
    assert png.is_file() and svg.is_file()
    assert png.read_bytes()[:8] == PNG_SIGNATURE
    img = matplotlib.image.imread(png)
    assert img.ndim == 3 and img.shape[0] > 0 and img.shape[1] > 0 and img.shape[2] in (3, 4)
    assert (img.shape[1], img.shape[0]) == size_px
    assert img.std() > 0.01, "the image is blank"
    root = ET.parse(svg).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert len(list(root.iter())) > 100, "the SVG holds almost nothing"
    text = svg.read_text(encoding="utf-8")
    assert "<dc:date>" not in text, "the SVG carries a date: reruns would differ"


def check_columns(path: Path, expected: list[str]) -> list[dict[str, str]]:
    columns, rows = read_csv(path)
    assert columns == expected
    assert rows
    return rows


# ---------------------------------------------------------------------------------------------
# SEC paper Fig. 3 (shape): quad_torus, f = sin x, reference DEC at level 4, n = 0..2

SEC_COLUMNS = ["mesh", "rhs", "n", "vertices", "faces", "series", "method", "level", "fine_level",
               "reference_level", "reference_vertices", "l2_relative", "linf_relative"]


@pytest.fixture(scope="module")
def sec_dir(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("sec_convergence")
    stdout = run_study("sec_convergence", out)
    assert "| n | vertices | faces |" in stdout
    return out


def test_sec_convergence_files(sec_dir):
    check_images(sec_dir, "sec_convergence", (650, 420))
    check_columns(sec_dir / "sec_convergence.csv", SEC_COLUMNS)


def test_sec_convergence_has_the_papers_shape(sec_dir):
    rows = check_columns(sec_dir / "sec_convergence.csv", SEC_COLUMNS)
    by = {(r["series"], int(r["n"])): r for r in rows}
    assert sorted(by) == [("dec", 0), ("dec", 1), ("dec", 2), ("sec_LKn", 0), ("sec_LKn", 1), ("sec_LKn", 2)]
    for r in rows:
        n = int(r["n"])
        # The control meshes are the torus's 48 quads subdivided n times; every solution is
        # compared with DEC on the same level-4 mesh (48 * 4^4 vertices).
        assert int(r["vertices"]) == 48 * 4**n
        assert int(r["reference_level"]) == 4 - n and int(r["reference_vertices"]) == 48 * 4**4
        assert r["mesh"] == "quad_torus.obj" and r["rhs"] == "sin(x)"
    dec = [num(by[("dec", n)], "l2_relative") for n in range(3)]
    sec = [num(by[("sec_LKn", n)], "l2_relative") for n in range(3)]
    # DEC is second order in h: the error falls ~4x per n (measured 2.10, 2.09).
    for a, b in zip(dec, dec[1:]):
        assert 1.7 < math.log2(a / b) < 2.5
    assert 0.1 < dec[0] < 0.2  # 0.151 (docs/VERIFICATION.md, quad_torus n = 0)
    # SEC pulling back the reference's inner products: far below DEC, and falling faster.
    assert all(s < d / 50 for s, d in zip(sec, dec))
    assert sec[0] > sec[1] > sec[2]
    assert math.log2(sec[1] / sec[2]) > 3.8  # measured 4.49 once asymptotic
    # The slopes written to the JSON (and the legend) are the least-squares fits of these numbers.
    summary = json.loads((sec_dir / "sec_convergence.json").read_text())
    series = summary["cases"]["quad_torus.obj"]["series"]
    assert -1.25 < series["dec"]["slope"] < -0.85
    assert series["sec_LKn"]["slope"] < -1.5
    vertices = [48, 192, 768]
    for key, err in (("dec", dec), ("sec_LKn", sec)):
        assert series[key]["l2_relative"] == err
        assert math.isclose(series[key]["slope"], _slope(vertices, err), rel_tol=1e-12)


def _slope(x, y):
    lx = [math.log(v) for v in x]
    ly = [math.log(v) for v in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


# ---------------------------------------------------------------------------------------------
# Exact volume against the polyhedra of levels 0..3

VOLUME_COLUMNS = ["scheme", "mesh", "level", "faces", "polyhedral_volume", "exact_volume", "difference",
                  "relative_difference", "factor", "richardson_volume", "richardson_relative"]


@pytest.fixture(scope="module")
def volume_dir(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("volume_levels")
    run_study("volume_levels", out)
    return out


def test_volume_levels_files(volume_dir):
    check_images(volume_dir, "volume_levels", (1000, 420))
    check_columns(volume_dir / "volume_levels.csv", VOLUME_COLUMNS)


def test_volume_levels_converge_at_rate_four(volume_dir):
    rows = check_columns(volume_dir / "volume_levels.csv", VOLUME_COLUMNS)
    cases = {}
    for r in rows:
        cases.setdefault((r["scheme"], r["mesh"]), []).append(r)
    assert {s for s, _ in cases} == {"catmull-clark", "loop", "doo-sabin"}
    for (scheme, mesh), rs in cases.items():
        assert [int(r["level"]) for r in rs] == [0, 1, 2, 3]
        exact = num(rs[0], "exact_volume")
        assert exact > 0 and all(num(r, "exact_volume") == exact for r in rs)
        # The numbers are consistent: difference = polyhedral - exact, relative to the exact.
        for r in rs:
            diff = num(r, "polyhedral_volume") - exact
            assert math.isclose(num(r, "difference"), diff, rel_tol=1e-9, abs_tol=1e-15)
            assert math.isclose(num(r, "relative_difference"), diff / exact, rel_tol=1e-9, abs_tol=1e-15)
        # Faces: x4 per level for Catmull-Clark and Loop; Doo-Sabin adds a face per vertex and edge.
        faces = [int(r["faces"]) for r in rs]
        if scheme != "doo-sabin":
            assert faces == [faces[0] * 4**lv for lv in range(4)]
        else:
            assert faces[0] < faces[1] < faces[2] < faces[3]
        # The polyhedra converge to the exact volume: more than 2x closer every level, and at the
        # O(h^2) rate (factor -> 4) by level 3.
        rel = [abs(num(r, "relative_difference")) for r in rs]
        for lv in range(1, 4):
            assert rel[lv - 1] / rel[lv] > 2.0, f"{scheme} {mesh} level {lv}"
            assert math.isclose(num(rs[lv], "factor"), rel[lv - 1] / rel[lv], rel_tol=1e-12)
        assert 3.5 < rel[2] / rel[3] < 4.6, f"{scheme} {mesh}"
        # Richardson extrapolation of the polyhedra lands much closer to the exact volume.
        assert num(rs[3], "richardson_relative") < rel[3] / 10  # 15x (Doo-Sabin cube) to 500x
    # The published Doo-Sabin unit cube: 6241/9920 (docs/VERIFICATION.md, Exact volume); the
    # level-0 polyhedron is the unit cube itself.
    cube = cases[("doo-sabin", "cube.obj")]
    assert abs(num(cube[0], "exact_volume") - 6241 / 9920) < 1e-14
    assert num(cube[0], "polyhedral_volume") == pytest.approx(1.0, abs=1e-14)
    assert num(cases[("catmull-clark", "cube.obj")][0], "polyhedral_volume") == pytest.approx(1.0, abs=1e-14)
    summary = json.loads((volume_dir / "volume_levels.json").read_text())
    assert summary["levels"] == 3 and len(summary["cases"]) == len(cases)


def test_volume_levels_rerun_writes_identical_files(volume_dir, tmp_path):
    run_study("volume_levels", tmp_path)
    for name in ("volume_levels.csv", "volume_levels.json", "volume_levels.png", "volume_levels.svg"):
        assert (tmp_path / name).read_bytes() == (volume_dir / name).read_bytes(), name


# ---------------------------------------------------------------------------------------------
# Kirchhoff-Love plate against Navier, levels 0..2 on quad_grid and plate_ev35

PLATE_COLUMNS = ["mesh", "level", "vertices", "faces", "centre_deflection", "navier_centre_deflection",
                 "max_deflection", "quarter_deflection", "navier_quarter_deflection", "l2_relative_error",
                 "energy_relative_error", "centre_relative_error", "quarter_relative_error"]


@pytest.fixture(scope="module")
def plate_dir(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("plate_errors")
    run_study("plate_errors", out)
    return out


def test_plate_errors_files(plate_dir):
    check_images(plate_dir, "plate_errors", (1350, 430))
    check_columns(plate_dir / "plate_errors.csv", PLATE_COLUMNS)


def test_plate_errors_converge_to_navier(plate_dir):
    rows = check_columns(plate_dir / "plate_errors.csv", PLATE_COLUMNS)
    grid = [r for r in rows if r["mesh"] == "quad_grid.obj"]
    ev35 = [r for r in rows if r["mesh"] == "plate_ev35.obj"]
    assert len(grid) == 3 and len(ev35) == 3 and len(rows) == 6
    # The 4x4 grid refined l times has (4 * 2^l + 1)^2 control vertices.
    assert [int(r["vertices"]) for r in grid] == [25, 81, 289]
    # Navier's series for the uniformly loaded square: w(centre) = 0.00406 p a^4 / D (Timoshenko,
    # Table 8); quad_grid is a = 2 with p = 1e4, t = 0.1, E = 2e11, nu = 0.3.
    d = 2e11 * 0.1**3 / (12 * (1 - 0.3**2))
    navier = num(grid[0], "navier_centre_deflection")
    assert navier == pytest.approx(0.00406235 * 1e4 * 2**4 / d, rel=1e-5)
    for r in grid:
        w = num(r, "centre_deflection")
        assert math.isclose(num(r, "centre_relative_error"), (w - navier) / navier, rel_tol=1e-6, abs_tol=1e-15)
    # Regular grid: L2 and centre errors fall > 10x per level (order ~4), energy > 3x (order ~2).
    for a, b in zip(grid, grid[1:]):
        assert num(a, "l2_relative_error") / num(b, "l2_relative_error") > 10
        assert abs(num(a, "centre_relative_error")) / abs(num(b, "centre_relative_error")) > 10
        assert num(a, "energy_relative_error") / num(b, "energy_relative_error") > 3
    assert num(grid[-1], "l2_relative_error") < 1e-4
    # Unstructured (valences 3 and 5): slower, but the L2 and energy errors fall every level.
    for a, b in zip(ev35, ev35[1:]):
        assert num(a, "l2_relative_error") / num(b, "l2_relative_error") > 1.5
        assert num(a, "energy_relative_error") > num(b, "energy_relative_error")
    summary = json.loads((plate_dir / "plate_errors.json").read_text())
    g = summary["cases"]["quad_grid.obj"]
    assert g["l2_relative_error"]["slope"] < -1.8  # measured -2.35 over levels 1..2
    assert -1.5 < g["energy_relative_error"]["slope"] < -0.8  # measured -1.20
