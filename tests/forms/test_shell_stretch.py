"""The shell with thickness stretch (model "stretch_shell", freefem/shell.idp) alone: a
flat strip of coating between a uniform pressure p on its top face and the equal
reaction on its bottom face (tests/forms/freefem/shell_arch.edp with curvature 0).

1. Confined (v = 0 everywhere, a strip of an infinite layer): the layer compresses by
   the constrained-modulus value p h (1 + nu)(1 - 2 nu)/(E (1 - nu)), exactly.
2. Free to expand sideways (clamped at one end, free at the other): sigma11 = 0, the
   plane-strain uniaxial value (1 - nu^2) p/E, exactly, and T11 = 0.
   The Timoshenko shell's faces cannot move apart: its epsilon is zero in both.
3. The element matrix on an arch is symmetric, and its three near-rigid modes stay
   apart from the rest: P4 cannot follow a circle's rigid motions (cos, sin), so
   eps11 = v' + k w keeps a small remainder that epsilon (P2, continuous) cannot quite
   cancel at the Simpson points (measured 6e-14 of the largest eigenvalue at R/h = 100
   on a quarter circle, the fourth 4e-7): the stretch terms add no spurious mode and
   no locking (the Timoshenko element's three are exact zeros, tests/forms/test_shell_curved.py).
The end-loaded and exp-loaded cantilevers with stretch: tests/forms/test_shell.py.
"""

import numpy as np
import pytest

YOUNG, POISSON, THICKNESS, LENGTH, PRESSURE = 2.5, 0.27, 0.2, 3.0, 0.04


def strip(run_freefem, tmp_path, support, stretch=1, **extra):
    """Solve the strip; return its samples (a record array, shell_arch.edp's columns)."""
    arguments = {"curvature": 0.0, "length": LENGTH, "thickness": THICKNESS, "E": YOUNG,
                 "nu": POISSON, "elements": 3, "support": support, "stretch": stretch,
                 "topNormal": -PRESSURE, "bottomNormal": PRESSURE, **extra}
    command = []
    for option, value in arguments.items():
        command += [f"-{option}", value if isinstance(value, str) else repr(value)]
    output = tmp_path / f"strip_{support}_{stretch}.csv"
    run_freefem("shell_arch.edp", *command, "-output", str(output))
    return np.genfromtxt(output, delimiter=",", names=True)


def test_a_confined_layer_compresses_by_the_constrained_modulus(run_freefem, tmp_path):
    samples = strip(run_freefem, tmp_path, "confined")
    constrained = YOUNG * (1 - POISSON) / ((1 + POISSON) * (1 - 2 * POISSON))
    compression = PRESSURE * THICKNESS * (1 + POISSON) * (1 - 2 * POISSON) / (YOUNG * (1 - POISSON))
    np.testing.assert_allclose(THICKNESS * samples["epsilon"], -compression, rtol=1e-12)
    np.testing.assert_allclose(samples["epsilon"], -PRESSURE / constrained, rtol=1e-12)
    np.testing.assert_allclose(samples["T33"], -PRESSURE * THICKNESS, rtol=1e-12)
    # the mid-line stays put (round-off only): the faces move by -+ h epsilon/2
    assert np.max(np.abs(samples["v"])) < 1e-20
    assert np.max(np.abs(samples["w"])) < 1e-10 * compression


def test_a_free_layer_compresses_by_the_uniaxial_plane_strain_value(run_freefem, tmp_path):
    samples = strip(run_freefem, tmp_path, "clamp")
    np.testing.assert_allclose(samples["epsilon"], -(1 - POISSON**2) * PRESSURE / YOUNG,
                               rtol=1e-11)
    # sideways it expands: eps11 = nu (1 + nu) p/E, and sigma11 = T11/h = 0
    np.testing.assert_allclose(samples["v"], POISSON * (1 + POISSON) * PRESSURE / YOUNG
                               * samples["s"], rtol=1e-11, atol=1e-16)
    assert np.max(np.abs(samples["T11"])) < 1e-12 * PRESSURE * THICKNESS
    np.testing.assert_allclose(samples["T33"], -PRESSURE * THICKNESS, rtol=1e-11)


@pytest.mark.parametrize("support", ["confined", "clamp"])
def test_the_timoshenko_shell_does_not_compress(run_freefem, tmp_path, support):
    samples = strip(run_freefem, tmp_path, support, stretch=0)
    assert np.all(samples["epsilon"] == 0.0)


def test_element_matrix_with_stretch_has_exactly_three_zero_energy_modes(run_freefem, tmp_path):
    radius = 10.0
    h = radius / 100
    run_freefem("shell_arch.edp", "-curvature", repr(1 / radius), "-length",
                repr(np.pi / 2 * radius), "-thickness", repr(h), "-elements", "1",
                "-stretch", "1", "-tangential", "1", "-matrix", str(tmp_path / "element.csv"),
                "-output", str(tmp_path / "arch.csv"))
    stiffness = np.loadtxt(tmp_path / "element.csv", delimiter=",")
    assert stiffness.shape == (18, 18)        # 5 functions each of v, w, gamma; 3 of epsilon
    largest = np.abs(stiffness).max()
    assert np.abs(stiffness - stiffness.T).max() < 1e-14 * largest
    eigenvalues = np.sort(np.abs(np.linalg.eigvalsh(stiffness))) / largest
    assert np.all(eigenvalues[:3] < 1e-4 * eigenvalues[3]), eigenvalues[:4]
    assert eigenvalues[3] > 0.01 * (h / (np.pi / 2 * radius))**2, eigenvalues[:4]
