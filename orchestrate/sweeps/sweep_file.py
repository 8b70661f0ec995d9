"""A sweep file and its points (README, "Sweeps"; docs/reference.md, "Sweeps").

A sweep file names scene and settings values: any solver setting (Settings,
orchestrate/model/scene.py), the paper's parameters (h2, E2, model, ...;
scene_file.SHORTHANDS), any scene key in dotted form ("indenter.radius", "coating[2].E",
"load.force"), and ``scene``, a scene file (relative to the sweep file; default: the
paper's scene):

    name = "example"                 # results/<name>/ (default: the file's stem)
    warm_start = true                # each run starts from its nearest converged
                                     # neighbour (orchestrate/run/warm_start.py; default false)
    [fixed]                          # values shared by every run
    eps_u = 1e-6
    [grid]                           # the product of these lists
    model = ["shell", "elastic"]
    h2 = [1.0, 0.125]
    [[grids]]                        # more products, each merged with [fixed]
    method = ["paper"]
    rho = [0.3, 0.5]
    [[runs]]                         # and/or single points, each merged with [fixed]
    model = "shell"
    h2 = 0.0625

Every point is checked before the first run (its scene, settings and size): a bad one
refuses the sweep, all bad points named.
"""

from dataclasses import fields
from itertools import product
from pathlib import Path
import re
import sys
import time

from orchestrate.errors import ParameterError
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import is_scene_key, read_toml, scene_and_settings
from orchestrate.sweeps.run_names import run_names, values_hash

SETTINGS_FIELDS = {f.name for f in fields(Settings)}
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")      # fullmatch: no trailing newline
CHECK_REPORT_SECONDS = 5.0   # a long check says how far it is this often


def load_sweep(path):
    """(name, points): every point a dict of scene and settings values, in file order.
    A malformed file is refused naming what is wrong."""
    path = Path(path)
    data = read_toml(path, "sweep file")
    unknown_sections = set(data) - {"name", "warm_start", "fixed", "grid", "grids", "runs"}
    if unknown_sections:
        raise ParameterError(f"{path}: unknown sweep section(s) {sorted(unknown_sections)} "
                             "(allowed: name, warm_start, fixed, grid, grids, runs)")
    if not isinstance(data.get("warm_start", False), bool):
        raise ParameterError(f"{path}: warm_start = {data['warm_start']!r} must be true or "
                             "false")
    name = data.get("name", path.stem)
    if not isinstance(name, str) or not NAME.fullmatch(name):
        raise ParameterError(f"{path}: name = {name!r} must be a plain folder name (letters, "
                             "digits, _ . -, not starting with . or -): the sweep's folder is "
                             "results/<name>")
    fixed = data.get("fixed", {})
    grids = data.get("grids", [])
    singles = data.get("runs", [])
    for where, tables in (("fixed", [fixed]), ("grid", [data.get("grid", {})]),
                          ("grids", grids), ("runs", singles)):
        if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
            raise ParameterError(f"{path}: [{where}] must be a table (or [[{where}]] tables)")
    grids = ([data["grid"]] if "grid" in data else []) + grids
    for table in (fixed, *grids, *singles):
        unknown = {key for key in table if key not in SETTINGS_FIELDS and key != "scene"
                   and not is_scene_key(key)}
        if unknown:
            raise ParameterError(f"{path}: unknown scene or settings parameter(s) "
                                 f"{sorted(unknown)}")
    points = []
    for grid in grids:
        for key, values in grid.items():
            if not isinstance(values, list) or not values:
                raise ParameterError(f"{path}: grid value {key} = {values!r} must be a "
                                     "non-empty list")
        keys = list(grid)
        points += [{**fixed, **dict(zip(keys, combination))}
                   for combination in product(*(grid[k] for k in keys))]
    points += [{**fixed, **single} for single in singles]
    if not points:
        raise ParameterError(f"{path} defines no run: give a [grid], [[grids]] or [[runs]]")
    return name, points


def warm_start_of(path):
    """Whether a sweep file asks its runs to start from their nearest finished neighbour
    (``warm_start = true``; load_sweep has checked the value)."""
    return read_toml(path, "sweep file").get("warm_start", False)


def check_points(points, scene_dir=".", stream=sys.stderr):
    """Refuse the sweep, before any run, if any point's scene, settings or size is bad;
    the message names every bad point. A long check says how far it is, every
    CHECK_REPORT_SECONDS (about a millisecond a point)."""
    from orchestrate.run.plan import prepare

    problems = []
    last_report = time.monotonic()
    first_of = {}       # (keys, scene, settings) -> the first point that gives them
    for number, values in enumerate(points, start=1):
        if time.monotonic() - last_report > CHECK_REPORT_SECONDS:
            stream.write(f"checking the sweep's points: {number - 1} of {len(points)}\n")
            stream.flush()
            last_report = time.monotonic()
        try:
            scene, settings = point_scene(values, scene_dir)
            prepare(scene, settings)
        except (ParameterError, TypeError, ValueError) as error:
            problems.append(f"point {number} {values}: {error}")
            continue
        # the same keys set to the same run, written otherwise ("2 um" and 0.002 in mm):
        # two folders of one run. A default set in another grid (mesh_level = 1 beside
        # E2 = 1) is another point, as the sweep file says.
        first = first_of.setdefault((tuple(sorted(values)), repr(scene), repr(settings)),
                                   number)
        if first != number and values != points[first - 1]:
            problems.append(f"point {number} {values}: the same run as point {first} "
                            f"{points[first - 1]}, its values written otherwise")
    if problems:
        shown = problems[:10] + ([f"... and {len(problems) - 10} more"] if len(problems) > 10 else [])
        raise ParameterError(f"{len(problems)} of {len(points)} points refused:\n  "
                             + "\n  ".join(shown))


def point_scene(values, scene_dir="."):
    """The scene and settings of a point; its scene file is relative to ``scene_dir``."""
    overrides = {k: v for k, v in values.items() if is_scene_key(k)}
    settings = {k: v for k, v in values.items() if k in SETTINGS_FIELDS}
    if not isinstance(values.get("scene", ""), str):
        raise ParameterError(f"scene = {values['scene']!r} must be the path of a scene file")
    scene_file = Path(scene_dir) / values["scene"] if "scene" in values else None
    return scene_and_settings(scene_file, overrides, settings)


def named_points(points):
    """(run folder name, values) of each distinct point, in the points' order."""
    distinct = list({values_hash(values): values for values in points}.values())
    return list(zip(run_names(distinct), distinct))
