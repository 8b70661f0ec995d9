"""Finding FreeFEM and running its scripts with the project's include path.

The scripts and forms are read from ``freefem/``, or from the folder named by the
environment variable ORCHESTRATE_FORMS (a copy of it with edited forms, say): every
worker, the monolithic solve and the forms' hashes in a run's provenance
(orchestrate/workers/provenance.py) read the same folder."""

import functools
import os
import shutil
import subprocess

from orchestrate.paths import forms_dir
from orchestrate.workers.children import die_with_parent

# Debian's /etc/freefem++.pref points to a plugin folder that does not exist.
DEFAULT_PLUGIN_DIR = "/usr/lib/freefem++"


class FreeFemMissing(RuntimeError):
    """FreeFEM is not installed or not on PATH."""


def executable():
    """Path of FreeFem++ (or $FREEFEM), or a clear error naming what is missing."""
    path = shutil.which(os.environ.get("FREEFEM", "FreeFem++"))
    if path is None:
        raise FreeFemMissing(
            "FreeFEM not found: FreeFem++ is not on PATH (set $FREEFEM to its path, or "
            "install it with `make setup`, i.e. apt-get install freefem++ libfreefem++)")
    return path


def environment():
    """Environment for a FreeFEM process: our scripts on the include path, plugins found."""
    env = dict(os.environ)
    env["FF_INCLUDEPATH"] = str(forms_dir())
    env.setdefault("FF_LOADPATH", DEFAULT_PLUGIN_DIR)
    return env


def command(script, arguments):
    """The command line that runs ``script`` (a file in freefem/ or a path) headless."""
    script_path = forms_dir() / script if not os.path.isabs(str(script)) else script
    return [executable(), "-nw", "-v", "0", str(script_path), *map(str, arguments)]


def run_script(script, arguments, log_path, timeout=None):
    """Run a script to completion (it dies with this process: a monolithic solve of a
    killed study ran on); raise with the end of its log if it fails."""
    with open(log_path, "w") as log:
        completed = subprocess.run(command(script, arguments), stdout=log,
                                   stderr=subprocess.STDOUT, env=environment(),
                                   timeout=timeout, start_new_session=True,
                                   preexec_fn=functools.partial(die_with_parent, os.getpid()))
    if completed.returncode != 0:
        raise RuntimeError(f"FreeFEM script {script} failed (exit {completed.returncode}):\n"
                           + log_tail(log_path))


def log_tail(log_path, lines=15):
    try:
        with open(log_path) as log:
            return "".join(log.readlines()[-lines:])
    except OSError:
        return "(no log)"
