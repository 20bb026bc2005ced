#!/usr/bin/python3
"""The shell obstacle course: Kirchhoff-Love shells on Catmull-Clark limit surfaces against published values.

`limsurf shell --json` (docs/guide/shell.md; iga-with-catmull-clark §5) on the three classical tests of
Belytschko et al. (1985) and MacNeal and Harder (1985), each control mesh refined L = 0..4 times with its
points projected onto the exact surface (`--surface`):

  Scordelis-Lo roof      R = 25, L = 50, 80 degrees, t = 0.25, E = 4.32e8, nu = 0, self-weight 90,
                         rigid diaphragms: the vertical displacement at the middle of a free edge,
                         0.3006 (the converged Kirchhoff-Love value; 0.3024 with transverse shear)
  pinched cylinder       R = 300, L = 600, t = 3, E = 3e6, nu = 0.3, two unit loads pinching it,
                         rigid diaphragms: the radial displacement under a load, 1.8248e-5
  pinched hemisphere     R = 10 with an 18-degree hole, t = 0.04, E = 6.825e7, nu = 0.3, four loads of
                         2 at the equator: the displacement under a load, 0.0924 (0.0940 for the
                         thin-shell limit)

Written:

  shells.csv          one row per (problem, level): control vertices, unknowns, strain energy, the
                      displacement, its ratio to the reference, the relative error, and the relative
                      change from the level before (how far the discretisation still moves)
  shells.json         per problem: the references, the finest displacement and its ratio to each,
                      the log-log slope of the change per level over the control vertices
  shells.{png,svg}    (a) displacement / reference against control vertices, with the other
                      published values; (b) the relative change per level

  /usr/bin/python3 studies/shells.py build/release/cli/limsurf out/studies

--quick: L = 0..2 (a few seconds).
"""

from __future__ import annotations

import sys

import studylib as sl

NAME = "shells"

LEVELS = 4
QUICK_LEVELS = 2

# name: (mesh, arguments, probe component, sign, reference, label of the reference)
PROBLEMS = {
    "scordelis_lo": ("shell_scordelis_lo.obj",
                     ["--E", "4.32e8", "--nu", "0", "--thickness", "0.25", "--gravity", "90",
                      "--fix", "abs(y) > 24.999:xz", "--probe", "16.06969024216348,0,19.15111107797445",
                      "--surface", "x^2+z^2-625"], 2, -1.0, 0.3006, "0.3006 (Kirchhoff–Love)"),
    "pinched_cylinder": ("shell_pinched_cylinder.obj",
                         ["--E", "3e6", "--nu", "0.3", "--thickness", "3", "--fix", "1:xy",
                          "--point-load", "300,0,0:-1,0,0", "--point-load", "-300,0,0:1,0,0",
                          "--probe", "300,0,0", "--surface", "x^2+y^2-90000", "--degree", "6", "--tiles", "0"],
                         0, -1.0, 1.8248e-5, "1.8248e-5 (Flügge's series)"),
    "pinched_hemisphere": ("shell_hemisphere.obj",
                           ["--E", "6.825e7", "--nu", "0.3", "--thickness", "0.04",
                            "--point-load", "10,0,0:2,0,0", "--point-load", "-10,0,0:-2,0,0",
                            "--point-load", "0,10,0:0,-2,0", "--point-load", "0,-10,0:0,2,0",
                            "--probe", "10,0,0", "--surface", "x^2+y^2+z^2-100"], 0, 1.0, 0.0924,
                           "0.0924 (MacNeal–Harder)"),
}
TITLES = {"scordelis_lo": "Scordelis–Lo roof", "pinched_cylinder": "pinched cylinder",
          "pinched_hemisphere": "pinched hemisphere"}
# Other published values drawn for comparison: the roof with shear, the hemisphere's thin-shell limit.
OTHER_REFERENCES = {"scordelis_lo": (0.3024, "0.3024 (with shear)"),
                    "pinched_hemisphere": (0.0940, "0.0940 (thin-shell limit)")}

COLUMNS = ["problem", "level", "vertices", "faces", "unknowns", "rigid_motions_removed", "strain_energy",
           "displacement", "reference", "ratio", "relative_error", "change"]


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    levels = QUICK_LEVELS if args.quick else LEVELS
    names = list(PROBLEMS)
    tasks = [lambda n=n: sl.run_json(args.limsurf, "shell", sl.mesh(PROBLEMS[n][0]), *PROBLEMS[n][1],
                                     "--levels", str(levels)) for n in names]
    rows = []
    for name, out in zip(names, sl.run_all(args.jobs, tasks)):
        _, _, component, sign, reference, _ = PROBLEMS[name]
        if len(out["levels"]) != levels + 1:
            sys.exit(f"error: shell {name}: {len(out['levels'])} levels, expected {levels + 1}")
        before = None
        for level in out["levels"]:
            u = sign * level["probes"][0]["displacement"][component]
            rows.append(dict(problem=name, level=level["level"], vertices=level["vertices"], faces=level["faces"],
                             unknowns=level["unknowns"], rigid_motions_removed=level["rigid_motions_removed"],
                             strain_energy=level["strain_energy"], displacement=u, reference=reference,
                             ratio=u / reference, relative_error=abs(u - reference) / reference,
                             change=None if before is None else abs(u - before) / abs(u)))
            before = u
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    summary = {"levels": levels, "problems": {}}
    for name in names:
        mine = [r for r in rows if r["problem"] == name]
        changed = [r for r in mine if r["change"] is not None]
        entry = {"reference": PROBLEMS[name][4], "finest_displacement": mine[-1]["displacement"],
                 "finest_ratio": mine[-1]["ratio"], "finest_vertices": mine[-1]["vertices"],
                 "change_slope": sl.fit_slope([r["vertices"] for r in changed[-3:]], [r["change"] for r in changed[-3:]])}
        if name in OTHER_REFERENCES:
            entry["other_reference"] = OTHER_REFERENCES[name][0]
            entry["finest_ratio_to_other"] = mine[-1]["displacement"] / OTHER_REFERENCES[name][0]
        summary["problems"][name] = entry
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(rows, names, args.outdir)
    print_summary(rows)
    return 0


def print_summary(rows):
    print("| problem | level | control vertices | displacement | / reference | change from the level before |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        change = "" if r["change"] is None else f"{r['change']:.2e}"
        print(f"| {r['problem']} | {r['level']} | {r['vertices']} | {r['displacement']:.6g} | {r['ratio']:.5f} |"
              f" {change} |")


STYLE = {"scordelis_lo": ("tab:blue", "o"), "pinched_cylinder": ("tab:red", "s"),
         "pinched_hemisphere": ("tab:green", "^")}


def plot(rows, names, outdir):
    plt = sl.pyplot()
    fig, (ax_ratio, ax_error) = plt.subplots(1, 2, figsize=(11.0, 4.4))
    for name in names:
        colour, marker = STYLE[name]
        mine = [r for r in rows if r["problem"] == name]
        vertices = [r["vertices"] for r in mine]
        ax_ratio.semilogx(vertices, sl.plotted([r["ratio"] for r in mine]), color=colour, marker=marker, ms=5,
                          lw=1.0, label=f"{TITLES[name]}: reference {PROBLEMS[name][5]}")
        if name in OTHER_REFERENCES:
            value, label = OTHER_REFERENCES[name]
            ax_ratio.axhline(float(f"{value / PROBLEMS[name][4]:.4g}"), color=colour, lw=0.7, ls=":",
                             label=f"{TITLES[name]}: {label}")
        changed = [r for r in mine if r["change"] is not None]
        ax_error.loglog([r["vertices"] for r in changed], sl.plotted([r["change"] for r in changed]), color=colour,
                        marker=marker, ms=5, lw=1.0, label=TITLES[name])
    ax_ratio.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax_ratio.set_ylim(0.94, 1.03)  # the coarsest levels of the pinched problems (0.18-0.95) lie below
    ax_ratio.text(0.02, 0.03, "pinched problems at levels 0–1: 0.18–0.95 (below the axis)",
                  transform=ax_ratio.transAxes, fontsize=7, color="0.35")
    ax_ratio.set_xlabel("control vertices")
    ax_ratio.set_ylabel("displacement / reference")
    ax_ratio.set_title("(a) the shell obstacle course, Catmull–Clark")
    ax_ratio.legend(loc="lower right", fontsize=6.5, bbox_to_anchor=(1.0, 0.07))
    ax_error.set_xlabel("control vertices")
    ax_error.set_ylabel("|u_L − u_(L−1)| / |u_L|")
    ax_error.set_title("(b) the change per refinement level")
    ax_error.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
