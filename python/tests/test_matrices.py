"""The exported system matrices: an independent eigen solution (scipy.linalg.eigh) equals
`geardyn modes`; the MatrixMarket files of `geardyn matrices` (read with scipy.io.mmread) equal
the Python matrices; K(θ) rebuilt from the harmonics has the mesh's mean and the mean K."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.io
import scipy.linalg

import geardyn
from conftest import cli_json, run_cli


@pytest.mark.parametrize("scene", ["builtin:helical-pair", "builtin:kahraman-blankenship-rig",
                                   "builtin:planetary-lin-parker", "builtin:geared-shafts"])
def test_eigh_of_the_exported_pencil_equals_modes(scene):
    x = geardyn.system_matrices(scene)
    k, m = x.stiffness.toarray(), x.mass.toarray()
    n = k.shape[0]
    lam = scipy.linalg.eigh(k, m, eigvals_only=True)
    reference = cli_json("modes", scene, "--modes", str(n), "--method", "dense")["frequencies_hz"]
    expected = (2 * math.pi * np.asarray(reference)) ** 2
    # Two dense solvers (LAPACK dsygvd here, geardyn's own path there), compared as λ = ω²: a
    # rigid-body λ is round-off of λ_max, which a square root would turn into 1e-4 Hz.
    np.testing.assert_allclose(lam, expected, rtol=0, atol=1e-9 * expected.max())
    nonzero = expected > 1e-6 * expected.max()
    f = np.sqrt(lam[nonzero]) / (2 * math.pi)
    np.testing.assert_allclose(f, np.asarray(reference)[nonzero], rtol=1e-9)


def test_the_commands_files_equal_the_python_matrices(tmp_path):
    scene = "builtin:kahraman-blankenship-rig"
    done = run_cli("matrices", scene, "--harmonics", "2", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    x = geardyn.system_matrices(scene, harmonics=2)
    for name, a in (("M", x.mass), ("C", x.damping), ("K", x.stiffness)):
        b = scipy.io.mmread(tmp_path / f"{name}.mtx")
        np.testing.assert_array_equal(b.toarray(), a.toarray(), err_msg=name)
    np.testing.assert_array_equal(scipy.io.mmread(tmp_path / "f.mtx").toarray().ravel(),
                                  x.mean_load)
    for m in (1, 2):
        np.testing.assert_array_equal(scipy.io.mmread(tmp_path / f"K_{m}.mtx").toarray(),
                                      x.stiffness_harmonics[m])
    dofs = json.loads((tmp_path / "dofs.json").read_text())
    assert dofs == x.report
    assert [d["name"] for d in dofs["dofs"]] == [d["name"] for d in x.dofs]


def test_the_harmonics_follow_the_mesh_stiffness_table():
    scene = "builtin:kahraman-blankenship-rig"
    x = geardyn.system_matrices(scene, harmonics=5)
    np.testing.assert_allclose(x.stiffness_harmonics[0].real, x.stiffness.toarray(),
                               rtol=0, atol=1e-12 * abs(x.stiffness).max())
    assert x.period_meshes == 1
    # A spur mesh enters K(θ) as k(θ) times a fixed pattern, so an entry of K_m is a constant
    # times the m-th Fourier coefficient of the mesh's k(θ). Those come here from an independent
    # path: a rectangle-rule DFT of `geardyn mesh`'s sampled table (error ≈ step / N at N =
    # 4096 samples, the steps being the tooth-pair changes).
    table = geardyn.mesh(scene, samples=4096).meshes["pinion-wheel"]
    theta = 2 * math.pi * table.cycle
    k_m = [np.mean(table.stiffness * np.exp(-1j * m * theta)) for m in range(6)]
    kh = x.stiffness_harmonics
    i, j = np.unravel_index(np.argmax(np.abs(kh[1])), kh[1].shape)
    ratio = kh[1][i, j] / k_m[1]
    assert abs(ratio.imag) < 1e-6 * abs(ratio)  # the first mesh has phase 0
    entries = np.array([kh[m][i, j] for m in range(1, 6)])
    # The quadrature's error is about step / N of k on every coefficient: relative to k_1.
    np.testing.assert_allclose(entries, ratio * np.array(k_m[1:]), rtol=0,
                               atol=2e-3 * abs(kh[1][i, j]))
