"""A run called converged is right within its tolerance, whatever the accepted settings.

The stopping test (orchestrate/ddm/robin.py) bounds the error of the interface displacements
and tractions by the residual times the amplification the loop has shown; a run at the
default eps_u = 1e-6 must then be within eps_u of the same scene run to 1e-9, in the
contact and the bond stresses (relative L2), also where the loop is slow: a Robin
parameter 200 times below its best (gamma = 0.01 E/b: the residual alone understates
the error 1000 times there; measured 3e-7 against a run to 1e-10), and the paper's own
loop (fixed relaxation, soft penalty). A run that solves its contact sets directly, or
corrects its iterations on a coarse mesh, is held to the plain iterated loop's answer."""

import numpy as np
import pandas as pd
import pytest

import orchestrate
from orchestrate.errors import RunFailed
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, load_scene, paper_scene
from orchestrate.run.solve import solve

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

CASES = {
    "gamma 0.01": dict(robin=0.01, max_iterations=3000, inner_solve="iterate"),
    "paper loop, theta 1": dict(method="paper", theta=1.0, max_iterations=3000),
    # contact sets solved directly (interface_system.py): against the loop run to 1e-9
    "direct": dict(inner_solve="direct"),
    # iterated with a coarse correction (coarse.py): its estimate from the corrected map
    "two-level": dict(inner_solve="two-level", mesh_level=2),
}


def _distance(a, b):
    return float(np.sqrt(np.sum((a - b) ** 2) / np.sum(b ** 2)))


@pytest.mark.parametrize("settings", list(CASES.values()), ids=list(CASES))
def test_a_converged_run_is_within_its_tolerance(settings, tmp_path):
    run = solve(paper_scene(), Settings(**settings), tmp_path / "run")
    # 1e-9, not tighter: at gamma = 0.01 the loop's round-off (relative changes ~5e-15)
    # times its amplification (~1e4) and the margin reaches 1e-10, and it stagnates there
    reference = dict(settings, inner_solve="iterate") if "inner_solve" in settings else settings
    solve(paper_scene(), Settings(**reference, eps_u=1e-9), tmp_path / "tight")
    assert run["converged"] and run["error_estimate"] < 1e-6
    for name, column in (("contact.csv", "sigma_n"), ("interface.csv", "sigma_n"),
                         ("interface.csv", "sigma_t")):   # the bond's shear, apart
        ours = pd.read_csv(tmp_path / "run" / name)[column].to_numpy()
        reference = pd.read_csv(tmp_path / "tight" / name)[column].to_numpy()
        assert _distance(ours, reference) < 1e-6, (name, column)


def test_the_papers_loop_is_not_called_converged_far_from_its_answer(tmp_path):
    """The paper's loop at its own eps_u = 1e-3 and theta = 1e-3 on a soft 2D coating: a
    contact set that changes every iteration fooled an estimate from the contraction of
    the last 10 changes, and the run was called converged 42 % off in force. Converged
    now only if within its tolerance (it hits its iteration limit)."""
    scene = paper_scene(model="elastic", h2=0.125, E2=0.2)
    settings = Settings(method="paper", eps_u=1e-3, rho=0.5, max_iterations=3000)
    try:
        run = solve(scene, settings, tmp_path / "run")
    except RunFailed as failure:
        assert failure.summary["status"] in ("max_iterations", "stagnated", "diverged")
        return
    reference = solve(scene, Settings(), tmp_path / "reference")
    assert abs(run["contact_force"] / reference["contact_force"] - 1) < 1e-3


def _relative_l2(table, reference, interface, column):
    """Relative L2 distance along s of one interface's column (trapezoidal weights)."""
    ours = table[table["interface"] == interface]
    theirs = reference[reference["interface"] == interface]
    s = theirs["s"].to_numpy()
    assert np.allclose(ours["s"].to_numpy(), s)
    difference = ours[column].to_numpy() - theirs[column].to_numpy()
    return float(np.sqrt(np.trapezoid(difference ** 2, s)
                         / np.trapezoid(theirs[column].to_numpy() ** 2, s)))


def test_a_dip_of_the_residual_does_not_stop_the_loop_early():
    """The gallery's pads at mesh level 2, eps_u = 1e-3: the far pad, which the cylinder does
    not touch, has a bond shear of a third of a percent of the largest traction and converges
    last. Anderson's residual dips while that error does not; the pairs' amplification times
    such a residual called the run converged with that shear 2.7 times eps_u off (measured).
    A stop is now confirmed by the history's bound (Anderson.answer_errors): within eps_u
    (0.21 of it, measured). Against the default eps_u = 1e-6, a thousand times tighter.
    The loose run's recurring contact set tightens its updates below eps_u (robin.py's
    SET_TOLERANCE_FLOOR): it had stopped cycling there and fallen back to the direct
    solve, six times the loop's time."""
    scene, settings = load_scene(SCENES_DIR / "gallery" / "patches_and_bare_base.toml")
    settings = {**settings, "mesh_level": 2}
    with orchestrate.Session() as session:     # the reference's workers the run's: half its time
        run = orchestrate.solve(scene, {**settings, "eps_u": 1e-3}, session=session)
        reference = orchestrate.solve(scene, settings, session=session)
    assert run.summary["converged"] and run.summary["error_estimate"] < 1e-3
    assert run.summary["inner_solve_fallback"] is None
    far_pad = "bond-coating3"
    tractions = reference.interface[reference.interface["interface"] == far_pad]
    largest = reference.interface[["sigma_n", "sigma_t"]].abs().max().max()
    assert tractions["sigma_t"].abs().max() < 0.01 * largest       # a small part of the whole
    assert _relative_l2(run.interface, reference.interface, far_pad, "sigma_t") < 1e-3
