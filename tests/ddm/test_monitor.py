"""A diverging or stagnating Robin loop stops with a report and writes no results."""

import pytest
import json
import math
import subprocess
import sys

import numpy as np

from orchestrate.ddm.robin import ConvergenceMonitor
from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


def _monitor():
    return ConvergenceMonitor(max_iterations=1000, displacement_scale=1e-3, window=50)


def test_non_finite_values_are_divergence():
    status, reason = _monitor().check(3, np.array([0.0, math.nan]), 0.1)
    assert status == "diverged" and "non-finite" in reason


def test_runaway_displacements_are_divergence():
    status, reason = _monitor().check(3, np.array([0.0, 5.0]), 0.1)
    assert status == "diverged" and "scale" in reason


def test_growing_changes_are_divergence():
    monitor, x = _monitor(), np.zeros(2)
    for iteration, change in enumerate([1e-2, 1e-3, 1e-4, 1e-3, 1e-2, 1e-1, 1.0], start=1):
        outcome = monitor.check(iteration, x, change)
    assert outcome[0] == "diverged" and "grew" in outcome[1]


def test_flat_changes_are_stagnation():
    monitor, x = _monitor(), np.zeros(2)
    outcome = None
    for iteration in range(1, 200):
        outcome = monitor.check(iteration, x, 1e-3 * (1.0 + 0.01 * math.sin(iteration)))
        if outcome:
            break
    assert outcome[0] == "stagnated" and iteration == 51


def test_a_steady_decrease_runs_on():
    monitor, x = _monitor(), np.zeros(2)
    assert all(monitor.check(i, x, 0.8 ** i) is None for i in range(1, 100))


def test_the_papers_loop_at_a_small_penalty_is_reported_not_written(tmp_path):
    """theta = 1e-3 makes the paper's loop contract by ~1 - 1e-4 per iteration: with
    eps_u = 1e-6 it is caught as stagnating, and no stresses are written."""
    out = tmp_path / "run"
    result = subprocess.run(
        [sys.executable, "-m", "orchestrate", "solve", "--out", str(out), "--quiet",
         "--method", "paper", "--eps-u", "1e-6"],
        cwd=PROJECT_DIR, capture_output=True, text=True, timeout=300)
    assert result.returncode == 1
    assert "not converged: stagnated" in result.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["converged"] is False and summary["status"] == "stagnated"
    assert summary["final_relative_change"] > 1e-6
    assert (out / "history.csv").exists()
    assert not (out / "contact.csv").exists() and not (out / "interface.csv").exists()
