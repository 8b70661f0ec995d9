"""Shared test helpers: running a FreeFEM test script, reading its CSV output."""

import os
import sys
from pathlib import Path

import pytest

PROJECT_DIR = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT_DIR))

from orchestrate import freefem  # noqa: E402

TESTS_FREEFEM_DIR = Path(__file__).resolve().parent / "freefem"


@pytest.fixture
def run_freefem(tmp_path):
    """Run tests/freefem/<script> with arguments; return the folder it ran in.

    The script finds the project's .idp files on FreeFEM's include path; a failing
    script fails the test with the end of its log."""
    def run(script, *arguments):
        freefem.run_script(str(TESTS_FREEFEM_DIR / script), list(arguments),
                           os.path.join(tmp_path, f"{Path(script).stem}.log"))
        return tmp_path
    return run
