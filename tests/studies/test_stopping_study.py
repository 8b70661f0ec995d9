"""The stopping study measures each traction component as the stopping test does: its
relative L2 error along s against its own norm, or against component_floor times the
largest component's where it is smaller."""

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from studies.stopping import COMPONENT_FLOOR, largest_error


def _result(pressure, shear):
    s = np.linspace(0.0, 1.0, 11)
    table = pd.DataFrame({"interface": "contact-base", "s": s, "sigma_n": pressure(s),
                          "sigma_t": 0.0 * s})
    bond = pd.DataFrame({"interface": "bond-coating", "s": s, "sigma_n": 0.0 * s,
                         "sigma_t": shear(s)})
    return SimpleNamespace(contact=table, interface=bond)


def test_each_component_against_its_own_norm_or_the_floor():
    reference = _result(lambda s: 1.0 - s ** 2, lambda s: 1e-2 * s)
    # the pressure 1e-4 off everywhere (relative), the small shear 1e-3 of itself off
    run = _result(lambda s: (1.0 + 1e-4) * (1.0 - s ** 2), lambda s: (1e-2 + 1e-5) * s)
    error, part = largest_error(run, reference)
    assert part == "bond-coating sigma_t" and error == pytest.approx(1e-3, rel=1e-9)
    # a shear below the floor is measured against the floor, not itself
    reference = _result(lambda s: 1.0 - s ** 2, lambda s: 1e-6 * s)
    run = _result(lambda s: 1.0 - s ** 2, lambda s: 2e-6 * s)
    error, part = largest_error(run, reference)
    pressure_norm = np.sqrt(np.trapezoid((1.0 - np.linspace(0, 1, 11) ** 2) ** 2,
                                         np.linspace(0, 1, 11)))
    shear_norm = np.sqrt(np.trapezoid((1e-6 * np.linspace(0, 1, 11)) ** 2,
                                      np.linspace(0, 1, 11)))
    assert error == pytest.approx(shear_norm / (COMPONENT_FLOOR * pressure_norm), rel=1e-9)
