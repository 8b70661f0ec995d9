"""The Robin loop against the monolithic solve under friction (full sliding): the
tangential traces carry mu p (robin.robin_laws), the monolithic matrix the
non-symmetric friction block (freefem/monolithic.edp; partial slip:
test_monolithic_partial_slip.py); the same checks as
test_monolithic.py's, on its own scenes (a file of its own, so that the test processes
share the work). At eps_u 1e-8: a friction side's data holds mu p over its small Robin
parameter (robin_parameters.FRICTION_SHARE), whose rounding holds the estimate near
2e-10; a rigid indenter's at 1e-7, as in test_monolithic.py."""

from dataclasses import replace

import pytest

from orchestrate.model.scene import Settings
from tests.ddm.test_monolithic import (  # noqa: F401  (the tests, run on this file's cases)
    _file,
    solved_case,
    test_every_patch_passes_on_what_it_receives,
    test_forces_balance,
    test_robin_loop_equals_monolithic_solve)


def _sliding(model, friction=0.3, **overrides):
    """The cylinder scene as a full model, its patch [-2 b, 2 b] a 2D coating or a shell
    5 times as stiff as the bodies, the indenter sliding towards +x1 under friction
    (Dundurs' beta of the coated base against the indenter is not 0: the friction
    traction shifts the pressure)."""
    scene = _file("cylinder", **{"coating[1].model": model, **overrides})
    return replace(scene, symmetric=False, friction=friction, sliding=True,
                   coatings=(replace(scene.coatings[0], start=-2.0),))


CASES = {
    "sliding cylinder on a 2D coating, mu 0.3": (_sliding("elastic"), Settings(eps_u=1e-8)),
    "sliding cylinder on a shell, mu 0.3": (_sliding("shell"), Settings(eps_u=1e-8)),
    "sliding cylinder 3 E on a stretch shell, mu 0.5": (
        _sliding("stretch_shell", 0.5, **{"indenter.E": 3.0}), Settings(eps_u=1e-8)),
    "rigid cylinder sliding on a 2D coating, mu 0.3": (
        _sliding("elastic", **{"indenter.rigid": True}), Settings(eps_u=1e-7)),
    # each contact set solved directly from the workers' maps (interface_system.py: a
    # friction entry's data take its contact's tractions)
    "sliding cylinder 3 E on a 2D coating, mu 0.5, direct": (
        _sliding("elastic", 0.5, **{"indenter.E": 3.0}), Settings(eps_u=1e-8, inner_solve="direct")),
}


@pytest.fixture(scope="module", params=[pytest.param(name, marks=pytest.mark.slow)
                                        for name in CASES])
def case(request, tmp_path_factory):
    return solved_case(CASES[request.param], tmp_path_factory)
