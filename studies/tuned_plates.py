#!/usr/bin/python3
"""Kirchhoff-Love plates with IGA-tuned Catmull-Clark weights against Navier (the paper's §4).

`limsurf plate MESH --levels L --load uniform|sinusoidal --tuned none|auto --json` solves the simply
supported plate [0, 10]^2 (E = 2e11, t = 0.1, nu = 0.3, p = 1e4: the CLI's defaults) on the limit
surface of a planar Catmull-Clark control mesh refined 0..L times, and reports the relative L2 and
energy-norm errors against the Navier series. --tuned none is Catmull-Clark everywhere
("classical"); --tuned auto (iga-tuned-catmull-clark-weights §3.4, §4) solves once with the cup-
tuned weights at every interior extraordinary vertex of valence >= 5 (the "cup pass", JSON
"first_pass"), decomposes the local solution at each such vertex into the cup k3 (xi1^2 + xi2^2)
and the saddles k4 (xi1^2 - xi2^2), k5 (2 xi1 xi2) ((37), (38)) with the cup-saddle ratio
R = k3^2 / (k4^2 + k5^2) (1 + nu) / (1 - nu) (R >= 1: cup, else saddle; the library's
decompose_shapes), and solves again with each vertex's chosen weights ("auto"). Every level
decides for itself (the paper decides once, on level 2 or 3, and keeps the choice). Three
examples, as the paper's Figs. 10, 12 and 14: plate_sym (fourfold symmetric, valences 3 and 5
inside: the stand-in for Fig. 8a) under the uniform and the sinusoidal load
p sin(2 pi x / a) sin(2 pi y / b), and plate_flip (no symmetry, valences 3 and 5: Fig. 8b) under the
sinusoidal load. The paper shows its meshes only as pictures; ours put the valence-5 vertices where
its R values say they are (data/meshes/README.md). Next to each R the study writes Navier's own:
the exact solution's Hessian at the vertex's limit point, taken to its characteristic coordinates
through the decomposition's tangents. Written:

  tuned_plates.csv         one row per (example, level): vertices, the classical, cup-pass and auto
                           L2 and energy errors, and the reductions against classical (percent,
                           positive: the tuned weights are closer to Navier)
  tuned_plates_ratios.csv  one row per (example, level, tuned vertex): valence, the limit point
                           (x, y), k3, k4, k5, R, Navier's R there, and the chosen shape with its
                           lambda and weights
  tuned_plates.json        per example: the slopes of log error against log (control vertices),
                           least squares over levels >= 1 as plate_errors.py, for classical, cup
                           pass and auto; the reductions at the finest level; the R values and
                           verdicts per level
  tuned_plates.{png,svg}   per example the L2 and the energy error against control vertices,
                           classical against tuned (cup pass and auto)

Orders in h are -2 x slope (the vertex count grows like h^-2).

  /usr/bin/python3 studies/tuned_plates.py build/release/cli/limsurf out/studies

Full: levels 0..4 on plate_sym (16641 control vertices, as the paper's level 5 of a four times
coarser mesh) and 0..5 on plate_flip (20865), some 3 minutes with two jobs. --quick: plate_sym under
the uniform load, levels 0..2 (15-25 s).
"""

from __future__ import annotations

import math
import sys

import studylib as sl

NAME = "tuned_plates"

# (example, mesh, load, label, full levels)
EXAMPLES = [
    ("sym_uniform", "plate_sym.obj", "uniform", "plate_sym, uniform load (Fig. 10)", 4),
    ("sym_sinusoidal", "plate_sym.obj", "sinusoidal", "plate_sym, sinusoidal load (Fig. 12)", 4),
    ("flip_sinusoidal", "plate_flip.obj", "sinusoidal", "plate_flip, sinusoidal load (Fig. 14)", 5),
]
QUICK = {"sym_uniform": 2}
PLATE = 10.0  # the CLI's default square [0, 10]^2
NU = 0.3
FIT_FROM_LEVEL = 1

SERIES = [  # (key, legend, colour, marker, line style)
    ("classical", "Catmull–Clark", "black", "o", "-"),
    ("cup", "tuned, cup pass (all λ cup)", "tab:blue", "^", "--"),
    ("auto", "tuned, auto (cup or saddle by R)", "tab:red", "s", "-"),
]
ERRORS = [("l2", "l2_relative_error", "L² error"), ("energy", "energy_relative_error", "energy-norm error")]

COLUMNS = (["example", "mesh", "load", "level", "vertices"]
           + [f"{s}_{e}" for s, *_ in SERIES for e, _, _ in ERRORS]
           + [f"{s}_{e}_reduction_pct" for s in ("cup", "auto") for e, _, _ in ERRORS])

RATIO_COLUMNS = ["example", "level", "vertex", "valence", "x", "y", "k3", "k4", "k5", "R", "R_navier", "shape",
                 "lambda", "alpha", "beta", "gamma"]


def extra_options(p):
    p.add_argument("--levels", type=int, default=None,
                   help="levels 0..L on every example (default 5, as the paper; --quick: 2 on plate_ev35 uniform)")


def reduction(classical: float, tuned: float) -> float:
    return 100.0 * (1.0 - tuned / classical)


def navier_hessian(load: str, x: float, y: float) -> tuple[float, float, float]:
    """(w_xx, w_yy, w_xy) of Navier's deflection up to a common factor: the uniform load's series
    over odd m, n (Timoshenko ch. 5), or the sinusoidal load's own shape."""
    if load == "sinusoidal":
        a = 2 * math.pi / PLATE
        s, c = math.sin(a * x) * math.sin(a * y), math.cos(a * x) * math.cos(a * y)
        return -s, -s, c
    hxx = hyy = hxy = 0.0
    for m in range(1, 402, 2):
        a = m * math.pi / PLATE
        sx, cx = math.sin(a * x), math.cos(a * x)
        for n in range(1, 402, 2):
            b = n * math.pi / PLATE
            w = 1.0 / (m * n * (m * m + n * n) ** 2)
            sxy, cxy = sx * math.sin(b * y), cx * math.cos(b * y)
            hxx -= w * a * a * sxy
            hyy -= w * b * b * sxy
            hxy += w * a * b * cxy
    return hxx, hyy, hxy


def navier_ratio(load: str, decomposition: dict) -> float:
    """R of (38) of Navier's solution at the vertex: its Hessian H at the limit point taken to the
    characteristic coordinates, J^T H J = 2 [[k3 + k4, k5], [k5, k3 - k4]], J = the tangents."""
    x, y, _ = decomposition["position"]
    (t1x, t1y, _), (t2x, t2y, _) = decomposition["tangents"]
    hxx, hyy, hxy = navier_hessian(load, x, y)
    g11 = t1x * (hxx * t1x + hxy * t1y) + t1y * (hxy * t1x + hyy * t1y)
    g22 = t2x * (hxx * t2x + hxy * t2y) + t2y * (hxy * t2x + hyy * t2y)
    g12 = t1x * (hxx * t2x + hxy * t2y) + t1y * (hxy * t2x + hyy * t2y)
    k3, k4, k5 = (g11 + g22) / 4, (g11 - g22) / 4, g12 / 2
    return k3 * k3 / (k4 * k4 + k5 * k5) * (1 + NU) / (1 - NU)


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    examples = []
    for ex, mesh_name, load, label, full in EXAMPLES:
        if args.quick and ex not in QUICK:
            continue
        levels = args.levels if args.levels is not None else (QUICK[ex] if args.quick else full)
        examples.append((ex, mesh_name, load, label, levels))
    runs = [(e, tuned) for e in examples for tuned in ("auto", "none")]
    # The costliest (auto: two passes) first: with two jobs they overlap the others.
    order = list(reversed(range(len(runs))))
    order.sort(key=lambda i: runs[i][1] != "auto")
    tasks = [lambda r=runs[i]: sl.run_json(args.limsurf, "plate", sl.mesh(r[0][1]), "--levels", str(r[0][4]),
                                           "--load", r[0][2], "--tuned", r[1])
             for i in order]
    results = {}
    for i, out in zip(order, sl.run_all(args.jobs, tasks)):
        results[(runs[i][0][0], runs[i][1])] = out

    rows, ratio_rows = [], []
    summary = {"fit_from_level": FIT_FROM_LEVEL, "support": "simply", "examples": {}}
    for ex, mesh_name, load, label, levels in examples:
        classical, auto = results[(ex, "none")], results[(ex, "auto")]
        for out, tuned in ((classical, "none"), (auto, "auto")):
            if (out["load"] != load or out["support"] != "simply" or out.get("tuned") != tuned
                    or len(out["levels"]) != levels + 1):
                sys.exit(f"error: {ex} --tuned {tuned}: unexpected plate output")
        per = {"label": label, "mesh": mesh_name, "load": load, "vertices": [], "levels": []}
        for lc, la in zip(classical["levels"], auto["levels"]):
            if lc["level"] != la["level"] or lc["vertices"] != la["vertices"] or "first_pass" not in la:
                sys.exit(f"error: {ex}: the classical and tuned runs do not match at level {lc['level']}")
            nav = {"classical": lc["navier"], "cup": la["first_pass"]["navier"], "auto": la["navier"]}
            row = dict(example=ex, mesh=mesh_name, load=load, level=lc["level"], vertices=lc["vertices"])
            for s, *_ in SERIES:
                for e, key, _ in ERRORS:
                    row[f"{s}_{e}"] = nav[s][key]
            for s in ("cup", "auto"):
                for e, _, _ in ERRORS:
                    row[f"{s}_{e}_reduction_pct"] = reduction(row[f"classical_{e}"], row[f"{s}_{e}"])
            rows.append(row)
            verdicts = []
            for v in la["tuned_vertices"]:
                d = v["decomposition"]
                exact = navier_ratio(load, d)
                ratio_rows.append(dict(example=ex, level=lc["level"], vertex=v["vertex"], valence=v["valence"],
                                       x=d["position"][0], y=d["position"][1], k3=d["k3"], k4=d["k4"], k5=d["k5"],
                                       R=d["ratio"], R_navier=exact, shape=v["shape"],
                                       **{k: v[k] for k in ("lambda", "alpha", "beta", "gamma")}))
                verdicts.append({"vertex": v["vertex"], "valence": v["valence"], "x": d["position"][0],
                                 "y": d["position"][1], "R": d["ratio"], "R_navier": exact, "shape": v["shape"],
                                 "lambda": v["lambda"]})
            per["vertices"].append(lc["vertices"])
            per["levels"].append({"level": lc["level"], "tuned_vertices": verdicts})
        mine = [r for r in rows if r["example"] == ex]
        fit = [r for r in mine if r["level"] >= FIT_FROM_LEVEL]
        for s, *_ in SERIES:
            per[s] = {}
            for e, _, _ in ERRORS:
                err = [r[f"{s}_{e}"] for r in mine]
                slope = sl.fit_slope([r["vertices"] for r in fit], [r[f"{s}_{e}"] for r in fit]) \
                    if len(fit) >= 2 else None
                per[s][e] = {"errors": err, "factors": sl.ratios(err), "slope": slope,
                             "order_h": None if slope is None else -2 * slope}
        finest = mine[-1]
        per["finest_level"] = finest["level"]
        per["reduction_pct_finest"] = {f"{s}_{e}": finest[f"{s}_{e}_reduction_pct"]
                                       for s in ("cup", "auto") for e, _, _ in ERRORS}
        summary["examples"][ex] = per
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    sl.write_csv(args.outdir / f"{NAME}_ratios.csv", RATIO_COLUMNS, ratio_rows)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(summary, examples, args.outdir)
    print_summary(rows, ratio_rows, summary)
    return 0


def print_summary(rows, ratio_rows, summary):
    print("| example | level | vertices | classical L2 | cup L2 | auto L2 | classical energy | cup energy |"
          " auto energy | auto L2 reduction % | auto energy reduction % |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['example']} | {r['level']} | {r['vertices']} | {r['classical_l2']:.3e} | {r['cup_l2']:.3e} |"
              f" {r['auto_l2']:.3e} | {r['classical_energy']:.3e} | {r['cup_energy']:.3e} | {r['auto_energy']:.3e} |"
              f" {r['auto_l2_reduction_pct']:.1f} | {r['auto_energy_reduction_pct']:.1f} |")
    print("\ncup-saddle ratio R and the verdict per level (vertex:valence at (x, y): R (Navier's R) shape):")
    for ex, per in summary["examples"].items():
        for lv in per["levels"]:
            cells = ", ".join(f"{v['vertex']}:{v['valence']} at ({v['x']:.3f}, {v['y']:.3f}): {v['R']:.3g} "
                              f"({v['R_navier']:.3g}) {v['shape']}" for v in lv["tuned_vertices"])
            print(f"  {ex} level {lv['level']}: {cells}")
    print(f"\nslopes against vertices, levels >= {FIT_FROM_LEVEL} (order in h = -2 slope):")
    for ex, per in summary["examples"].items():
        cells = "; ".join(f"{s} L2 {sl.signed(per[s]['l2']['slope'])} energy {sl.signed(per[s]['energy']['slope'])}"
                          for s, *_ in SERIES if per[s]["l2"]["slope"] is not None)
        print(f"  {ex}: {cells}")


def plot(summary, examples, outdir):
    plt = sl.pyplot()
    fig, axes = plt.subplots(len(ERRORS), len(examples), figsize=(13.5, 7.6), squeeze=False)
    for col, (ex, _, _, label, _) in enumerate(examples):
        per = summary["examples"][ex]
        for row, (e, _, title) in enumerate(ERRORS):
            ax = axes[row][col]
            # auto before the cup pass: where every vertex chose the cup they coincide, and the
            # dashed cup line stays visible on top.
            for s, legend, colour, marker, ls in (SERIES[0], SERIES[2], SERIES[1]):
                d = per[s][e]
                text = legend if d["slope"] is None else f"{legend}: slope {sl.signed(d['slope'])}"
                ax.loglog(per["vertices"], sl.plotted(d["errors"]), marker=marker, color=colour, ls=ls, lw=1.1,
                          ms=4.5, label=text)
            red = per["reduction_pct_finest"][f"auto_{e}"]
            verb = "lowers" if red >= 0 else "raises"
            ax.set_title(f"{label}\n{title}: at level {per['finest_level']} auto {verb} it by {abs(red):.0f} %",
                         fontsize=9)
            ax.set_xlabel("control vertices (levels 0, 1, …)")
            ax.set_ylabel("relative error against Navier")
            sl.vertex_ticks(ax, per["vertices"])
            ax.grid(True, which="major", lw=0.5, alpha=0.5)
            ax.legend(loc="lower left", frameon=True, fontsize=7)
    fig.suptitle("Simply supported plate [0, 10]², Catmull–Clark against IGA-tuned weights at the valence ≥ 5 "
                 f"vertices\n(slopes over levels ≥ {summary['fit_from_level']}; lowered by: 1 − tuned / classical)",
                 fontsize=10)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
