"""Faults, injected: every run ends with the exit status of orchestrate/errors.py and
leaves no process, FIFO, working folder, or file that looks complete but is not.

Each run gets its own TMPDIR (its working folder robin-* lives there) and output folder.
A run is held at a phase of its life by orchestrate/faults.py's pause points (it writes
a marker file and waits until the test removes it), so that a signal or a worker's
death lands in that phase: meshing (signals wait for the mesher: gmsh resets the
handlers while it works), set-up, iterations, output (the workers writing their files),
committing (the run complete in its scratch folder). Afterwards the output folder is
either absent or one complete run, and nothing is left beside it; after a SIGKILL of the
driver, which can clean nothing, the next run into the same folder and TMPDIR removes
what it left.
"""

import json
import os
import resource
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

from tests.conftest import PROJECT_DIR, processes_mentioning

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

PHASES = ("meshing", "setup", "iterating", "output", "committing")


class Run:
    """A `solve` command in its own TMPDIR, optionally held at a phase."""

    def __init__(self, root, *arguments, pause=None, out=None, limit_bytes=None):
        self.root = root
        self.tmp = root / "tmp"
        self.tmp.mkdir(exist_ok=True)
        self.out = out or root / "run"
        self.marker = root / "paused"
        env = dict(os.environ, TMPDIR=str(self.tmp))
        if pause:
            env.update(ORCHESTRATE_PAUSE_AT=pause, ORCHESTRATE_PAUSE_FILE=str(self.marker))

        def limit():
            if limit_bytes is not None:
                resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
        self.process = subprocess.Popen(
            [sys.executable, "-m", "orchestrate", "solve", "--out", str(self.out), "--quiet",
             *arguments], cwd=PROJECT_DIR, env=env, stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, text=True, preexec_fn=limit)

    def wait_paused(self, timeout=60):
        deadline = time.monotonic() + timeout
        while not self.marker.exists():
            assert self.process.poll() is None, self.finish()
            assert time.monotonic() < deadline, "the run did not reach its pause"
            time.sleep(0.02)

    def resume(self):
        self.marker.unlink(missing_ok=True)

    def finish(self, timeout=120):
        _, self.stderr = self.process.communicate(timeout=timeout)
        return self.process.returncode

    def workers(self):
        return [pid for pid in processes_mentioning(str(self.tmp))
                if b"FreeFem++" in open(f"/proc/{pid}/cmdline", "rb").read()]

    def worker(self, script):
        return next(pid for pid in self.workers()
                    if script.encode() in open(f"/proc/{pid}/cmdline", "rb").read())

    def assert_clean(self, completed):
        """Nothing alive, no working folder, and the output folder a complete run or
        absent, with nothing beside it."""
        deadline = time.monotonic() + 5
        while processes_mentioning(str(self.tmp)) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert processes_mentioning(str(self.tmp)) == []
        assert list(self.tmp.iterdir()) == []
        beside = [p.name for p in self.out.parent.iterdir() if p.name.startswith(f".{self.out.name}.")]
        assert beside == []
        if completed:
            assert_complete(self.out)
        else:
            assert not self.out.exists()


def assert_complete(folder):
    summary = json.loads((folder / "summary.json").read_text())
    pd.read_csv(folder / "history.csv")
    if summary["converged"]:
        for name in ("contact.csv", "interface.csv", "traces.csv", "indenter.csv", "base.csv"):
            assert len(pd.read_csv(folder / name)) > 0, name
    else:
        assert sorted(os.listdir(folder)) == ["history.csv", "summary.json"]
    return summary


# ---- signals and deaths in every phase --------------------------------------------------

@pytest.mark.parametrize("phase", PHASES)
@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)],
                         ids=["SIGINT", "SIGTERM"])
def test_a_signal_in_any_phase_stops_the_run_cleanly(tmp_path, phase, signum, code):
    run = Run(tmp_path, pause=phase)
    run.wait_paused()
    run.process.send_signal(signum)
    if phase == "meshing":       # held back until the mesher is done with the body
        time.sleep(0.3)
        assert run.process.poll() is None
        run.resume()
    assert run.finish() == code, run.stderr
    run.assert_clean(completed=False)


@pytest.mark.parametrize("phase", PHASES)
def test_a_killed_driver_leaves_what_the_next_run_removes(tmp_path, phase):
    run = Run(tmp_path, pause=phase)
    run.wait_paused()
    run.process.kill()
    assert run.finish() == -signal.SIGKILL
    time.sleep(0.3)                                    # its workers follow it
    assert processes_mentioning(str(run.tmp)) == []
    again = Run(tmp_path, "--eps-u", "1e-4")
    assert again.finish() == 0, again.stderr
    again.assert_clean(completed=True)


@pytest.mark.parametrize("phase", ["setup", "iterating", "output"])
@pytest.mark.parametrize("script", ["body.edp", "shell.edp"])
def test_a_dying_worker_fails_the_run_cleanly(tmp_path, phase, script):
    run = Run(tmp_path, pause=phase)
    run.wait_paused()
    os.kill(run.worker(script), signal.SIGKILL)
    run.resume()
    assert run.finish() == 3, run.stderr
    assert "died: killed" in run.stderr
    run.assert_clean(completed=False)


def test_a_stopped_worker_fails_the_run_after_its_timeout(tmp_path):
    run = Run(tmp_path, "--worker-timeout", "2", pause="iterating")
    run.wait_paused()
    os.kill(run.worker("shell.edp"), signal.SIGSTOP)
    run.resume()
    assert run.finish() == 3, run.stderr
    assert "gave no answer for 2 s" in run.stderr
    run.assert_clean(completed=False)


# ---- files ---------------------------------------------------------------------------

@pytest.mark.parametrize("limit", [20_000, 200_000], ids=["inputs", "outputs"])
def test_a_file_size_limit_fails_the_run_naming_it(tmp_path, limit):
    """20 kB: the meshes cannot be written; 200 kB: a body's nodal CSV (300 kB) cannot."""
    run = Run(tmp_path, limit_bytes=limit)
    assert run.finish() == 3, run.stderr
    assert "file size limit" in run.stderr
    run.assert_clean(completed=False)


def test_a_full_disk_fails_the_run_naming_it(tmp_path):
    disk = tmp_path / "small"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=400k", "tmpfs", str(disk)],
                             capture_output=True)
    if mounted.returncode != 0:
        pytest.skip("cannot mount a small tmpfs here (not root)")
    try:
        run = Run(tmp_path, out=disk / "run")
        assert run.finish() == 3, run.stderr
        assert "the disk is full" in run.stderr
        run.assert_clean(completed=False)
        assert os.listdir(disk) == []
    finally:
        subprocess.run(["umount", str(disk)], check=True)


# ---- one folder, one run --------------------------------------------------------------

def test_two_runs_into_one_folder_the_second_is_refused(tmp_path):
    first = Run(tmp_path, pause="setup")
    first.wait_paused()
    second = Run(tmp_path, "--model", "elastic", out=first.out)
    assert second.finish() == 2
    assert "another run is writing into it" in second.stderr
    first.resume()
    assert first.finish() == 0, first.stderr
    first.assert_clean(completed=True)
    summary = json.loads((first.out / "summary.json").read_text())
    assert summary["scene"]["coatings"][0]["model"] == "shell"


def test_an_earlier_run_is_kept_unless_overwritten_and_then_replaced_whole(tmp_path):
    first = Run(tmp_path, "--eps-u", "1e-4")
    assert first.finish() == 0
    (first.out / "notes.txt").write_text("mine")
    refused = Run(tmp_path, "--eps-u", "1e-4")
    assert refused.finish() == 2 and "holds an earlier run" in refused.stderr
    assert (first.out / "notes.txt").exists()
    # a run that does not converge replaces it whole: no old stresses beside the report
    failed = Run(tmp_path, "--overwrite", "--max-iterations", "3")
    assert failed.finish() == 1, failed.stderr
    failed.assert_clean(completed=True)
    assert not (first.out / "notes.txt").exists()
    plotted = subprocess.run([sys.executable, "-m", "orchestrate", "plot", str(first.out)],
                             cwd=PROJECT_DIR, capture_output=True, text=True)
    assert plotted.returncode == 2 and "did not converge" in plotted.stderr


def test_a_folder_of_other_files_is_never_written(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("do not touch")
    run = Run(tmp_path, "--overwrite", out=out)
    assert run.finish() == 2 and "not a run's" in run.stderr
    assert os.listdir(out) == ["thesis.tex"]


def test_an_unwritable_output_is_refused_before_any_work(tmp_path):
    target = tmp_path / "file"
    target.write_text("")
    start = time.monotonic()
    run = Run(tmp_path, out=target)
    assert run.finish() == 2 and "is a file" in run.stderr
    assert time.monotonic() - start < 10
    assert list(run.tmp.iterdir()) == [] and target.read_text() == ""


@pytest.mark.parametrize("signum, code", [(signal.SIGHUP, 129), (signal.SIGQUIT, 131)],
                         ids=["SIGHUP", "SIGQUIT"])
def test_a_hang_up_or_quit_stops_the_run_cleanly(tmp_path, signum, code):
    run = Run(tmp_path, pause="iterating")
    run.wait_paused()
    run.process.send_signal(signum)
    assert run.finish() == code, run.stderr
    run.assert_clean(completed=False)


def test_a_second_ctrl_c_does_not_cut_the_clean_up_short(tmp_path):
    run = Run(tmp_path, pause="iterating")
    run.wait_paused()
    run.process.send_signal(signal.SIGINT)
    time.sleep(0.05)
    run.process.send_signal(signal.SIGINT)
    assert run.finish() == 130, run.stderr
    run.assert_clean(completed=False)


def test_a_closed_stdout_does_not_stop_the_run(tmp_path):
    reader, writer = os.pipe()
    os.close(reader)
    env = dict(os.environ, TMPDIR=str(tmp_path))
    out = tmp_path / "run"
    process = subprocess.run([sys.executable, "-m", "orchestrate", "solve", "--out", str(out),
                              "--eps-u", "1e-4"], cwd=PROJECT_DIR, env=env, stdout=writer,
                             stderr=subprocess.PIPE, text=True, timeout=120)
    os.close(writer)
    assert process.returncode == 0, process.stderr
    assert_complete(out)
    assert [p.name for p in tmp_path.iterdir()] == ["run"]
