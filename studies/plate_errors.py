#!/usr/bin/python3
"""Kirchhoff-Love plate errors against Navier's series, by level.

`limsurf plate MESH --levels L --json` solves the simply supported plate under a uniform load on
the limit surface of a planar Catmull-Clark control mesh refined 0..L times (the same plate; the
command takes Catmull-Clark only) and reports relative errors against the Navier series solution
of the rectangle: L2 and energy norms, the deflection at the centre (where the exact deflection is
largest) and at the quarter point. Three meshes: the regular 4x4 grid on [-1, 1]^2, and the
unstructured plate_ev35 (valences 3 and 5 inside) and plate_asym (valences 3, 5, 6, no symmetry)
on [0, 10]^2. Written:

  plate_errors.csv   one row per (mesh, level): vertices, faces, deflections and the relative errors
  plate_errors.json  the slopes of log error against log (control vertices), least squares over
                     levels >= 1 (level 0 is pre-asymptotic on the unstructured meshes), and the
                     factors per level
  plate_errors.{png,svg}  the L2, energy and maximum (centre) deflection errors, log-log

Orders in h are -2 x slope (the vertex count grows like h^-2).

  /usr/bin/python3 studies/plate_errors.py build/release/cli/limsurf out/studies

--quick: quad_grid and plate_ev35, levels 0..2 (a few seconds).
"""

from __future__ import annotations

import sys

import studylib as sl

NAME = "plate_errors"

# (mesh, label, colour, marker, full levels)
CASES = [
    ("quad_grid.obj", "quad_grid (regular 4×4)", "tab:blue", "o", 4),
    ("plate_ev35.obj", "plate_ev35 (valences 3, 5)", "tab:green", "s", 4),
    ("plate_asym.obj", "plate_asym (valences 3, 5, 6)", "tab:red", "^", 4),
]
QUICK = {"quad_grid.obj": 2, "plate_ev35.obj": 2}

ERRORS = [  # (key in the CLI's "navier" object, column, panel title)
    ("l2_relative_error", "l2_relative_error", "L² error of the deflection"),
    ("energy_relative_error", "energy_relative_error", "energy-norm error"),
    ("centre_relative_error", "centre_relative_error", "maximum deflection (centre) error"),
]

COLUMNS = ["mesh", "level", "vertices", "faces", "centre_deflection", "navier_centre_deflection",
           "max_deflection", "quarter_deflection", "navier_quarter_deflection", "l2_relative_error",
           "energy_relative_error", "centre_relative_error", "quarter_relative_error"]

FIT_FROM_LEVEL = 1


def extra_options(p):
    p.add_argument("--levels", type=int, default=None,
                   help="levels 0..L on every mesh (default 4; --quick: 2 on quad_grid and plate_ev35)")


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    cases = []
    for mesh_name, label, colour, marker, full in CASES:
        if args.quick and mesh_name not in QUICK:
            continue
        levels = args.levels if args.levels is not None else (QUICK[mesh_name] if args.quick else full)
        cases.append((mesh_name, label, colour, marker, levels))
    # The costliest (plate_asym, last) first: with two jobs it overlaps the others.
    order = list(reversed(range(len(cases))))
    tasks = [lambda c=cases[i]: sl.run_json(args.limsurf, "plate", sl.mesh(c[0]), "--levels", str(c[4]))
             for i in order]
    results = [None] * len(cases)
    for i, out in zip(order, sl.run_all(args.jobs, tasks)):
        results[i] = out

    rows, summary = [], {"fit_from_level": FIT_FROM_LEVEL, "load": "uniform", "support": "simply",
                         "cases": {}}
    for (mesh_name, label, _, _, levels), out in zip(cases, results):
        if out["load"] != "uniform" or out["support"] != "simply" or len(out["levels"]) != levels + 1:
            sys.exit(f"error: {mesh_name}: unexpected plate output")
        if isinstance(out.get("navier"), str):
            sys.exit(f"error: {mesh_name}: {out['navier']}")
        for lv in out["levels"]:
            nav = lv.get("navier")
            if nav is None:
                sys.exit(f"error: {mesh_name}: no Navier comparison (not a rectangle?)")
            rows.append(dict(mesh=mesh_name, level=lv["level"], vertices=lv["vertices"], faces=lv["faces"],
                             centre_deflection=lv["centre_deflection"],
                             navier_centre_deflection=nav["centre_deflection"],
                             max_deflection=lv["max_deflection"], quarter_deflection=lv["quarter_deflection"],
                             navier_quarter_deflection=nav["quarter_deflection"],
                             l2_relative_error=nav["l2_relative_error"],
                             energy_relative_error=nav["energy_relative_error"],
                             centre_relative_error=nav["centre_relative_error"],
                             quarter_relative_error=nav["quarter_relative_error"]))
        mine = [r for r in rows if r["mesh"] == mesh_name]
        fit = [r for r in mine if r["level"] >= FIT_FROM_LEVEL]
        per = {"label": label, "rectangle": out["rectangle"], "vertices": [r["vertices"] for r in mine]}
        for key, column, _ in ERRORS:
            err = [abs(r[column]) for r in mine]
            slope = sl.fit_slope([r["vertices"] for r in fit], [abs(r[column]) for r in fit]) \
                if len(fit) >= 2 else None
            per[column] = {"errors": err, "factors": sl.ratios(err), "slope": slope,
                           "order_h": None if slope is None else -2 * slope}
        summary["cases"][mesh_name] = per
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(summary, cases, args.outdir)

    print("| mesh | level | vertices | L2 | energy | centre |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['mesh']} | {r['level']} | {r['vertices']} | {r['l2_relative_error']:.2e} |"
              f" {r['energy_relative_error']:.2e} | {abs(r['centre_relative_error']):.2e} |")
    print(f"\nslopes against vertices, levels >= {FIT_FROM_LEVEL} (order in h = -2 slope):")
    for mesh_name, per in summary["cases"].items():
        cells = ", ".join(f"{c.split('_')[0]} {sl.signed(per[c]['slope'])}" for _, c, _ in ERRORS
                          if per[c]["slope"] is not None)
        print(f"  {mesh_name}: {cells}")
    return 0


def plot(summary, cases, outdir):
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, len(ERRORS), figsize=(13.5, 4.3))
    for ax, (_, column, title) in zip(axes, ERRORS):
        for mesh_name, label, colour, marker, _ in cases:
            per = summary["cases"][mesh_name]
            s = per[column]
            text = label if s["slope"] is None else \
                f"{label}: slope {sl.signed(s['slope'])} ($h^{{{s['order_h']:.1f}}}$)"
            ax.loglog(per["vertices"], sl.plotted(s["errors"]), marker=marker, color=colour, lw=1.2, ms=4.5, label=text)
        ax.set_title(title)
        ax.set_xlabel("control vertices (levels 0, 1, …)")
        ax.set_ylabel("relative error against Navier")
        ax.xaxis.set_minor_locator(plt.NullLocator())
        ax.grid(True, which="major", lw=0.5, alpha=0.5)
        ax.legend(loc="lower left", frameon=True, fontsize=7)
    fig.suptitle("Simply supported Kirchhoff–Love plate, uniform load, Catmull–Clark limit surface "
                 f"(slopes fitted over levels ≥ {summary['fit_from_level']})", fontsize=10)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
