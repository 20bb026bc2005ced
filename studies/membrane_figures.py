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
- Fig. 11 (Helfrich, v0 = 0.5, m0 = 1.05, F_tetra,3) from several initial guesses: the round tetra_3, three
  randomly perturbed and rotated copies of it, and a prolate spheroid. The paper: Willmore energies agreeing in
  the first 4 significant digits.
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

  /usr/bin/python3 studies/membrane_figures.py build/release/cli/limsurf out/studies      # ~15 min on 2 cores

--quick (the test): F_tetra,2 (34 vertices): Fig. 11 from three guesses and Fig. 12, at most 800 iterations; ~20 s.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import membranes as mb
import studylib as sl

NAME = "membrane_figures"
AREA = 4.0 * math.pi
COLUMNS = ["study", "case", "scheme", "mesh", "vertices", "initial", "reduced_volume", "reduced_mean_curvature",
           "epsilon", "W", "W_over_4pi", "harmonic", "reduced_volume_reached", "reduced_mean_curvature_reached",
           "regularized_W", "regularized_harmonic", "self_intersecting", "intersecting_pairs",
           "intersection_resolution", "converged", "iterations", "seconds"]


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
    if initial == "stomatocyte":
        return stomatocyte_obj(source, out, 0.84 if v0 < 0.3 else 0.7)
    if initial.startswith("perturbed"):
        return perturbed_obj(source, out, seed=int(initial[len("perturbed"):]))
    raise ValueError(initial)


# ---------------------------------------------------------------------------------------------
# Runs

def run_membrane(cli: str, work: Path, case: str, scheme: str, mesh: str, start: Path, initial: str, v0: float,
                 m0: float | None = None, epsilon: float | None = None, max_iterations: int = 4000) -> dict:
    tag = f"{case}_{scheme}_{mesh}_{initial}"
    obj, vtk = work / "shapes" / f"{tag}.obj", work / "shapes" / f"{tag}.vtk"
    cmd = [cli, "membrane", str(start), "--scheme", scheme, "--area", repr(AREA), "--reduced-volume", repr(v0),
           "--max-iterations", str(max_iterations), "-o", str(obj), "--field-output", str(vtk), "--resolution", "12",
           "--json"]
    if m0 is not None:
        cmd += ["--reduced-mean-curvature", repr(m0)]
    if epsilon is not None:
        cmd += ["--regularize-harmonic", repr(epsilon)]
    wall = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        raise sl.CliError(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stderr.strip()}")
    out = json.loads(r.stdout)
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
            "iterations": out["iterations"] + (reg["iterations"] if reg else 0),
            "seconds": out["seconds"] + (reg["seconds"] if reg else 0.0), "obj": str(obj), "vtk": str(vtk)}


def fig13_start(cli: str, work: Path, v0: float, m0: float, max_iterations: int) -> tuple[dict, Path]:
    """The Fig. 13 problem on F_tetra,3 from a prolate spheroid, refined once by C2g0 onto F_tetra,4."""
    coarse = run_membrane(cli, work, "fig13_coarse", "c2g0", "tetra_3", initial_guess(work, "tetra_3", "prolate", v0),
                          "prolate", v0, m0, max_iterations=max_iterations)
    fine = work / "initial" / "tetra_4_from_tetra_3.obj"
    sl.run_cli(cli, "subdivide", coarse["obj"], "--scheme", "c2g0", "--levels", "1", "-o", str(fine))
    return coarse, fine


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
        ws = [r["W"] for r in fig11]
        out["fig11"] = {"W": {r["initial"]: r["W"] for r in fig11}, "relative_spread": relative_spread(ws),
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


def cross_section(vtk: Path) -> np.ndarray:
    """Segments (k, 2, 2) in (x, z) where the limit tessellation meets the plane y = (its centroid's y)."""
    points, triangles = mb.read_vtk_triangles(vtk)
    d = points[:, 1] - points[:, 1].mean()
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
            segments = cross_section(Path(r["vtk"]))
            label = f"{r[key]}: W/4π {r['W_over_4pi']:.4f}" + (" (crosses itself)" if r["self_intersecting"] else "")
            ax.add_collection(LineCollection(segments, colors=colours[k % len(colours)], linewidths=1.0,
                                             label=label))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x")
        ax.set_ylabel("z")
        ax.legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)


# ---------------------------------------------------------------------------------------------

def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    work = args.outdir
    for sub in ("initial", "shapes"):
        (work / sub).mkdir(exist_ok=True)
    cli = args.limsurf
    tasks = []
    if args.quick:
        mesh, iterations = "tetra_2", 800
        guesses = ["round", "perturbed1", "prolate"]
    else:
        mesh, iterations = "tetra_3", 6000
        guesses = ["round", "perturbed1", "perturbed2", "perturbed3", "prolate"]
        for initial in ("prolate", "oblate", "stomatocyte"):
            tasks.append(lambda i=initial: run_membrane(cli, work, "branches", "c2g0", mesh,
                                                        initial_guess(work, mesh, i, 0.5), i, 0.5,
                                                        max_iterations=iterations))
        for scheme in ("c2g0", "loop"):
            tasks.append(lambda s=scheme: run_membrane(cli, work, "fig7", s, mesh,
                                                       initial_guess(work, mesh, "stomatocyte", 0.18), "stomatocyte",
                                                       0.18, max_iterations=iterations))
    for initial in guesses:
        # Fig. 12 is the round start's solve followed by (3.12); its first stage is the Fig. 11 row.
        case, epsilon = ("fig12", 0.003) if initial == "round" else ("fig11", None)
        tasks.append(lambda i=initial, c=case, e=epsilon: run_membrane(
            cli, work, c, "c2g0", mesh, initial_guess(work, mesh, i, 0.5), i, 0.5, 1.05, e, max_iterations=iterations))
    rows = sl.run_all(args.jobs, tasks)
    # The round start's first stage belongs to Fig. 11 too.
    rows += [dict(r, case="fig11", epsilon=None, regularized_W=None, regularized_harmonic=None)
             for r in rows if r["case"] == "fig12"]
    if not args.quick:
        coarse, start = fig13_start(cli, work, 0.4, 1.8, iterations)
        rows.append(coarse)
        rows.append(run_membrane(cli, work, "fig13", "c2g0", "tetra_4", start, "tetra_3 solution refined", 0.4, 1.8,
                                 0.08, max_iterations=iterations))

    sl.write_csv(work / f"{NAME}.csv", COLUMNS, rows)
    summary = summarize(rows)
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
    if "fig11" in summary:
        print(f"\nfig11: W relative spread {summary['fig11']['relative_spread']:.2e} over {len(summary['fig11']['W'])} "
              f"starts; agree in 4 significant digits: {summary['fig11']['agree_in_4_significant_digits']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
