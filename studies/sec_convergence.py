#!/usr/bin/python3
"""SEC paper Fig. 3 (shape): Poisson relative L2 error against the control-mesh resolution.

The control meshes are a bundled mesh subdivided n = 0..3 times with `limsurf subdivide` (the same
limit surface, h halving per n). On each, -Δu = f is solved with `limsurf poisson` by

  dec          the control polygon's inner products,
  decsnap      the same with the vertices snapped to the limit surface,
  sec L=3      SEC inner products of level 3 (the paper's recommendation),
  secsnap L=3  the same on the level-3 mesh snapped to the limit surface,
  sec L=K-n    SEC pulling back the reference's own inner products (only the projection error of
               the control space is left),

and compared (`--reference-level K - n`) with DEC on the input subdivided K times: the same fine
mesh for every n (the paper's reference construction; it compares at level 7). The numbers go to
sec_convergence.csv, the least-squares slopes of log error against log (control vertices) to
sec_convergence.json, the plot (log-log, slopes in the legend) to sec_convergence.{png,svg}, and
a markdown table (as studies/sec_convergence.sh prints) to stdout. SEC L=3 is run only where
3 <= K - n (finer inner products than the reference's would be compared with a coarser solution).

  /usr/bin/python3 studies/sec_convergence.py build/release/cli/limsurf out/studies
  /usr/bin/python3 studies/sec_convergence.py build/release/cli/limsurf out/studies --reference-level 6

--quick: the torus only, n = 0..2, DEC and SEC L=K-n, K = 4 (a few seconds).
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import studylib as sl

NAME = "sec_convergence"

# (mesh, right-hand side, title): the two meshes of docs/VERIFICATION.md "Convergence".
CASES = [
    ("quad_torus.obj", "sin(x)", "quad_torus (all valences 4), f = sin x"),
    ("genus2.obj", "sin(2*x)", "genus2 (valences 3, 4, 5), f = sin 2x"),
]

# series key -> (method, level: int, "K-n" or None, legend label, colour, marker)
SERIES = {
    "dec": ("dec", None, "DEC", "tab:red", "o"),
    "decsnap": ("decsnap", None, "DECsnap", "tab:orange", "v"),
    "sec_L3": ("sec", 3, "SEC, L = 3", "tab:blue", "s"),
    "secsnap_L3": ("secsnap", 3, "SECsnap, L = 3", "tab:purple", "D"),
    "sec_LKn": ("sec", "K-n", "SEC, L = K − n", "tab:green", "^"),
}

COLUMNS = ["mesh", "rhs", "n", "vertices", "faces", "series", "method", "level", "fine_level",
           "reference_level", "reference_vertices", "l2_relative", "linf_relative"]


def extra_options(p):
    p.add_argument("--reference-level", type=int, default=None,
                   help="K: the reference is DEC on the input subdivided K times (default 5; 4 with --quick)")
    p.add_argument("--levels", type=int, default=None,
                   help="control meshes subdivided n = 0..N times (default 3; 2 with --quick)")


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    fine = args.reference_level if args.reference_level is not None else (4 if args.quick else 5)
    top = args.levels if args.levels is not None else (2 if args.quick else 3)
    if not 0 <= top < fine:
        sys.exit("error: need 0 <= --levels < --reference-level")
    cases = CASES[:1] if args.quick else CASES
    series = ["dec", "sec_LKn"] if args.quick else list(SERIES)

    rows = []
    with tempfile.TemporaryDirectory(prefix="limsurf-sec-") as work:
        tasks, keys = [], []
        for mesh_name, rhs, _ in cases:
            for n in range(top + 1):
                control = Path(work) / f"{Path(mesh_name).stem}_{n}.obj"
                sl.run_cli(args.limsurf, "subdivide", sl.mesh(mesh_name), "--scheme", "catmull-clark",
                           "--levels", str(n), "-o", str(control))
                faces = sl.run_json(args.limsurf, "info", str(control))["num_faces"]
                k = fine - n
                for key in series:
                    method, level, _, _, _ = SERIES[key]
                    if level == "K-n":
                        level = k
                    if level is not None and level > k:
                        continue
                    cmd = ["poisson", str(control), "--scheme", "catmull-clark", "--method", method,
                           "--rhs", rhs, "--reference-level", str(k)]
                    if level is not None:
                        cmd += ["--level", str(level)]
                    tasks.append(lambda cmd=cmd: sl.run_json(args.limsurf, *cmd))
                    keys.append(dict(mesh=mesh_name, rhs=rhs, n=n, faces=faces, series=key, method=method,
                                     level=level, fine_level=fine, reference_level=k))
        sl.log(f"{NAME}: {len(tasks)} poisson runs, reference DEC at level {fine}")
        for key, out in zip(keys, sl.run_all(args.jobs, tasks)):
            ref = out["reference"]
            rows.append(dict(key, vertices=out["vertices"], reference_vertices=ref["vertices"],
                             l2_relative=ref["l2_relative"], linf_relative=ref["linf_relative"]))

    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)

    # Slopes: least squares of log error against log vertices over all n of a series; orders:
    # log2 of successive ratios (h halves per n, so order = -2 slope).
    summary = {"reference_level": fine, "levels": top, "cases": {}}
    for mesh_name, rhs, title in cases:
        per = {}
        for key in series:
            pts = [r for r in rows if r["mesh"] == mesh_name and r["series"] == key]
            if len(pts) < 2:
                continue
            err = [r["l2_relative"] for r in pts]
            slope = sl.fit_slope([r["vertices"] for r in pts], err)
            per[key] = {"n": [r["n"] for r in pts], "vertices": [r["vertices"] for r in pts],
                        "l2_relative": err, "slope": slope, "order_h": -2 * slope,
                        "orders": [math.log2(q) for q in sl.ratios(err)]}
        summary["cases"][mesh_name] = {"rhs": rhs, "title": title, "series": per}
    sl.write_json(args.outdir / f"{NAME}.json", summary)

    plot(summary, series, args.outdir)
    print_tables(rows, summary, cases, series, fine)
    return 0


def plot(summary, series, outdir):
    plt = sl.pyplot()
    cases = summary["cases"]
    fig, axes = plt.subplots(1, len(cases), figsize=(max(6.5, 5.0 * len(cases)), 4.2), squeeze=False)
    for ax, (mesh_name, case) in zip(axes[0], cases.items()):
        for key in series:
            if key not in case["series"]:
                continue
            s = case["series"][key]
            _, _, label, colour, marker = SERIES[key]
            ax.loglog(s["vertices"], sl.plotted(s["l2_relative"]), marker=marker, color=colour, lw=1.3, ms=5,
                      label=f"{label}: slope {sl.signed(s['slope'])} ($h^{{{s['order_h']:.1f}}}$)")
        ax.set_title(case["title"])
        ax.set_xlabel("control vertices (input subdivided n = 0, 1, … times)")
        ax.set_ylabel(f"relative L² difference from DEC at level {summary['reference_level']}")
        sl.vertex_ticks(ax, sorted({v for s in case["series"].values() for v in s["vertices"]}))
        ax.grid(True, which="major", lw=0.5, alpha=0.5)
        ax.grid(True, which="minor", lw=0.3, alpha=0.25)
        ax.legend(loc="lower left", frameon=True)
    fig.suptitle("Poisson −Δu = f on Catmull–Clark limit surfaces: DEC vs SEC (SEC paper Fig. 3, shape)",
                 fontsize=10)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


def print_tables(rows, summary, cases, series, fine):
    for mesh_name, rhs, _ in cases:
        print(f"\n{mesh_name}, f = {rhs}, reference DEC at level {fine}\n")
        print("| n | vertices | faces | " + " | ".join(SERIES[k][2] for k in series) + " |")
        print("|---|---|---|" + "---|" * len(series))
        ns = sorted({r["n"] for r in rows if r["mesh"] == mesh_name})
        for n in ns:
            at = {r["series"]: r for r in rows if r["mesh"] == mesh_name and r["n"] == n}
            first = next(iter(at.values()))
            cells = [f"{at[k]['l2_relative']:.3e}" if k in at else "–" for k in series]
            print(f"| {n} | {first['vertices']} | {first['faces']} | " + " | ".join(cells) + " |")
        per = summary["cases"][mesh_name]["series"]
        print("\nslopes against vertices (orders in h, log2 of successive ratios):")
        for k, s in per.items():
            orders = ", ".join(f"{o:.2f}" for o in s["orders"])
            print(f"  {SERIES[k][2]}: {s['slope']:.2f} ({orders})")


if __name__ == "__main__":
    sys.exit(main())
