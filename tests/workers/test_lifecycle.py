"""No FreeFEM process, FIFO or temporary file outlives its run: after success, after
Ctrl-C or SIGTERM, and after a worker dies mid-run (which ends the run with a clear
error). Each run gets its own TMPDIR so that what it leaves behind can be seen."""

import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from tests.conftest import PROJECT_DIR, processes_mentioning

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


def _start(tmp_path, *arguments):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = dict(os.environ, TMPDIR=str(scratch))
    process = subprocess.Popen(
        [sys.executable, "-m", "orchestrate", "solve", "--out", str(tmp_path / "run"),
         "--quiet", *arguments],
        cwd=PROJECT_DIR, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return process, scratch


def _wait_for_workers(scratch, count=3, timeout=60):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        workers = [pid for pid in processes_mentioning(str(scratch))
                   if b"FreeFem++" in open(f"/proc/{pid}/cmdline", "rb").read()]
        if len(workers) >= count:
            return workers
        time.sleep(0.05)
    raise AssertionError("the workers did not start")


def _assert_nothing_left(scratch):
    deadline = time.monotonic() + 5
    while processes_mentioning(str(scratch)) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert processes_mentioning(str(scratch)) == []
    assert list(scratch.iterdir()) == []


# The paper's loop at the default penalty runs for a long time: a run to interrupt.
LONG_RUN = ("--method", "paper", "--max-iterations", "100000")


def test_a_finished_run_leaves_nothing(tmp_path):
    process, scratch = _start(tmp_path, "--eps-u", "1e-4")
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 0, stderr
    _assert_nothing_left(scratch)


@pytest.mark.parametrize("signal_number, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)],
                         ids=["Ctrl-C", "SIGTERM"])
def test_an_interrupted_run_leaves_nothing(tmp_path, signal_number, code):
    process, scratch = _start(tmp_path, *LONG_RUN)
    _wait_for_workers(scratch)
    time.sleep(1.0)                      # well inside the Robin loop
    process.send_signal(signal_number)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == code, stderr
    assert ("interrupted" if signal_number == signal.SIGINT else "terminated") in stderr
    _assert_nothing_left(scratch)
    assert not (tmp_path / "run" / "summary.json").exists()


def test_a_dying_worker_ends_the_run_with_a_clear_error(tmp_path):
    process, scratch = _start(tmp_path, *LONG_RUN)
    workers = _wait_for_workers(scratch)
    time.sleep(1.0)
    coating = [pid for pid in workers
               if b"shell.edp" in open(f"/proc/{pid}/cmdline", "rb").read()]
    os.kill(coating[0], signal.SIGKILL)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 3, stderr
    assert "worker coating1 died: killed" in stderr
    _assert_nothing_left(scratch)
    assert not (tmp_path / "run" / "summary.json").exists()


def test_a_worker_is_killed_and_reaped_even_where_a_signal_left_its_wait_lock_held(tmp_path):
    """A signal that interrupts Popen.poll between its lock's acquire and its try leaves
    the lock held (CPython's lock and try are not signal-safe), and Popen.wait would
    then block for ever: a run terminated by SIGTERM under load hung so in its clean-up,
    one worker killed and not reaped, the next never killed. Worker.kill reaps by
    os.waitpid. Here a process stands in for the worker, its lock held as such a signal
    leaves it."""
    from orchestrate.workers.worker import Worker
    worker = Worker.__new__(Worker)
    worker.process = subprocess.Popen(["sleep", "60"], start_new_session=True)
    worker._request_fd = worker._reply_fd = None
    worker.request_path = worker.reply_path = str(tmp_path / "absent")
    worker.process._waitpid_lock.acquire()
    killing = threading.Thread(target=worker.kill, daemon=True)
    killing.start()
    killing.join(timeout=10)
    assert not killing.is_alive(), "kill blocked"
    assert worker.process.returncode == -signal.SIGKILL
    assert not os.path.exists(f"/proc/{worker.process.pid}")      # reaped, not a zombie
