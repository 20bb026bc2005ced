#!/usr/bin/python3
"""The Canham problem min W = ∫H² dA s.t. A = A0, V = V0 solved by Surface Evolver: the independent peer.

Test-only driver (tests/membrane/evolver_peer_test.py, studies/membranes.py). It writes an Evolver datafile
for the level-K icosphere (10·4^K + 2 vertices) stretched along z into a prolate or oblate spheroid whose
discrete reduced volume is v0 and area A0, runs Evolver 2.70 on it and prints one JSON line.

The datafile: facet tension 0 (no surface-tension energy); the energy is the `star_perp_sq_mean_curvature`
method, ∫h² dA with h = (k1 + k2)/2 — the same normalisation as limsurf's W (4π on a round sphere;
--evaluate-sphere measures it on the unit icosphere: 12.7276, 12.6069, 12.5766, 12.5689 at K = 2..5, the
difference to 4π = 12.5664 falling 4x per level; h = k1 + k2 would give 16π); the area is a fixed global
`facet_area` quantity and the volume a body volume, both hard constraints Evolver projects onto after
every step. The script: conjugate gradients with the motion projected on the normal (`normal_motion`;
without it the discrete energy has tangential vertex-bunching directions and Evolver slides below the
continuum minimum, 1.3697·4π instead of 1.391·4π at K = 3, v0 = 0.8), equiangulation `u` and vertex
averaging `V` while the shape is far away, then blocks of `g 20; hessian_seek` until one block changes W by
less than --tolerance relative. Evolver's discretisation error is O(h²): compare K, K + 1 (the study
extrapolates).

  tests/membrane/evolver_canham.py --reduced-volume 0.8 --area 12.566370614359172 --refine 3 \\
      --initial prolate [--time]
  tests/membrane/evolver_canham.py --evaluate-sphere --refine 4

JSON: W, W_over_4pi, area, volume, reduced_volume, vertices, unknowns (3 × vertices), blocks, converged,
seconds (Evolver's `clock`, its CPU time; --time adds the trace of (seconds, W) per block) and the principal
inertia moments of the vertex cloud (prolate and axisymmetric: I1 < I2 ≈ I3).
Exit 2 when Evolver is missing, 1 when it fails.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

Vec = tuple[float, float, float]

_ICOSAHEDRON_FACES = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
                      (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
                      (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]


def _unit(p) -> Vec:
    n = math.sqrt(sum(c * c for c in p))
    return (p[0] / n, p[1] / n, p[2] / n)


def icosphere(level: int) -> tuple[list[Vec], list[tuple[int, int, int]]]:
    """The icosahedron split `level` times at edge midpoints projected onto the unit sphere; outward faces."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    points = [_unit(p) for p in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                                 (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    faces = list(_ICOSAHEDRON_FACES)
    for _ in range(level):
        midpoint: dict[tuple[int, int], int] = {}

        def mid(a: int, b: int) -> int:
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                points.append(_unit([(points[a][i] + points[b][i]) / 2.0 for i in range(3)]))
                midpoint[key] = len(points) - 1
            return midpoint[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return points, faces


def area_volume(points: list[Vec], faces) -> tuple[float, float]:
    """Area and enclosed volume of the closed, outward-oriented triangle mesh."""
    area = volume = 0.0
    for a, b, c in faces:
        p, q, r = points[a], points[b], points[c]
        u = [q[i] - p[i] for i in range(3)]
        w = [r[i] - p[i] for i in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        area += 0.5 * math.sqrt(sum(x * x for x in n))
        volume += sum(p[i] * n[i] for i in range(3)) / 6.0
    return area, volume


def reduced_volume(area: float, volume: float) -> float:
    return volume / (4.0 * math.pi / 3.0 * (area / (4.0 * math.pi)) ** 1.5)


def spheroid(level: int, v0: float, initial: str, area0: float) -> tuple[list[Vec], list]:
    """The icosphere stretched along z (prolate: factor > 1, oblate: < 1) to discrete reduced volume v0,
    then scaled to area area0. Raises ValueError when v0 is out of reach (above the icosphere's own)."""
    points, faces = icosphere(level)

    def stretched(s: float) -> list[Vec]:
        return [(x, y, z * s) for x, y, z in points]

    lo, hi = (1.0, 20.0) if initial == "prolate" else (0.02, 1.0)
    if not reduced_volume(*area_volume(stretched(lo if initial == "prolate" else hi), faces)) > v0:
        raise ValueError(f"reduced volume {v0} is above the level-{level} icosphere's")
    for _ in range(80):  # bisection: the reduced volume is monotone in the stretch on either side of 1
        s = 0.5 * (lo + hi)
        above = reduced_volume(*area_volume(stretched(s), faces)) > v0
        if (initial == "prolate") == above:
            lo = s
        else:
            hi = s
    shape = stretched(0.5 * (lo + hi))
    k = math.sqrt(area0 / area_volume(shape, faces)[0])
    return [(k * x, k * y, k * z) for x, y, z in shape], faces


def obj_mesh(path: Path, area0: float) -> tuple[list[Vec], list]:
    """The vertices and triangles of an OBJ file, scaled about the vertex centroid to area area0."""
    points, faces = [], []
    for line in path.read_text().splitlines():
        fields = line.split()
        if fields and fields[0] == "v":
            points.append(tuple(float(t) for t in fields[1:4]))
        elif fields and fields[0] == "f":
            corners = [int(t.split("/")[0]) - 1 for t in fields[1:]]
            if len(corners) != 3:
                raise ValueError(f"{path}: only triangles, got a face of {len(corners)} corners")
            faces.append(tuple(corners))
    centre = [sum(p[k] for p in points) / len(points) for k in range(3)]
    points = [tuple(p[k] - centre[k] for k in range(3)) for p in points]
    k = math.sqrt(area0 / area_volume(points, faces)[0])
    return [(k * x, k * y, k * z) for x, y, z in points], faces


def datafile(points: list[Vec], faces, area0: float | None, volume0: float | None) -> str:
    """Evolver's vertices/edges/faces/bodies; hard constraints only for the targets given."""
    lines = ["// The Canham problem: written by tests/membrane/evolver_canham.py",
             "quantity willmore energy method star_perp_sq_mean_curvature global"]
    if area0 is not None:
        lines.append(f"quantity area_c fixed = {area0!r} method facet_area global")
    lines += ["", "vertices"]
    lines += [f"{i + 1} {x!r} {y!r} {z!r}" for i, (x, y, z) in enumerate(points)]
    lines += ["", "edges"]
    edges: dict[tuple[int, int], int] = {}
    for a, b, c in faces:
        for p, q in ((a, b), (b, c), (c, a)):
            key = (min(p, q), max(p, q))
            if key not in edges:
                edges[key] = len(edges) + 1
                lines.append(f"{edges[key]} {key[0] + 1} {key[1] + 1}")
    lines += ["", "faces"]
    for i, (a, b, c) in enumerate(faces):
        signed = [edges[(p, q)] if p < q else -edges[(q, p)] for p, q in ((a, b), (b, c), (c, a))]
        lines.append(f"{i + 1} {signed[0]} {signed[1]} {signed[2]} tension 0")
    lines += ["", "bodies", "1 " + " ".join(str(i + 1) for i in range(len(faces)))
              + (f" volume {volume0!r}" if volume0 is not None else "")]
    return "\n".join(lines) + "\n"


_REPORT = ('report := {printf "REPORT %.17g %.17g %.17g %d %.6f %d\\n", willmore.value, total_area, '
           'body[1].volume, vertex_count, clock, nblk}')


def script(tolerance: float, max_blocks: int, trace: bool) -> str:
    """Evolver commands: mesh relaxation, then gradient + Hessian-seek blocks to a stationary W; the
    vertices last (for the inertia moments)."""
    per_block = "; report" if trace else ""
    return "\n".join([
        "nblk := 0", "oldw := 0", _REPORT, "quiet on", "normal_motion on", "U",
        "{ g 50; u; V } 6", "g 100", "report",
        f"while (abs(oldw - willmore.value) > {tolerance!r} * willmore.value and nblk < {max_blocks}) do "
        f"{{ oldw := willmore.value; g 20; hessian_seek; nblk += 1{per_block} }}",
        "report",
        'foreach vertex vv do printf "VERTEX %.17g %.17g %.17g\\n", vv.x, vv.y, vv.z',
        'printf "DONE\\n"', "quit", ""])


def inertia_moments(points: list[Vec]) -> list[float]:
    """Principal moments of the vertex cloud about its centroid (ascending): axisymmetry = two equal."""
    import numpy as np
    x = np.asarray(points)
    x = x - x.mean(axis=0)
    tensor = np.eye(3) * (x * x).sum() - x.T @ x
    return sorted(float(m) for m in np.linalg.eigvalsh(tensor / len(x)))


def run_evolver(evolver: str, fe: str, commands: str, timeout: float) -> str:
    with tempfile.TemporaryDirectory(prefix="evolver_canham_") as tmp:
        (Path(tmp) / "shape.fe").write_text(fe)
        (Path(tmp) / "run.cmd").write_text(commands)
        # EVOLVERPATH ends in ':::' so that no system example folder is searched.
        env = dict(os.environ, EVOLVERPATH=":::")
        r = subprocess.run([evolver, "-x", "-f", "run.cmd", "shape.fe"], cwd=tmp, capture_output=True,
                           text=True, timeout=timeout, env=env, stdin=subprocess.DEVNULL, check=False)
    if "DONE" not in r.stdout:
        tail = "\n".join((r.stdout + r.stderr).splitlines()[-15:])
        raise RuntimeError(f"evolver failed (exit {r.returncode}):\n{tail}")
    return r.stdout


def parse(stdout: str) -> tuple[list[tuple[float, float, float, int, float, int]], list[Vec]]:
    reports = [(float(m[1]), float(m[2]), float(m[3]), int(m[4]), float(m[5]), int(m[6]))
               for m in re.finditer(r"^REPORT (\S+) (\S+) (\S+) (\d+) (\S+) (\d+)$", stdout, re.M)]
    vertices = [(float(m[1]), float(m[2]), float(m[3]))
                for m in re.finditer(r"^VERTEX (\S+) (\S+) (\S+)$", stdout, re.M)]
    return reports, vertices


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--reduced-volume", type=float, help="v0 in (0, 1)")
    p.add_argument("--area", type=float, default=4.0 * math.pi, help="A0 (default 4π)")
    p.add_argument("--refine", type=int, default=3, help="icosphere level K: 10·4^K + 2 vertices (default 3)")
    p.add_argument("--initial", choices=("prolate", "oblate"), default="prolate")
    p.add_argument("--initial-mesh", default=None,
                   help="start from this closed triangle mesh (OBJ, e.g. a limsurf shape subdivided) instead of a "
                        "spheroid: scaled to area A0 about its centroid; --refine and --initial are then unused")
    p.add_argument("--tolerance", type=float, default=1e-10, help="stop when a block changes W less (relative)")
    p.add_argument("--max-blocks", type=int, default=400)
    p.add_argument("--time", action="store_true", help="add the (seconds, W) trace of every block")
    p.add_argument("--evaluate-sphere", action="store_true",
                   help="only W, A, V of the unit icosphere of level K (the normalisation check)")
    p.add_argument("--evolver", default=shutil.which("evolver"), help="the Evolver binary (default: on PATH)")
    p.add_argument("--timeout", type=float, default=1800.0)
    args = p.parse_args(argv)
    if not args.evolver:
        print("evolver_canham: Surface Evolver (`evolver`) is not installed", file=sys.stderr)
        return 2
    if not 0 <= args.refine <= 6:
        p.error("--refine must be in 0..6")
    start = time.monotonic()
    if args.evaluate_sphere:
        points, faces = icosphere(args.refine)
        fe = datafile(points, faces, None, None)
        commands = "\n".join(["nblk := 0", _REPORT, "report", 'printf "DONE\\n"', "quit", ""])
    else:
        if args.reduced_volume is None or not 0.0 < args.reduced_volume < 1.0 or args.area <= 0.0:
            p.error("--reduced-volume must be in (0, 1) and --area positive")
        volume0 = args.reduced_volume * 4.0 * math.pi / 3.0 * (args.area / (4.0 * math.pi)) ** 1.5
        if args.initial_mesh:
            points, faces = obj_mesh(Path(args.initial_mesh), args.area)
        else:
            points, faces = spheroid(args.refine, args.reduced_volume, args.initial, args.area)
        fe = datafile(points, faces, args.area, volume0)
        commands = script(args.tolerance, args.max_blocks, args.time)
    try:
        stdout = run_evolver(args.evolver, fe, commands, args.timeout)
    except (RuntimeError, subprocess.TimeoutExpired) as e:
        print(f"evolver_canham: {e}", file=sys.stderr)
        return 1
    reports, vertices = parse(stdout)
    w, area, volume, nv, seconds, blocks = reports[-1]
    out = {"W": w, "W_over_4pi": w / (4.0 * math.pi), "area": area, "volume": volume,
           "reduced_volume": reduced_volume(area, volume), "vertices": nv, "unknowns": 3 * nv,
           "refine": args.refine, "blocks": blocks, "seconds": seconds,
           "wall_seconds": time.monotonic() - start}
    if not args.evaluate_sphere:
        out.update({"initial": args.initial_mesh or args.initial, "target_reduced_volume": args.reduced_volume,
                    "target_area": args.area, "converged": blocks < args.max_blocks,
                    "inertia_moments": inertia_moments(vertices)})
        if args.time:
            out["trace"] = [[r[4], r[0]] for r in reports]
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
