"""Python driver of the Robin domain decomposition: scenes, meshes, FreeFEM workers,
the Robin loop, results. ``python -m orchestrate --help`` lists the commands."""

import os

# The driver's linear algebra is small (the interface); a multi-threaded BLAS would
# spin on the cores the FreeFEM workers need (measured: 12.7 -> 9.1 ms per iteration).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import importlib  # noqa: E402
from typing import TYPE_CHECKING  # noqa: E402

# The Python API (orchestrate/run/api.py): ``orchestrate.solve(scene, settings)`` -> Result.
# Each name is imported when first asked for: the command line (``python -m orchestrate``)
# needs no pandas for most commands, and ``--help`` had taken over a second.
_PUBLIC = {"Result": "orchestrate.run.api", "solve": "orchestrate.run.api",
           "Scene": "orchestrate.model.scene", "Settings": "orchestrate.model.scene",
           "load_scene": "orchestrate.model.scene_file",
           "paper_scene": "orchestrate.model.scene_file",
           "Session": "orchestrate.workers.session", "Units": "orchestrate.model.units"}
__all__ = sorted(_PUBLIC)

if TYPE_CHECKING:       # for readers, linters and the import graph
    from orchestrate.model.scene import Scene, Settings
    from orchestrate.model.scene_file import load_scene, paper_scene
    from orchestrate.model.units import Units
    from orchestrate.run.api import Result, solve
    from orchestrate.workers.session import Session


def __getattr__(name):
    if name not in _PUBLIC:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_PUBLIC[name]), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted({*globals(), *_PUBLIC})
