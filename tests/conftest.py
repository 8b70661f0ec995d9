"""Shared test helpers: running a FreeFEM test script, reading its CSV output."""

import os
import sys
from pathlib import Path

import pytest

PROJECT_DIR = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT_DIR))

from orchestrate.workers import freefem  # noqa: E402

TESTS_FREEFEM_DIR = Path(__file__).resolve().parent / "forms" / "freefem"

# A steel cylinder on a steel block with a hard coating, in mm and MPa (b = 2.5 mm: the
# paper's bodies, 4 b by 8 b); a contact about 1.8 mm wide, 11 interface elements.
STEEL_SCENE = """
symmetric = true
[units]
length = "mm"
stress = "MPa"
b = 2.5
[indenter]
radius = 100.0
width = 10.0
height = 20.0
E = {E}
nu = 0.3
[base]
width = 10.0
height = 20.0
E = {E}
nu = 0.3
[[coating]]
start = 0.0
end = 5.0
thickness = {thickness}
E = {E2}
nu = 0.25
model = "{model}"
[load]
force = {force}
"""
STEEL_VALUES = dict(E=210000.0, thickness=0.1, E2=450000.0, model="shell", force=800.0)


def steel_scene(path, **values):
    """Write the steel scene with ``values`` over STEEL_VALUES into ``path``; return it."""
    path.write_text(STEEL_SCENE.format(**{**STEEL_VALUES, **values}))
    return path


@pytest.fixture
def run_freefem(tmp_path):
    """Run tests/forms/freefem/<script> with arguments; return the folder it ran in.

    The script finds the project's .idp files on FreeFEM's include path; a failing
    script fails the test with the end of its log."""
    def run(script, *arguments):
        freefem.run_script(str(TESTS_FREEFEM_DIR / script), list(arguments),
                           os.path.join(tmp_path, f"{Path(script).stem}.log"))
        return tmp_path
    return run


def full_model(scene):
    """The full model of a half model: every patch and the contact zone mirrored about
    x1 = 0 (a patch on the axis doubles)."""
    from orchestrate.model.scene_file import apply_overrides

    overrides = {"symmetric": False}
    for number, coating in enumerate(scene.coatings, start=1):
        overrides[f"coating[{number}].start"] = -coating.end if coating.start == 0 else coating.start
    if scene.contact_zone is not None:
        overrides["contact_zone"] = [-scene.contact_zone[1], scene.contact_zone[1]]
    mirrored = apply_overrides(scene, overrides)
    off_axis = [c for c in scene.coatings if c.start > 0]
    if off_axis:      # their mirror images join the list
        from dataclasses import replace
        extra = tuple(replace(c, start=-c.end, end=-c.start) for c in off_axis)
        mirrored = apply_overrides(replace(mirrored, coatings=mirrored.coatings + extra), {})
    return mirrored


@pytest.fixture(scope="session")
def coating_2d_run(tmp_path_factory):
    """(scene, run folder): the paper's scene with the 2D coating h2 = b/8, E2 = 5E (a
    fig. 5 scene), solved once for the modules that read a 2D coating's fields."""
    from orchestrate.model.scene import Settings
    from orchestrate.model.scene_file import paper_scene
    from orchestrate.run.solve import solve

    folder = tmp_path_factory.mktemp("coating_2d") / "run"
    scene = paper_scene(h2=0.125, E2=5.0, model="elastic")
    solve(scene, Settings(), str(folder))
    return scene, folder


def processes_mentioning(text):
    """PIDs of live processes whose command line contains ``text``."""
    pids = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/cmdline", "rb") as f:
                    if text.encode() in f.read():
                        pids.append(int(entry))
            except OSError:
                pass
    return pids
