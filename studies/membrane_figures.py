#!/usr/bin/python3
"""Biomembrane shapes of c2g0-sphere-scheme-biomembranes §3: the stomatocyte, Fig. 7, Figs. 11-13.

All runs are `limsurf membrane --json` with the C2g0 scheme on the paper's F_tetra,j (data/meshes/tetra_j.obj),
A0 = 4π, and Loop on the same control meshes where the paper compares the two:

- branches at v0 = 0.5 (Canham): the prolate, oblate and stomatocyte branches from a prolate spheroid, an
  oblate spheroid and an invaginated sphere (the stomatocyte initial guess below). Seifert, Berndl & Lipowsky
  (1991) place the stomatocyte lowest below v ≈ 0.59.
- Fig. 7 (Canham, v0 = 0.18, F_tetra,3, 130 vertices): C2g0 and Loop from the same invaginated guess, and
  whether each limit surface passes through itself (`self_intersection`, apps/self_intersection.h). The paper:
  the Loop surface intersects itself, the C2g0 one does not.
- Fig. 11 (Helfrich, v0 = 0.5, m0 = 1.05, F_tetra,3) from five initial guesses: the round tetra_3, three copies
  of it with every control point moved by a Gaussian of σ = 0.05 and rotated at random (seeds 1-3), and the
  prolate spheroid of reduced volume 0.8. The round and perturbed starts (v ≈ 1) reach v0 and m0 in
  FIG11_CONTINUATION continuation steps (`--continuation`), the prolate ones at once. The paper: Willmore
  energies agreeing in the first 4 significant digits. Agreement is measured over the runs that converged to
  an embedded surface; a start that ends passing through itself is reported, not counted.
- Fig. 12: the regularisation (3.12) with ε = 0.003 after the round start's solve: the harmonic energy E
  falls "substantially" while W rises by at most ε (the paper's absolute ε, docs/membrane.md).
- Fig. 13 (Helfrich, v0 = 0.4, m0 = 1.8, F_tetra,4, 514 vertices, then (3.12) with ε = 0.08): solved on
  F_tetra,3 from a prolate spheroid first, its control mesh refined once by C2g0 (the same limit surface on
  F_tetra,4's connectivity) as the F_tetra,4 initial guess.

The stomatocyte initial guess maps each control point of the unit-sphere mesh, by its polar angle, to a profile
curve of the same arc-length fraction: the outer sphere from its south pole to 20° short of its north pole, a
half-turn neck of radius 0.08, and an inner sphere of radius r down to its south pole (r = 0.84 at v0 = 0.18,
0.7 at v0 = 0.5), rotated about the z axis. Writes membrane_figures.csv (one row per run), .json (the
comparisons), .png/.svg (cross-sections of the limit surfaces through their centroid, plane y = const); the
shapes and their limit tessellations (VTK, mean and Gaussian curvature) go to OUTDIR/shapes.

  /usr/bin/python3 studies/membrane_figures.py build/release/cli/limsurf out/studies      # ~16 min on 2 cores

Surface Evolver (when installed) solves the stomatocyte of v0 = 0.5 and the oblate shape of v0 = 0.6 from
limsurf's shapes (run_evolver_from: the control mesh refined 1, 2 and 3 times by C2g0, 514, 2050 and 8194
vertices, Richardson-extrapolated); cached in OUTDIR/evolver, about 12 minutes.

--quick (the test): F_tetra,2 (34 vertices): Fig. 11 from three guesses and Fig. 12, at most 2000 iterations per stage; ~25 s.
"""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import membranes as mb
import studylib as sl

EVOLVER_TOLERANCE = 1e-9
EVOLVER_BLOCKS = 100
FIG11_CONTINUATION = 5  # steps of 0.1 in v from the round and perturbed starts

NAME = "membrane_figures"
AREA = 4.0 * math.pi
COLUMNS = ["study", "case", "scheme", "mesh", "vertices", "initial", "reduced_volume", "reduced_mean_curvature",
           "epsilon", "W", "W_over_4pi", "harmonic", "reduced_volume_reached", "reduced_mean_curvature_reached",
           "regularized_W", "regularized_harmonic", "self_intersecting", "intersecting_pairs",
           "intersection_resolution", "converged", "iterations", "seconds", "continuation_steps"]


# ---------------------------------------------------------------------------------------------
# Initial guesses

def stomatocyte_profile(inner_radius: float, neck: float = 0.08, gap_degrees: float = 20.0, n: int = 4000):
    """The (ρ, z) polyline of the invaginated profile and its cumulative arc length (see the module doc)."""
    beta = math.radians(gap_degrees)
    pts = [(math.sin(t), -math.cos(t)) for t in np.linspace(0.0, math.pi - beta, n, endpoint=False)]
    top = (math.sin(math.pi - beta), -math.cos(math.pi - beta))
    centre = (top[0] - neck, top[1])
    pts += [(centre[0] + neck * math.cos(t), centre[1] + neck * math.sin(t))
            for t in np.linspace(0.0, math.pi, n, endpoint=False)]
    start = (top[0] - 2.0 * neck, top[1])  # where the inner sphere begins, on it
    z_centre = start[1] - math.sqrt(max(inner_radius ** 2 - start[0] ** 2, 0.0))
    t0 = math.atan2(start[0], start[1] - z_centre)
    pts += [(inner_radius * math.sin(t), z_centre + inner_radius * math.cos(t))
            for t in np.linspace(t0, math.pi, n + 1)]
    pts = np.array(pts)
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    return pts, arc


def stomatocyte_obj(source: Path, out: Path, inner_radius: float) -> Path:
    points, rest = mb.read_obj(source)
    profile, arc = stomatocyte_profile(inner_radius)
    moved = []
    for x, y, z in points:
        theta = math.acos(max(-1.0, min(1.0, -z / math.sqrt(x * x + y * y + z * z))))  # 0 at the south pole
        s = theta / math.pi * arc[-1]
        rho, height = np.interp(s, arc, profile[:, 0]), np.interp(s, arc, profile[:, 1])
        phi = math.atan2(y, x)
        moved.append((rho * math.cos(phi), rho * math.sin(phi), height))
    return mb.write_obj(out, moved, rest)


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    q = q @ np.diag(np.sign(np.diag(r)))
    return q if np.linalg.det(q) > 0 else -q


def perturbed_obj(source: Path, out: Path, seed: int, amplitude: float = 0.05) -> Path:
    """The mesh with every control point moved by a Gaussian of σ = amplitude, then rotated at random."""
    points, rest = mb.read_obj(source)
    rng = np.random.default_rng(seed)
    p = np.array(points)
    p = (p + amplitude * rng.standard_normal(p.shape)) @ random_rotation(rng).T
    return mb.write_obj(out, [tuple(map(float, row)) for row in p], rest)


def initial_guess(work: Path, mesh: str, initial: str, v0: float) -> Path:
    source = Path(sl.mesh(f"{mesh}.obj"))
    out = work / "initial" / f"{mesh}_{initial}_v{v0}.obj"
    if initial == "round":
        return source
    if initial in ("prolate", "oblate"):
        return mb.stretched_obj(source, out, v0, initial)
    if initial.startswith("prolate"):  # prolateV: the prolate spheroid of reduced volume V
        return mb.stretched_obj(source, out, float(initial[len("prolate"):]), "prolate")
    if initial == "stomatocyte":
        return stomatocyte_obj(source, out, 0.84 if v0 < 0.3 else 0.7)
    if initial.startswith("perturbed"):
        return perturbed_obj(source, out, seed=int(initial[len("perturbed"):]))
    raise ValueError(initial)


# ---------------------------------------------------------------------------------------------
# Runs

def run_membrane(cli: str, work: Path, case: str, scheme: str, mesh: str, start: Path, initial: str, v0: float,
                 m0: float | None = None, epsilon: float | None = None, max_iterations: int = 4000,
                 continuation: int = 1) -> dict:
    tag = f"{case}_{scheme}_{mesh}_{initial}"
    obj, vtk = work / "shapes" / f"{tag}.obj", work / "shapes" / f"{tag}.vtk"
    cmd = [cli, "membrane", str(start), "--scheme", scheme, "--area", repr(AREA), "--reduced-volume", repr(v0),
           "--max-iterations", str(max_iterations), "-o", str(obj), "--field-output", str(vtk), "--resolution", "12",
           "--json"]
    if m0 is not None:
        cmd += ["--reduced-mean-curvature", repr(m0)]
    if epsilon is not None:
        cmd += ["--regularize-harmonic", repr(epsilon)]
    if continuation > 1:
        cmd += ["--continuation", str(continuation)]
    # A finished run is kept next to its shape with its command line and reused by a rerun of the same
    # command (the full study takes a while; delete OUTDIR/shapes to start afresh).
    cache = work / "shapes" / f"{tag}.json"
    wall = time.monotonic()
    if cache.is_file() and json.loads(cache.read_text()).get("command") == cmd and obj.is_file() and vtk.is_file():
        out = json.loads(cache.read_text())["result"]
    else:
        r = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if r.returncode != 0:
            raise sl.CliError(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stderr.strip()}")
        out = json.loads(r.stdout)
        cache.write_text(json.dumps({"command": cmd, "result": out}))
    reg = out["regularization"]
    si = out["self_intersection"]
    sl.log(f"{tag}: W/4π {out['willmore'] / AREA:.6f}, converged {out['converged']}, "
           f"self-intersecting {si['intersects']} ({time.monotonic() - wall:.0f} s)")
    return {"study": NAME, "case": case, "scheme": scheme, "mesh": mesh, "vertices": out["vertices"],
            "initial": initial, "reduced_volume": v0, "reduced_mean_curvature": m0, "epsilon": epsilon,
            "W": out["willmore"], "W_over_4pi": out["willmore"] / AREA, "harmonic": out["harmonic"],
            "reduced_volume_reached": out["reduced_volume"],
            "reduced_mean_curvature_reached": out["reduced_mean_curvature"],
            "regularized_W": reg["willmore"] if reg else None, "regularized_harmonic": reg["harmonic"] if reg else None,
            "self_intersecting": si["intersects"], "intersecting_pairs": si["intersecting_pairs"],
            "intersection_resolution": si["resolution"],
            "converged": bool(out["converged"]) and (reg is None or bool(reg["converged"])),
            "iterations": out["iterations"] + (reg["iterations"] if reg else 0)
            + sum(step["iterations"] for step in out["continuation"]),
            "seconds": out["seconds"] + (reg["seconds"] if reg else 0.0)
            + sum(step["seconds"] for step in out["continuation"]),
            "continuation_steps": continuation, "obj": str(obj), "vtk": str(vtk)}


def fig13_start(cli: str, work: Path, v0: float, m0: float, max_iterations: int) -> tuple[dict, Path]:
    """The Fig. 13 problem on F_tetra,3 from a prolate spheroid, refined once by C2g0 onto F_tetra,4."""
    coarse = run_membrane(cli, work, "fig13_coarse", "c2g0", "tetra_3", initial_guess(work, "tetra_3", "prolate", v0),
                          "prolate", v0, m0, max_iterations=max_iterations)
    fine = work / "initial" / "tetra_4_from_tetra_3.obj"
    sl.run_cli(cli, "subdivide", coarse["obj"], "--scheme", "c2g0", "--levels", "1", "-o", str(fine))
    return coarse, fine


def run_evolver_from(cli: str, evolver: str, work: Path, row: dict, levels=(1, 2, 3)) -> dict:
    """Surface Evolver on the same Canham problem, started from `row`'s shape: its control mesh refined k
    times by C2g0 (a polyhedron near the limit surface; 514, 2050 and 8194 vertices from F_tetra,3), relaxed
    and minimised by tests/membrane/evolver_canham.py (at most EVOLVER_BLOCKS blocks of 20 steps and a
    Hessian seek: from these starts W then changes by less than 1e-5 relative per 40 blocks); the O(h²)
    error of Evolver's discrete W removed by Richardson extrapolation of the two finest levels (h halves:
    factor 4), the observed factor of the three levels reported next to it. Cached in OUTDIR/evolver."""
    tag = f"{row['case']}_{row['initial']}_v{row['reduced_volume']}"
    runs = []
    for k in levels:
        mesh = work / "evolver" / f"{tag}_L{k}.obj"
        cache = work / "evolver" / f"{tag}_L{k}.json"
        cmd = [sys.executable, str(mb.EVOLVER_DRIVER), "--reduced-volume", repr(row["reduced_volume"]), "--area",
               repr(AREA), "--initial-mesh", str(mesh), "--tolerance", repr(EVOLVER_TOLERANCE), "--max-blocks",
               str(EVOLVER_BLOCKS), "--time", "--evolver", evolver]
        if not cache.is_file() or json.loads(cache.read_text()).get("command") != cmd:
            sl.run_cli(cli, "subdivide", row["obj"], "--scheme", "c2g0", "--levels", str(k), "-o", str(mesh))
            r = subprocess.run(cmd, capture_output=True, text=True, check=False)
            if r.returncode != 0:
                raise sl.CliError(f"evolver_canham.py {tag} L{k}: exit {r.returncode}\n{r.stderr}")
            cache.write_text(json.dumps({"command": cmd, "result": json.loads(r.stdout)}))
        runs.append(json.loads(cache.read_text())["result"])
    w = [r["W"] for r in runs]
    extrapolated = (4.0 * w[-1] - w[-2]) / 3.0
    factor = (w[-3] - w[-2]) / (w[-2] - w[-1]) if len(w) >= 3 else None
    sl.log(f"evolver from {tag}: W/4π {[x / AREA for x in w]} → {extrapolated / AREA:.6f} (factor {factor})")
    return {"case": row["case"], "initial": row["initial"], "reduced_volume": row["reduced_volume"],
            "vertices": [r["vertices"] for r in runs], "W_over_4pi": [x / AREA for x in w],
            "converged": [r["converged"] for r in runs], "blocks": [r["blocks"] for r in runs],
            "seconds": [r["seconds"] for r in runs], "W_over_4pi_extrapolated": extrapolated / AREA,
            "observed_factor": factor, "limsurf_W_over_4pi": row["W_over_4pi"],
            "relative_difference": abs(row["W"] / extrapolated - 1.0)}


# ---------------------------------------------------------------------------------------------
# Summaries and the picture

def relative_spread(values: list[float]) -> float:
    return (max(values) - min(values)) / min(values)


def summarize(rows: list[dict]) -> dict:
    out: dict = {"area": AREA}
    branch = {r["initial"]: r for r in rows if r["case"] == "branches"}
    if branch:
        order = sorted(branch, key=lambda k: branch[k]["W"])
        out["branches_v0.5"] = {"W_over_4pi": {k: branch[k]["W_over_4pi"] for k in order},
                                "reduced_mean_curvature": {k: branch[k]["reduced_mean_curvature_reached"]
                                                           for k in order},
                                "lowest": order[0], "stomatocyte_lowest": order[0] == "stomatocyte"}
    fig7 = {r["scheme"]: r for r in rows if r["case"] == "fig7"}
    if fig7:
        out["fig7"] = {s: {"W_over_4pi": r["W_over_4pi"], "self_intersecting": r["self_intersecting"],
                           "intersecting_pairs": r["intersecting_pairs"], "converged": r["converged"]}
                       for s, r in fig7.items()}
        out["fig7"]["paper_verdicts_reproduced"] = (
            "c2g0" in fig7 and "loop" in fig7 and not fig7["c2g0"]["self_intersecting"]
            and fig7["loop"]["self_intersecting"])
    fig11 = [r for r in rows if r["case"] == "fig11"]
    if fig11:
        good = [r for r in fig11 if r["converged"] and not r["self_intersecting"]]
        ws = [r["W"] for r in good]
        out["fig11"] = {"W": {r["initial"]: r["W"] for r in fig11},
                        "counted": [r["initial"] for r in good],
                        "not_counted": {r["initial"]: ("self-intersecting" if r["self_intersecting"] else "not converged")
                                        for r in fig11 if r not in good},
                        "relative_spread": relative_spread(ws) if ws else None,
                        "agree_in_4_significant_digits": len({f"{w:.4g}" for w in ws}) == 1,
                        "harmonic": {r["initial"]: r["harmonic"] for r in fig11}}
    for case in ("fig12", "fig13"):
        reg = [r for r in rows if r["case"] == case and r["regularized_W"] is not None]
        if reg:
            r = reg[0]
            out[case] = {"mesh": r["mesh"], "epsilon": r["epsilon"], "W0": r["W"], "W": r["regularized_W"],
                         "W_rise": r["regularized_W"] - r["W"], "harmonic_before": r["harmonic"],
                         "harmonic_after": r["regularized_harmonic"],
                         "harmonic_drop_relative": 1.0 - r["regularized_harmonic"] / r["harmonic"],
                         "converged": r["converged"]}
    return out


def cross_section(vtk: Path, principal: bool = False) -> np.ndarray:
    """Segments (k, 2, 2) where the limit tessellation meets a plane through its centroid: y = const in
    (x, z) (the starts of the axisymmetric cases are symmetric about z, and so stay the shapes), or with
    `principal` the plane of the two largest principal axes of the surface's second moments, in those
    axes (signs fixed by the third moments), so that shapes rotated by their random starts line up."""
    points, triangles = mb.read_vtk_triangles(vtk)
    if principal:
        corners = points[triangles]
        area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
        centres = corners.mean(axis=1)
        centre = (area[:, None] * centres).sum(axis=0) / area.sum()
        q = centres - centre
        _, axes = np.linalg.eigh((area[:, None, None] * q[:, :, None] * q[:, None, :]).sum(axis=0))
        axes = axes[:, ::-1]  # largest spread first
        local = (points - centre) @ axes
        skew = (area[:, None] * ((centres - centre) @ axes) ** 3).sum(axis=0)
        local *= np.where(skew < 0.0, -1.0, 1.0)
        points = local[:, [0, 2, 1]]  # the plane of axes 1 and 2 as (x, z), axis 3 as y
    d = points[:, 1] - (0.0 if principal else points[:, 1].mean())
    segments = []
    for tri in triangles:
        crossing = []
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            if (d[a] < 0.0) != (d[b] < 0.0):
                t = d[a] / (d[a] - d[b])
                p = points[a] + t * (points[b] - points[a])
                crossing.append((p[0], p[2]))
        if len(crossing) == 2:
            segments.append(crossing)
    return np.array(segments).reshape(-1, 2, 2)


def plot(rows: list[dict], outdir: Path) -> None:
    from matplotlib.collections import LineCollection
    plt = sl.pyplot()
    panels = [("fig7", "Fig. 7: Canham v0 = 0.18, F_tetra,3", "scheme"),
              ("branches", "Canham v0 = 0.5: three branches", "initial"),
              ("fig11", "Fig. 11: Helfrich v0 = 0.5, m0 = 1.05", "initial")]
    panels = [p for p in panels if any(r["case"] == p[0] for r in rows)]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.6 * len(panels), 3.8), squeeze=False)
    colours = ["tab:blue", "tab:red", "tab:green", "tab:orange", "tab:purple", "tab:brown"]
    for ax, (case, title, key) in zip(axes[0], panels):
        mine = [r for r in rows if r["case"] == case]
        for k, r in enumerate(mine):
            segments = cross_section(Path(r["vtk"]), principal=(case == "fig11"))
            label = f"{r[key]}: W/4π {r['W_over_4pi']:.4f}" + (" (crosses itself)" if r["self_intersecting"] else "")
            ax.add_collection(LineCollection(segments, colors=colours[k % len(colours)], linewidths=1.0,
                                             label=label, rasterized=True))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("principal axis 1" if case == "fig11" else "x")
        ax.set_ylabel("principal axis 2" if case == "fig11" else "z")
        ax.legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)


# ---------------------------------------------------------------------------------------------

def extra_options(p):
    p.add_argument("--evolver", default=shutil.which("evolver"), help="Surface Evolver (default: on PATH)")


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    work = args.outdir
    for sub in ("initial", "shapes", "evolver"):
        (work / sub).mkdir(exist_ok=True)
    cli = args.limsurf
    tasks = []
    if args.quick:
        mesh, iterations = "tetra_2", 2000
        guesses = ["round", "perturbed1", "prolate"]
    else:
        mesh, iterations = "tetra_3", 6000
        guesses = ["round", "perturbed1", "perturbed2", "perturbed3", "prolate0.8"]
        for initial in ("prolate", "oblate", "stomatocyte"):
            tasks.append(lambda i=initial: run_membrane(cli, work, "branches", "c2g0", mesh,
                                                        initial_guess(work, mesh, i, 0.5), i, 0.5,
                                                        max_iterations=iterations))
        # The oblate shape of v0 = 0.6 (the oblate branch's minimum, SBL 1991), for Evolver below.
        tasks.append(lambda: run_membrane(cli, work, "peer", "c2g0", mesh, initial_guess(work, mesh, "oblate", 0.6),
                                          "oblate", 0.6, max_iterations=iterations))
        for scheme in ("c2g0", "loop"):
            tasks.append(lambda s=scheme: run_membrane(cli, work, "fig7", s, mesh,
                                                       initial_guess(work, mesh, "stomatocyte", 0.18), "stomatocyte",
                                                       0.18, max_iterations=iterations))
    for initial in guesses:
        # Fig. 12 is the round start's solve followed by (3.12); its first stage is the Fig. 11 row.
        case, epsilon = ("fig12", 0.003) if initial == "round" else ("fig11", None)
        # The starts near the sphere (v ≈ 1) reach v0 = 0.5 in FIG11_CONTINUATION steps: solved at once, their
        # first long steps can end in a shape that passes through itself (docs/membrane.md, "Continuation").
        steps = 1 if initial.startswith("prolate") else FIG11_CONTINUATION
        tasks.append(lambda i=initial, c=case, e=epsilon, k=steps: run_membrane(
            cli, work, c, "c2g0", mesh, initial_guess(work, mesh, i, 0.5), i, 0.5, 1.05, e, max_iterations=iterations,
            continuation=k))
    rows = sl.run_all(args.jobs, tasks)
    # The round start's first stage belongs to Fig. 11 too.
    rows += [dict(r, case="fig11", epsilon=None, regularized_W=None, regularized_harmonic=None)
             for r in rows if r["case"] == "fig12"]
    if not args.quick:
        coarse, start = fig13_start(cli, work, 0.4, 1.8, iterations)
        rows.append(coarse)
        rows.append(run_membrane(cli, work, "fig13", "c2g0", "tetra_4", start, "tetra_3 solution refined", 0.4, 1.8,
                                 0.08, max_iterations=iterations))

    evolver_runs = []
    if not args.quick and args.evolver:
        # One at a time: the 8194-vertex runs take a core for minutes.
        for row in rows:
            if (row["case"], row["initial"]) in (("branches", "stomatocyte"), ("peer", "oblate")):
                evolver_runs.append(run_evolver_from(cli, args.evolver, work, row))
    elif not args.quick:
        sl.log("evolver is not installed: the Evolver comparison is left out")

    sl.write_csv(work / f"{NAME}.csv", COLUMNS, rows)
    summary = summarize(rows)
    summary["evolver"] = evolver_runs
    summary["rows"] = [{k: v for k, v in r.items() if k not in ("obj", "vtk")} for r in rows]
    sl.write_json(work / f"{NAME}.json", summary)
    plot(rows, work)

    print("| case | scheme | mesh | start | v0 | m0 | W/4π | E | self-intersecting | converged | iterations | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        m0 = "" if r["reduced_mean_curvature"] is None else r["reduced_mean_curvature"]
        print(f"| {r['case']} | {r['scheme']} | {r['mesh']} | {r['initial']} | {r['reduced_volume']} | {m0} | "
              f"{r['W_over_4pi']:.6f} | {r['harmonic']:.4f} | {r['self_intersecting']} ({r['intersecting_pairs']}) | "
              f"{r['converged']} | {r['iterations']} | {r['seconds']:.1f} |")
    for case in ("fig12", "fig13"):
        if case in summary:
            s = summary[case]
            print(f"\n{case} ({s['mesh']}, ε = {s['epsilon']}): W {s['W0']:.6f} → {s['W']:.6f} (rise {s['W_rise']:.2e}),"
                  f" harmonic E {s['harmonic_before']:.4f} → {s['harmonic_after']:.4f} "
                  f"({100 * s['harmonic_drop_relative']:.1f} % lower)")
    for e in evolver_runs:
        print(f"\nEvolver from limsurf's {e['initial']} shape at v0 = {e['reduced_volume']}: W/4π "
              f"{', '.join(f'{w:.6f}' for w in e['W_over_4pi'])} ({e['vertices']} vertices) → extrapolated "
              f"{e['W_over_4pi_extrapolated']:.6f}; limsurf {e['limsurf_W_over_4pi']:.6f} "
              f"(relative difference {e['relative_difference']:.1e})")
    if "fig11" in summary:
        f11 = summary["fig11"]
        print(f"\nfig11: W relative spread {f11['relative_spread']:.2e} over the {len(f11['counted'])} starts that "
              f"converged to an embedded surface; agree in 4 significant digits: "
              f"{f11['agree_in_4_significant_digits']}; not counted: {f11['not_counted']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
