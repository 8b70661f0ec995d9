"""The studies run from the repository, apart from the installed tool: every study
module's command line answers --help (it imports, through the tool's public API), and a
non-editable install of the tool carries its FreeFEM forms but no study."""

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

STUDIES = sorted(path.stem for path in (PROJECT_DIR / "studies").glob("*.py")
                 if "def main(" in path.read_text())


# Each study as `python -m studies.NAME --help` runs it (runpy, as __main__), all in one
# interpreter apart from the tests' (one start of the tool's imports instead of one each):
# {name: [exit code, what it printed]} as JSON
HELP_OF_EVERY_STUDY = """
import contextlib, io, json, runpy, sys, traceback
answers = {}
for study in sys.argv[1:]:
    out, code = io.StringIO(), None
    sys.argv = [f"studies.{study}", "--help"]
    try:
        with contextlib.redirect_stdout(out):
            runpy.run_module(f"studies.{study}", run_name="__main__", alter_sys=True)
    except SystemExit as exit:
        code = exit.code or 0
    except BaseException:
        code, out = 1, io.StringIO(traceback.format_exc())
    answers[study] = [code, out.getvalue()]
print(json.dumps(answers))
"""


@pytest.fixture(scope="module")
def study_help():
    run = subprocess.run([sys.executable, "-c", HELP_OF_EVERY_STUDY, *STUDIES],
                         cwd=PROJECT_DIR, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("study", STUDIES)
def test_every_study_runs_from_the_repository(study, study_help):
    code, printed = study_help[study]
    assert code == 0 and "usage" in printed, printed


SOLVE_ELSEWHERE = """
import json, orchestrate, orchestrate.paths
result = orchestrate.solve(orchestrate.paper_scene(h2=0.25), {"eps_u": 1e-4})
print(json.dumps({"forms": str(orchestrate.paths.FREEFEM_DIR),
                  "converged": result.summary["converged"],
                  "gallery": sorted(p.name for p in
                                    (orchestrate.paths.SCENES_DIR / "gallery").glob("*.toml"))}))
"""


def test_an_install_of_the_tool_has_its_forms_and_no_study(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    python = venv / "bin" / "python"
    site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()"
                           "['purelib'])"], capture_output=True, text=True, check=True).stdout
    # the pinned dependencies from the project's venv (no network in a test)
    Path(site.strip(), "project_dependencies.pth").write_text(
        sysconfig.get_paths()["purelib"] + "\n")
    build_env = dict(os.environ, PYTHONPATH=sysconfig.get_paths()["purelib"])
    source = tmp_path / "source"                 # built from a copy: the build's own files
    for name in ("orchestrate", "freefem", "studies"):   # stay out of the checkout
        shutil.copytree(PROJECT_DIR / name, source / name, symlinks=True,
                        ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(PROJECT_DIR / name, source / name)
    install = subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps",
                              "--disable-pip-version-check", "--no-build-isolation",
                              str(source)], capture_output=True, text=True, timeout=600,
                             env=build_env, cwd=tmp_path)
    assert install.returncode == 0, install.stderr
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    solved = subprocess.run([str(python), "-c", SOLVE_ELSEWHERE], cwd=elsewhere, env=env,
                            capture_output=True, text=True, timeout=600)
    assert solved.returncode == 0, solved.stderr
    found = solved.stdout.strip().splitlines()[-1]
    assert '"converged": true' in found and site.strip() in found      # the installed forms
    gallery = sorted(p.name for p in (PROJECT_DIR / "orchestrate/scenes/gallery").glob("*.toml"))
    assert gallery and json.loads(found)["gallery"] == gallery      # and the gallery's scenes
    studies = subprocess.run([str(python), "-c", "import studies"], cwd=elsewhere, env=env,
                             capture_output=True, text=True, timeout=60)
    assert studies.returncode != 0 and "No module named 'studies'" in studies.stderr
