#!/usr/bin/python3
"""SEC paper §4.1 (Figs. 1 and 5): parameterisation with DEC against SEC, and against a reference.

Two experiments with `limsurf parameterize`:

  spectral   the spectral conformal map (Mullen et al. 2008) of the bundled pinched hemisphere
             (shell_hemisphere.obj, Catmull–Clark) by dec, decsnap, sec L = 1..3 and secsnap L = 3:
             the quasi-conformal distortion σ1/σ2 on the limit surface (area-weighted mean, max;
             1 is conformal) — the paper's Fig. 1 metric (1.784 DEC against 1.005 SEC on its head);
  circle     the boundary on the unit circle by limit arc length, harmonic interior, on a spherical
             cap (the bundled planar disk_ev5_quads lifted onto the sphere of radius 1.2, then
             subdivided n = 0..2 times and pushed back onto the sphere: finer control meshes of the
             same cap), by dec and sec L = 1..3, compared with DEC on the K-times subdivided mesh
             (--reference-level K): relative L2 (level-K mass) and L∞ — the paper's Fig. 5 (SEC 7×
             below DEC in L2, 2× in L∞, on its half big guy).

Writes parameterization.csv (one row per run), parameterization.json (the rows, the DEC/SEC ratios
and the timings) and parameterization.{png,svg} (left: distortion excess mean − 1 per method; right:
L2 error against control vertices) to OUTDIR.

  /usr/bin/python3 studies/parameterization.py build/release/cli/limsurf out/studies

--quick: spectral with dec and sec L = 1, 3; circle with n = 0, 1, dec and sec L = 1, 3, K = 3.
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import studylib as sl

NAME = "parameterization"
RADIUS = 1.2  # of the sphere the cap lies on

# key -> (method, level, label, colour, marker)
SERIES = {
    "dec": ("dec", 0, "DEC", "tab:red", "o"),
    "decsnap": ("decsnap", 0, "DECsnap", "tab:orange", "v"),
    "sec_L1": ("sec", 1, "SEC, L = 1", "tab:cyan", "^"),
    "sec_L2": ("sec", 2, "SEC, L = 2", "tab:green", "D"),
    "sec_L3": ("sec", 3, "SEC, L = 3", "tab:blue", "s"),
    "secsnap_L3": ("secsnap", 3, "SECsnap, L = 3", "tab:purple", "P"),
}

COLUMNS = ["experiment", "mesh", "control_vertices", "series", "method", "level", "eigenvalue", "distortion_mean",
           "distortion_max", "flipped", "reference_level", "reference_vertices", "l2_relative", "linf_relative",
           "time_assembly", "time_solve", "time_distortion", "time_reference"]


def extra_options(p) -> None:
    p.add_argument("--reference-level", type=int, default=None, help="K of the circle reference (default 4; quick 3)")


def read_obj(path: Path) -> tuple[list[list[float]], list[str]]:
    """The vertex positions and the other lines (faces, tags) of an OBJ."""
    points, rest = [], []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("v "):
            points.append([float(t) for t in line.split()[1:4]])
        elif not line.startswith("#"):
            rest.append(line)
    return points, rest


def write_obj(path: Path, points: list[list[float]], rest: list[str]) -> None:
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in points] + rest
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def cap_meshes(cli: str, work: Path, levels: int) -> list[Path]:
    """The spherical cap with control meshes subdivided n = 0..levels times, on the sphere."""
    points, rest = read_obj(Path(sl.mesh("disk_ev5_quads.obj")))
    lifted = [[x, y, math.sqrt(RADIUS ** 2 - x * x - y * y)] for x, y, _ in points]
    base = work / "cap_0.obj"
    write_obj(base, lifted, rest)
    out = [base]
    for n in range(1, levels + 1):
        fine = work / f"cap_{n}_raw.obj"
        sl.run_cli(cli, "subdivide", str(base), "--scheme", "catmull-clark", "--levels", str(n), "-o", str(fine))
        pts, others = read_obj(fine)
        on_sphere = [[c * RADIUS / math.sqrt(x * x + y * y + z * z) for c in (x, y, z)] for x, y, z in pts]
        path = work / f"cap_{n}.obj"
        write_obj(path, on_sphere, others)
        out.append(path)
    return out


def row_from(experiment: str, mesh: str, series: str, out: dict) -> dict:
    ref = out.get("reference") or {}
    return {
        "experiment": experiment, "mesh": mesh, "control_vertices": out["vertices"], "series": series,
        "method": out["method"], "level": out["level"], "eigenvalue": out["eigenvalue"],
        "distortion_mean": out["distortion"]["mean"], "distortion_max": out["distortion"]["max"],
        "flipped": out["distortion"]["flipped"], "reference_level": ref.get("level"),
        "reference_vertices": ref.get("vertices"), "l2_relative": ref.get("l2_relative"),
        "linf_relative": ref.get("linf_relative"), "time_assembly": out["times"]["assembly"],
        "time_solve": out["times"]["solve"], "time_distortion": out["times"]["distortion"],
        "time_reference": out["times"]["reference"],
    }


def run(cli: str, path: str, series: str, *extra: str) -> dict:
    method, level, _, _, _ = SERIES[series]
    level_option = ["--level", str(level)] if method.startswith("sec") else []  # only sec and secsnap take it
    return sl.run_json(cli, "parameterize", path, "--scheme", "catmull-clark", "--method", method, *level_option,
                       *extra)


def plot(rows: list[dict], outdir: Path) -> list[Path]:
    plt = sl.pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    spectral = [r for r in rows if r["experiment"] == "spectral"]
    labels = [SERIES[r["series"]][2] for r in spectral]
    excess = sl.plotted([r["distortion_mean"] - 1 for r in spectral])
    left.bar(range(len(spectral)), excess, color=[SERIES[r["series"]][3] for r in spectral])
    left.set_xticks(range(len(spectral)), labels, rotation=30, ha="right")
    left.set_yscale("log")
    left.set_ylabel("mean σ1/σ2 − 1 on the limit surface")
    left.set_title("spectral conformal map, shell_hemisphere")
    circle = [r for r in rows if r["experiment"] == "circle"]
    vertices = sorted({r["control_vertices"] for r in circle})
    for key in SERIES:
        pts = sorted((r["control_vertices"], r["l2_relative"]) for r in circle if r["series"] == key)
        if pts:
            _, _, label, colour, marker = SERIES[key]
            right.loglog([p[0] for p in pts], sl.plotted([p[1] for p in pts]), marker=marker, color=colour,
                         label=label)
    sl.vertex_ticks(right, vertices)
    k = circle[0]["reference_level"] if circle else 0
    right.set_xlabel("control vertices (spherical cap, refined n = 0, 1, …)")
    right.set_ylabel(f"relative L2 error vs DEC on level {k}")
    right.set_title("circle boundary, harmonic interior")
    right.legend()
    fig.tight_layout()
    paths = sl.save_figure(fig, outdir, NAME)
    plt.close(fig)
    return paths


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    k = args.reference_level if args.reference_level is not None else (3 if args.quick else 4)
    spectral_series = ["dec", "sec_L1", "sec_L3"] if args.quick else list(SERIES)
    circle_series = ["dec", "sec_L1", "sec_L3"] if args.quick else ["dec", "decsnap", "sec_L1", "sec_L2", "sec_L3"]
    top = 1 if args.quick else 2
    rows = []
    with tempfile.TemporaryDirectory(prefix="limsurf-param-") as work:
        shell = sl.mesh("shell_hemisphere.obj")
        results = sl.run_all(args.jobs, [lambda s=s: run(args.limsurf, shell, s) for s in spectral_series])
        rows += [row_from("spectral", "shell_hemisphere", s, out) for s, out in zip(spectral_series, results)]
        caps = cap_meshes(args.limsurf, Path(work), top)
        tasks, keys = [], []
        for n, path in enumerate(caps):
            for s in circle_series:
                tasks.append(lambda p=path, s=s: run(args.limsurf, str(p), s, "--boundary", "circle",
                                                     "--reference-level", str(k)))
                keys.append((f"cap_{n}", s))
        for (mesh, s), out in zip(keys, sl.run_all(args.jobs, tasks)):
            rows.append(row_from("circle", mesh, s, out))
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)

    def pick(experiment, mesh, series):
        return next(r for r in rows if r["experiment"] == experiment and r["mesh"] == mesh and r["series"] == series)

    dec_s, sec_s = pick("spectral", "shell_hemisphere", "dec"), pick("spectral", "shell_hemisphere", "sec_L3")
    summary = {
        "spectral": {"dec_mean": dec_s["distortion_mean"], "sec_L3_mean": sec_s["distortion_mean"],
                     "excess_ratio": (dec_s["distortion_mean"] - 1) / (sec_s["distortion_mean"] - 1),
                     "paper": {"dec_mean": 1.784, "sec_L3_mean": 1.005, "dec_max": 9.4, "sec_L3_max": 3.0}},
        "circle": {},
    }
    for n in range(top + 1):
        dec_c, sec_c = pick("circle", f"cap_{n}", "dec"), pick("circle", f"cap_{n}", "sec_L3")
        summary["circle"][f"cap_{n}"] = {
            "control_vertices": dec_c["control_vertices"],
            "l2_ratio_dec_over_sec_L3": dec_c["l2_relative"] / sec_c["l2_relative"],
            "linf_ratio_dec_over_sec_L3": dec_c["linf_relative"] / sec_c["linf_relative"],
            "time_sec_L3_over_reference": (sec_c["time_assembly"] + sec_c["time_solve"]) / sec_c["time_reference"],
        }
    summary["circle"]["paper"] = {"l2_ratio": 7.0, "linf_ratio": 2.0, "sec_speedup_over_reference": 6.0}
    sl.write_json(args.outdir / f"{NAME}.json", {"reference_level": k, "rows": rows, "summary": summary})
    plot(rows, args.outdir)
    print(f"| experiment | mesh | V | method | mean σ1/σ2 | max | L2 | L∞ |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        l2 = "" if r["l2_relative"] is None else f"{r['l2_relative']:.3g}"
        linf = "" if r["linf_relative"] is None else f"{r['linf_relative']:.3g}"
        print(f"| {r['experiment']} | {r['mesh']} | {r['control_vertices']} | {SERIES[r['series']][2]} | "
              f"{r['distortion_mean']:.5f} | {r['distortion_max']:.4g} | {l2} | {linf} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
