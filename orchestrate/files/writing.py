"""Files written whole or not at all: each goes to a partial name beside its place and is
renamed once written, so a file that exists is complete (a run's files, sweep tables,
figures). A run itself writes into a private scratch folder (folders.py) that takes its
output folder's name once complete."""

import csv
import json
import os
from pathlib import Path

import meshio
import numpy as np

from orchestrate.errors import system_failure


def partial_path(path):
    """Where ``written`` writes ``path`` before the rename."""
    path = Path(path)
    return path.with_name(f".{path.name}.partial")


def _atomic(path):
    return Path(path), partial_path(path)


def written(path, write):
    """Run write(partial path), then rename; a failed write leaves nothing and says why."""
    path, partial = _atomic(path)
    try:
        write(partial)
        os.replace(partial, path)
    except OSError as error:
        partial.unlink(missing_ok=True)
        raise system_failure(error, f"writing {path.name}") from None


def write_json(path, data):
    write_text(path, json.dumps(data, indent=2) + "\n")


def write_text(path, text):
    written(path, lambda partial: Path(partial).write_text(text))


def write_vtu(path, mesh):
    """Write a meshio mesh as VTU (binary, the arrays' own precision)."""
    written(path, lambda partial: meshio.write(partial, mesh, file_format="vtu"))


def write_csv(path, columns):
    """Write ``{name: values}`` as CSV, columns in the given order, full precision."""
    names = list(columns)
    rows = zip(*(np.asarray(columns[n]).tolist() for n in names))

    def write(partial):
        with open(partial, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(names)
            writer.writerows(rows)
    written(path, write)
