"""Hostile input: every case is refused before any work, naming the key (and the file),
or accepted as a scene the tool solves; never an internal error.

The cases are generated from tables: every scene key, setting and [units] key given a
wrong type, a wrong or unknown unit, a wrong sign, zero, NaN, infinities, huge and tiny
magnitudes; whole files that are empty, too large, not TOML, with a byte-order mark, a
folder, missing; every kind of bad ``start_from``. Each is checked where the command
line checks it (the scene file, its overrides and settings, then orchestrate/run/solve.py's
prepare, which decides everything before a worker starts), in this process; a sample
goes through the command line itself (exit status 2, no traceback), and the start_from
cases through solve() with starting a worker made to fail the test.
"""

import json
import math
import shutil
import subprocess
import sys
import tomllib

import numpy as np
import pandas as pd
import pytest

from orchestrate.workers import worker
from orchestrate.errors import ParameterError
from orchestrate.model.scene_file import SCENES_DIR, scene_and_settings
from orchestrate.run.solve import prepare, solve
from tests.conftest import PROJECT_DIR, steel_scene

# ---- a minimal TOML writer for the cases' files -------------------------------------------


def _toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and math.isnan(value):
        return "nan"
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(value)


def _tables(value):
    return isinstance(value, list) and value and all(isinstance(v, dict) for v in value)


def write_toml(path, data):
    lines = [f"{key} = {_toml_value(value)}" for key, value in data.items()
             if not isinstance(value, dict) and not _tables(value)]
    for key, value in data.items():
        if isinstance(value, dict):
            lines += [f"[{key}]"] + [f"{k} = {_toml_value(v)}" for k, v in value.items()]
        elif _tables(value):
            for table in value:
                lines += [f"[[{key}]]"] + [f"{k} = {_toml_value(v)}" for k, v in table.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


# ---- the cases -------------------------------------------------------------------------

NOT_A_NUMBER = ["stiff", [1.0, 2.0], {"a": 1.0}, True]
NUMBERS = [-1.0, 0.0, math.nan, math.inf, -math.inf, 1e300, 1e-300]

# key: (base scene, values that must be refused, values that must be accepted)
SCENE_KEYS = {
    "indenter.radius": ("paper", [*NOT_A_NUMBER, -1.0, 0.0, math.nan, -math.inf, 1e300,
                                  "20 MPa", "20 mm"], [math.inf, 1e6]),
    "indenter.width": ("paper", [*NOT_A_NUMBER, *NUMBERS, "4 GPa", "4 mm"], [3.0]),
    "indenter.height": ("paper", [*NOT_A_NUMBER, *NUMBERS, "8 zorks"], [6.0]),
    "indenter.centre": ("paper", [*NOT_A_NUMBER, -1.0, 1.0, math.nan, math.inf, 1e300], [0.0]),
    "indenter.E": ("paper", [*NOT_A_NUMBER, *NUMBERS, "1 mm", "1 GPa"], [2.0, 1e-3]),
    "indenter.nu": ("paper", [*NOT_A_NUMBER, -1.0, 0.5, math.nan, math.inf, 1e300, "0.3 mm"],
                    [0.0, 0.49, -0.5]),
    "indenter.profile": ("paper", ["square", 1.0, [], True], ["circle"]),
    "indenter.face_mesh": ("paper", ["curved", 1.0, [], True], ["shaped"]),
    "base.width": ("paper", [*NOT_A_NUMBER, *NUMBERS, "4 MPa"], [5.0]),
    "base.height": ("paper", [*NOT_A_NUMBER, *NUMBERS, "8 MPa"], [9.0]),
    "base.E": ("paper", [*NOT_A_NUMBER, *NUMBERS, "1 GPa"], [0.5]),
    "base.nu": ("paper", [*NOT_A_NUMBER, -1.0, 0.5, math.nan, math.inf], [0.25]),
    "base.shape": ("paper", ["disc", 1.0, True], []),
    "base.radius": ("roller", [*NOT_A_NUMBER, *NUMBERS, "16 MPa"], [20.0]),
    "base.bore": ("roller", [*NOT_A_NUMBER, *NUMBERS, 15.0, "8 MPa"], [4.0]),
    "coating.start": ("paper", [*NOT_A_NUMBER, -1.0, math.nan, math.inf, 1e300, 2.0],
                      [0.0]),
    "coating.end": ("paper", [*NOT_A_NUMBER, -1.0, 0.0, math.nan, math.inf, 1e300, 5.0,
                              "2 MPa"], [2.0]),
    "coating.thickness": ("paper", [*NOT_A_NUMBER, *NUMBERS, 8.0, "0.1 MPa"], [0.25]),
    "coating.E": ("paper", [*NOT_A_NUMBER, *NUMBERS, "5 mm", 1e7], [5.0, 0.2]),
    "coating.nu": ("paper", [*NOT_A_NUMBER, -1.0, 0.5, math.nan, math.inf], [0.45]),
    "coating.model": ("paper", ["beam", 1.0, [], True], ["elastic", "auto"]),
    "coating.shear_factor": ("paper", [*NOT_A_NUMBER, *NUMBERS], [1.0]),
    "load.displacement": ("paper", [*NOT_A_NUMBER, -1.0, math.nan, math.inf, 1e300, 1e-300,
                                    "0.001 MPa"], [0.0, 1e-3]),
    "load.force": ("cylinder", [*NOT_A_NUMBER, -1.0, math.nan, math.inf, 1e300, 1e-300,
                                "0.02 mm"], [0.01]),
    "symmetric": ("paper", ["yes", 1.0, [], {"a": 1.0}], [False]),
    "contact_zone": ("paper", ["all", [1.0], [2.0, 0.0], [math.nan, 2.0], [0.0, math.inf],
                               [0.0, "2 MPa"], {"a": 1.0}], [[0.0, 3.0], [0.0, 1.0]]),
    "indenter.colour": ("paper", ["red"], []),
    "coatings.E": ("paper", [5.0], []),
}
UNITS_KEYS = {
    "units.length": ["mms", "furlongs per day", "MPa", "", 1.0, "2 mm", True],
    "units.stress": ["Mpa", "mm", "N", "", 1.0, "2 MPa"],
    "units.b": [-1.0, 0.0, math.nan, math.inf, "abc", "2.5 MPa", "2.5 zorks", True, [1.0],
                1e-300],
}
SETTINGS = {
    "theta": [-1.0, 0.0, math.nan, math.inf, 10.0, 1e-9, "small"],
    "method": ["newton", 1.0],
    "inner_solve": ["lu", 1.0],
    "robin": [-1.0, 0.0, math.nan, math.inf, 1e6, "big"],
    "rho": [-1.0, 0.0, 1.5, math.nan],
    "eps_u": [-1.0, 0.0, 0.1, math.nan, math.inf],
    "max_iterations": [0, -5, 1.5, "many", math.nan],
    "mesh_level": [0, -1, 1000000, 2.5, "fine", math.nan],
    "element_size": [-1.0, 0.0, 1e-9, math.nan, math.inf, "10 MPa", "10 um"],
    "workers": ["threads", 1.0],
    "worker_timeout": [0.0, -1.0, math.nan, "long"],
    "memory_limit": [-1.0, 0.0, math.nan, "big"],
    "model_tolerance": [0.0, -0.1, 2.0, math.nan],
    "model_answers": ["shear", 1.0, ["contact"]],
    "body_fields": ["yes", 1.0],
    "solver": ["mumps"],
}
BASES = {"paper": SCENES_DIR / "paper.toml", "roller": SCENES_DIR / "roller.toml",
         "cylinder": SCENES_DIR / "cylinder.toml"}


def _set(data, key, value):
    table, _, name = key.partition(".")
    if not name:
        data[table] = value
    elif table == "coating":
        data["coating"][0][name] = value
    else:
        data.setdefault(table, {})[name] = value


def _cases():
    cases = []
    for key, (base, refused, accepted) in SCENE_KEYS.items():
        cases += [(f"{key}={value!r}", base, {key: value}, "refused") for value in refused]
        cases += [(f"{key}={value!r}", base, {key: value}, "accepted") for value in accepted]
    for key, values in UNITS_KEYS.items():
        cases += [(f"{key}={value!r}", "steel", {key: value}, "refused") for value in values]
    for key, values in SETTINGS.items():
        cases += [(f"settings.{key}={value!r}", "paper", {f"settings.{key}": value},
                   "refused") for value in values]
    return cases


CASES = _cases()


def _named(key):
    """How a message names a key: coating.E of the one patch is coating[1].E; a key of
    an unknown table is named by the table."""
    table = key.split(".")[0]
    if table not in ("indenter", "base", "coating", "load", "units", "settings", "symmetric",
                     "contact_zone"):
        return table
    return key.replace("coating.", "coating[1].").replace("settings.", "")


@pytest.mark.parametrize("base, changes, outcome", [case[1:] for case in CASES],
                         ids=[case[0] for case in CASES])
def test_a_scene_file_value_is_refused_naming_file_and_key_or_accepted(
        tmp_path, base, changes, outcome):
    if base == "steel":
        data = tomllib.loads(steel_scene(tmp_path / "steel.toml").read_text())
    else:
        data = tomllib.loads(BASES[base].read_text())
    for key, value in changes.items():
        _set(data, key, value)
    path = write_toml(tmp_path / "scene.toml", data)
    (key,) = changes
    try:
        scene, settings = scene_and_settings(path)
        prepare(scene, settings)                 # everything decided before a worker
    except ParameterError as error:
        assert outcome == "refused", f"accepted value refused: {error}"
        message = str(error)
        assert str(path) in message, message
        assert _named(key) in message, message
        return
    assert outcome == "accepted", f"{changes} was accepted"


def test_there_are_at_least_150_cases():
    assert len(CASES) + len(FILES) + len(STARTS) >= 150


# ---- whole files -------------------------------------------------------------------------

FILES = {
    "empty": (b"", "[indenter] is missing"),
    "not TOML": (b"[indenter\nradius = ", "not a valid TOML file"),
    "binary": (bytes(range(256)) * 4, "not"),
    "too large": (b"# " + b"x" * 10_000_001 + b"\n", "more than a scene file holds"),
    "nested too deeply": (b"a = " + b"[" * 100_000 + b"]" * 100_000 + b"\n", "nested"),
    "a folder": (None, "is a folder, not a file"),
    "missing": ("missing", "No such file"),
}


@pytest.mark.parametrize("name", FILES)
def test_a_bad_file_is_refused_naming_it(tmp_path, name):
    contents, words = FILES[name]
    path = tmp_path / "scene.toml"
    if contents is None:
        path.mkdir()
    elif contents != "missing":
        path.write_bytes(contents)
    with pytest.raises(ParameterError) as error:
        scene_and_settings(path)
    assert str(path) in str(error.value) and words in str(error.value), str(error.value)
    assert len(str(error.value)) < 1000


def test_a_byte_order_mark_is_read_as_the_file_without_it(tmp_path):
    text = (SCENES_DIR / "cylinder_mm.toml").read_bytes()
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + text)
    assert scene_and_settings(path) == scene_and_settings(SCENES_DIR / "cylinder_mm.toml")


# ---- start_from ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """A finished run of the paper's scene, and one of another layout (two patches)."""
    folder = tmp_path_factory.mktemp("finished")
    solve(*scene_and_settings(None, {"h2": 0.25}), folder / "run")
    discrete = SCENES_DIR / "discrete.toml"
    solve(*scene_and_settings(discrete, settings={"eps_u": 1e-4}), folder / "other")
    return folder


def _copy_with(finished, tmp_path, change):
    copy = tmp_path / "start"
    shutil.copytree(finished / "run", copy)
    change(copy)
    return copy


def _nan_in(name, column):
    def change(folder):
        table = pd.read_csv(folder / name)
        table.loc[0, column] = np.nan
        table.to_csv(folder / name, index=False)
    return change


STARTS = {
    "missing folder": (lambda f, t: t / "nothing", "no such folder"),
    "a file": (lambda f, t: f / "run" / "summary.json", "not a folder"),
    "an empty folder": (lambda f, t: t, "holds no finished run"),
    "another layout": (lambda f, t: f / "other", "another layout"),
    "not converged": (lambda f, t: _copy_with(f, t, lambda c: (c / "summary.json").write_text(
        json.dumps({**json.loads((c / "summary.json").read_text()), "converged": False,
                    "status": "stagnated"}))), "did not converge"),
    "summary not JSON": (lambda f, t: _copy_with(f, t, lambda c: (c / "summary.json")
                                                 .write_text("{")), "no readable summary"),
    "summary a list": (lambda f, t: _copy_with(f, t, lambda c: (c / "summary.json")
                                               .write_text("[]")), "not a run's"),
    "NaN in contact.csv": (lambda f, t: _copy_with(f, t, _nan_in("contact.csv", "sigma_n")),
                           "not finite"),
    "NaN in traces.csv": (lambda f, t: _copy_with(f, t, _nan_in("traces.csv", "a_n")),
                          "not finite"),
    "a table missing": (lambda f, t: _copy_with(f, t, lambda c: (c / "interface.csv").unlink()),
                        "interface.csv is missing"),
    "a column missing": (lambda f, t: _copy_with(f, t, lambda c: pd.read_csv(
        c / "traces.csv").drop(columns="b_n").to_csv(c / "traces.csv", index=False)),
                         "lacks the column"),
    "a scene not readable": (lambda f, t: _copy_with(f, t, lambda c: (c / "summary.json")
                             .write_text(json.dumps({**json.loads((c / "summary.json")
                                                                  .read_text()),
                                                     "scene": {"indenter": 1}}))),
                             "scene is not readable"),
}


@pytest.mark.parametrize("name", STARTS)
def test_a_bad_start_is_refused_before_any_worker_starts(finished, tmp_path, name,
                                                        monkeypatch):
    def no_worker(*args, **kwargs):
        raise AssertionError("a worker started")
    monkeypatch.setattr(worker.Worker, "__init__", no_worker)
    start, words = STARTS[name]
    scene, settings = scene_and_settings(None, {"h2": 0.25})
    with pytest.raises(ParameterError) as error:
        solve(scene, settings, tmp_path / "out", start_from=start(finished, tmp_path))
    assert error.value.key == "start_from" and words in str(error.value), str(error.value)
    assert not (tmp_path / "out").exists()


# ---- through the command line ---------------------------------------------------------------

COMMAND_LINE = [
    (["--set", "indenter.radius=1e160"], "indenter.radius"),
    (["--length", "1e300"], "indenter.width"),
    (["--set", "coating.E=nan"], "coating[1].E"),
    (["--h2", "20 um"], "has a unit"),
    (["--E2", "5 zorks"], "unknown unit"),
    (["--mesh-level", "1000000"], "mesh_level"),
    (["--set", "coating.E=" + "x" * 10_000], "characters"),
    (["--scene", str(SCENES_DIR)], "is a folder"),
    (["--element-size", "-1"], "element_size"),
    (["--out", "a\nb"], "line break"),
]


@pytest.mark.parametrize("arguments, words", COMMAND_LINE,
                         ids=[" ".join(a)[:40] for a, _ in COMMAND_LINE])
def test_the_command_line_refuses_with_exit_2_and_no_traceback(tmp_path, arguments, words):
    out = [] if "--out" in arguments else ["--out", str(tmp_path / "out")]
    run = subprocess.run([sys.executable, "-m", "orchestrate", "solve", *out, *arguments],
                         cwd=PROJECT_DIR, capture_output=True, text=True, timeout=120)
    assert run.returncode == 2, run.stderr
    assert "Traceback" not in run.stderr and words in run.stderr, run.stderr
    assert len(run.stderr) < 2000
