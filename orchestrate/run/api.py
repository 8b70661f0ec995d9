"""The Python API: solve a scene and get its results as arrays, no output folder needed.

    import orchestrate
    result = orchestrate.solve(orchestrate.paper_scene(h2=0.125, E2=5.0))
    result.contact                  # pandas: interface, x1, x2, s, sigma_n
    result.answers["contact"]["peak_pressure"]
    result.fields["coating1"]       # a patch's nodes (2D) or mid-line forces (shell)
    result.save("run1")             # the files `python -m orchestrate solve --out run1` writes
    orchestrate.solve(other_scene, start_from=result)   # from a nearby answer: faster

The run itself is the command line's (orchestrate/run/solve.py): same checks, same files,
written into a private temporary folder that is removed after the run (and, if the
process is killed meanwhile, by the next run: orchestrate/files/folders.py). The Result
is the run's data in memory as the run hands it back (outputs.py's RunFiles): its
tables and fields as frames, its files' bytes for ``save``.
"""

from dataclasses import dataclass, field, fields
from pathlib import Path

import pandas as pd

from orchestrate.run import solve as run
from orchestrate.errors import ParameterError
from orchestrate.files.folders import RunFolder, WorkFolder
from orchestrate.files.writing import write_bytes
from orchestrate.model.scene import Scene, Settings
from orchestrate.model.scene_file import apply_overrides, scene_and_settings, settings_of

TABLES = ("contact", "interface", "traces", "history")


@dataclass
class Result:
    """A finished run: its summary (summary.json as a dict), its tables and fields as
    pandas frames, and every file it wrote (name -> bytes) for ``save``."""

    summary: dict
    contact: pd.DataFrame
    interface: pd.DataFrame
    traces: pd.DataFrame
    history: pd.DataFrame
    fields: dict = field(default_factory=dict)   # subdomain name -> DataFrame
    files: dict = field(default_factory=dict, repr=False)
    folder: Path = None                          # where save() last wrote it

    @property
    def answers(self):
        """What a coating engineer looks for (orchestrate/run/answers.py)."""
        return self.summary["answers"]

    def save(self, out_dir, overwrite=False, remember=True):
        """Write the run's files into ``out_dir`` (it appears once complete, as a run of
        the command line does; ``overwrite`` replaces an earlier run's folder); a run
        started from this Result then names that folder."""
        with RunFolder(out_dir, overwrite) as folder:
            for name, data in self.files.items():
                write_bytes(Path(folder.scratch) / name, data)
            folder.commit()
        if remember:
            self.folder = Path(out_dir).resolve()
        return Path(out_dir)


def _scene_and_settings(scene, settings, overrides):
    """A Scene or a scene file's path, with ``overrides`` (dotted keys or the paper's
    shorthands, as flags and sweeps give them: scene_file.apply_overrides); Settings, a
    dict of settings values or None (over a file's [settings])."""
    if isinstance(settings, Settings):
        if not isinstance(scene, Scene):
            scene, _ = scene_and_settings(scene)
        return apply_overrides(scene, overrides or {}), settings
    values = dict(settings or {})
    known = {f.name for f in fields(Settings)}
    for key in values:
        if key not in known:
            raise ParameterError(f"settings: unknown setting {key!r} (known: "
                                 f"{', '.join(sorted(known))})", key)
    if isinstance(scene, Scene):
        scene = apply_overrides(scene, overrides or {})
        return scene, settings_of(values, scene.units)
    return scene_and_settings(scene, overrides, settings=values)


def solve(scene, settings=None, progress=None, start_from=None, session=None,
          overrides=None):
    """Solve ``scene`` (a Scene, or the path of a scene file) with ``settings`` (Settings,
    a dict of setting values, or None: the defaults or the file's); return its Result.
    ``overrides``: scene values over the scene's, as the command line's flags and sweeps
    give them, e.g. ``{"h2": "20 um", "coating.E": "450 GPa", "load.force": 200}``
    (values with a unit converted into the scene's units, orchestrate/model/units.py).
    ``start_from``: a finished run (a Result or a run folder) of a nearby scene, whose
    interface state starts the loop (orchestrate/run/warm_start.py): fewer iterations, the
    same answer. ``session``: a Session whose workers the scenes solved in it share
    where their bodies are the same (orchestrate/workers/session.py). Raises as
    orchestrate/run/solve.py's solve does: ParameterError before any work, RunFailed (with
    the summary) if the loop does not converge, SystemFailure."""
    scene, settings = _scene_and_settings(scene, settings, overrides)
    start_name = None
    if isinstance(start_from, Result):           # its tables, in memory
        start_name = str(start_from.folder) if start_from.folder else "a Result in memory"
    with WorkFolder(WorkFolder.API_PREFIX) as scratch:     # removed after a killed process too
        written = run.solve_run(scene, settings, Path(scratch) / "run", progress=progress,
                                start_from=start_from, session=session,
                                start_name=start_name, keep=True)
    tables = {name: pd.DataFrame(written.tables.get(f"{name}.csv", {})) for name in TABLES}
    return Result(summary=written.summary, files=written.contents,
                  fields={name: pd.DataFrame(columns) for name, columns in written.fields.items()},
                  **tables)
