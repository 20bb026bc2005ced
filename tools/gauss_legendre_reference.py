#!/usr/bin/env python3
"""Writes tests/data/quadrature/gauss_legendre_40_digits.txt: Gauss–Legendre nodes and weights on
[0, 1] to 40 significant digits, for QuadratureRules.GaussLegendreIsCorrectlyRounded.

An independent witness of src/limsurf/quadrature/rules.cpp: the roots of mpmath's own Legendre
function (hypergeometric, not the three-term recurrence) found by Newton's method at 60 digits,
and the weights 1 / ((1 − z²) P_n'(z)²) with P_n' from mpmath.diff. The rule sizes are those where
the long-double computation of rules.cpp before 2026-12-05 gave a value one ulp off on x86-64
(n = 11, 29) and the largest (n = 64). Needs python3-mpmath; the test reads the file only.

    python3 tools/gauss_legendre_reference.py > tests/data/quadrature/gauss_legendre_40_digits.txt
"""
import mpmath

mpmath.mp.dps = 60


def rule(n):
    """Nodes on [0, 1] (increasing) and weights on [0, 1] of the n-point rule."""
    nodes, weights = [], []
    for i in range(n):
        guess = mpmath.cos(mpmath.pi * (i + mpmath.mpf(3) / 4) / (n + mpmath.mpf(1) / 2))
        z = guess
        for _ in range(100):  # Newton's method, P_n' by mpmath's numerical differentiation
            step = mpmath.legendre(n, z) / mpmath.diff(lambda x: mpmath.legendre(n, x), z)
            z -= step
            if abs(step) < mpmath.mpf(10) ** -55:
                break
        else:
            raise RuntimeError(f"no root {i} of P_{n}")
        dp = mpmath.diff(lambda x: mpmath.legendre(n, x), z)
        nodes.append((1 - z) / 2)
        weights.append(1 / ((1 - z * z) * dp * dp))
    order = sorted(range(n), key=lambda k: nodes[k])
    return [nodes[k] for k in order], [weights[k] for k in order]


def main():
    print("# n i node weight: Gauss-Legendre on [0, 1], 40 significant digits (tools/gauss_legendre_reference.py)")
    for n in (11, 29, 64):
        nodes, weights = rule(n)
        for i in range(n):
            print(n, i, mpmath.nstr(nodes[i], 40, min_fixed=1, max_fixed=0),
                  mpmath.nstr(weights[i], 40, min_fixed=1, max_fixed=0))


if __name__ == "__main__":
    main()
