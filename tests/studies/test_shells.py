"""studies/shells.py --quick: its files are valid and the shell obstacle course reaches its published values.

Run by ctest (`studies.plots`) with LIMSURF_CLI naming the limsurf binary (test_studies.py says how
by hand). --quick is levels 0..2. Checked: shells.{csv,json,png,svg} exist and parse; the control
meshes grow as a refinement of each bundled grid does; the supports leave the rigid motions the
problems have (the roof and the cylinder slide along their axis, the free hemisphere keeps all six);
at level 2 the displacements are the published ones — Scordelis-Lo 0.3006 within 0.5 %, the pinched
cylinder 1.8248e-5 within 3 % (approached from below, every level closer), the pinched hemisphere
between MacNeal and Harder's 0.0924 and the thin-shell 0.0940 (1 % either side); the change per
level shrinks.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_studies import check_columns, check_images, num, study_outdir  # noqa: E402

COLUMNS = ["problem", "level", "vertices", "faces", "unknowns", "rigid_motions_removed", "strain_energy",
           "displacement", "reference", "ratio", "relative_error", "change"]


@pytest.fixture(scope="module")
def outdir(tmp_path_factory) -> Path:
    return study_outdir(tmp_path_factory, "shells", "| problem | level | control vertices |")


@pytest.fixture(scope="module")
def by_problem(outdir):
    rows = check_columns(outdir / "shells.csv", COLUMNS)
    out = {}
    for r in rows:
        out.setdefault(r["problem"], []).append(r)
    return out


def test_shells_files(outdir):
    check_images(outdir, "shells", (1100, 440))


def test_meshes_and_rigid_motions(by_problem):
    assert sorted(by_problem) == ["pinched_cylinder", "pinched_hemisphere", "scordelis_lo"]
    # The roof: a 9 x 9 grid of control points; the cylinder: 16 around, 9 along; the hemisphere 16 x 9.
    sizes = {"scordelis_lo": lambda L: (8 * 2**L + 1) ** 2, "pinched_cylinder": lambda L: 16 * 2**L * (8 * 2**L + 1),
             "pinched_hemisphere": lambda L: 16 * 2**L * (8 * 2**L + 1)}
    motions = {"scordelis_lo": 1, "pinched_cylinder": 1, "pinched_hemisphere": 6}
    for name, rows in by_problem.items():
        assert [int(r["level"]) for r in rows] == [0, 1, 2]
        for r in rows:
            assert int(r["vertices"]) == sizes[name](int(r["level"])), name
            assert int(r["unknowns"]) == 3 * int(r["vertices"])
            assert int(r["rigid_motions_removed"]) == motions[name]
            assert num(r, "strain_energy") > 0


def test_the_published_displacements(outdir, by_problem):
    roof = [num(r, "displacement") for r in by_problem["scordelis_lo"]]
    assert roof[2] == pytest.approx(0.3006, rel=5e-3)
    cylinder = [num(r, "displacement") for r in by_problem["pinched_cylinder"]]
    assert cylinder[2] == pytest.approx(1.8248e-5, rel=3e-2)
    assert cylinder[0] < cylinder[1] < cylinder[2] < 1.8248e-5
    hemisphere = num(by_problem["pinched_hemisphere"][2], "displacement")
    assert 0.99 * 0.0924 < hemisphere < 1.01 * 0.0940
    for rows in by_problem.values():
        changes = [num(r, "change") for r in rows[1:]]
        assert changes[1] < changes[0]
        for r in rows:
            assert num(r, "ratio") == pytest.approx(num(r, "displacement") / num(r, "reference"), rel=1e-12)
    summary = json.loads((outdir / "shells.json").read_text())
    assert summary["levels"] == 2
    assert summary["problems"]["scordelis_lo"]["finest_displacement"] == roof[2]
