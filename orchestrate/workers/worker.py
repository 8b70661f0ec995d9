"""Persistent FreeFEM workers that answer requests through FIFOs.

A worker script (freefem/body.edp, freefem/shell.edp) assembles and factorises once,
replies that it is ready, then loops: read a request, solve, reply; requests and replies
are the records of orchestrate/workers/exchange.py. The driver keeps both FIFOs open
read-write for the worker's whole life, so that the worker's opens never block
and a reply can be awaited with a timeout while checking that the worker is alive. A
worker that dies, or says nothing for ``timeout`` seconds, raises ``WorkerError`` with
the end of its log.
"""

import fcntl
import functools
import os
import re
import select
import signal
import subprocess
import time

from orchestrate.workers import freefem
from orchestrate.workers.children import die_with_parent
from orchestrate.workers.exchange import BinaryNumbers, Command, RecordError, encode_binary
from orchestrate.errors import SystemFailure

# Workers run side by side, one per core. FreeFEM links OpenMP, whose idle threads spin:
# with more than one per worker they take the cores the other workers need (measured at
# mesh level 3: 25-30 % more time per Robin iteration). One thread each.
THREADS = {"OMP_NUM_THREADS": "1"}

_POLL_SECONDS = 0.05
REPLY_BUFFER = 1 << 20       # bytes of a reply FIFO (_widen)

# what a worker's death by a signal most likely means
_DEATHS = {signal.SIGXFSZ: "a file size limit was reached (ulimit -f)",
           signal.SIGKILL: "killed (by a user, or by the kernel for want of memory)",
           signal.SIGSEGV: "crashed (segmentation fault)",
           signal.SIGABRT: "aborted"}


# What a worker's log says when it ran out of memory: MUMPS's error -13 (its factors could
# not be allocated), C++'s bad_alloc.
_OUT_OF_MEMORY = re.compile(r"Mumps seq: number -13|INFOG\(1\)= +-13|bad_alloc")


def _widen(fd):
    """Let a FIFO hold a whole reply of fields (a body's, on the paper's mesh), so that
    the workers write theirs side by side while the driver reads one after the other;
    at most what the system allows an unprivileged process, else as it was."""
    try:
        with open("/proc/sys/fs/pipe-max-size") as limit:
            fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, min(REPLY_BUFFER, int(limit.read())))
    except (OSError, ValueError):
        pass


class WorkerError(SystemFailure):
    """A worker died, timed out or answered something unexpected."""


class Worker:
    """One FreeFEM process; ``name`` (its subdomain's) names it in messages, ``stem`` (by
    default the name) its FIFOs and log inside ``workdir``."""

    def __init__(self, name, script, arguments, workdir, timeout, stem=None):
        self.name = name
        self.timeout = timeout
        stem = stem or name
        self.request_path = os.path.join(workdir, f"{stem}.request")
        self.reply_path = os.path.join(workdir, f"{stem}.reply")
        self.log_path = os.path.join(workdir, f"{stem}.log")
        self.process = None
        self._request_fd = self._reply_fd = None
        self._replies_owed = 0      # requests sent whose replies are not read
        self._arrived = bytearray()  # reply bytes read from the FIFO, not yet taken
        command = freefem.command(script, [*arguments, "-request", self.request_path,
                                           "-reply", self.reply_path])
        try:
            os.mkfifo(self.request_path)
            os.mkfifo(self.reply_path)
            # O_RDWR keeps a reader and a writer on each FIFO: the worker's opens return
            # at once, and select() sees a reply only when there is one.
            self._request_fd = os.open(self.request_path, os.O_RDWR)
            self._reply_fd = os.open(self.reply_path, os.O_RDWR | os.O_NONBLOCK)
            _widen(self._reply_fd)
            with open(self.log_path, "w") as log:
                self.process = subprocess.Popen(
                    command, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                    env=freefem.environment() | THREADS, start_new_session=True,
                    preexec_fn=functools.partial(die_with_parent, os.getpid()))
        except BaseException:
            self.kill()
            raise

    # -- messages ---------------------------------------------------------------------
    def wait_ready(self):
        """Wait for the worker's set-up (assembly, factorisation); return its dof count."""
        numbers = BinaryNumbers(self._take, "a ready reply")
        try:
            unknowns = numbers.integer()
            numbers.end()
        except RecordError as error:
            raise WorkerError(f"worker {self.name} did not start properly: {error}") from None
        return unknowns

    def send(self, command, record=None):
        """Write one request: the command's number, then its record (exchange.py)."""
        self._write(encode_binary(int(command))
                    + (record.encode() if record is not None else b""))
        self._replies_owed += 1

    def receive(self, decode, *sizes):
        """Read one reply and return its record, ``decode(numbers, *sizes)`` (a record's
        decode, exchange.py); WorkerError if it is not that record, whole."""
        numbers = BinaryNumbers(self._take, "a reply")
        try:
            record = decode(numbers, *sizes)
            numbers.end()
        except RecordError as error:
            raise WorkerError(f"worker {self.name} sent {error}") from None
        self._replies_owed -= 1
        return record

    # -- lifetime -----------------------------------------------------------------------
    def stop(self, grace=5.0):
        """Ask the worker to exit; kill it if it does not; release the FIFOs."""
        try:
            self.ask_to_stop(grace)
            self.wait_stopped(grace)
        finally:
            self.kill()

    def ask_to_stop(self, grace=5.0):
        """Send the worker its stop, not waiting for it to exit (workers stopped together
        exit side by side: ``wait_stopped`` each after asking all). One that owes a reply
        (its run failed elsewhere meanwhile) reads no request until that reply, which no
        one will read, is written: it is killed at once, not waited for."""
        if self._replies_owed:
            self.kill()
        elif self.process is not None and self.process.poll() is None:
            try:
                self._write(encode_binary(int(Command.STOP)), timeout=grace)
            except (WorkerError, OSError):
                pass

    def wait_stopped(self, grace=5.0):
        """Wait up to ``grace`` seconds for the worker asked to stop to exit (then kill
        it and release its FIFOs: ``kill``)."""
        try:
            if self.process is not None:
                self.process.wait(timeout=grace)
        except subprocess.TimeoutExpired:
            pass
        finally:
            self.kill()

    def kill(self):
        """Kill the worker's process group and remove its FIFOs; safe to call twice."""
        if self.process is not None and self.process.returncode is None:
            try:
                os.killpg(self.process.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            _reap(self.process)
        for attribute in ("_request_fd", "_reply_fd"):
            fd = getattr(self, attribute)
            if fd is not None:
                os.close(fd)
                setattr(self, attribute, None)
        for path in (self.request_path, self.reply_path):
            if os.path.exists(path):
                os.unlink(path)

    # -- low level ----------------------------------------------------------------------
    def _check_alive(self):
        code = self.process.poll()
        if code is not None:
            how = (f"died: {_DEATHS.get(-code, signal.Signals(-code).name)}" if code < 0
                   else f"exited with code {code}")
            log = freefem.log_tail(self.log_path)
            if _OUT_OF_MEMORY.search(log):
                how += " (out of memory: lower --memory-limit's estimate, or coarsen the mesh)"
            raise WorkerError(f"worker {self.name} {how}:\n" + log)

    def _write(self, data, timeout=None):
        deadline = time.monotonic() + (timeout or self.timeout)
        view = memoryview(data)
        while view:
            self._check_alive()
            _, writable, _ = select.select([], [self._request_fd], [], _POLL_SECONDS)
            if writable:
                written = os.write(self._request_fd, view[:65536])
                view = view[written:]
            elif time.monotonic() > deadline:
                self.kill()         # unresponsive: no grace to wait out when the run stops
                raise WorkerError(f"worker {self.name} stopped reading its requests")

    def _take(self, n):
        """The next ``n`` bytes of the worker's replies, waited for as they arrive."""
        start = time.monotonic()
        while len(self._arrived) < n:
            readable, _, _ = select.select([self._reply_fd], [], [], _POLL_SECONDS)
            if readable:
                self._arrived += os.read(self._reply_fd, max(n - len(self._arrived), 1 << 16))
            else:
                self._check_alive()
                if time.monotonic() - start > self.timeout:
                    message = (f"worker {self.name} gave no answer for {self.timeout:g} s "
                               "(Settings.worker_timeout; a stopped or overloaded "
                               "process?):\n" + freefem.log_tail(self.log_path))
                    self.kill()     # unresponsive: no grace to wait out when the run stops
                    raise WorkerError(message)
        taken = self._arrived[:n]
        del self._arrived[:n]
        return taken


def _reap(process):
    """Wait for a killed worker to exit, by os.waitpid, not Popen.wait: a signal that
    interrupts Popen.poll between its lock's acquire and its try (CPython's lock and try
    are not signal-safe) leaves that lock held, and Popen.wait then blocks for ever. A
    run terminated by SIGTERM under load hung so in its clean-up (poll runs at every
    reply), one worker killed and not reaped, the next never killed."""
    try:
        _, status = os.waitpid(process.pid, 0)
    except ChildProcessError:       # reaped already, by Popen.poll
        return
    process.returncode = os.waitstatus_to_exitcode(status)
