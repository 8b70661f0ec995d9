"""Parameter sweeps: the sweep file and its points (sweep_file.py), the manifest that says
which run folder is which point (manifest.py), one point solved in a worker process
(point.py), the engines, local processes or Dask, and the progress line (engines.py), the
table (table.py), the run folders' names (run_names.py), and the sweep that runs them
all (sweep.py)."""

from orchestrate.sweeps.engines import kill_pool
from orchestrate.sweeps.manifest import point_stamp, read_manifest, run_status, why_stale
from orchestrate.sweeps.sweep import run_sweep
from orchestrate.sweeps.sweep_file import check_points, load_sweep, named_points, point_scene
from orchestrate.sweeps.table import OUTCOME_COLUMNS

__all__ = ["OUTCOME_COLUMNS", "check_points", "kill_pool", "load_sweep", "named_points",
           "point_scene", "point_stamp", "read_manifest", "run_status", "run_sweep",
           "why_stale"]
