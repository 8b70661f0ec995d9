"""The shell-edge study's alternation: nothing for a pressure linear between nodes, and
the swing of one alternating from node to node (its first and last two nodes left out,
where a contact zone's edge bends it)."""

import numpy as np
import pandas as pd
import pytest

from studies.shell_edge_penalty import alternation


def _contact(pressure):
    s = np.linspace(0.0, 1.0, len(pressure))
    return pd.DataFrame({"interface": "contact-coating1", "s": s, "sigma_n": -pressure})


def test_a_linear_pressure_does_not_alternate():
    assert alternation(_contact(np.linspace(2.0, 1.0, 12))) == pytest.approx(0.0, abs=1e-15)


def test_an_alternating_pressure_swings_by_its_amplitude():
    swing = np.where(np.arange(12) % 2 == 0, 0.05, -0.05)
    pressure = 1.0 + swing
    pressure[-2:] = [3.0, 0.0]         # an edge peak and a free node: left out
    assert alternation(_contact(pressure)) == pytest.approx(0.1 / 3.0, rel=1e-12)
