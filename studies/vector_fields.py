#!/usr/bin/python3
"""SEC paper §4.3 and Fig. 8: vector-field design and Helmholtz–Hodge decomposition, DEC vs SEC vs reference.

On the bundled genus-2 mesh (Catmull–Clark, 48 vertices, 100 edges, valences 3, 4, 5):

  design   `limsurf vector-field` with three constraint sets — vortices and a stroke (the paper's kind of
           field), sources and sinks, and all of them — by dec, decsnap, sec L=3, secsnap L=3, each compared
           (`--reference-level K`) with the same constraints designed by DEC on the K-times subdivided mesh
           (each coarse constraint carried to the fine mesh as the functional that agrees with it on every
           subdivided coarse 1-form: docs/guide/vector_field.md "The reference"); the relative L2 difference
           of the minimisers (the paper: DEC 1.338, SEC 0.263 — absolute numbers of their own field);
  hodge    `limsurf hodge` of the 1-form of the vector field (−y, x, sin x) by the same methods, each part
           compared with DEC's decomposition of the subdivided 1-form on the K-times subdivided mesh (the
           paper: SEC improves the L2 error by 80 % over DEC).

Times are the CLI's wall-clock seconds without the reference (median of 3; include reading the mesh and the
inner products). Writes vector_fields.csv (one row per run), vector_fields.json (errors, ratios, times) and
the plot vector_fields.{png,svg}; prints a markdown table.

  /usr/bin/python3 studies/vector_fields.py build/release/cli/limsurf out/studies

--quick: dec and sec L=2, K = 2 (a few seconds).
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import studylib as sl

NAME = "vector_fields"
MESH = "genus2.obj"
FIELD = "-y;x;sin(x)"

# The stroke 0 -> 1 -> 6 follows edges of genus2.obj (checked by the CLI: it refuses a path off the edges).
CONSTRAINTS = {
    "vortices+stroke": ["--vorticity", "7:0.5", "--vorticity", "40:-0.5", "--stroke", "0,1,6:0.5"],
    "sources+sinks": ["--source", "0:1", "--sink", "30:1"],
    "all": ["--source", "0:1", "--sink", "30:1", "--vorticity", "7:0.5", "--vorticity", "40:-0.5",
            "--stroke", "0,1,6:0.5"],
}

COLUMNS = ["study", "case", "method", "level", "reference_level", "reference_edges", "l2_relative",
           "exact_l2_relative", "coexact_l2_relative", "harmonic_l2_relative", "energy", "reference_energy",
           "max_residual", "seconds"]


def methods(quick: bool) -> list[tuple[str, int]]:
    if quick:
        return [("dec", 0), ("sec", 2)]
    return [("dec", 0), ("decsnap", 0), ("sec", 3), ("secsnap", 3)]


def timed(cli: str, args: list[str], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        sl.run_cli(cli, *args)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def method_args(method: str, level: int) -> list[str]:
    return ["--method", method] + (["--level", str(level)] if method.startswith("sec") else [])


def design_row(cli: str, case: str, method: str, level: int, K: int, repeats: int) -> dict:
    args = ["vector-field", sl.mesh(MESH), "--scheme", "catmull-clark", *method_args(method, level),
            *CONSTRAINTS[case]]
    out = sl.run_json(cli, *args, "--reference-level", str(K))
    ref = out["reference"]
    return {"study": "design", "case": case, "method": method, "level": out["level"], "reference_level": K,
            "reference_edges": ref["edges"], "l2_relative": ref["l2_relative"], "energy": out["energy"],
            "reference_energy": ref["energy"], "max_residual": out["max_residual"],
            "seconds": timed(cli, args, repeats)}


def hodge_row(cli: str, method: str, level: int, K: int, repeats: int) -> dict:
    args = ["hodge", sl.mesh(MESH), "--scheme", "catmull-clark", *method_args(method, level), "--field", FIELD,
            "--no-basis"]
    out = sl.run_json(cli, *args, "--reference-level", str(K))
    ref = out["reference"]
    return {"study": "hodge", "case": "field " + FIELD, "method": method, "level": out["level"],
            "reference_level": K, "reference_edges": ref["edges"], "l2_relative": ref["l2_relative"],
            "exact_l2_relative": ref["exact_l2_relative"], "coexact_l2_relative": ref["coexact_l2_relative"],
            "harmonic_l2_relative": ref["harmonic_l2_relative"], "seconds": timed(cli, args, repeats)}


def label(row: dict) -> str:
    return row["method"] + (f" L={row['level']}" if row["method"].startswith("sec") else "")


def summarise(rows: list[dict], K: int) -> dict:
    summary: dict = {"mesh": MESH, "reference_level": K, "design": {}, "hodge": {},
                     "paper": {"design_l2_dec": 1.338, "design_l2_sec": 0.263, "hodge_improvement": 0.80}}
    for row in rows:
        entry = {k: row[k] for k in COLUMNS if row.get(k) is not None and k not in ("study", "case", "method")}
        if row["study"] == "design":
            summary["design"].setdefault(row["case"], {})[label(row)] = entry
        else:
            summary["hodge"][label(row)] = entry
    sec_label = next(label(r) for r in rows if r["method"] == "sec")
    for case, by_method in summary["design"].items():
        by_method["sec_over_dec"] = by_method[sec_label]["l2_relative"] / by_method["dec"]["l2_relative"]
    h = summary["hodge"]
    h["improvement_sec_over_dec"] = 1.0 - h[sec_label]["l2_relative"] / h["dec"]["l2_relative"]
    return summary


def plot(rows: list[dict], outdir: Path) -> None:
    plt = sl.pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    labels = list(dict.fromkeys(label(r) for r in rows))
    colours = ["tab:red", "tab:orange", "tab:blue", "tab:purple"]
    cases = list(CONSTRAINTS)
    width = 0.8 / len(labels)
    for i, name in enumerate(labels):
        values = [next(r["l2_relative"] for r in rows if r["study"] == "design" and r["case"] == c and label(r) == name)
                  for c in cases]
        left.bar([k + i * width for k in range(len(cases))], values, width, label=name, color=colours[i])
    left.set_xticks([k + 0.4 - width / 2 for k in range(len(cases))], cases)
    left.set_ylabel("relative L2 difference from the reference")
    left.set_title(f"Vector-field design on {MESH} (reference: DEC, level {rows[0]['reference_level']})")
    left.set_yscale("log")
    left.legend()
    parts = ["exact_l2_relative", "coexact_l2_relative", "harmonic_l2_relative", "l2_relative"]
    names = ["dα", "δβ", "h", "all"]
    for i, name in enumerate(labels):
        row = next(r for r in rows if r["study"] == "hodge" and label(r) == name)
        right.bar([k + i * width for k in range(len(parts))], [row[p] for p in parts], width, label=name,
                  color=colours[i])
    right.set_xticks([k + 0.4 - width / 2 for k in range(len(parts))], names)
    right.set_ylabel("relative L2 difference from the reference")
    right.set_title(f"Hodge decomposition of ({FIELD.replace(';', ', ')})")
    right.set_yscale("log")
    right.legend()
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv)
    K = 2 if args.quick else 3
    repeats = 1 if args.quick else 3
    tasks = []
    for method, level in methods(args.quick):
        for case in CONSTRAINTS:
            tasks.append(lambda m=method, lv=level, c=case: design_row(args.limsurf, c, m, lv, K, repeats))
        tasks.append(lambda m=method, lv=level: hodge_row(args.limsurf, m, lv, K, repeats))
    rows = sl.run_all(args.jobs, tasks)
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    summary = summarise(rows, K)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(rows, args.outdir)
    print(f"| study | case | method | L2 vs reference (K={K}) | seconds |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['study']} | {r['case']} | {label(r)} | {r['l2_relative']:.4g} | {r['seconds']:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
