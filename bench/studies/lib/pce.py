"""Second-order polynomial chaos on a Smolyak sparse grid (non-intrusive spectral projection):
the input uncertainty of keff_validation.py, as [KE] computed theirs (docs/physics.md, main
sources). Inputs uniform on their ranges, mapped to x in [-1, 1]^3; basis: the Legendre
polynomials orthonormal under the uniform density (1, sqrt(3) x, sqrt(5) (3x^2 - 1)/2), products
of total degree <= 2 (10 terms). Quadrature: Smolyak's combination of nested Clenshaw–Curtis
rules (1, 3, 5 points) at level 2, 25 points in 3D, exact for total degree 5 >= the degree 4 of
the products f psi_a that a quadratic response needs (Smolyak 1963; Gerstner & Griebel 1998,
Numer. Algorithms 18, for the combination formula)."""
import math
from itertools import product

import numpy as np

CC_RULES = {  # level -> (points, weights under the uniform density on [-1, 1])
    1: ([0.0], [1.0]),
    2: ([-1.0, 0.0, 1.0], [1 / 6, 2 / 3, 1 / 6]),
    3: ([-1.0, -math.sqrt(0.5), 0.0, math.sqrt(0.5), 1.0], [1 / 30, 4 / 15, 2 / 5, 4 / 15, 1 / 30]),
}


def smolyak_grid(dim=3, level=2):
    """Points and weights of the Smolyak rule A(level + dim, dim) from CC_RULES."""
    q = level + dim
    grid = {}
    for i in product(range(1, level + 2), repeat=dim):
        s = sum(i)
        if not (q - dim + 1 <= s <= q):
            continue
        coef = (-1) ** (q - s) * math.comb(dim - 1, q - s)
        for idx in product(*(range(len(CC_RULES[k][0])) for k in i)):
            point = tuple(round(CC_RULES[k][0][j], 15) for k, j in zip(i, idx))
            weight = coef * math.prod(CC_RULES[k][1][j] for k, j in zip(i, idx))
            grid[point] = grid.get(point, 0.0) + weight
    return [(np.array(p), w) for p, w in grid.items() if abs(w) > 1e-15]


def legendre(n, x):
    return [1.0, math.sqrt(3) * x, math.sqrt(5) * (3 * x * x - 1) / 2][n]


BASIS = [a for a in product(range(3), repeat=3) if sum(a) <= 2]


def pce(f_values, grid):
    """Mean, standard deviation and first-order Sobol indices of the response sampled at the
    grid points."""
    coef = {a: sum(w * f * math.prod(legendre(n, x) for n, x in zip(a, p))
                   for (p, w), f in zip(grid, f_values)) for a in BASIS}
    var = sum(c * c for a, c in coef.items() if any(a))
    sobol = [sum(c * c for a, c in coef.items() if a[k] and sum(a) == a[k]) / var if var else 0.0
             for k in range(3)]
    return coef[(0, 0, 0)], math.sqrt(var), sobol
