"""The Robin loop against the monolithic solve under friction (full sliding): the
tangential traces carry mu p (robin.robin_laws), the monolithic matrix the
non-symmetric friction block (freefem/monolithic.edp); the same checks as
test_monolithic.py's, on its own scenes (a file of its own, so that the test processes
share the work). At eps_u 1e-8: a friction side's data holds mu p over its small Robin
parameter (robin_parameters.FRICTION_SHARE), whose rounding holds the estimate near
2e-10; a rigid indenter's at 1e-7, as in test_monolithic.py."""

from dataclasses import replace

import pytest

from orchestrate.model.scene import Settings
from orchestrate.run.monolithic import monolithic_solution
from orchestrate.run.solve import solve
from tests.ddm.test_monolithic import (_file, test_every_patch_passes_on_what_it_receives,  # noqa: F401
                                       test_forces_balance, test_robin_loop_equals_monolithic_solve)


def _sliding(model, friction=0.3, **overrides):
    """The cylinder scene as a full model, its patch [-2 b, 2 b] a 2D coating or a shell
    5 times as stiff as the bodies, the indenter sliding towards +x1 under friction
    (Dundurs' beta of the coated base against the indenter is not 0: the friction
    traction shifts the pressure)."""
    scene = _file("cylinder", **{"coating[1].model": model, **overrides})
    return replace(scene, symmetric=False, friction=friction, sliding=True,
                   coatings=(replace(scene.coatings[0], start=-2.0),))


def _partial(model, share, friction=0.5, **overrides):
    """The cylinder scene as a full model under a tangential force ``share`` times the
    friction's limit mu P (partial slip), its patch [-2 b, 2 b] a 2D coating or a
    shell, or (model None) the bare block."""
    scene = _file("cylinder", **overrides)
    coatings = () if model is None else (replace(scene.coatings[0], start=-2.0, model=model),)
    load = replace(scene.load, tangential_force=share * friction * scene.load.force)
    return replace(scene, symmetric=False, friction=friction, coatings=coatings, load=load)


def _pressed_first(scene):
    return replace(scene, load=replace(scene.load, path="pressed_first"))


CASES = {
    "sliding cylinder on a 2D coating, mu 0.3": (_sliding("elastic"), Settings(eps_u=1e-8)),
    "sliding cylinder on a shell, mu 0.3": (_sliding("shell"), Settings(eps_u=1e-8)),
    "sliding cylinder 3 E on a stretch shell, mu 0.5": (
        _sliding("stretch_shell", 0.5, **{"indenter.E": 3.0}), Settings(eps_u=1e-8)),
    "rigid cylinder sliding on a 2D coating, mu 0.3": (
        _sliding("elastic", **{"indenter.rigid": True}), Settings(eps_u=1e-7)),
    # each contact set solved directly from the workers' maps (interface_system.py: a
    # friction entry's data take its contact's tractions)
    "sliding cylinder on a shell, mu 0.3, direct": (
        _sliding("shell"), Settings(eps_u=1e-8, inner_solve="direct")),
    "sliding cylinder 3 E on a 2D coating, mu 0.5, direct": (
        _sliding("elastic", 0.5, **{"indenter.E": 3.0}), Settings(eps_u=1e-8, inner_solve="direct")),
    # partial slip: the stamp shifted to carry Q < mu P, each point sticking (the
    # penalty on the slip) or slipping (mu p), both sets updated (robin.py,
    # monolithic.edp); the bodies of one material, and a coated block under 3 E
    "partial slip, bare block, Q = mu P / 2": (_partial(None, 0.5), Settings(eps_u=1e-8)),
    "partial slip, 3 E on a 2D coating, Q = 0.6 mu P": (
        _partial("elastic", 0.6, **{"indenter.E": 3.0}), Settings(eps_u=1e-8)),
    "partial slip, shell, Q = 0.3 mu P": (_partial("shell", 0.3), Settings(eps_u=1e-8)),
    # a load path: pressed alone first (its sticking points keep where they stood after
    # it), then pulled; both steps in the monolithic solve too
    "pressed, then pulled: 3 E on a 2D coating, Q = mu P / 2": (
        _pressed_first(_partial("elastic", 0.5, **{"indenter.E": 3.0})), Settings(eps_u=1e-8)),
}


@pytest.fixture(scope="module", params=[pytest.param(name, marks=pytest.mark.slow)
                                        for name in CASES])
def case(request, tmp_path_factory):
    scene, settings = CASES[request.param]
    out = tmp_path_factory.mktemp("friction")
    summary = solve(scene, settings, out)
    problem, traces, stresses = monolithic_solution(scene, settings)
    return summary, out, problem, traces, stresses
