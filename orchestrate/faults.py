"""Pause points, for the reliability tests to signal a run (or its workers) in a given
phase of its life (tests/run/test_reliability.py).

With ORCHESTRATE_PAUSE_AT = a phase and ORCHESTRATE_PAUSE_FILE = a path, a run that
reaches that phase writes the path and waits, at most PAUSE_SECONDS, until the path is
gone; signals reach it meanwhile (but during meshing, where they wait for the mesher).
Without them a checkpoint costs one dictionary lookup.
"""

import os
import time

PHASES = ("meshing", "setup", "iterating", "output", "committing")
PAUSE_SECONDS = 60.0


def checkpoint(phase):
    if os.environ.get("ORCHESTRATE_PAUSE_AT") != phase:
        return
    path = os.environ["ORCHESTRATE_PAUSE_FILE"]
    with open(path, "w") as marker:
        marker.write(f"{phase} {os.getpid()}\n")
    deadline = time.monotonic() + PAUSE_SECONDS
    while os.path.exists(path) and time.monotonic() < deadline:
        time.sleep(0.02)
