"""Every run says what it ran, and an edited form takes effect in every path.

The forms are read from a copy of freefem/ (ORCHESTRATE_FORMS, orchestrate/workers/freefem.py),
edited here as a user edits freefem/: the bodies' law made 25 % stiffer (the Lame
constants' functions of elasticity.idp scaled). Then a fresh run, a kept worker (a
Session) and a resumed sweep must all give the edited law's answer, and the recorded
hashes must tell the two laws apart.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

import orchestrate
from orchestrate.paths import FORMS_VARIABLE, FREEFEM_DIR
from orchestrate.workers.provenance import forms_digest, forms_hashes
from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

SCENE = {"h2": 0.125, "E2": 1.0, "model": "shell"}


def edit_law(folder):
    """Scale the Lame constants of elasticity.idp by 1.25 in the forms ``folder``."""
    path = folder / "elasticity.idp"
    text = path.read_text()
    edited = re.sub(r"(func real lame(Lambda|Mu)\(real E, real nu\) \{ return )", r"\g<1>1.25*",
                    text)
    assert edited.count("1.25*") == 2, "elasticity.idp no longer has the Lame functions"
    path.write_text(edited)


@pytest.fixture
def forms(tmp_path, monkeypatch):
    """A copy of freefem/ that the runs read."""
    copy = tmp_path / "forms"
    shutil.copytree(FREEFEM_DIR, copy)
    monkeypatch.setenv(FORMS_VARIABLE, str(copy))
    return copy


def _peak(result):
    return result.summary["peak_contact_stress"]


def test_a_run_records_its_code_and_the_hash_of_every_form_it_read(forms):
    first = orchestrate.solve(orchestrate.paper_scene(**SCENE))
    recorded = first.summary["provenance"]
    assert recorded["forms_dir"] == str(forms)
    assert set(recorded["forms"]) == {path.name for path in FREEFEM_DIR.iterdir()
                                      if path.suffix in (".idp", ".edp")} - {"monolithic.edp"}
    assert recorded["forms"] == forms_hashes() and recorded["forms_digest"] == forms_digest()
    assert recorded["package_version"] == orchestrate_version()
    if (PROJECT_DIR / ".git").exists():
        assert re.fullmatch(r"[0-9a-f]{40}", recorded["git_commit"])
        assert isinstance(recorded["git_tree_modified"], bool)
    edit_law(forms)
    second = orchestrate.solve(orchestrate.paper_scene(**SCENE))
    changed = {name for name, value in second.summary["provenance"]["forms"].items()
               if recorded["forms"][name] != value}
    assert changed == {"elasticity.idp"}
    assert second.summary["provenance"]["forms_digest"] != recorded["forms_digest"]
    assert abs(_peak(second) / _peak(first) - 1.0) > 0.01       # the edit shows


def orchestrate_version():
    from importlib import metadata
    return metadata.version("orchestrate")


def test_a_kept_worker_takes_an_edited_form_before_its_next_scene(forms):
    scene = orchestrate.paper_scene(**SCENE)
    with orchestrate.Session() as session:
        before = orchestrate.solve(scene, session=session)
        kept = orchestrate.solve(scene, session=session)
        assert kept.summary["workers_kept"]                      # the session keeps them
        edit_law(forms)
        after = orchestrate.solve(scene, session=session)
    assert not after.summary["workers_kept"]                      # restarted: new forms
    fresh = orchestrate.solve(scene)                              # the edited law, alone
    assert _peak(after) == pytest.approx(_peak(fresh), rel=1e-9)
    assert abs(_peak(after) / _peak(before) - 1.0) > 0.01
    assert after.summary["provenance"]["forms_digest"] == fresh.summary["provenance"][
        "forms_digest"] != before.summary["provenance"]["forms_digest"]


def test_a_sweep_resumed_after_an_edit_runs_its_points_again(forms, tmp_path):
    sweep = tmp_path / "sweep.toml"
    sweep.write_text('name = "edited"\n[fixed]\nmodel = "shell"\n[grid]\nh2 = [0.25, 0.125]\n')
    command = [sys.executable, "-m", "orchestrate", "sweep", str(sweep), "--jobs", "1",
               "--out", str(tmp_path / "out")]
    env_run = {"cwd": PROJECT_DIR, "capture_output": True, "text": True, "timeout": 300}
    first = subprocess.run(command, **env_run)
    assert first.returncode == 0, first.stderr
    before = pd.read_csv(tmp_path / "out" / "runs.csv")
    again = subprocess.run(command, **env_run)                  # nothing edited: nothing run
    assert again.returncode == 0 and "other FreeFEM forms" not in again.stderr
    assert (pd.read_csv(tmp_path / "out" / "runs.csv")["wall_time_s"]
            == before["wall_time_s"]).all()
    edit_law(forms)
    resumed = subprocess.run(command, **env_run)
    assert resumed.returncode == 0, resumed.stderr
    assert ("2 point(s) since they ran: solved with other FreeFEM forms than the files' now"
            in resumed.stderr)
    after = pd.read_csv(tmp_path / "out" / "runs.csv")
    assert set(after["forms_digest"]) == {forms_digest()} != set(before["forms_digest"])
    assert np.all(np.abs(after["peak_contact_stress"] / before["peak_contact_stress"] - 1)
                  > 0.01)
    summary = json.loads((tmp_path / "out" / "runs" / after["id"][0] / "summary.json")
                         .read_text())
    assert summary["provenance"]["forms_dir"] == str(forms)


def test_forms_edited_while_a_sweep_runs_leave_no_stale_point(forms, tmp_path):
    """The forms edited once the first point is solved (the sweep's worker process keeps
    its FreeFEM workers from point to point): the later points restart their workers,
    and the first is solved again once the pass is over; every row is the edited law's."""
    from orchestrate.sweeps import run_sweep

    sweep = tmp_path / "sweep.toml"
    sweep.write_text('name = "mid"\n[fixed]\nmodel = "shell"\n[grid]\nh2 = [0.25, 0.125]\n')
    solved = []

    def edit_after_the_first(name=None):
        if name is not None:
            solved.append(name)
            if len(solved) == 1:
                edit_law(forms)
    table = run_sweep(sweep, tmp_path / "out", jobs=1, stream=open("/dev/null", "w"),
                      run_done=edit_after_the_first)
    assert len(solved) == 3 and solved[0] == solved[2]        # the first point again
    assert set(table["forms_digest"]) == {forms_digest()}
    fresh = [orchestrate.solve(orchestrate.paper_scene(model="shell", h2=h2))
             for h2 in (0.25, 0.125)]
    assert table["peak_contact_stress"].tolist() == pytest.approx(
        [_peak(result) for result in fresh], rel=1e-9)


def test_a_form_edited_while_a_run_goes_on_is_said(forms, tmp_path):
    """The run paused once its workers have started (orchestrate/faults.py), a form
    edited meanwhile: the run cannot tell which version its workers read, and says so
    (warning forms_edited); its provenance keeps the hashes of its start."""
    marker, out = tmp_path / "paused", tmp_path / "run"
    before = forms_digest()
    env = dict(os.environ, ORCHESTRATE_PAUSE_AT="setup", ORCHESTRATE_PAUSE_FILE=str(marker))
    run = subprocess.Popen([sys.executable, "-m", "orchestrate", "solve", "--quiet", "--out",
                            str(out)], cwd=PROJECT_DIR, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not marker.exists():
        assert run.poll() is None and time.monotonic() < deadline, run.communicate()
        time.sleep(0.02)
    with open(forms / "shell.idp", "a") as form:
        form.write("// an edit while the run goes on\n")
    marker.unlink()
    _, stderr = run.communicate(timeout=300)
    assert run.returncode == 0, stderr
    summary = json.loads((out / "summary.json").read_text())
    assert "forms_edited" in [w["code"] for w in summary["warnings"]]
    assert "warning (forms_edited)" in stderr
    assert summary["provenance"]["forms_digest"] == before != forms_digest()
