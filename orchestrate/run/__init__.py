"""One run: everything decided before any work (plan.py), the run itself (solve.py), its
files, each written once in the scene's units (outputs.py), the answers a coating
engineer looks for (answers.py), the warnings where a run leaves its model
(validity.py), a start from a finished run (warm_start.py), the coarse level's own
workers (coarse_level.py), ParaView collections (paraview.py), the monolithic solve of
the same discrete problem (monolithic.py) and the Python API (api.py).
``solve_into(scene, settings, folder)`` is a run into a folder, as the command line's;
``solve_result`` (``orchestrate.solve``) returns a Result without one."""

import importlib
from typing import TYPE_CHECKING

# Each name is imported when first asked for (orchestrate/__init__.py says why): {name:
# (module, its name there)}
_PUBLIC = {"END_ZONE": ("orchestrate.run.answers", "END_ZONE"),
           "near_patch_ends": ("orchestrate.run.answers", "near_patch_ends"),
           "Result": ("orchestrate.run.api", "Result"),
           "solve_result": ("orchestrate.run.api", "solve"),
           "RunFailed": ("orchestrate.errors", "RunFailed"),
           "monolithic_curves": ("orchestrate.run.monolithic", "monolithic_curves"),
           "monolithic_of": ("orchestrate.run.monolithic", "monolithic_of"),
           "monolithic_solution": ("orchestrate.run.monolithic", "monolithic_solution"),
           "prepare": ("orchestrate.run.plan", "prepare"),
           "solve_into": ("orchestrate.run.solve", "solve"),
           "edge_elements": ("orchestrate.run.validity", "edge_elements")}
__all__ = sorted(_PUBLIC)

if TYPE_CHECKING:       # for readers, linters and the import graph
    from orchestrate.errors import RunFailed
    from orchestrate.run.answers import END_ZONE, near_patch_ends
    from orchestrate.run.api import Result
    from orchestrate.run.api import solve as solve_result
    from orchestrate.run.monolithic import monolithic_curves, monolithic_of, monolithic_solution
    from orchestrate.run.plan import prepare
    from orchestrate.run.solve import solve as solve_into
    from orchestrate.run.validity import edge_elements


def __getattr__(name):
    """A public name, or (AttributeError) none: ``from orchestrate.run import solve``
    then imports the module of that name."""
    if name not in _PUBLIC:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    module, attribute = _PUBLIC[name]
    value = getattr(importlib.import_module(module), attribute)
    globals()[name] = value
    return value


def __dir__():
    return sorted({*globals(), *_PUBLIC})
