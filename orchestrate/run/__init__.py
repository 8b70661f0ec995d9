"""One run: everything decided before any work (plan.py), the run itself (solve.py), its
files, each written once in the scene's units (outputs.py), the answers a coating
engineer looks for (answers.py), the warnings where a run leaves its model
(validity.py), a start from a finished run (warm_start.py), the coarse level's own
workers (coarse_level.py), ParaView collections (paraview.py), the monolithic solve of
the same discrete problem (monolithic.py) and the Python API (api.py).
``solve_into(scene, settings, folder)`` is a run into a folder, as the command line's;
``solve_result`` (``orchestrate.solve``) returns a Result without one."""

from orchestrate.errors import RunFailed
from orchestrate.run.answers import END_ZONE, near_patch_ends
from orchestrate.run.api import Result
from orchestrate.run.api import solve as solve_result
from orchestrate.run.monolithic import monolithic_curves, monolithic_of, monolithic_solution
from orchestrate.run.plan import prepare
from orchestrate.run.solve import solve as solve_into
from orchestrate.run.validity import edge_elements

__all__ = ["END_ZONE", "Result", "RunFailed", "edge_elements", "monolithic_curves",
           "monolithic_of", "monolithic_solution", "near_patch_ends", "prepare", "solve_into",
           "solve_result"]
