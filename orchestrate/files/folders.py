"""The folders a run owns: its output folder and its private working folder.

The output folder (RunFolder):

Everything a run writes goes first into a private scratch folder beside the output
folder, ``.NAME.partial-XXXX``; once complete (summary.json last) the scratch folder
takes the output folder's name, replacing an earlier run's folder whole. So a folder
under the output's name is always one run's complete output, never a mix, and a run
that fails or is killed leaves none of its files there.

Two runs into one folder: the lock file ``.NAME.lock`` beside it, held with flock for
the run's life, refuses the second (the kernel drops the lock when its holder dies, even
by SIGKILL). Holding the lock, a run removes the scratch folders of dead runs into that
folder. A folder that holds files is refused unless ``overwrite``, and even then only if
it holds a run (a run's summary.json): never an unrelated folder.

The working folder (WorkFolder): meshes, sides files, FIFOs and worker logs in
``robin-XXXX`` under the temporary folder, removed when the run ends however it ends.
A run killed by SIGKILL cannot remove its own: every working folder holds a lock file
while its run lives, and the next run removes those whose lock is free.
"""

import errno
import fcntl
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

from orchestrate.errors import ParameterError, system_failure

NAME_MAX = 255            # bytes in a file name on Linux file systems
# what the scratch folder's name adds to the output folder's: ".", ".partial-" and
# tempfile's 8 random characters
SCRATCH_EXTRA = len(".") + len(".partial-") + 8
YOUNG_SECONDS = 60        # a working folder without its lock is dead once this old


class RunFolder:
    def __init__(self, path, overwrite=False, option="--out"):
        if any(character in str(path) for character in "\n\r\0"):
            raise ParameterError(f"{option} {str(path)!r}: a folder's path cannot hold a line "
                                 "break or a NUL", option)
        if os.path.islink(path):            # write where the link points, keep the link
            if not os.path.isdir(path):
                raise ParameterError(f"{option} {path} is a symbolic link to no folder",
                                     option)
            path = os.path.realpath(path)
        self.path = Path(os.path.abspath(path))
        if len(self.path.name.encode()) > NAME_MAX - SCRATCH_EXTRA:
            raise ParameterError(f"{option}: the folder's name is too long (at most "
                                 f"{NAME_MAX - SCRATCH_EXTRA} bytes, for the scratch folder "
                                 "beside it)", option)
        self.overwrite = overwrite
        self.option = option
        self.scratch = None
        self._lock = None

    # ---- claiming ----------------------------------------------------------------------
    def claim(self):
        """Lock the folder, check it may be written, clean up after dead runs, make the
        scratch folder. Refusals (ParameterError) come before anything is written but
        the parent folder and the lock file."""
        parent, name = self.path.parent, self.path.name
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise ParameterError(f"{self.option} {self.path}: cannot create its folder: "
                                 f"{error.strerror}", self.option) from None
        self._take_lock(parent / f".{name}.lock")
        try:
            self._check_free()
            for stale in parent.glob(f".{name}.partial-*"):
                shutil.rmtree(stale, ignore_errors=True)
            for stale in parent.glob(f".{name}.old-*"):
                shutil.rmtree(stale, ignore_errors=True)
            try:
                self.scratch = Path(tempfile.mkdtemp(prefix=f".{name}.partial-", dir=parent))
                umask = os.umask(0)
                os.umask(umask)
                self.scratch.chmod(0o777 & ~umask)     # a folder like any other, not 0700
            except OSError as error:
                raise system_failure(error, f"making a scratch folder in {parent}") from None
        except BaseException:
            self.release()
            raise
        return self.scratch

    def _take_lock(self, lock_path):
        self._lock = hold_lock(lock_path, f"{self.option} {self.path}",
                               "another run is writing into it", self.option)

    def _check_free(self):
        if not self.path.exists():
            return
        if not self.path.is_dir():
            raise ParameterError(f"{self.option} {self.path} is a file, not a folder", self.option)
        contents = os.listdir(self.path)
        if not contents:
            return
        if not holds_a_run(self.path):
            raise ParameterError(f"{self.option} {self.path} holds files that are not a run's: "
                                 "choose another folder", self.option)
        if not self.overwrite:
            raise ParameterError(f"{self.option} {self.path} holds an earlier run: choose "
                                 "another folder, or --overwrite to replace it", self.option)

    # ---- finishing ---------------------------------------------------------------------
    def commit(self):
        """Put the scratch folder in place of the output folder (an earlier run's folder
        goes whole)."""
        parent, name = self.path.parent, self.path.name
        old = None
        try:
            if self.path.exists():
                old = Path(tempfile.mkdtemp(prefix=f".{name}.old-", dir=parent))
                os.replace(self.path, old / "run")
            os.replace(self.scratch, self.path)
        except OSError as error:
            raise system_failure(error, f"moving the run into {self.path}") from None
        self.scratch = None
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)

    def discard(self):
        if self.scratch is not None:
            shutil.rmtree(self.scratch, ignore_errors=True)
            self.scratch = None

    def release(self):
        if self._lock is not None:
            release_lock(self._lock)
            self._lock = None

    def __enter__(self):
        self.claim()
        return self

    def __exit__(self, *exc):
        self.discard()
        self.release()


def holds_a_run(folder):
    """Whether FOLDER is a run's output: its summary.json, written last, is a run's."""
    try:
        with open(Path(folder) / "summary.json", encoding="utf-8") as f:
            summary = json.load(f)
    except (OSError, ValueError):
        return False
    return isinstance(summary, dict) and {"scene", "settings", "converged"} <= set(summary)


def remove_dead_run_leftovers(directory):
    """Remove what dead runs left beside their output folders in ``directory`` (their
    lock files, scratch and old folders): those whose lock is free."""
    for lock in Path(directory).glob(".*.lock"):
        name = lock.name[1:-len(".lock")]
        try:
            handle = hold_lock(lock, name, "alive")
        except (ParameterError, OSError):
            continue                                  # its run is alive
        for stale in [*lock.parent.glob(f".{name}.partial-*"), *lock.parent.glob(f".{name}.old-*")]:
            shutil.rmtree(stale, ignore_errors=True)
        release_lock(handle)


def hold_lock(lock_path, what, busy, key=None):
    """flock a lock file (made if missing) for ``what`` (a folder, named in messages);
    ParameterError saying ``busy`` if another process holds it. The kernel releases the
    lock when its holder dies, even by SIGKILL. Returns the handle for release_lock."""
    for _ in range(10):
        try:
            fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as error:
            raise ParameterError(f"{what}: cannot write its lock {lock_path} "
                                 f"({error.strerror})", key) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as error:
            os.close(fd)
            if error.errno in (errno.EWOULDBLOCK, errno.EAGAIN):
                raise ParameterError(f"{what}: {busy}", key) from None
            raise
        try:        # still the file under that name? its holder may have just removed it
            same = os.path.samestat(os.fstat(fd), os.stat(lock_path))
        except FileNotFoundError:
            same = False
        if same:
            return fd, lock_path
        os.close(fd)
    raise ParameterError(f"{what}: its lock {lock_path} keeps changing", key)


def release_lock(handle):
    fd, lock_path = handle
    try:
        os.unlink(lock_path)
    except OSError:
        pass
    os.close(fd)


class WorkFolder:
    """A run's private working folder under ``tempfile.gettempdir()``: ``robin-*`` for
    its workers, ``orchestrate-api-*`` for a run of the Python API (orchestrate/run/api.py:
    the run's folder, until the run ends), ``monolithic-*`` for a monolithic solve
    (orchestrate/run/monolithic.py). A folder whose process died is removed by the next
    one made (remove_dead_work_folders)."""

    PREFIX = "robin-"
    API_PREFIX = "orchestrate-api-"
    MONOLITHIC_PREFIX = "monolithic-"
    PREFIXES = (PREFIX, API_PREFIX, MONOLITHIC_PREFIX)
    LOCK = ".alive"

    def __init__(self, prefix=PREFIX):
        self.prefix = prefix
        self.path = None
        self._fd = None

    def __enter__(self):
        remove_dead_work_folders()
        try:
            self.path = tempfile.mkdtemp(prefix=self.prefix)
            taking = os.path.join(self.path, self.LOCK + ".taking")
            self._fd = os.open(taking, os.O_RDWR | os.O_CREAT, 0o644)
            fcntl.flock(self._fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            os.rename(taking, os.path.join(self.path, self.LOCK))   # locked before it is seen
        except OSError as error:
            self.__exit__()
            raise system_failure(error, "making the working folder") from None
        return self.path

    def __exit__(self, *exc):
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None
        if self.path is not None:
            shutil.rmtree(self.path, ignore_errors=True)
            self.path = None


def remove_dead_work_folders(directory=None):
    """Remove the working folders of runs that died without cleaning up: those whose
    lock file is free, and those without one (a run dies between making its folder and
    locking it) once older than YOUNG_SECONDS."""
    directory = Path(directory or tempfile.gettempdir())
    try:
        candidates = [folder for prefix in WorkFolder.PREFIXES
                      for folder in directory.glob(f"{prefix}*")]
    except OSError:
        return
    for folder in candidates:
        lock = folder / WorkFolder.LOCK
        try:
            fd = os.open(lock, os.O_RDWR)
        except OSError:
            try:
                if (folder.is_dir() and time.time() - folder.stat().st_mtime > YOUNG_SECONDS
                        and not lock.exists()):
                    shutil.rmtree(folder, ignore_errors=True)
            except OSError:
                pass
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            continue                        # its run is alive
        finally:
            os.close(fd)
        shutil.rmtree(folder, ignore_errors=True)
