"""lib/pce.py on responses whose mean, variance and Sobol indices are known in closed form
(inputs uniform on [-1, 1]^3). Run from bench/studies: python3 -m pytest lib/tests"""
import pytest

from lib import pce


@pytest.fixture(scope="module")
def grid():
    return pce.smolyak_grid()


def test_grid_is_the_level_2_rule(grid):
    assert len(grid) == 25
    assert sum(w for _, w in grid) == pytest.approx(1.0, abs=1e-12)


def test_quadratic_mean_and_variance(grid):
    # f = 1 + x + y^2: mean 1 + 1/3, variance Var(x) + Var(y^2) = 1/3 + 4/45
    mean, sd, sobol = pce.pce([1 + p[0] + p[1] ** 2 for p, _ in grid], grid)
    assert mean == pytest.approx(4 / 3, abs=1e-12)
    assert sd ** 2 == pytest.approx(1 / 3 + 4 / 45, abs=1e-12)
    assert sobol == pytest.approx([(1 / 3) / (1 / 3 + 4 / 45), (4 / 45) / (1 / 3 + 4 / 45), 0.0],
                                  abs=1e-12)


def test_interaction_has_no_first_order_index(grid):
    # f = x z: variance 1/9, all of it in the (x, z) interaction
    mean, sd, sobol = pce.pce([p[0] * p[2] for p, _ in grid], grid)
    assert mean == pytest.approx(0.0, abs=1e-12)
    assert sd ** 2 == pytest.approx(1 / 9, abs=1e-12)
    assert sobol == pytest.approx([0.0, 0.0, 0.0], abs=1e-12)


def test_constant_has_no_variance(grid):
    mean, sd, _ = pce.pce([2.5 for _ in grid], grid)
    assert mean == pytest.approx(2.5, abs=1e-12)
    assert sd == pytest.approx(0.0, abs=1e-12)
