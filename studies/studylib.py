"""Shared plumbing of the study scripts: running the limsurf CLI, tables, fits and deterministic plots.

The studies run the CLI as a subprocess with --json (never the library), read only the
repository's data/meshes, and write into one output directory: NAME.csv (one row per number),
NAME.json (the fitted slopes and rates), NAME.png and NAME.svg. Plots use matplotlib's Agg
backend with a fixed figure size, dpi, SVG hash salt and no date, so a rerun on the same machine
writes identical bytes.

Run the scripts with Debian's /usr/bin/python3 (python3-numpy, python3-matplotlib).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

REPO = Path(__file__).resolve().parent.parent
MESHES = REPO / "data" / "meshes"

DPI = 100


def parse_args(description: str, argv: Sequence[str] | None = None,
               extra: Callable[[argparse.ArgumentParser], None] | None = None) -> argparse.Namespace:
    """The common command line: LIMSURF OUTDIR [--quick] [--jobs N] plus a study's own options."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("limsurf", help="path of the limsurf CLI binary (e.g. build/release/cli/limsurf)")
    p.add_argument("outdir", help="directory for NAME.csv, NAME.json, NAME.png and NAME.svg (created)")
    p.add_argument("--quick", action="store_true",
                   help="small levels only (a few seconds; what the tests run)")
    p.add_argument("--jobs", type=int, default=2, help="CLI runs at a time (default 2)")
    if extra is not None:
        extra(p)
    args = p.parse_args(argv)
    cli = Path(args.limsurf)
    if not (cli.is_file() and os.access(cli, os.X_OK)):
        p.error(f"not an executable: {cli}")
    if args.jobs < 1:
        p.error("--jobs must be at least 1")
    args.limsurf = str(cli.resolve())
    args.outdir = Path(args.outdir)
    args.outdir.mkdir(parents=True, exist_ok=True)
    return args


class CliError(RuntimeError):
    pass


def run_cli(cli: str, *args: str) -> str:
    """Runs `cli args...`; returns stdout, raises CliError with the command and stderr on failure."""
    cmd = [cli, *args]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        raise CliError(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stderr.strip()}")
    return r.stdout


def run_json(cli: str, *args: str) -> Any:
    """Runs `cli args... --json` and parses its stdout."""
    out = run_cli(cli, *args, "--json")
    try:
        return json.loads(out)
    except json.JSONDecodeError as e:
        raise CliError(f"{cli} {' '.join(args)} --json: not JSON ({e})") from e


def run_all(jobs: int, tasks: Iterable[Callable[[], Any]]) -> list[Any]:
    """Runs the callables with `jobs` workers; results in the order of `tasks`."""
    tasks = list(tasks)
    if jobs == 1:
        return [t() for t in tasks]
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        return list(pool.map(lambda t: t(), tasks))


def mesh(name: str) -> str:
    path = MESHES / name
    if not path.is_file():
        raise FileNotFoundError(path)
    return str(path)


def write_csv(path: Path, columns: Sequence[str], rows: Iterable[dict[str, Any]]) -> None:
    """One header line, then the rows; floats written with repr (round-trip exact)."""
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(columns)
        for row in rows:
            w.writerow(["" if row.get(c) is None else (repr(row[c]) if isinstance(row[c], float) else row[c])
                        for c in columns])


def write_json(path: Path, data: Any) -> None:
    with open(path, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2, sort_keys=True)
        f.write("\n")


def fit_slope(x: Sequence[float], y: Sequence[float]) -> float:
    """Least-squares slope of log y against log x."""
    if len(x) != len(y) or len(x) < 2:
        raise ValueError("a slope needs two points or more")
    lx = [math.log(v) for v in x]
    ly = [math.log(v) for v in y]
    mx = sum(lx) / len(lx)
    my = sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    sxy = sum((a - mx) * (b - my) for a, b in zip(lx, ly))
    return sxy / sxx


def ratios(values: Sequence[float]) -> list[float]:
    """Successive factors values[i] / values[i+1]."""
    return [a / b for a, b in zip(values, values[1:])]


# ---------------------------------------------------------------------------------------------
# Plots

def pyplot():
    """matplotlib.pyplot on the Agg backend with the deterministic settings."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    matplotlib.rcParams.update({
        "svg.hashsalt": "limsurf-studies",
        "svg.fonttype": "path",
        "font.size": 9,
        "axes.titlesize": 10,
        "legend.fontsize": 7.5,
        "figure.dpi": DPI,
        "savefig.dpi": DPI,
        "path.simplify": False,
    })
    return plt


def save_figure(fig, outdir: Path, name: str) -> list[Path]:
    """NAME.png and NAME.svg, without dates or version stamps, so reruns are byte-identical."""
    png = outdir / f"{name}.png"
    svg = outdir / f"{name}.svg"
    fig.savefig(png, dpi=DPI, metadata={"Software": None})
    fig.savefig(svg, metadata={"Date": None, "Creator": None})
    return [png, svg]


def log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def signed(x: float, digits: int = 2) -> str:
    """x with a typographic minus (U+2212), as matplotlib writes tick labels."""
    return f"{x:.{digits}f}".replace("-", "\u2212")


def vertex_ticks(ax, values: Sequence[int]) -> None:
    """Label a log x axis at the data's own abscissae (control-vertex counts), nothing else."""
    from matplotlib.ticker import FixedLocator, NullLocator
    ax.xaxis.set_major_locator(FixedLocator(list(values)))
    ax.xaxis.set_major_formatter(lambda v, _pos: f"{int(round(v))}")
    ax.xaxis.set_minor_locator(NullLocator())


def plotted(values: Sequence[float]) -> list[float]:
    """The values rounded to 4 significant digits, as they are drawn.

    Finer digits are invisible on a log axis, and some CLI outputs vary in their last digits from
    run to run (the plate's stiffness is summed in thread-completion order); rounded, the PNG and
    SVG coordinates do not (a variation of 1e-9 relative crosses a 4-digit boundary with
    probability ~1e-5 per value).
    """
    return [float(f"{v:.4g}") for v in values]
