"""The Robin loop against the monolithic solve on bodies of revolution (axisymmetric
scenes): the same checks as test_monolithic.py's, on its own scenes (a file of its own,
so that the test processes share the work)."""

import pytest

from orchestrate.model.scene import Settings
from tests.ddm.test_monolithic import (  # noqa: F401  (the tests, run on this file's cases)
    TIGHT,
    _file,
    solved_case,
    test_every_patch_passes_on_what_it_receives,
    test_forces_balance,
    test_robin_loop_equals_monolithic_solve)

CASES = {
    # bodies of revolution: the forms and interfaces weighted by 2 pi r, the hoop strain
    "sphere on a coated disc, 2D coating": (_file("sphere"), TIGHT),
    "rigid sphere on a coated ring, iterated inside the base's worker": (
        _file("sphere", **{"indenter.rigid": True, "coating[1].start": 0.5}),
        Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside")),
    "sphere under a descent, iterated, bond exchanged": (
        _file("sphere", stamp=0.04), Settings(eps_u=1e-10, inner_solve="iterate",
                                              bonds="exchanged")),
    # shells of revolution (freefem/shell_revolution.idp, its form times 2 pi): a disc,
    # u = beta = 0 on the axis, with and without thickness stretch; a ring, iterated in
    # the base's worker (freefem/coated_base.edp builds it with the shell's includes)
    "sphere on a coated disc, shell of revolution": (_file("sphere", model="shell"), TIGHT),
    "sphere on a coated disc, stretch shell of revolution": (
        _file("sphere", model="stretch_shell"), TIGHT),
    "sphere on a coated ring, shell of revolution, iterated inside the base's worker": (
        _file("sphere", model="shell", **{"coating[1].start": 0.5}),
        Settings(eps_u=1e-8, inner_solve="iterate", bonds="inside")),
}


@pytest.fixture(scope="module", params=[pytest.param(name, marks=pytest.mark.slow)
                                        for name in CASES])
def case(request, tmp_path_factory):
    return solved_case(CASES[request.param], tmp_path_factory)
