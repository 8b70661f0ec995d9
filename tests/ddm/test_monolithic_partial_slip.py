"""The Robin loop against the monolithic solve under partial slip (the stamp's shift, the
stick and slip states) and on a load path (pressed, pulled, turned back): the same checks as
test_monolithic.py's (a file of its own, so that the test processes share the work)."""

from dataclasses import replace

import pytest

from orchestrate.model.scene import LoadStep, Settings
from tests.ddm.test_monolithic import (  # noqa: F401  (the tests, run on this file's cases)
    _file,
    solved_case,
    test_every_patch_passes_on_what_it_receives,
    test_forces_balance,
    test_robin_loop_equals_monolithic_solve)


def _partial(model, share, friction=0.5, **overrides):
    """The cylinder scene as a full model under a tangential force ``share`` times the
    friction's limit mu P (partial slip), its patch [-2 b, 2 b] a 2D coating or a
    shell, or (model None) the bare block."""
    scene = _file("cylinder", **overrides)
    coatings = () if model is None else (replace(scene.coatings[0], start=-2.0, model=model),)
    load = replace(scene.load, tangential_force=share * friction * scene.load.force)
    return replace(scene, symmetric=False, friction=friction, coatings=coatings, load=load)


def _shifted(model, shift, friction=0.5):
    """The same scene with the stamp's shift along x1 given (displacement control)."""
    scene = _partial(model, 0.0, friction)
    return replace(scene, load=replace(scene.load, tangential_force=None,
                                       tangential_displacement=shift))


def _turned(scene, peak):
    """A load path: pressed alone, pulled to ``peak`` times the load's tangential force,
    then brought to the load's own."""
    load = scene.load
    return replace(scene, load=replace(load, path=(
        LoadStep(tangential_force=0.0), LoadStep(tangential_force=peak * load.tangential_force))))


CASES = {
    # partial slip: the stamp shifted to carry Q < mu P, each point sticking (the
    # penalty on the slip) or slipping (mu p), both sets updated (robin.py,
    # monolithic.edp); the bodies of one material, and a shell (a coated block under
    # 3 E: the load path's below, whose pull is this at another origin)
    "partial slip, bare block, Q = mu P / 2": (_partial(None, 0.5), Settings(eps_u=1e-8)),
    # the shift given (Q its answer, 0.3 mu P at a shift of 0.042 b)
    "partial slip, shell, the stamp shifted by 0.05 b": (_shifted("shell", 0.05),
                                                         Settings(eps_u=1e-8)),
    # a load path: pressed alone first, pulled to Q*, then turned back past zero (each
    # step's sticking points keep where they stood at the end of the step before, the
    # slip reverses at the ends); every step in the monolithic solve too
    "pressed, pulled to mu P / 2, turned to -mu P / 4: 3 E on a 2D coating": (
        _turned(_partial("elastic", -0.25, **{"indenter.E": 3.0}), -2.0), Settings(eps_u=1e-8)),
}


@pytest.fixture(scope="module", params=[pytest.param(name, marks=pytest.mark.slow)
                                        for name in CASES])
def case(request, tmp_path_factory):
    return solved_case(CASES[request.param], tmp_path_factory)
