#!/usr/bin/python3
"""Effective stiffness of periodic cells on the limit surface, level by level (iga-with-catmull-clark §6).

`limsurf elasticity MESH --E 1 --nu 0.3 --material GROUP:10,0.3 --levels L --json` solves the
periodic cell (u = e x + periodic fluctuation, plane strain) on the limit surface of the control mesh
refined 0..L times and reports the effective stiffness C* (3 x 3 Voigt, gamma_xy = 2 eps_xy) from the
three unit macroscopic strains, the material areas and the Voigt, Reuss and Hashin-Shtrikman bounds.
Two cells of the unit square, matrix E = 1, nu = 0.3 and a ten times stiffer second phase:

  square_inclusion  a centred disc (limit radius 0.25 at the interface vertices): its 24 interface
                    edges are infinitely sharp creases, so the displacement may kink there
  rve_block         four grains (the faces around four vertices), no crease: the basis is C2 across
                    the material jump, so the strain cannot jump with the stiffness

Nothing here knows C*: the study measures the differences between consecutive levels,
d_l = ||C_l - C_(l-1)||_F / ||C_l||_F, and their rate log2(d_(l-1) / d_l) (an order in h: each level
halves it); the bounds must hold at every level. (The peer test tests/apps/elasticity_freefem_test.cpp
compares square_inclusion with FreeFem++'s body-fitted P2 elements.) Written:

  elasticity_rve.csv      one row per (example, level): vertices, seconds, the inclusion's area fraction,
                          C*, kappa* = (C11 + C12) / 2, the shear moduli C33 and (C11 - C12) / 2, d_l and its
                          rate, and where C* stands between the bounds
  elasticity_rve.json     per example: the bounds, the differences and rates, the last rate and the
                          finest level's estimated error d_L / (2^p - 1) with p that rate
  elasticity_rve.{png,svg} the differences against control vertices; kappa* against its lower
                          Hashin-Shtrikman bound; C11 between Reuss and Voigt

The Hashin-Shtrikman bounds on kappa hold for any cell geometry; those on the shear modulus only for
isotropic cells, which a square cell is not (it has two shear moduli): they are reported, not required.

  /usr/bin/python3 studies/elasticity_rve.py build/release/cli/limsurf out/studies

Full: levels 0..4 (about 3 minutes on two cores, 2.8 GB for level 4 of square_inclusion: 50497
control vertices). --quick: levels 0..2 (a few seconds).
"""

from __future__ import annotations

import math
import sys

import studylib as sl

NAME = "elasticity_rve"

MATRIX = (1.0, 0.3)
SECOND = (10.0, 0.3)
# (example, mesh, the second phase's group, label)
EXAMPLES = [
    ("square_inclusion", "square_inclusion.obj", "inclusion", "square_inclusion (creased interface)"),
    ("rve_block", "rve_block.obj", "grain", "rve_block (grains, no crease)"),
]
FULL_LEVELS = 4
QUICK_LEVELS = 2
COLOURS = {"square_inclusion": ("tab:blue", "o"), "rve_block": ("tab:red", "s")}

ENTRIES = [f"C{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
COLUMNS = (["example", "mesh", "level", "vertices", "faces", "seconds", "fraction"] + ENTRIES
           + ["kappa", "mu_33", "mu_d", "difference", "rate", "kappa_over_hs_lower", "c11_between_reuss_voigt",
              "voigt_margin", "reuss_margin", "within_bounds"])


def extra_options(p):
    p.add_argument("--levels", type=int, default=None,
                   help=f"levels 0..L (default {FULL_LEVELS}; --quick: {QUICK_LEVELS})")


def frobenius(A) -> float:
    return math.sqrt(sum(a * a for row in A for a in row))


def min_eigenvalue(A) -> float:
    import numpy as np
    M = np.array(A, dtype=float)
    return float(np.linalg.eigvalsh(0.5 * (M + M.T)).min())


def main(argv=None) -> int:
    args = sl.parse_args(__doc__.splitlines()[0], argv, extra_options)
    levels = args.levels if args.levels is not None else (QUICK_LEVELS if args.quick else FULL_LEVELS)
    if not 1 <= levels <= 6:
        sys.exit("error: --levels must be in 1..6 (a rate needs three levels, a difference two)")
    material = f"{SECOND[0]!r},{SECOND[1]!r}"
    tasks = [lambda e=e: sl.run_json(args.limsurf, "elasticity", sl.mesh(e[1]), "--E", repr(MATRIX[0]), "--nu",
                                     repr(MATRIX[1]), "--material", f"{e[2]}:{material}", "--levels", str(levels))
             for e in EXAMPLES]
    results = sl.run_all(args.jobs, tasks)

    rows = []
    summary = {"materials": {"matrix": {"E": MATRIX[0], "nu": MATRIX[1]}, "second": {"E": SECOND[0], "nu": SECOND[1]}},
               "model": "strain", "boundary": "periodic", "levels": levels, "examples": {}}
    for (ex, mesh_name, group, label), out in zip(EXAMPLES, results):
        if (out["model"] != "strain" or out["boundary"] != "periodic" or len(out["levels"]) != levels + 1
                or out["bounds"] is None or [m["name"] for m in out["materials"]] != ["default", group]):
            sys.exit(f"error: {ex}: unexpected elasticity output")
        bounds = out["bounds"]
        voigt, reuss = bounds["voigt"], bounds["reuss"]
        k_lo, k_hi = bounds["bulk_hashin_shtrikman"]
        m_lo, m_hi = bounds["shear_hashin_shtrikman"]
        per = {"label": label, "mesh": mesh_name, "group": group, "bounds": bounds, "vertices": [],
               "differences": [], "rates": [], "C": []}
        previous = None
        for lv in out["levels"]:
            C = lv["effective_stiffness"]
            area = lv["material_area"]
            kappa = 0.5 * (C[0][0] + C[0][1])
            row = dict(example=ex, mesh=mesh_name, level=lv["level"], vertices=lv["vertices"], faces=lv["faces"],
                       seconds=lv["seconds"], fraction=area[1] / sum(area), kappa=kappa, mu_33=C[2][2],
                       mu_d=0.5 * (C[0][0] - C[0][1]), kappa_over_hs_lower=kappa / k_lo,
                       c11_between_reuss_voigt=(C[0][0] - reuss[0][0]) / (voigt[0][0] - reuss[0][0]),
                       # smallest eigenvalues of Voigt - C* and C* - Reuss: >= 0 when the bounds hold
                       voigt_margin=min_eigenvalue([[v - c for v, c in zip(a, b)] for a, b in zip(voigt, C)]),
                       reuss_margin=min_eigenvalue([[c - r for c, r in zip(a, b)] for a, b in zip(C, reuss)]))
            row.update({f"C{i + 1}{j + 1}": C[i][j] for i in range(3) for j in range(3)})
            row["within_bounds"] = int(row["voigt_margin"] >= 0 and row["reuss_margin"] >= 0 and k_lo <= kappa <= k_hi)
            if previous is not None:
                change = [[a - b for a, b in zip(r, s)] for r, s in zip(C, previous)]
                row["difference"] = frobenius(change) / frobenius(C)
                per["differences"].append(row["difference"])
                if len(per["differences"]) >= 2:
                    row["rate"] = math.log2(per["differences"][-2] / per["differences"][-1])
                    per["rates"].append(row["rate"])
            previous = C
            per["vertices"].append(lv["vertices"])
            per["C"].append(C)
            rows.append(row)
        last = per["rates"][-1] if per["rates"] else None
        per["last_rate"] = last
        per["estimated_error_finest"] = (per["differences"][-1] / (2 ** last - 1)
                                         if last is not None and last > 0 else None)
        per["shear_hs_bounds_note"] = "isotropic cells only: reported, not required"
        per["mu_33_within_shear_hs"] = [m_lo <= C[2][2] <= m_hi for C in per["C"]]
        summary["examples"][ex] = per
    sl.write_csv(args.outdir / f"{NAME}.csv", COLUMNS, rows)
    sl.write_json(args.outdir / f"{NAME}.json", summary)
    plot(summary, args.outdir)
    print_summary(rows, summary)
    return 0


def print_summary(rows, summary):
    print("| example | level | vertices | C11 | C12 | C33 | kappa | difference | rate | within bounds | seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        d = "" if r.get("difference") is None else f"{r['difference']:.2e}"
        p = "" if r.get("rate") is None else f"{r['rate']:.2f}"
        print(f"| {r['example']} | {r['level']} | {r['vertices']} | {r['C11']:.6f} | {r['C12']:.6f} | {r['C33']:.6f} |"
              f" {r['kappa']:.6f} | {d} | {p} | {'yes' if r['within_bounds'] else 'NO'} | {r['seconds']:.1f} |")
    print()
    for ex, per in summary["examples"].items():
        b = per["bounds"]
        est = per["estimated_error_finest"]
        print(f"{ex}: kappa HS [{b['bulk_hashin_shtrikman'][0]:.6f}, {b['bulk_hashin_shtrikman'][1]:.6f}], "
              f"shear HS [{b['shear_hashin_shtrikman'][0]:.6f}, {b['shear_hashin_shtrikman'][1]:.6f}] "
              f"(isotropic cells only); last rate {per['last_rate']:.2f}"
              + ("" if est is None else f", estimated error of the finest level {est:.1e}"))


def plot(summary, outdir):
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.5))
    ax = axes[0]
    for ex, per in summary["examples"].items():
        colour, marker = COLOURS[ex]
        rate = per["last_rate"]
        text = per["label"] + ("" if rate is None else f": rate {rate:.2f}")
        ax.semilogy(range(1, len(per["vertices"])), sl.plotted(per["differences"]), marker=marker, color=colour,
                    lw=1.1, ms=4.5, label=text)
    ax.set_title("‖C*ₗ − C*ₗ₋₁‖ / ‖C*ₗ‖ (rate: order in h)")
    ax.set_xlabel("level l (h halves per level)")
    ax.set_ylabel("relative difference to the previous level")
    ax.set_xticks(range(1, summary["levels"] + 1))
    ax.grid(True, which="major", lw=0.5, alpha=0.5)
    ax.legend(loc="lower left", fontsize=7)
    for ax, key, title, ylabel in (
            (axes[1], "kappa_over_hs_lower", "κ* = (C11 + C12)/2 against the lower HS bound",
             "κ* / κ_HS− (≥ 1 for any cell)"),
            (axes[2], "c11_between_reuss_voigt", "C11 between the Reuss and the Voigt bound",
             "(C11 − Reuss) / (Voigt − Reuss)")):
        for ex, per in summary["examples"].items():
            colour, marker = COLOURS[ex]
            values = [_entry(summary, ex, l, key) for l in range(len(per["vertices"]))]
            ax.plot(range(len(values)), sl.plotted(values), marker=marker, color=colour, lw=1.1, ms=4.5,
                    label=per["label"])
        ax.axhline(1.0 if key == "kappa_over_hs_lower" else 0.0, color="black", lw=0.8, ls="--")
        ax.set_title(title)
        ax.set_xlabel("level")
        ax.set_ylabel(ylabel)
        ax.set_xticks(range(summary["levels"] + 1))
        ax.grid(True, lw=0.5, alpha=0.5)
        ax.legend(loc="upper right", fontsize=7)
    fig.suptitle("Periodic cells, plane strain, matrix E = 1 and a phase E = 10 (ν = 0.3): effective stiffness "
                 "by level", fontsize=10)
    fig.tight_layout()
    sl.save_figure(fig, outdir, NAME)
    plt.close(fig)


def _entry(summary, ex, level, key):
    per = summary["examples"][ex]
    C = per["C"][level]
    b = per["bounds"]
    if key == "kappa_over_hs_lower":
        return 0.5 * (C[0][0] + C[0][1]) / b["bulk_hashin_shtrikman"][0]
    return (C[0][0] - b["reuss"][0][0]) / (b["voigt"][0][0] - b["reuss"][0][0])


if __name__ == "__main__":
    sys.exit(main())
