"""What a run ran, recorded in its summary.json ("provenance"), so that a result can be
told from one computed by other code or other forms:

    package_version     the installed orchestrate's version
    git_commit          the commit of the checkout the package runs from (None outside
                        a git checkout), and git_tree_modified: whether tracked files
                        differ from it
    forms_dir           the folder of the FreeFEM scripts the workers read
                        (orchestrate/workers/freefem.py: freefem/, or $ORCHESTRATE_FORMS)
    forms               {file: SHA-256} of every .edp/.idp the run's workers read: their
                        scripts and, recursively, what those include
    forms_digest        one hash of all of them: equal digests, equal forms

A kept worker (orchestrate/workers/session.py) compiled its forms when it started: it serves a
scene only while the digest of the files is the one it started with, and a sweep runs
again a point whose recorded digest is not the files' (orchestrate/sweeps/sweep.py).
"""

import hashlib
from importlib import metadata
import re
import shutil
import subprocess

from orchestrate.paths import PROJECT_DIR, forms_dir

# The worker script of each kind of subdomain (freefem/): every script a run's workers run
SCRIPTS = {"body": "body.edp", "shell": "shell.edp", "rigid": "rigid.edp",
           "coated_base": "coated_base.edp"}    # the base with its coatings
WORKER_SCRIPTS = tuple(SCRIPTS.values())
_INCLUDE = re.compile(r'^\s*include\s+"([^"]+)"', re.MULTILINE)
_HASH_DIGITS = 16       # hex digits kept: 64 bits, far from any chance collision


def _digest(data):
    return hashlib.sha256(data).hexdigest()[:_HASH_DIGITS]


def forms_hashes(scripts=WORKER_SCRIPTS):
    """{file name: hash} of the scripts and every file they include, recursively, in
    the forms folder (a file missing there, e.g. a plugin's, is left out)."""
    folder = forms_dir()
    hashes, waiting = {}, list(scripts)
    while waiting:
        name = waiting.pop()
        if name in hashes:
            continue
        try:
            data = (folder / name).read_bytes()
        except OSError:
            continue
        hashes[name] = _digest(data)
        waiting += _INCLUDE.findall(data.decode(errors="replace"))
    return dict(sorted(hashes.items()))


def forms_digest(hashes=None):
    """One hash of the forms (forms_hashes): their names and contents."""
    hashes = forms_hashes() if hashes is None else hashes
    return _digest("\n".join(f"{name} {value}" for name, value in hashes.items()).encode())


def package_version():
    try:
        return metadata.version("orchestrate")
    except metadata.PackageNotFoundError:      # run from a source tree not installed
        return None


def git_state():
    """(commit, tree modified) of the checkout the package runs from; (None, None)
    outside one or without git."""
    if not (PROJECT_DIR / ".git").exists() or shutil.which("git") is None:
        return None, None
    try:
        described = subprocess.run(
            ["git", "-C", str(PROJECT_DIR), "describe", "--always", "--dirty", "--abbrev=40"],
            capture_output=True, text=True, timeout=10, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None, None
    commit, _, dirty = described.partition("-dirty")
    return commit or None, described.endswith("-dirty")


def provenance(hashes=None):
    """The summary's "provenance" entry (the module's text); ``hashes``: the forms'
    hashes the run's workers started with, if known."""
    hashes = forms_hashes() if hashes is None else hashes
    commit, modified = git_state()
    return {"package_version": package_version(), "git_commit": commit,
            "git_tree_modified": modified, "forms_dir": str(forms_dir()),
            "forms": hashes, "forms_digest": forms_digest(hashes)}
