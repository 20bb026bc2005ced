#!/usr/bin/python3
"""SEC paper §4.2 and Figs. 6, 9: heat-method geodesics, DEC vs SEC vs the reference.

`limsurf geodesic --json` from control vertex 0 on the bundled genus2 (Catmull–Clark) and tri_torus (Loop)
meshes by dec, decsnap, sec and secsnap at L = 1..3 (SEC's heat gradient normalised on the limit
surface, the default), each compared (`--reference-level K`) with the heat
method run with DEC on the K-times subdivided mesh with the same time step t (the paper's reference;
relative L2 in the level-K mass and relative L∞). The paper: SEC l = 3 reduces the L2 error 2.3–2.5×.
Also the effect of t = c·h_mean² (c = 0.25, 1, 4) on both. Writes geodesics.csv (one row per run),
geodesics.json (errors, ratios, the CLI's set-up/factorisation/solve seconds) and geodesics.{png,svg};
prints a markdown table.

  /usr/bin/python3 studies/geodesics.py build/release/cli/limsurf out/studies

--quick: dec and sec L = 1..3 at c = 1 with K = 3 (a few seconds).
"""

from __future__ import annotations

import sys
from pathlib import Path

import studylib as sl

NAME = "geodesics"
MESHES = [("genus2.obj", "catmull-clark"), ("tri_torus.obj", "loop")]
COLUMNS = ["study", "mesh", "scheme", "method", "level", "gradient", "time_factor", "t", "reference_level",
           "l2_relative", "linf_relative", "setup_seconds", "factorisation_seconds", "solve_seconds"]


def runs(quick: bool) -> list[tuple[str, int, float]]:
    methods = [("dec", 0)] + [("sec", level) for level in (1, 2, 3)]
    if quick:
        return [(m, level, 1.0) for m, level in methods]
    methods += [("decsnap", 0), ("secsnap", 3)]
    return [(m, level, c) for c in (0.25, 1.0, 4.0) for m, level in methods]


def run(cli: str, mesh: str, scheme: str, method: str, level: int, c: float, K: int) -> dict:
    level_option = ["--level", str(level)] if method.startswith("sec") else []  # only sec and secsnap take it
    out = sl.run_json(cli, "geodesic", sl.mesh(mesh), "--scheme", scheme, "--source", "0", "--method", method,
                      *level_option, "--time-factor", repr(c), "--reference-level", str(K))
    return {"study": NAME, "mesh": mesh, "scheme": scheme, "method": method, "level": level,
            "gradient": out["gradient"], "time_factor": c,
            "t": out["t"], "reference_level": K, "l2_relative": out["reference"]["l2_relative"],
            "linf_relative": out["reference"]["linf_relative"], "setup_seconds": out["seconds"]["setup"],
            "factorisation_seconds": out["seconds"]["factorisation"], "solve_seconds": out["seconds"]["solve"]}


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    K = 3
    tasks = [(mesh, scheme, m, level, c) for mesh, scheme in MESHES for m, level, c in runs(args.quick)]
    rows = sl.run_all(args.jobs, [lambda t=t: run(args.limsurf, *t, K) for t in tasks])
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    summary = {}
    for mesh, _ in MESHES:
        for c in sorted({r["time_factor"] for r in rows}):
            pick = {(r["method"], r["level"]): r for r in rows if r["mesh"] == mesh and r["time_factor"] == c}
            dec, sec3 = pick[("dec", 0)], pick[("sec", 3)]
            summary[f"{mesh} c={c}"] = {
                "dec_l2": dec["l2_relative"], "sec3_l2": sec3["l2_relative"],
                "l2_ratio_dec_over_sec3": dec["l2_relative"] / sec3["l2_relative"],
                "linf_ratio_dec_over_sec3": dec["linf_relative"] / sec3["linf_relative"],
                "sec_l2_by_level": [pick[("sec", level)]["l2_relative"] for level in (1, 2, 3)]}
    sl.write_json(args.outdir / f"{NAME}.json", {"reference_level": K, "paper_l2_ratio": [2.3, 2.5],
                                                 "summary": summary, "rows": rows})
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, len(MESHES), figsize=(7.0, 3.0))
    for ax, (mesh, _) in zip(axes, MESHES):
        for c in sorted({r["time_factor"] for r in rows}):
            sec = [r for r in rows if r["mesh"] == mesh and r["time_factor"] == c and r["method"] == "sec"]
            dec = [r for r in rows if r["mesh"] == mesh and r["time_factor"] == c and r["method"] == "dec"][0]
            line, = ax.semilogy([r["level"] for r in sec], [r["l2_relative"] for r in sec], "o-",
                                label=f"sec, t = {c:g} h²")
            ax.axhline(dec["l2_relative"], color=line.get_color(), ls="--", lw=0.8, label=f"dec, t = {c:g} h²")
        ax.set_title(f"{mesh}: against DEC on level {K}")
        ax.set_xlabel("SEC level L")
        ax.set_ylabel("relative L2 difference")
        ax.set_xticks([1, 2, 3])
        ax.legend()
    fig.tight_layout()
    sl.save_figure(fig, args.outdir, NAME)
    print("| mesh | t | dec L2 | sec L=1 | sec L=2 | sec L=3 | dec/sec3 |")
    print("|---|---|---|---|---|---|---|")
    for key, s in summary.items():
        mesh, c = key.split(" ")
        print(f"| {mesh} | {c[2:]} h² | {s['dec_l2']:.4f} | " + " | ".join(f"{v:.4f}" for v in s["sec_l2_by_level"])
              + f" | {s['l2_ratio_dec_over_sec3']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
