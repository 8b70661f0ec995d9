"""The Python API (orchestrate/run/api.py) as a notebook user meets it: the package
installed with `pip install -e .` into a fresh venv, imported from another directory,
``orchestrate.solve`` returning arrays and frames without an output folder."""

import dataclasses
import json
import os
import subprocess
import sys
import sysconfig
import time

import numpy as np
import pytest

import orchestrate
from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

USE = """
import json, orchestrate
result = orchestrate.solve(orchestrate.paper_scene(h2=0.125, E2=5.0))
print(json.dumps({"module": orchestrate.__file__, "type": type(result.contact).__name__,
                  "sigma_n": result.contact.sigma_n.tolist(),
                  "peak": result.answers["contact"]["peak_pressure"]["value"]}))
"""


@pytest.fixture(scope="module")
def api_result():
    return orchestrate.solve(orchestrate.paper_scene(h2=0.125, E2=5.0))


def test_a_fresh_venv_installs_the_package_and_solves_from_elsewhere(tmp_path, api_result):
    """The fresh venv takes the pinned dependencies from the project's venv (a .pth
    file: no network in a test) and installs only orchestrate itself."""
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    python = venv / "bin" / "python"
    site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          capture_output=True, text=True, check=True).stdout.strip()
    with open(os.path.join(site, "project_dependencies.pth"), "w") as pth:
        pth.write(sysconfig.get_paths()["purelib"] + "\n")
    # the build backend too (a venv of Python 3.11 brings an old setuptools of its own)
    build_env = dict(os.environ, PYTHONPATH=sysconfig.get_paths()["purelib"])
    install = subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps",
                              "--disable-pip-version-check", "--no-build-isolation", "-e",
                              str(PROJECT_DIR)],
                             capture_output=True, text=True, timeout=600, env=build_env)
    assert install.returncode == 0, install.stderr
    assert install.stdout + install.stderr == "", "the install warns"   # as `make` runs it
    elsewhere = tmp_path / "notebook"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run([str(python), "-c", USE], cwd=elsewhere, env=env,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    found = json.loads(run.stdout.strip().splitlines()[-1])
    assert found["module"] == str(PROJECT_DIR / "orchestrate" / "__init__.py")
    assert found["type"] == "DataFrame"
    # the same run as in this process (same scene, settings, meshes) up to the solvers'
    # round-off, which is not bit-reproducible between processes
    np.testing.assert_allclose(found["sigma_n"], api_result.contact.sigma_n.to_numpy(),
                               rtol=1e-9)
    assert found["peak"] == max(-np.array(found["sigma_n"]))


def test_the_result_holds_the_run_and_saves_the_command_lines_files(tmp_path, api_result):
    assert api_result.summary["converged"]
    assert set(api_result.fields) == {"indenter", "base", "coating1"}
    assert {"x1", "x2", "T11", "M11"} <= set(api_result.fields["coating1"].columns)
    assert len(api_result.interface) and len(api_result.history) == api_result.summary["iterations"]
    out = api_result.save(tmp_path / "saved")
    assert sorted(os.listdir(out)) == sorted(api_result.files)
    assert json.loads((out / "summary.json").read_text()) == api_result.summary
    with pytest.raises(Exception, match="saved"):
        api_result.save(tmp_path / "saved")          # a run's folder is never overwritten


def test_settings_as_a_dict_and_a_scene_file(api_result):
    from orchestrate.model.scene_file import SCENES_DIR
    result = orchestrate.solve(SCENES_DIR / "cylinder.toml", {"eps_u": 1e-4})
    assert result.summary["settings"]["eps_u"] == 1e-4
    assert result.summary["total_force"] == pytest.approx(0.02, rel=1e-6)


def test_an_unknown_setting_is_refused_by_name_before_any_work():
    from orchestrate.errors import ParameterError
    with pytest.raises(ParameterError, match="unknown setting 'bogus'"):
        orchestrate.solve(orchestrate.paper_scene(), {"bogus": 1})


def test_the_folder_of_an_api_run_killed_meanwhile_goes_with_the_next_run(tmp_path):
    """A process killed during orchestrate.solve (here while it commits its files) leaves
    its private folder under the temporary folder; the next run removes it (its lock is
    free), and leaves none of its own."""
    tmp, marker = tmp_path / "tmp", tmp_path / "paused"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp), ORCHESTRATE_PAUSE_AT="committing",
               ORCHESTRATE_PAUSE_FILE=str(marker))
    solving = "import orchestrate; orchestrate.solve(orchestrate.paper_scene(h2=0.25))"
    killed = subprocess.Popen([sys.executable, "-c", solving], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while not marker.exists():
        assert killed.poll() is None and time.monotonic() < deadline, killed.communicate()
        time.sleep(0.02)
    killed.kill()
    killed.wait()
    left = list(tmp.glob("orchestrate-api-*"))
    assert len(left) == 1 and list(left[0].glob("run")) + list(left[0].glob(".run.partial-*"))
    env.pop("ORCHESTRATE_PAUSE_AT")
    subprocess.run([sys.executable, "-c", solving], env=env, check=True, timeout=300,
                   capture_output=True)
    assert list(tmp.glob("orchestrate-api-*")) == [] and list(tmp.glob("robin-*")) == []


def test_a_run_started_from_a_result_names_it_not_a_deleted_folder(api_result, tmp_path):
    """Not the temporary folder its files were read from, gone by then: the folder it was
    saved into, or that it was not."""
    scene = orchestrate.paper_scene(h2=0.125, E2=5.0)
    unsaved = dataclasses.replace(api_result, folder=None)
    again = orchestrate.solve(scene, start_from=unsaved)
    assert again.summary["started_from"] == "a Result in memory"
    saved = unsaved.save(tmp_path / "saved")
    again = orchestrate.solve(scene, start_from=unsaved)
    assert again.summary["started_from"] == str(saved.resolve())


def test_a_process_killed_in_a_monolithic_solve_leaves_no_solver_and_its_folder_goes(tmp_path):
    """A study killed while it solves monolithically (SIGKILL: nothing of its own runs)
    takes its FreeFEM solve with it, and the next run's working folder removes its
    folder (its lock is free)."""
    from orchestrate.files.folders import WorkFolder, remove_dead_work_folders
    from tests.conftest import processes_mentioning
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    solving = ("from orchestrate.run.monolithic import monolithic_solution; "
               "from orchestrate.model.scene import Settings; import orchestrate; "
               "monolithic_solution(orchestrate.paper_scene(h2=0.25), Settings(mesh_level=3))")
    killed = subprocess.Popen([sys.executable, "-c", solving], cwd=PROJECT_DIR,
                              env=dict(os.environ, TMPDIR=str(tmp)),
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while not [pid for pid in processes_mentioning(str(tmp))
               if b"monolithic.edp" in open(f"/proc/{pid}/cmdline", "rb").read()]:
        assert killed.poll() is None and time.monotonic() < deadline, killed.communicate()
        time.sleep(0.02)
    killed.kill()
    killed.wait()
    time.sleep(0.3)                                   # the solver follows it
    assert processes_mentioning(str(tmp)) == []
    assert len(list(tmp.glob(WorkFolder.MONOLITHIC_PREFIX + "*"))) == 1
    remove_dead_work_folders(tmp)
    assert list(tmp.iterdir()) == []


def test_the_command_line_loads_no_pandas_until_a_command_needs_it():
    """The package's names are imported when first asked for (orchestrate/__init__.py,
    orchestrate/run/__init__.py): the command line and a run without a load path or a
    start need no pandas (with it, `--help` had taken over a second), while the API's
    names are there when asked."""
    probe = ("import sys, orchestrate, orchestrate.cli, orchestrate.run.solve\n"
             "print('pandas' in sys.modules)\n"
             "from orchestrate import Result, solve\n"
             "print(solve is orchestrate.run.api.solve, Result.__name__)\n"
             "print(sorted(set(orchestrate.__all__) - set(dir(orchestrate))))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          cwd=PROJECT_DIR, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:3] == ["False", "True Result", "[]"]
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        orchestrate.nothing
