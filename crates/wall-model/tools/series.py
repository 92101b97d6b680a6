#!/usr/bin/env python3
"""Coefficients of the polynomials behind `fast_log2` and `fast_exp2` (src/real.rs).

Each polynomial interpolates its function at Chebyshev nodes of its range (close to the
minimax polynomial of the same degree) with the constant term held at exactly 1, and the
script prints the coefficients with the largest relative error of the polynomial itself
(before any floating-point rounding), found on a grid of 4000 points in 50-digit arithmetic.

    pip install mpmath && python3 crates/wall-model/tools/series.py
"""
from mpmath import mp, mpf, cos, pi, exp, expm1, atanh, sqrt, log, matrix, lu_solve

mp.dps = 50


def chebyshev_interpolant(f, a, b, n):
    """Power-basis coefficients of the degree n-1 polynomial through f at n Chebyshev nodes."""
    xs = [(a + b) / 2 + (b - a) / 2 * cos(pi * (2 * k + 1) / (2 * n)) for k in range(n)]
    vandermonde, values = matrix(n, n), matrix(n, 1)
    for i, x in enumerate(xs):
        for j in range(n):
            vandermonde[i, j] = x**j
        values[i] = f(x)
    c = lu_solve(vandermonde, values)
    return [c[j] for j in range(n)]


def worst_relative_error(f, c, a, b, points=4000):
    worst = mpf(0)
    for k in range(points + 1):
        x = a + (b - a) * k / points
        worst = max(worst, abs(sum(cj * x**j for j, cj in enumerate(c)) / f(x) - 1))
    return worst


def one_plus_x_times(f, fit_of_rest, a, b, terms):
    """1 + x q(x): q interpolates (f(x) - 1)/x, so that the constant term is exactly 1."""
    return [mpf(1)] + chebyshev_interpolant(fit_of_rest, a, b, terms - 1)


half_ln2 = log(2) / 2
u_max = ((sqrt(2) - 1) / (sqrt(2) + 1)) ** 2  # z^2 at m = sqrt(2), z = (m - 1)/(m + 1)
atanh_over_z = lambda u: atanh(sqrt(u)) / sqrt(u) if u > 0 else mpf(1)

cases = [
    ("ATANH_F64", atanh_over_z, lambda u: (atanh_over_z(u) - 1) / u if u > 0 else mpf(1) / 3, mpf(0), u_max, 7),
    ("ATANH_F32", atanh_over_z, lambda u: (atanh_over_z(u) - 1) / u if u > 0 else mpf(1) / 3, mpf(0), u_max, 4),
    ("EXP_F64", exp, lambda g: expm1(g) / g if g != 0 else mpf(1), -half_ln2, half_ln2, 10),
    ("EXP_F32", exp, lambda g: expm1(g) / g if g != 0 else mpf(1), -half_ln2, half_ln2, 6),
]
for name, f, rest, a, b, terms in cases:
    c = one_plus_x_times(f, rest, a, b, terms)
    print(f"{name}: {terms} terms, relative error {float(worst_relative_error(f, c, a, b)):.2e}")
    print("    [" + ", ".join(repr(float(x)) for x in c) + "]")
