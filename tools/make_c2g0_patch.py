#!/usr/bin/env python3
"""Generate the regular (type-0) patch table of the C2g0 scheme.

The limit surface of C2g0 over a triangle whose 12 vertices at distance <= 1
all have valence 6 is the three-directional box spline with directions
[1,0], [0,1], [1,1] each repeated three times (c2g0-sphere-scheme-biomembranes
§1.2, symbol (1.3); §3.1 "type-0 triangle", (3.2)): a single polynomial of
degree 7 that depends on the 27 lattice points of the triangle's 2-ring. This
script computes, exactly with fractions.Fraction, the 27 x 36 matrix Q of its
Bernstein–Bézier coefficients and writes src/limsurf/limit/c2g0_patch_table.inc.

Lattice: points (x, y) in Z^2; the neighbours of (0,0) counter-clockwise are
(1,0), (1,1), (0,1), (-1,0), (-1,-1), (0,-1); hex distance max(|x|,|y|,|x-y|).
The triangle is P0 = (0,0), P1 = (1,0), P2 = (1,1) (counter-clockwise); its
barycentric coordinates (l0, l1, l2) are the ptex (1-u-v, u, v). Control point
i sits at offsets[i]; the surface is sum_i c_i phi_i with phi_i(x) =
B(x - offsets[i] + (3,3)) (the box spline centred at offsets[i]).
Bernstein index order: (j, k) with l1^j l2^k l0^(7-j-k), for j+k <= 7, by k
then j (bernstein_index below).

How the box spline is evaluated: the recursion (1.2) as a de Boor–Höllig
recurrence on the multiplicities of the three directions, at points off the
lattice lines (the interior of a lattice triangle), exactly. Each piece is
recovered by interpolation at 36 interior points (the degree-7 domain points
shrunk towards the centroid, a unisolvent set).

`--check` regenerates into memory, compares with the committed file, and
verifies: the 27 points are the 2-ring; partition of unity (coefficients of
every Bernstein function sum to 1); reproduction of linear functions (the
centred box spline is symmetric); the refinement equation with the mask of
(1.3): the patch of coarse data over the corner and middle children of the
triangle equals the patch of the data refined with the mask, at exact points;
and that every numerator and denominator is below 2^53 (so the double quotient
the C++ code forms is the correctly rounded value).
"""

import argparse
import os
import sys
from fractions import Fraction as F
from functools import lru_cache
from itertools import product
from math import comb, factorial

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join("src", "limsurf", "limit", "c2g0_patch_table.inc")
DEGREE = 7
DIRS = [(1, 0), (0, 1), (1, 1)]
MULT = (3, 3, 3)
TRIANGLE = [(0, 0), (1, 0), (1, 1)]


def hex_distance(a, b):
    x, y = a[0] - b[0], a[1] - b[1]
    return max(abs(x), abs(y), abs(x - y))


def two_ring():
    pts = [p for p in product(range(-3, 5), repeat=2) if min(hex_distance(p, c) for c in TRIANGLE) <= 2]
    # Canonical order: inner ring first (distance <= 1), then by y, then x.
    return sorted(pts, key=lambda p: (min(hex_distance(p, c) for c in TRIANGLE), p[1], p[0]))


def det(u, v):
    return u[0] * v[1] - u[1] * v[0]


@lru_cache(maxsize=None)
def box(m, x):
    """Box spline with multiplicities m of [1,0], [0,1], [1,1] at x (not on a lattice line)."""
    n = sum(m)
    if n == 2:
        idx = [i for i in range(3) for _ in range(m[i])]
        if idx[0] == idx[1]:
            return F(0)
        u, v = DIRS[idx[0]], DIRS[idx[1]]
        d = det(u, v)
        a = F(det(x, v), d)
        b = F(det(u, x), d)
        return F(1, abs(d)) if (0 <= a < 1 and 0 <= b < 1) else F(0)
    # x = sum t_i d_i over two present directions (the recurrence needs any such split).
    t = [F(0)] * 3
    if m[0] and m[1]:
        t[0], t[1] = x[0], x[1]
    elif m[0] and m[2]:
        t[2], t[0] = x[1], x[0] - x[1]
    elif m[1] and m[2]:
        t[2], t[1] = x[0], x[1] - x[0]
    else:
        return F(0)
    total = F(0)
    for i in range(3):
        if m[i] == 0:
            continue
        mm = list(m)
        mm[i] -= 1
        mm = tuple(mm)
        shifted = (x[0] - DIRS[i][0], x[1] - DIRS[i][1])
        total += t[i] * box(mm, x) + (m[i] - t[i]) * box(mm, shifted)
    return total / (n - 2)


def phi(offset, x):
    return box(MULT, (x[0] - offset[0] + 3, x[1] - offset[1] + 3))


def bernstein_indices():
    return [(j, k) for k in range(DEGREE + 1) for j in range(DEGREE + 1 - k)]


def bernstein(j, k, l):
    i = DEGREE - j - k
    c = factorial(DEGREE) // (factorial(i) * factorial(j) * factorial(k))
    return c * l[0] ** i * l[1] ** j * l[2] ** k


def lattice_point(l):
    """Barycentric (l0, l1, l2) on TRIANGLE -> lattice point."""
    return (l[1] + l[2], l[2])


def solve(A, B):
    """Exact Gauss–Jordan: A X = B (lists of Fractions)."""
    n = len(A)
    M = [A[r][:] + B[r][:] for r in range(n)]
    for c in range(n):
        p = next(r for r in range(c, n) if M[r][c] != 0)
        M[c], M[p] = M[p], M[c]
        inv = 1 / M[c][c]
        M[c] = [v * inv for v in M[c]]
        for r in range(n):
            if r != c and M[r][c] != 0:
                f = M[r][c]
                M[r] = [a - f * b for a, b in zip(M[r], M[c])]
    return [row[n:] for row in M]


def make_table():
    offsets = two_ring()
    assert len(offsets) == 27, len(offsets)
    idx = bernstein_indices()
    assert len(idx) == 36
    # Interpolation points: domain points shrunk by 1/2 towards the centroid (strictly interior).
    pts = []
    for j, k in idx:
        d = (F(DEGREE - j - k, DEGREE), F(j, DEGREE), F(k, DEGREE))
        pts.append(tuple(F(1, 6) + di / 2 for di in d))
    A = [[F(bernstein(j, k, l)) for (j, k) in idx] for l in pts]
    B = [[phi(o, lattice_point(l)) for o in offsets] for l in pts]
    X = solve(A, B)  # 36 x 27
    Q = [[X[b][i] for b in range(36)] for i in range(27)]
    return offsets, idx, Q


def evaluate(Q, data, l):
    """Patch value at barycentric l for control data (list of 27)."""
    idx = bernstein_indices()
    return sum(data[i] * sum(Q[i][b] * bernstein(j, k, l) for b, (j, k) in enumerate(idx)) for i in range(27))


def mask():
    a = {}
    for i, j, k in product(range(4), repeat=3):
        key = (i + k - 3, j + k - 3)
        a[key] = a.get(key, 0) + F(comb(3, i) * comb(3, j) * comb(3, k), 128)
    return a


def checks(offsets, idx, Q):
    errors = []
    for b in range(36):
        if sum(Q[i][b] for i in range(27)) != 1:
            errors.append("partition of unity fails at Bernstein coefficient %d" % b)
    # Linear reproduction: data = x and y give the lattice coordinates back.
    for l in [(F(1, 3), F(1, 3), F(1, 3)), (F(1, 2), F(1, 5), F(3, 10)), (F(1), F(0), F(0)), (F(0), F(0), F(1))]:
        p = lattice_point(l)
        for comp in range(2):
            got = evaluate(Q, [F(o[comp]) for o in offsets], l)
            if got != p[comp]:
                errors.append("linear reproduction fails at %s: %s != %s" % (l, got, p[comp]))
    # Refinement equation: coarse data on a window, fine data by the mask; the coarse patch on
    # TRIANGLE equals the fine patch on its children.
    a = mask()
    window = [p for p in product(range(-6, 8), repeat=2)]
    coarse = {p: F((7 * p[0] * p[0] * p[1] + 3 * p[1] ** 3 + 11 * p[0] + 5 * (p[0] * p[1]) % 13 + p[0] ** 4 % 7), 3 + p[1] % 4)
              for p in window}
    fine = {}
    for q in product(range(-5, 9), repeat=2):
        # Fine point q = sum over coarse alpha of a[q - 2 alpha] times the coarse value.
        fine[q] = sum((a[(q[0] - 2 * al[0], q[1] - 2 * al[1])] * coarse[al] for al in window
                       if (q[0] - 2 * al[0], q[1] - 2 * al[1]) in a), F(0))
    # Children of TRIANGLE in the fine lattice (fine coords = 2 x coarse): corner child at P0
    # and the middle child; each is a lattice triangle (f0, f1, f2) counter-clockwise.
    children = [
        ((0, 0), (1, 0), (1, 1)),  # corner at P0: same orientation
        ((2, 1), (1, 1), (1, 0)),  # middle child: rotated by 180 degrees
        ((2, 0), (2, 1), (1, 0)),  # corner at P1
    ]
    for f0, f1, f2 in children:
        # Lattice affine map TRIANGLE -> child: P0 -> f0, P1 -> f1, P2 -> f2.
        e1 = (f1[0] - f0[0], f1[1] - f0[1])
        e2 = (f2[0] - f1[0], f2[1] - f1[1])

        def to_fine(o):
            return (f0[0] + o[0] * e1[0] + o[1] * e2[0], f0[1] + o[0] * e1[1] + o[1] * e2[1])

        data = [fine[to_fine(o)] for o in offsets]
        for l in [(F(1, 3), F(1, 3), F(1, 3)), (F(1, 2), F(1, 5), F(3, 10)), (F(1, 7), F(2, 7), F(4, 7))]:
            # The same point in coarse barycentrics: fine point f = sum l_i f_i, coarse = f / 2.
            fx = sum(l[i] * (f0, f1, f2)[i][0] for i in range(3)) / 2
            fy = sum(l[i] * (f0, f1, f2)[i][1] for i in range(3)) / 2
            lc = (1 - fx, fx - fy, fy)
            lhs = evaluate(Q, [coarse[o] for o in offsets], lc)
            rhs = evaluate(Q, data, l)
            if lhs != rhs:
                errors.append("refinement equation fails on child %s at %s" % ((f0, f1, f2), l))
    for row in Q:
        for q in row:
            if abs(q.numerator) >= 2 ** 53 or q.denominator >= 2 ** 53:
                errors.append("coefficient %s does not fit a double exactly" % q)
    return errors


def render(offsets, idx, Q):
    lines = [
        "// Generated by tools/make_c2g0_patch.py; do not edit (python3 tools/make_c2g0_patch.py --check).",
        "//",
        "// The C2g0 regular (type-0) patch: the box spline with directions [1,0], [0,1], [1,1] each",
        "// thrice (c2g0-sphere-scheme-biomembranes (1.3), (3.2)) over the lattice triangle",
        "// P0 = (0,0), P1 = (1,0), P2 = (1,1), as Bernstein–Bézier coefficients of degree 7.",
        "// c2g0_offsets[i]: lattice point of control point i (neighbours of (0,0) counter-clockwise:",
        "//   (1,0), (1,1), (0,1), (-1,0), (-1,-1), (0,-1)).",
        "// c2g0_bernstein[b] = (j, k): Bernstein function 7!/(i! j! k!) l0^i l1^j l2^k, i = 7 - j - k,",
        "//   with (l0, l1, l2) = (1 - u - v, u, v).",
        "// c2g0_coefficients[i][b] = {numerator, denominator}, exact (both below 2^53).",
        "// clang-format off",
        "inline constexpr int c2g0_offsets[27][2] = {",
    ]
    for o in offsets:
        lines.append("    {%d, %d}," % o)
    lines.append("};")
    lines.append("inline constexpr int c2g0_bernstein[36][2] = {")
    for j, k in idx:
        lines.append("    {%d, %d}," % (j, k))
    lines.append("};")
    lines.append("inline constexpr long long c2g0_coefficients[27][36][2] = {")
    for row in Q:
        cells = ", ".join("{%d, %d}" % (q.numerator, q.denominator) for q in row)
        lines.append("    {" + cells + "},")
    lines.append("};")
    lines.append("// clang-format on")
    return "\n".join(lines) + "\n"


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="verify the committed table and the identities")
    args = parser.parse_args(argv)
    offsets, idx, Q = make_table()
    errors = checks(offsets, idx, Q)
    text = render(offsets, idx, Q)
    path = os.path.join(ROOT, OUT)
    if args.check:
        try:
            with open(path, encoding="utf-8") as f:
                if f.read() != text:
                    errors.append("%s differs from the generated table" % OUT)
        except OSError:
            errors.append("%s is missing" % OUT)
        for e in errors:
            print("make_c2g0_patch --check: " + e, file=sys.stderr)
        if errors:
            print("make_c2g0_patch --check: FAILED; rerun python3 tools/make_c2g0_patch.py", file=sys.stderr)
            return 1
        print("make_c2g0_patch --check: %s is up to date; partition of unity, linear reproduction and "
              "the refinement equation hold" % OUT)
        return 0
    if errors:
        for e in errors:
            print("make_c2g0_patch: " + e, file=sys.stderr)
        return 1
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
