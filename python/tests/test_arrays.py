"""numpy shapes, dtypes, units and memory ownership of the results (documented in
geardyn/_results.py: every array is a copy the result owns)."""

from __future__ import annotations

import gc
import math
import weakref

import numpy as np
import pytest

import geardyn

PAIR = "builtin:helical-pair"


def test_modes_shapes_dtypes_and_units():
    r = geardyn.modes(PAIR, shapes=True)
    n = len(r.dof_names)
    m = len(r.frequencies_hz)
    assert (n, m) == (12, 12)
    assert r.frequencies_hz.dtype == np.float64 and r.shapes.shape == (n, m)
    assert r.kinetic_fractions.shape == (m, 4)
    # f = √λ / 2π [Hz] with λ = ω² [rad²/s²].
    np.testing.assert_allclose(r.frequencies_hz, np.sqrt(np.maximum(r.eigenvalues, 0)) / (2 * math.pi),
                               rtol=1e-14)
    # The energy fractions of each mode sum to one.
    np.testing.assert_allclose(r.kinetic_fractions.sum(axis=1), 1.0, rtol=1e-12)


def test_mode_shapes_are_mass_orthonormal():
    r = geardyn.modes(PAIR, shapes=True)
    mats = geardyn.system_matrices(PAIR)
    m = mats.mass.toarray()
    phi = r.shapes
    np.testing.assert_allclose(phi.T @ m @ phi, np.eye(phi.shape[1]), atol=1e-10)


def test_without_shapes_the_array_is_empty_not_missing():
    r = geardyn.modes(PAIR)
    assert r.shapes.shape == (0, 0) and r.dof_names == []


def test_floquet_multipliers_are_complex_and_2n():
    r = geardyn.floquet(PAIR)
    assert r.multipliers.dtype == np.complex128 and r.multipliers.shape == (24,)
    assert r.max_abs_multiplier == pytest.approx(np.abs(r.multipliers).max(), rel=1e-15)
    # μ = ln(λ)/T: |λ| = e^{Re μ T}.
    np.testing.assert_allclose(np.abs(r.multipliers),
                               np.exp(r.exponents.real * r.period_s), rtol=1e-10)


def test_arrays_outlive_their_result_and_own_their_memory():
    r = geardyn.modes(PAIR, shapes=True)
    f, phi = r.frequencies_hz, r.shapes
    expected_f, expected_phi = f.copy(), phi.copy()
    ref = weakref.ref(r)
    del r
    gc.collect()
    assert ref() is None
    # Allocate and compute again: freed memory would be overwritten.
    for _ in range(3):
        geardyn.modes("builtin:geared-shafts", shapes=True)
    np.testing.assert_array_equal(f, expected_f)
    np.testing.assert_array_equal(phi, expected_phi)
    # Each result's arrays are its own: writing one leaves another run's untouched.
    a = geardyn.modes(PAIR).frequencies_hz
    b = geardyn.modes(PAIR).frequencies_hz
    a[1] = -1.0
    assert b[1] > 0.0
    assert a.flags.writeable


def test_chart_grid_is_ny_by_nx_and_undetermined_is_nan():
    r = geardyn.stability_chart("builtin:kahraman-singh-oscillator",
                                x=("oscillator.frequency_ratio", 0.5, 2.5, 9),
                                y=("oscillator.alpha", 0.0, 0.4, 3), threads=1)
    assert r.max_abs_multiplier.shape == (3, 9) and r.stable.shape == (3, 9)
    assert r.x.shape == (9,) and r.y.shape == (3,)
    assert np.all(np.isnan(r.stable) == ~r.determined)
    assert r.x[0] == 0.5 and r.x[-1] == 2.5


def test_matrices_are_scipy_sparse_with_the_dof_map():
    import scipy.sparse as sp

    x = geardyn.system_matrices(PAIR, harmonics=3)
    n = len(x.dofs)
    for a in (x.mass, x.damping, x.stiffness):
        assert sp.issparse(a) and a.shape == (n, n) and a.dtype == np.float64
    assert x.mean_load.shape == (n,)
    assert len(x.stiffness_harmonics) == 4
    assert all(k.shape == (n, n) and k.dtype == np.complex128 for k in x.stiffness_harmonics)
    assert {d["unit"] for d in x.dofs} == {"m", "rad"}
