#!/usr/bin/python3
"""IGA-tuned Catmull-Clark weights: the error curves of Figs. 6 and 7 and the tuned weights by valence.

`limsurf tune --valence V --shape cup|saddle --quadrature Q --samples M --json` (iga-tuned-catmull-
clark-weights §3.3) gives, for the rule of an extraordinary vertex of valence V, the relative
thin-plate energy-norm errors (32) of the cup xi1^2 + xi2^2 and the saddle xi1^2 - xi2^2 over the
subdominant eigenvalue lambda (the curve, M samples over the feasible range), the lambda that
minimises the searched shape's error while the other shape's error stays at or below Catmull-
Clark's ("tuned"), the minimum without that protection ("unconstrained") and Catmull-Clark's own
weights and errors ("classical"). Where the exact system (30) has two real candidates the curve
keeps the one better for the searched shape, so the cup and the saddle runs can differ there; the
cup panels use the cup runs' curves, the saddle panels the saddle runs'. Written:

  tuned_weights.csv        one row per run (valence, shape, Gauss points): the feasible range, the
                           tuned, unconstrained and classical lambda, weights and both errors, and
                           the tuned shape's error reduction against Catmull-Clark (percent)
  tuned_weights_curve.csv  valence 5: the curves, one row per (Gauss points, searched shape, lambda)
  tuned_weights.json       the table by valence and shape, and at valence 5 the tuned lambda and
                           the spread of the curves over the numbers of Gauss points (Fig. 6)
  tuned_weights.{png,svg}  Fig. 6a/6b (cup and saddle errors over lambda for 2..6 Gauss points)
                           and Fig. 7 (4 Gauss points: both errors, Catmull-Clark's errors and the
                           tuned optima), lambda restricted to [0.45, 0.70]

  /usr/bin/python3 studies/tuned_weights.py build/release/cli/limsurf out/studies

--quick: valence 5 only, 4 Gauss points only, 21 samples (a few seconds).
"""

from __future__ import annotations

import sys

import studylib as sl

NAME = "tuned_weights"

VALENCES = [3, 5, 6, 7, 8, 10, 12]
QUADRATURES = [2, 3, 4, 5, 6]
SHAPES = ["cup", "saddle"]
FIG7_QUADRATURE = 4  # the paper's 4 x 4 Gauss points
FIG_VALENCE = 5
SAMPLES = 121  # curve spacing ~0.004 over valence 5's feasible range [0.32, 0.82]
QUICK_SAMPLES = 21
WINDOW = (0.45, 0.70)  # the plotted lambda axis (Figs. 6 and 7)

WEIGHT_KEYS = ["lambda", "alpha", "beta", "gamma", "constraint", "lambda3", "lambda4", "cup_error", "saddle_error"]

COLUMNS = (["valence", "shape", "quadrature", "samples", "feasible_lo", "feasible_hi", "protection_binds"]
           + [f"tuned_{k}" for k in WEIGHT_KEYS]
           + [f"unconstrained_{k}" for k in WEIGHT_KEYS]
           + ["classical_lambda", "classical_alpha", "classical_cup_error", "classical_saddle_error",
              "reduction_pct", "other_change_pct"])

CURVE_COLUMNS = ["valence", "quadrature", "shape"] + WEIGHT_KEYS


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    samples = QUICK_SAMPLES if args.quick else SAMPLES
    quadratures = [FIG7_QUADRATURE] if args.quick else QUADRATURES
    valences = [FIG_VALENCE] if args.quick else VALENCES
    runs = [(FIG_VALENCE, shape, q) for q in quadratures for shape in SHAPES]
    runs += [(v, shape, FIG7_QUADRATURE) for v in valences if v != FIG_VALENCE for shape in SHAPES]
    # The costliest (high valences) first: with two jobs they overlap the others.
    order = sorted(range(len(runs)), key=lambda i: -runs[i][0])
    tasks = [lambda r=runs[i]: sl.run_json(args.limsurf, "tune", "--valence", str(r[0]), "--shape", r[1],
                                           "--quadrature", str(r[2]), "--samples", str(samples))
             for i in order]
    results = {}
    for i, out in zip(order, sl.run_all(args.jobs, tasks)):
        results[runs[i]] = out

    rows, curve_rows = [], []
    for (valence, shape, q) in sorted(results):
        out = results[(valence, shape, q)]
        if (out.get("command") != "tune" or out["valence"] != valence or out["shape"] != shape
                or out["quadrature_points"] != q or len(out["curve"]) != samples):
            sys.exit(f"error: tune --valence {valence} --shape {shape} --quadrature {q}: unexpected output")
        tuned, free, cc = out["tuned"], out["unconstrained"], out["classical"]
        other = "saddle" if shape == "cup" else "cup"
        row = dict(valence=valence, shape=shape, quadrature=q, samples=samples,
                   feasible_lo=out["feasible_range"][0], feasible_hi=out["feasible_range"][1],
                   protection_binds=int(bool(out["protection_binds"])),
                   classical_lambda=cc["lambda"], classical_alpha=cc["alpha"],
                   classical_cup_error=cc["cup_error"], classical_saddle_error=cc["saddle_error"],
                   reduction_pct=100.0 * (1.0 - tuned[f"{shape}_error"] / cc[f"{shape}_error"]),
                   other_change_pct=100.0 * (tuned[f"{other}_error"] / cc[f"{other}_error"] - 1.0))
        for k in WEIGHT_KEYS:
            row[f"tuned_{k}"] = tuned[k]
            row[f"unconstrained_{k}"] = free[k]
        rows.append(row)
        if valence == FIG_VALENCE:
            for w in out["curve"]:
                curve_rows.append(dict(valence=valence, quadrature=q, shape=shape, **{k: w[k] for k in WEIGHT_KEYS}))
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    sl.write_csv(args.outdir / f"{NAME}_curve.csv", CURVE_COLUMNS, curve_rows)

    summary = {"samples": samples, "fig7_quadrature": FIG7_QUADRATURE, "window": list(WINDOW),
               "valences": {}, "valence5_by_quadrature": {}}
    for r in rows:
        if r["quadrature"] != FIG7_QUADRATURE:
            continue
        per = summary["valences"].setdefault(str(r["valence"]), {
            "feasible_range": [r["feasible_lo"], r["feasible_hi"]],
            "classical": {"lambda": r["classical_lambda"], "alpha": r["classical_alpha"],
                          "cup_error": r["classical_cup_error"], "saddle_error": r["classical_saddle_error"]}})
        per[r["shape"]] = {
            "tuned": {k: r[f"tuned_{k}"] for k in WEIGHT_KEYS},
            "unconstrained": {k: r[f"unconstrained_{k}"] for k in WEIGHT_KEYS},
            "protection_binds": bool(r["protection_binds"]),
            "reduction_pct": r["reduction_pct"], "other_change_pct": r["other_change_pct"]}
    for q in quadratures:
        by = {r["shape"]: r for r in rows if r["valence"] == FIG_VALENCE and r["quadrature"] == q}
        summary["valence5_by_quadrature"][str(q)] = {
            s: {"tuned_lambda": by[s]["tuned_lambda"], f"tuned_{s}_error": by[s][f"tuned_{s}_error"],
                "unconstrained_lambda": by[s]["unconstrained_lambda"]} for s in SHAPES}
    summary["valence5_quadrature_spread"] = quadrature_spread(curve_rows, quadratures)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(rows, curve_rows, quadratures, args.outdir)
    print_summary(rows, summary)
    return 0


def in_window(lam: float) -> bool:
    return WINDOW[0] <= lam <= WINDOW[1]


def quadrature_spread(curve_rows, quadratures):
    """Fig. 6's claim in numbers: over the window, the largest difference of each shape's error
    between any number of Gauss points and the most (relative to that error), and the spread of
    the tuned lambda over the numbers of Gauss points."""
    out = {}
    finest = max(quadratures)
    for shape in SHAPES:
        key = f"{shape}_error"
        ref = {w["lambda"]: w[key] for w in curve_rows if w["quadrature"] == finest and w["shape"] == shape}
        worst = 0.0
        for w in curve_rows:
            if w["shape"] == shape and in_window(w["lambda"]) and w["lambda"] in ref:
                worst = max(worst, abs(w[key] - ref[w["lambda"]]) / ref[w["lambda"]])
        out[shape] = {"max_relative_difference_to_q%d" % finest: worst}
    return out


def print_summary(rows, summary):
    print("| valence | shape | feasible lambda | tuned lambda | alpha | beta | gamma | cup error "
          "(CC) | saddle error (CC) | reduction % | unconstrained lambda (cup, saddle error) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["quadrature"] != FIG7_QUADRATURE:
            continue
        print(f"| {r['valence']} | {r['shape']} | [{r['feasible_lo']:.4f}, {r['feasible_hi']:.4f}] |"
              f" {r['tuned_lambda']:.6f} | {r['tuned_alpha']:.6f} | {r['tuned_beta']:.6f} | {r['tuned_gamma']:.6f} |"
              f" {r['tuned_cup_error']:.4f} ({r['classical_cup_error']:.4f}) |"
              f" {r['tuned_saddle_error']:.4f} ({r['classical_saddle_error']:.4f}) | {r['reduction_pct']:.1f} |"
              f" {r['unconstrained_lambda']:.4f} ({r['unconstrained_cup_error']:.4f},"
              f" {r['unconstrained_saddle_error']:.4f}) |")
    print(f"\nvalence {FIG_VALENCE}, tuned lambda by Gauss points per direction:")
    for q, per in summary["valence5_by_quadrature"].items():
        print(f"  {q}: cup {per['cup']['tuned_lambda']:.6f} (error {per['cup']['tuned_cup_error']:.4f}),"
              f" saddle {per['saddle']['tuned_lambda']:.6f} (error {per['saddle']['tuned_saddle_error']:.4f})")
    for shape, d in summary["valence5_quadrature_spread"].items():
        (k, v), = d.items()
        print(f"  {shape} curves on lambda in [{WINDOW[0]}, {WINDOW[1]}]: {k.replace('_', ' ')} {v:.2e}")


def plot(rows, curve_rows, quadratures, outdir):
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.3))
    colours = {2: "tab:blue", 3: "tab:orange", 4: "tab:green", 5: "tab:red", 6: "tab:purple"}
    for ax, shape, title in ((axes[0], "cup", "Fig. 6a: cup ξ₁² + ξ₂²"),
                             (axes[1], "saddle", "Fig. 6b: saddle ξ₁² − ξ₂²")):
        for q in quadratures:
            pts = [w for w in curve_rows if w["quadrature"] == q and w["shape"] == shape and in_window(w["lambda"])]
            ax.plot([w["lambda"] for w in pts], sl.plotted([w[f"{shape}_error"] for w in pts]),
                    color=colours.get(q, "black"), lw=1.0, marker=".", ms=3, label=f"{q}×{q} Gauss points")
        ax.set_title(f"{title}, valence {FIG_VALENCE}")
        ax.set_ylabel("relative energy-norm error")
    ax = axes[2]
    q = FIG7_QUADRATURE
    styles = {"cup": ("tab:blue", "o"), "saddle": ("tab:red", "s")}
    by = {r["shape"]: r for r in rows if r["valence"] == FIG_VALENCE and r["quadrature"] == q}
    for shape in SHAPES:
        colour, marker = styles[shape]
        pts = [w for w in curve_rows if w["quadrature"] == q and w["shape"] == shape and in_window(w["lambda"])]
        ax.plot([w["lambda"] for w in pts], sl.plotted([w[f"{shape}_error"] for w in pts]),
                color=colour, lw=1.1, label=f"{shape}, tuned weights")
        r = by[shape]
        cc = r[f"classical_{shape}_error"]
        ax.axhline(float(f"{cc:.4g}"), color=colour, lw=0.8, ls="--")
        ax.plot([float(f"{r['classical_lambda']:.4g}")], [float(f"{cc:.4g}")], marker=marker, color=colour,
                mfc="white", ms=6, ls="none", label=f"{shape}, Catmull–Clark (λ = {r['classical_lambda']:.5f})")
        lam = r["tuned_lambda"]
        ax.axvline(float(f"{lam:.4g}"), color=colour, lw=0.8, ls=":")
        ax.plot([float(f"{lam:.4g}")], [float(f"{r[f'tuned_{shape}_error']:.4g}")], marker=marker, color=colour,
                ms=6, ls="none", label=f"{shape} optimum λ = {lam:.3f}")
    ax.set_title(f"Fig. 7: {q}×{q} Gauss points, valence {FIG_VALENCE}")
    ax.set_ylabel("relative energy-norm error")
    for ax in axes:
        ax.set_xlim(*WINDOW)
        ax.set_ylim(0.0, 1.5 * ax.get_ylim()[1])  # room for the legend above the curves
        ax.set_xlabel("subdominant eigenvalue λ")
        ax.grid(True, lw=0.5, alpha=0.5)
        ax.legend(loc="upper center", frameon=True, fontsize=7)
    fig.suptitle("IGA-tuned Catmull–Clark weights: thin-plate energy-norm errors of the quadratic shapes "
                 "(limsurf tune; dashed: Catmull–Clark's errors)", fontsize=10)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
