#!/usr/bin/python3
"""Reverse Catmull-Clark subdivision: the coarse mesh recovered from a refined one, exactly and under noise.

Each bundled mesh is refined L = 1, 2, 3 times by `limsurf subdivide --scheme catmull-clark`, its fine
vertices are moved by Gaussian noise of standard deviation sigma x (the bounding-box diagonal) per
coordinate (sigma = 0, 1e-10, ..., 1e-2; one seed per run), and `limsurf reverse --levels L --json`
(iga-with-catmull-clark §3; docs/guide/reverse.md) recovers the coarse mesh: its topology from the
fine faces alone, its positions by least squares. limsurf numbers the children of old vertices first,
so the recovered coarse vertices compare one to one with the original control points. Written:

  reverse.csv         one row per (mesh, L, sigma): counts, the first reversed level's residual
                      (rms and max, over the diagonal), its prediction for pure noise
                      sqrt(3 (1 - n/m)) sigma (n coarse and m fine vertices of that level: the noise's
                      part outside the range of S0), and the coarse positions' error against the
                      original control points (max and rms, over the diagonal)
  reverse.json        per mesh and L: the fitted log-log slopes of the error and the residual over
                      sigma > 0, and the sigma = 0 errors
  reverse.{png,svg}   (a) the coarse error against sigma, (b) the first level's residual over its
                      prediction

  /usr/bin/python3 studies/reverse.py build/release/cli/limsurf out/studies

--quick: genus2 and plate_sym, L = 1, 2, sigma = 0, 1e-8, 1e-4 (a second or two).
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import numpy as np

import studylib as sl

NAME = "reverse"

MESHES = ["genus2.obj", "cube_ngons.obj", "plate_sym.obj", "torus_8x10.obj"]
QUICK_MESHES = ["genus2.obj", "plate_sym.obj"]
LEVELS = [1, 2, 3]
QUICK_LEVELS = [1, 2]
SIGMAS = [0.0, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2]
QUICK_SIGMAS = [0.0, 1e-8, 1e-4]

COLUMNS = ["mesh", "levels", "sigma", "fine_vertices", "fine_faces", "coarse_vertices", "coarse_faces",
           "first_level_fine_vertices", "first_level_coarse_vertices", "residual_rms", "residual_max",
           "predicted_residual_rms", "error_max", "error_rms", "unique"]


def read_obj_vertices(path: Path) -> np.ndarray:
    return np.array([[float(x) for x in line.split()[1:4]]
                     for line in path.read_text(encoding="utf-8").splitlines() if line.startswith("v ")])


def write_moved(source: Path, target: Path, moved: np.ndarray) -> None:
    """source with its vertices replaced by moved (every other line, tags included, kept)."""
    rows = iter(moved)
    out = []
    for line in source.read_text(encoding="utf-8").splitlines():
        if line.startswith("v "):
            x, y, z = next(rows)
            out.append(f"v {x!r} {y!r} {z!r}")
        else:
            out.append(line)
    target.write_text("\n".join(out) + "\n", encoding="utf-8")


def refined(work: Path, mesh: str, levels: int) -> Path:
    return work / f"{Path(mesh).stem}_L{levels}.obj"


def refine(cli: str, work: Path, mesh: str, levels: int) -> None:
    sl.run_cli(cli, "subdivide", sl.mesh(mesh), "--scheme", "catmull-clark", "--levels", str(levels),
               "-o", str(refined(work, mesh, levels)))


def run_case(cli: str, work: Path, mesh: str, levels: int, sigma: float, seed: int) -> dict:
    """One noisy reversal of the refinement refine() wrote."""
    original = read_obj_vertices(Path(sl.mesh(mesh)))
    diagonal = float(np.linalg.norm(original.max(axis=0) - original.min(axis=0)))
    fine = refined(work, mesh, levels)
    stem = fine.stem
    noisy = work / f"{stem}_s{sigma:g}.obj"
    points = read_obj_vertices(fine)
    rng = np.random.default_rng(seed)
    write_moved(fine, noisy, points + sigma * diagonal * rng.standard_normal(points.shape))
    coarse = work / f"{stem}_s{sigma:g}_coarse.obj"
    out = sl.run_json(cli, "reverse", str(noisy), "--levels", str(levels), "-o", str(coarse))
    recovered = read_obj_vertices(coarse)
    if recovered.shape != original.shape:
        raise sl.CliError(f"{noisy}: {recovered.shape[0]} coarse vertices, the original has {original.shape[0]}")
    error = np.linalg.norm(recovered - original, axis=1) / diagonal
    first = out["per_level"][0]
    m, n = first["fine_vertices"], first["coarse_vertices"]
    return dict(mesh=mesh, levels=levels, sigma=sigma, fine_vertices=out["input"]["num_vertices"],
                fine_faces=out["input"]["num_faces"], coarse_vertices=out["output"]["num_vertices"],
                coarse_faces=out["output"]["num_faces"], first_level_fine_vertices=m, first_level_coarse_vertices=n,
                residual_rms=first["residual_rms"] / diagonal, residual_max=first["residual_max"] / diagonal,
                predicted_residual_rms=math.sqrt(3.0 * (1.0 - n / m)) * sigma,
                error_max=float(error.max()), error_rms=float(np.sqrt(np.mean(error**2))),
                unique=int(all(level["unique"] for level in out["per_level"])))


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    meshes = QUICK_MESHES if args.quick else MESHES
    levels = QUICK_LEVELS if args.quick else LEVELS
    sigmas = QUICK_SIGMAS if args.quick else SIGMAS
    cases = [(mesh, L, s) for mesh in meshes for L in levels for s in sigmas]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        # One refinement per (mesh, L) first, then the noisy reversals side by side.
        sl.run_all(args.jobs, [lambda m=m, L=L: refine(args.limsurf, work, m, L) for m in meshes for L in levels])
        tasks = [lambda c=c, i=i: run_case(args.limsurf, work, *c, seed=1000 + i) for i, c in enumerate(cases)]
        rows = sl.run_all(args.jobs, tasks)
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    summary = {"sigmas": sigmas, "cases": {}}
    for mesh in meshes:
        for L in levels:
            mine = [r for r in rows if r["mesh"] == mesh and r["levels"] == L]
            noisy = [r for r in mine if r["sigma"] > 0]
            exact = next(r for r in mine if r["sigma"] == 0)
            summary["cases"][f"{mesh} L={L}"] = {
                "exact_error_max": exact["error_max"], "exact_residual_max": exact["residual_max"],
                "error_slope": sl.fit_slope([r["sigma"] for r in noisy], [r["error_rms"] for r in noisy]),
                "residual_slope": sl.fit_slope([r["sigma"] for r in noisy], [r["residual_rms"] for r in noisy]),
                "residual_over_prediction": [r["residual_rms"] / r["predicted_residual_rms"] for r in noisy],
                "error_over_sigma": [r["error_rms"] / r["sigma"] for r in noisy]}
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(rows, meshes, levels, args.outdir)
    print_summary(rows)
    return 0


def print_summary(rows):
    print("| mesh | L | sigma | fine vertices | coarse vertices | residual rms / prediction | error rms / sigma |"
          " error max (sigma = 0) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["sigma"] == 0:
            ratio, per_sigma, exact = "-", "-", f"{r['error_max']:.1e}"
        else:
            ratio = f"{r['residual_rms'] / r['predicted_residual_rms']:.3f}"
            per_sigma, exact = f"{r['error_rms'] / r['sigma']:.3f}", ""
        print(f"| {r['mesh']} | {r['levels']} | {r['sigma']:g} | {r['fine_vertices']} | {r['coarse_vertices']} |"
              f" {ratio} | {per_sigma} | {exact} |")


MARKERS = {1: "o", 2: "s", 3: "^"}
COLOURS = ["tab:blue", "tab:red", "tab:green", "tab:purple"]
ZERO_AT = 1e-13  # where sigma = 0 is drawn on the log axis (its tick reads "0")


def plot(rows, meshes, levels, outdir):
    plt = sl.pyplot()
    fig, (ax_error, ax_residual) = plt.subplots(1, 2, figsize=(11.0, 4.4))
    sigmas = sorted({r["sigma"] for r in rows if r["sigma"] > 0})
    for colour, mesh in zip(COLOURS, meshes):
        for L in levels:
            mine = [r for r in rows if r["mesh"] == mesh and r["levels"] == L]
            noisy = [r for r in mine if r["sigma"] > 0]
            exact = [r for r in mine if r["sigma"] == 0]
            label = f"{Path(mesh).stem}, L = {L}"
            ax_error.loglog([r["sigma"] for r in noisy], sl.plotted([r["error_rms"] for r in noisy]), color=colour,
                            marker=MARKERS[L], ms=4, lw=0.9, label=label)
            ax_error.loglog([ZERO_AT] * len(exact), sl.plotted([max(r["error_rms"], 1e-17) for r in exact]),
                            color=colour, marker=MARKERS[L], ms=4, ls="none")
            ax_residual.semilogx([r["sigma"] for r in noisy],
                                 sl.plotted([r["residual_rms"] / r["predicted_residual_rms"] for r in noisy]),
                                 color=colour, marker=MARKERS[L], ms=4, lw=0.8, label=label)
    ax_error.loglog([sigmas[0], sigmas[-1]], [sigmas[0], sigmas[-1]], color="grey", lw=0.8, ls="--", label="error = σ")
    ax_error.axvline(math.sqrt(ZERO_AT * sigmas[0]), color="0.75", lw=0.6, ls=":")
    ax_error.set_xticks([ZERO_AT] + sigmas)
    ax_error.set_xticklabels(["0"] + [f"1e{round(math.log10(x))}" for x in sigmas])
    ax_error.minorticks_off()
    ax_error.set_xlabel("noise σ per coordinate (× bounding-box diagonal)")
    ax_error.set_ylabel("rms error of the recovered control points (× diagonal)")
    ax_error.set_title("(a) the coarse mesh: exact from a refinement, linear in the noise")
    ax_error.legend(loc="upper left", ncol=2, fontsize=6.5)
    ax_residual.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax_residual.set_ylim(0.8, 1.2)
    ax_residual.set_xticks(sigmas)
    ax_residual.minorticks_off()
    ax_residual.set_xlabel("noise σ per coordinate (× bounding-box diagonal)")
    ax_residual.set_ylabel("first level's rms residual / √(3 (1 − n/m)) σ")
    ax_residual.set_title("(b) the residual is the noise outside the range of S0")
    ax_residual.legend(loc="upper left", ncol=2, fontsize=6.5)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
