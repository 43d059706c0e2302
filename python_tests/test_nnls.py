"""fenestra._core.nnls against SciPy's Lawson-Hanson implementation."""

import numpy as np
import pytest
from scipy.optimize import nnls as scipy_nnls

from fenestra import _core


def wall_contributions(rng, sensors, rows, cols):
    """Irradiance-like matrix: sensors facing a wall of elements; smooth positive columns, neighbours
    nearly collinear (as in the solver's contribution matrices)."""
    s = np.column_stack([rng.uniform(0, 4, sensors), rng.uniform(0.5, 4, sensors), rng.uniform(0.5, 1.5, sensors)])
    size = 3.0 / rows
    ex = ((np.arange(cols) + 0.5) * 4.0 / cols)[None, :].repeat(rows, 0).ravel()
    ez = ((np.arange(rows) + 0.5) * size)[:, None].repeat(cols, 1).ravel()
    dx, dz = ex[None, :] - s[:, :1], ez[None, :] - s[:, 2:]
    d2 = dx**2 + s[:, 1:2] ** 2 + dz**2
    return s[:, 1:2] * size**2 / d2**1.5


def check_against_scipy(A, b, unique):
    x, residual = _core.nnls(A, b)
    x_ref, residual_ref = scipy_nnls(A, b, maxiter=10 * A.shape[1])
    assert x.dtype == np.float64 and x.shape == (A.shape[1],)
    assert np.all(x >= 0)
    assert residual == pytest.approx(np.linalg.norm(A @ x - b), rel=1e-12, abs=1e-12 * np.linalg.norm(b))
    # The residual norm is unique even when x is not.
    assert residual == pytest.approx(residual_ref, rel=1e-9, abs=1e-9 * np.linalg.norm(b))
    if unique:
        np.testing.assert_allclose(x, x_ref, rtol=1e-8, atol=1e-9 * np.abs(x_ref).max())
    return x


@pytest.mark.parametrize("seed", range(5))
def test_overdetermined_random_problems_match_scipy(seed):
    rng = np.random.default_rng(seed)
    m, n = 60 + 10 * seed, 25 + 5 * seed
    A = rng.standard_normal((m, n))
    b = rng.standard_normal(m)
    check_against_scipy(A, b, unique=True)  # full column rank: strictly convex


@pytest.mark.parametrize("seed", range(5))
def test_more_columns_than_rows_matches_scipy(seed):
    rng = np.random.default_rng(100 + seed)
    m, n = 20 + 5 * seed, 80 + 20 * seed
    A = np.abs(rng.standard_normal((m, n)))
    b = rng.standard_normal(m) + 0.5 * A.sum(axis=1) / n * seed
    check_against_scipy(A, b, unique=False)


def test_known_nonnegative_solution_is_recovered():
    rng = np.random.default_rng(7)
    A = rng.standard_normal((50, 30))
    x_true = np.abs(rng.standard_normal(30))
    x_true[::4] = 0.0
    x = check_against_scipy(A, A @ x_true, unique=True)
    np.testing.assert_allclose(x, x_true, atol=1e-10)


@pytest.mark.parametrize("seed", range(4))
def test_nearly_collinear_columns_match_scipy(seed):
    rng = np.random.default_rng(200 + seed)
    base = rng.standard_normal((40, 6))
    A = np.repeat(base, 3, axis=1) + 1e-6 * rng.standard_normal((40, 18))
    check_against_scipy(A, rng.standard_normal(40), unique=False)


@pytest.mark.parametrize("seed", range(3))
def test_contribution_like_matrices_match_scipy(seed):
    rng = np.random.default_rng(300 + seed)
    E = wall_contributions(rng, 80, 8, 12)  # 80 sensors x 96 elements
    goal = np.full(80, 0.3 * E.sum(axis=1).mean())
    check_against_scipy(E, goal, unique=False)
    noisy = E @ (rng.uniform(size=96) < 0.3) * (1 + 0.05 * rng.standard_normal(80))
    check_against_scipy(E, noisy, unique=False)


def test_input_is_converted_to_float64():
    rng = np.random.default_rng(9)
    A = np.asfortranarray(rng.standard_normal((30, 10)).astype(np.float32))
    b = rng.standard_normal(60)[::2]  # not contiguous
    x, residual = _core.nnls(A, b)
    x_ref, residual_ref = scipy_nnls(A.astype(np.float64), b)
    np.testing.assert_allclose(x, x_ref, rtol=1e-8, atol=1e-12)
    assert residual == pytest.approx(residual_ref, rel=1e-9)


def test_zero_right_hand_side_gives_zero():
    x, residual = _core.nnls(np.ones((4, 3)), np.zeros(4))
    assert np.all(x == 0.0) and residual == 0.0


def test_invalid_input_raises_value_error():
    A = np.ones((3, 2))
    with pytest.raises(ValueError, match="3 rows"):
        _core.nnls(A, np.ones(4))
    with pytest.raises(ValueError, match="shape"):
        _core.nnls(np.ones(3), np.ones(3))
    with pytest.raises(ValueError, match="shape"):
        _core.nnls(A, np.ones((3, 1)))
    bad = A.copy()
    bad[1, 0] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        _core.nnls(bad, np.ones(3))
    with pytest.raises(ValueError, match="not finite"):
        _core.nnls(A, np.array([1.0, np.inf, 0.0]))


def test_iteration_limit_raises_runtime_error():
    rng = np.random.default_rng(4)
    A = np.abs(rng.standard_normal((30, 20)))
    with pytest.raises(RuntimeError, match="not converged"):
        _core.nnls(A, A @ np.ones(20), max_iterations=2)


def test_consistent_ill_conditioned_system_fits_to_default_accuracy():
    # Smooth columns make tiny gradients compatible with a small nonzero residual: the default
    # tolerance stops there (~1e-7 relative), well below the noise of traced contributions.
    rng = np.random.default_rng(300)
    E = wall_contributions(rng, 80, 8, 12)
    b = E @ (rng.uniform(size=96) < 0.3)
    x, residual = _core.nnls(E, b)
    assert np.all(x >= 0)
    assert residual <= 1e-6 * np.linalg.norm(b)
