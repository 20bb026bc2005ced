#!/usr/bin/python3
"""The spectra of the schemes at an extraordinary vertex: subdominant eigenvalues, curvature, characteristic maps.

`limsurf eigen --scheme S --valence N --json` (docs/eigen.md) gives the eigenvalues of the local
subdivision matrix around one extraordinary vertex, Fourier block by block, and the classical
verdicts: C1 (Reif: the spectrum and a regular, injective characteristic map), bounded curvature
(every eigenvalue after lambda_1 = lambda_2 at most lambda^2) and the necessary condition (17) for C2.
This study runs it for Catmull-Clark and Loop at valences 3..12, Doo-Sabin at 3..12 (the degree of
the extraordinary face), C2g0 at 3 and 6 and Table 1's tuned Catmull-Clark weights at valence 5, and
draws the sampled characteristic maps (`--characteristic-map`) of six of them. Written:

  spectra.csv         one row per run: lambda and its closed form where the literature has one
                      (Catmull-Clark: Doo and Sabin 1978; Loop: 3/8 + cos(2 pi/n)/4, Loop 1987;
                      Doo-Sabin: 1/2), the next eigenvalue and lambda^2, the verdicts, the
                      characteristic map's Jacobian range and winding number
  spectra.json        per scheme: the largest difference from the closed form and the valences
                      where each verdict holds
  spectra.{png,svg}   (a) lambda by valence with the closed forms, (b) the next eigenvalue over
                      lambda^2 (curvature bounded where <= 1), (c) six characteristic maps

  /usr/bin/python3 studies/spectra.py build/release/cli/limsurf out/studies

--quick: valences 3..8 (about a second).
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import studylib as sl

NAME = "spectra"

VALENCES = list(range(3, 13))
QUICK_VALENCES = list(range(3, 9))
TABLE1 = {"cup": "13.4575,0.999938,0.999938", "saddle": "13.9851,0.824885,0.824885"}
# The characteristic maps drawn: (scheme, valence, weights name or None).
MAPS = [("catmull-clark", 3, None), ("catmull-clark", 5, None), ("catmull-clark", 8, None),
        ("loop", 3, None), ("loop", 7, None), ("c2g0", 3, None)]

COLUMNS = ["scheme", "valence", "weights", "rings", "size", "lambda", "closed_form", "lambda_multiplicity",
           "next", "next_multiplicity", "lambda_squared", "next_over_lambda_squared", "c1_spectrum", "c1",
           "bounded_curvature", "c2_necessary", "min_jacobian", "max_jacobian", "winding_number"]


def closed_form(scheme: str, n: int) -> float | None:
    """The subdominant eigenvalue the literature gives in closed form (None where it gives none)."""
    if scheme == "catmull-clark":
        c, h = math.cos(2 * math.pi / n), math.cos(math.pi / n)
        return (5 + c + h * math.sqrt(2 * (9 + c))) / 16
    if scheme == "loop":
        return 3 / 8 + math.cos(2 * math.pi / n) / 4
    if scheme == "doo-sabin":
        return 0.5
    return None


def runs(valences):
    out = [(s, n, None) for s in ("catmull-clark", "loop", "doo-sabin") for n in valences]
    out += [("c2g0", 3, None), ("c2g0", 6, None)]
    out += [("catmull-clark", 5, w) for w in TABLE1]
    return out


def eigen_args(scheme, valence, weights):
    args = ["eigen", "--scheme", scheme, "--valence", str(valence)]
    if weights:
        args += ["--weights", TABLE1[weights]]
    return args


def read_obj(path: Path):
    """Vertices (x, y) and faces of the characteristic map the CLI wrote."""
    xy, faces = [], []
    for line in path.read_text(encoding="utf-8").splitlines():
        fields = line.split()
        if fields and fields[0] == "v":
            xy.append((float(fields[1]), float(fields[2])))
        elif fields and fields[0] == "f":
            faces.append([int(f.split("/")[0]) - 1 for f in fields[1:]])
    return xy, faces


def verdict(test) -> str:
    return "" if not test["checked"] else ("yes" if test["passed"] else "no")


def row_of(scheme, valence, weights, out):
    lam, nxt = out["subdominant"], out["subsubdominant"]
    m = out["characteristic_map"]
    tests = out["tests"]
    return dict(scheme=scheme, valence=valence, weights=weights or "", rings=out["rings"], size=out["size"],
                **{"lambda": lam}, closed_form=closed_form(scheme, valence) if weights is None else None,
                lambda_multiplicity=out["subdominant_multiplicity"], next=nxt,
                next_multiplicity=out["subsubdominant_multiplicity"], lambda_squared=lam * lam,
                next_over_lambda_squared=nxt / (lam * lam), c1_spectrum=verdict(tests["c1_spectrum"]),
                c1=verdict(tests["c1"]), bounded_curvature=verdict(tests["bounded_curvature"]),
                c2_necessary=verdict(tests["c2_necessary"]),
                min_jacobian=m.get("min_jacobian"), max_jacobian=m.get("max_jacobian"),
                winding_number=m.get("winding_number"))


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    valences = QUICK_VALENCES if args.quick else VALENCES
    todo = runs(valences)
    with tempfile.TemporaryDirectory() as tmp:
        maps = {(s, n, w): Path(tmp) / f"{s}_{n}.obj" for s, n, w in MAPS}
        tasks = [lambda r=r: sl.run_json(args.limsurf, *eigen_args(*r),
                                         *(["--characteristic-map", str(maps[r])] if r in maps else []))
                 for r in todo]
        results = sl.run_all(args.jobs, tasks)
        meshes = {r: read_obj(path) for r, path in maps.items()}
    rows = []
    for (scheme, valence, weights), out in zip(todo, results):
        if out["scheme"] != scheme or out["valence"] != valence:
            sys.exit(f"error: eigen --scheme {scheme} --valence {valence}: unexpected output")
        rows.append(row_of(scheme, valence, weights, out))
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    summary = {"valences": valences, "schemes": {}}
    for scheme in ("catmull-clark", "loop", "doo-sabin", "c2g0"):
        mine = [r for r in rows if r["scheme"] == scheme and not r["weights"]]
        entry = {key: [r["valence"] for r in mine if r[key] == "yes"]
                 for key in ("c1", "bounded_curvature", "c2_necessary")}
        known = [abs(r["lambda"] - r["closed_form"]) for r in mine if r["closed_form"] is not None]
        if known:
            entry["max_difference_from_closed_form"] = max(known)
        summary["schemes"][scheme] = entry
    summary["table1"] = {w: next(r["lambda"] for r in rows if r["weights"] == w) for w in TABLE1}
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(rows, meshes, valences, args.outdir)
    print_summary(rows)
    return 0


def print_summary(rows):
    print("| scheme | valence | weights | lambda | closed form | next (x) | lambda^2 | C1 | bounded curvature | C2 (17) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        cf = "" if r["closed_form"] is None else f"{r['closed_form']:.9f}"
        print(f"| {r['scheme']} | {r['valence']} | {r['weights']} | {r['lambda']:.9f} | {cf} |"
              f" {r['next']:.6f} ({r['next_multiplicity']}) | {r['lambda_squared']:.6f} | {r['c1'] or '-'} |"
              f" {r['bounded_curvature']} | {r['c2_necessary']} |")


STYLE = {"catmull-clark": ("tab:blue", "o", "Catmull–Clark"), "loop": ("tab:red", "s", "Loop"),
         "doo-sabin": ("tab:green", "^", "Doo–Sabin (face degree)"), "c2g0": ("black", "D", "C2g0")}


def plot(rows, meshes, valences, outdir):
    plt = sl.pyplot()
    from matplotlib.collections import PolyCollection
    fig = plt.figure(figsize=(12.0, 7.0))
    grid = fig.add_gridspec(2, 6, height_ratios=[1.0, 0.78], hspace=0.28, wspace=0.12, left=0.06, right=0.985,
                            top=0.95, bottom=0.07)
    top = grid[0, :].subgridspec(1, 2, wspace=0.2)
    ax_lambda = fig.add_subplot(top[0, 0])
    ax_ratio = fig.add_subplot(top[0, 1])
    fine = [valences[0] + i * (valences[-1] - valences[0]) / 200 for i in range(201)]
    for scheme, (colour, marker, label) in STYLE.items():
        mine = [r for r in rows if r["scheme"] == scheme and not r["weights"]]
        ax_lambda.plot([r["valence"] for r in mine], sl.plotted([r["lambda"] for r in mine]), ls="none",
                       marker=marker, color=colour, ms=5, label=f"{label}: limsurf eigen")
        if scheme in ("catmull-clark", "loop"):
            ax_lambda.plot(fine, sl.plotted([closed_form(scheme, n) for n in fine]), color=colour, lw=0.8,
                           label=f"{label}: closed form")
            ax_ratio.plot([r["valence"] for r in mine], sl.plotted([r["next_over_lambda_squared"] for r in mine]),
                          marker=marker, color=colour, ms=5, lw=0.8, label=label)
    for name, marker in (("cup", "P"), ("saddle", "X")):
        r = next(r for r in rows if r["weights"] == name)
        ax_lambda.plot([5], [float(f"{r['lambda']:.4g}")], marker=marker, color="tab:purple", ms=7, ls="none",
                       label=f"Catmull–Clark, Table 1 {name} weights (λ = {r['lambda']:.3f})")
    ax_lambda.set_xlabel("valence n")
    ax_lambda.set_ylabel("subdominant eigenvalue λ")
    ax_lambda.set_title("(a) λ by valence")
    ax_lambda.legend(loc="lower right", ncol=1)
    ax_ratio.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax_ratio.axhspan(1.0, 2.2, color="0.92", zorder=0)
    ax_ratio.set_ylim(0.9, 2.2)
    ax_ratio.text(valences[-1], 2.12, "curvature unbounded", ha="right", va="top", color="0.35")
    ax_ratio.text(valences[-1], 0.93, "bounded", ha="right", va="bottom", color="0.35")
    ax_ratio.set_xlabel("valence n")
    ax_ratio.set_ylabel("next eigenvalue / λ²")
    ax_ratio.set_title("(b) bounded curvature where ≤ 1")
    ax_ratio.legend(loc="upper left")
    for ax in (ax_lambda, ax_ratio):
        ax.set_xticks(valences)
    for k, key in enumerate(MAPS):
        scheme, valence, _ = key
        ax = fig.add_subplot(grid[1, k])
        xy, faces = meshes[key]
        polygons = [[(float(f"{xy[i][0]:.4g}"), float(f"{xy[i][1]:.4g}")) for i in face] for face in faces]
        # Rasterised in the SVG: six maps of ~1000 polygons each made it 1.5 MB.
        ax.add_collection(PolyCollection(polygons, facecolors="0.95", edgecolors=STYLE[scheme][0], linewidths=0.15,
                                         rasterized=True))
        ax.autoscale_view()
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"(c) {STYLE[scheme][2].split(' (')[0]}, n = {valence}", fontsize=8.5)
    fig.text(0.5, 0.015, "(c) the characteristic maps: the faces at the vertex, sampled 16 × 16 per face, mapped "
             "by the frequency-1 eigenvector of λ", ha="center", fontsize=8.5)
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
