"""Python driver of the Robin domain decomposition: scenes, meshes, FreeFEM workers,
the Robin loop, results. ``python -m orchestrate --help`` lists the commands."""

import os

# The driver's linear algebra is small (the interface); a multi-threaded BLAS would
# spin on the cores the FreeFEM workers need (measured: 12.7 -> 9.1 ms per iteration).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# The Python API (orchestrate/run/api.py): ``orchestrate.solve(scene, settings)`` -> Result
from orchestrate.run.api import Result, solve  # noqa: E402
from orchestrate.model.scene import Scene, Settings  # noqa: E402
from orchestrate.model.scene_file import load_scene, paper_scene  # noqa: E402
from orchestrate.workers.session import Session  # noqa: E402
from orchestrate.model.units import Units  # noqa: E402

__all__ = ["Result", "Scene", "Session", "Settings", "Units", "load_scene", "paper_scene",
           "solve"]
