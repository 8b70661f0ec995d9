"""Child processes that do not outlive the process that made them: a FreeFEM worker or
script, a sweep's point process."""

import ctypes
import os
import signal


def die_with_parent(parent=None):
    """Runs in the child (before exec): get SIGKILL when the parent dies, even by
    SIGKILL. ``parent``: the pid the child was made by; a parent that died before the
    request took effect is caught by looking again (the kernel's known race)."""
    PR_SET_PDEATHSIG = 1
    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except OSError:
        pass
    if parent is not None and os.getppid() != parent:
        os._exit(1)
