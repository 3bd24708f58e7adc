#!/usr/bin/env python3
"""Restitution coefficient of the Hertz + zeta-damping contact of docs/physics.md §4, computed
independently of the library (used once to write tests/data/hertz_restitution.csv).

Contact law: m x'' = -max(0, K x^(3/2) + c x'),  K = 4/3 E* sqrt(R*),
c = 2 zeta sqrt(m k_n), k_n = 2 E* sqrt(R* x) = 3/2 K x^(1/2).
With x = L X, t = T tau, L = (m v^2 / K)^(2/5), T = L / v the impact velocity drops out:
  X'' = -max(0, X^(3/2) + 2 sqrt(3/2) zeta X^(1/4) X'),  X(0) = 0, X'(0) = 1,
and e(zeta) = -X' when X returns to 0.  Classic RK4 with step h; run at h and h/2 to show the
error.  Usage: python3 hertz_restitution.py > hertz_restitution.csv
"""
import math


def restitution(zeta, h):
    c = 2.0 * math.sqrt(1.5) * zeta

    def acc(x, v):
        if x <= 0.0:
            return 0.0
        f = x ** 1.5 + c * x ** 0.25 * v
        return -f if f > 0.0 else 0.0

    x, v, t = 0.0, 1.0, 0.0
    while True:
        k1x, k1v = v, acc(x, v)
        k2x, k2v = v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v)
        k3x, k3v = v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v)
        k4x, k4v = v + h * k3v, acc(x + h * k3x, v + h * k3v)
        xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if xn <= 0.0 and vn < 0.0:
            # Crossing inside the step: interpolate the time linearly (the velocity is constant
            # once the force has clamped to zero, and changes by O(h x^1.5) otherwise).
            return -vn, t + h * x / (x - xn)
        x, v, t = xn, vn, t + h


if __name__ == "__main__":
    h = 2e-5
    zetas = [round(0.05 * i, 2) for i in range(21)]
    rows, worst = [], 0.0
    for z in zetas:
        e1, _ = restitution(z, h)
        e2, t2 = restitution(z, h / 2)
        worst = max(worst, abs(e1 - e2))
        rows.append((z, e2, t2))
    print("# e(zeta) of the Hertz + zeta-damping normal contact (docs/physics.md §4), independent of "
          "the library: dimensionless ODE X''=-max(0,X^1.5+2*sqrt(1.5)*zeta*X^0.25*X'), X(0)=0, "
          "X'(0)=1, classic RK4 at h=%g; halving h changes e by at most %.1e; made by "
          "tests/data/hertz_restitution.py (python3). tau_c: contact time in units of "
          "(m*^2/(v K^2))^(1/5), K = 4/3 E* sqrt(R*)" % (h / 2, worst))
    print("zeta,restitution,tau_c")
    for z, e, t in rows:
        print("%.2f,%.7f,%.7f" % (z, e, t))
