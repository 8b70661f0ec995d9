"""Boundary labels, read from ``freefem/labels.idp`` so that they are defined once."""

import re

from .paths import FREEFEM_DIR

_LABEL_LINE = re.compile(r"^\s*int\s+(\w+)\s*=\s*(\d+)\s*;")


def read_labels(path=FREEFEM_DIR / "labels.idp"):
    """Return ``{name: number}`` for every ``int Name = k;`` line of the file."""
    labels = {}
    for line in path.read_text().splitlines():
        match = _LABEL_LINE.match(line)
        if match:
            labels[match.group(1)] = int(match.group(2))
    return labels


LABELS = read_labels()
