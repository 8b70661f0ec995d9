"""Boundary labels, read from ``freefem/labels.idp`` (the forms' folder of
orchestrate/workers/freefem.py) so that they are defined once."""

import re

from orchestrate.paths import forms_dir

_LABEL_LINE = re.compile(r"^\s*int\s+(\w+)\s*=\s*(\d+)\s*;")


def read_labels(path=None):
    """Return ``{name: number}`` for every ``int Name = k;`` line of the file."""
    labels = {}
    for line in (path or forms_dir() / "labels.idp").read_text().splitlines():
        match = _LABEL_LINE.match(line)
        if match:
            labels[match.group(1)] = int(match.group(2))
    return labels


LABELS = read_labels()
