#!/usr/bin/python3
"""The exact limit volume against the volumes of the subdivided control polyhedra, by level.

`limsurf volume MESH --scheme S --levels L --json` gives the volume enclosed by the limit surface,
exactly (trilinear forms), and the volumes of the control polyhedra of levels 0..L. The polyhedra
converge to the limit surface like h^2, so their volumes approach the exact one by a factor of
about 4 per level (h halves). This study runs Catmull-Clark, Loop and Doo-Sabin on bundled
closed meshes, regular (the tori) and with extraordinary vertices or faces (cube, icosahedron,
genus 2), and writes

  volume_levels.csv   one row per (scheme, mesh, level): the polyhedral volume, the exact volume,
                      the relative difference, the factor from the level before, and the
                      Richardson extrapolation (4 V_l - V_{l-1}) / 3 of the polyhedral volumes
                      (an independent witness of the exact value)
  volume_levels.json  the factors per level and the last extrapolation error per case
  volume_levels.{png,svg}  the relative difference (log scale) and the factor per level

  /usr/bin/python3 studies/volume_levels.py build/release/cli/limsurf out/studies

--quick: levels 0..3 (under a second of CLI time).
"""

from __future__ import annotations

import sys

import studylib as sl

NAME = "volume_levels"

SCHEME_LABEL = {"catmull-clark": "Catmull–Clark", "loop": "Loop", "doo-sabin": "Doo–Sabin"}
SCHEME_COLOUR = {"catmull-clark": "tab:blue", "loop": "tab:green", "doo-sabin": "tab:red"}

# (scheme, mesh, what is irregular about it, line style, marker)
CASES = [
    ("catmull-clark", "quad_torus.obj", "regular", "-", "o"),
    ("catmull-clark", "cube.obj", "8 vertices of valence 3", "--", "s"),
    ("catmull-clark", "genus2.obj", "valences 3, 5", ":", "^"),
    ("loop", "tri_torus.obj", "regular", "-", "o"),
    ("loop", "icosahedron.obj", "12 vertices of valence 5", "--", "D"),
    ("doo-sabin", "quad_torus.obj", "regular", "-", "o"),
    ("doo-sabin", "cube.obj", "8 triangles after one step", "--", "s"),
]

COLUMNS = ["scheme", "mesh", "level", "faces", "polyhedral_volume", "exact_volume", "difference",
           "relative_difference", "factor", "richardson_volume", "richardson_relative"]


def extra_options(p):
    p.add_argument("--levels", type=int, default=None, help="levels 0..L (default 6; 3 with --quick)")


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    levels = args.levels if args.levels is not None else (3 if args.quick else 6)
    if levels < 2:
        sys.exit("error: --levels must be 2 or more (a factor needs two differences)")

    tasks = [lambda s=s, m=m: sl.run_json(args.limsurf, "volume", sl.mesh(m), "--scheme", s,
                                          "--levels", str(levels))
             for s, m, *_ in CASES]
    results = sl.run_all(args.jobs, tasks)

    rows, summary = [], {"levels": levels, "cases": []}
    for (scheme, mesh_name, irregular, _, _), out in zip(CASES, results):
        exact = out["volume"]
        poly = out["polyhedral"]
        if len(poly) != levels + 1:
            sys.exit(f"error: {mesh_name} ({scheme}): {len(poly)} polyhedral levels, asked for {levels + 1}")
        rel = [abs(p["relative_difference"]) for p in poly]
        factors = [None] + sl.ratios(rel)
        for i, p in enumerate(poly):
            rich = None if i == 0 else (4 * p["volume"] - poly[i - 1]["volume"]) / 3
            rows.append(dict(scheme=scheme, mesh=mesh_name, level=p["level"], faces=p["faces"],
                             polyhedral_volume=p["volume"], exact_volume=exact, difference=p["difference"],
                             relative_difference=p["relative_difference"], factor=factors[i],
                             richardson_volume=rich,
                             richardson_relative=None if rich is None else abs(rich - exact) / abs(exact)))
        last = rows[-1]
        summary["cases"].append({
            "scheme": scheme, "mesh": mesh_name, "irregular": irregular, "exact_volume": exact,
            "relative_difference": rel, "factors": factors[1:], "last_factor": factors[-1],
            "richardson_relative_last": last["richardson_relative"],
            "faces_last": last["faces"]})
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(summary, args.outdir)

    print(f"| scheme | mesh | exact volume | rel. difference, level 0 | level {levels} | factors per level |"
          f" Richardson, level {levels} |")
    print("|---|---|---|---|---|---|---|")
    for c in summary["cases"]:
        f = ", ".join(f"{x:.2f}" for x in c["factors"])
        print(f"| {SCHEME_LABEL[c['scheme']]} | {c['mesh']} | {c['exact_volume']:.12g} |"
              f" {c['relative_difference'][0]:.2e} | {c['relative_difference'][-1]:.2e} | {f} |"
              f" {c['richardson_relative_last']:.1e} |")
    return 0


def plot(summary, outdir):
    plt = sl.pyplot()
    fig, (ax, axf) = plt.subplots(1, 2, figsize=(10.0, 4.2), gridspec_kw={"width_ratios": [1.25, 1]})
    levels = list(range(summary["levels"] + 1))
    styles = {(s, m): (ls, mk) for s, m, _, ls, mk in CASES}
    for c in summary["cases"]:
        ls, mk = styles[(c["scheme"], c["mesh"])]
        colour = SCHEME_COLOUR[c["scheme"]]
        name = f"{SCHEME_LABEL[c['scheme']]}, {c['mesh'].removesuffix('.obj')}"
        ax.semilogy(levels, sl.plotted(c["relative_difference"]), ls=ls, marker=mk, color=colour, lw=1.2, ms=4.5,
                    label=f"{name} ({c['irregular']})")
        axf.plot(levels[1:], sl.plotted(c["factors"]), ls=ls, marker=mk, color=colour, lw=1.2, ms=4.5,
                 label=f"{name}: last {c['last_factor']:.3f}")
    ax.set_xlabel("subdivision level of the control polyhedron")
    ax.set_ylabel("|polyhedral − exact| / exact volume")
    ax.set_title("Polyhedral volumes converge to the exact limit volume")
    ax.set_xticks(levels)
    ax.grid(True, which="major", lw=0.5, alpha=0.5)
    ax.legend(loc="lower left", frameon=True)
    axf.axhline(4.0, color="0.3", lw=0.8, ls="--")
    axf.set_xlabel("level l")
    axf.set_ylabel("factor: difference at l − 1 / difference at l")
    axf.set_title("Convergence factor per level (→ 4: O(h²))")
    axf.set_xticks(levels[1:])
    axf.set_ylim(2.0, 8.5)
    axf.grid(True, lw=0.5, alpha=0.5)
    axf.legend(loc="upper right", frameon=True)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
