"""Files of a run. Every file is written to a temporary name and renamed, so a file
that exists is complete; summary.json, written last, marks a finished run."""

import csv
import json
import os
from pathlib import Path

import meshio
import numpy as np


def _atomic(path):
    path = Path(path)
    return path, path.with_name(f".{path.name}.partial")


def write_json(path, data):
    path, partial = _atomic(path)
    partial.write_text(json.dumps(data, indent=2, sort_keys=False) + "\n")
    os.replace(partial, path)


def write_csv(path, columns):
    """Write ``{name: values}`` as CSV, columns in the given order, full precision."""
    path, partial = _atomic(path)
    names = list(columns)
    rows = zip(*(np.asarray(columns[n]).tolist() for n in names))
    with open(partial, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(names)
        writer.writerows(rows)
    os.replace(partial, path)


def write_history(path, history):
    if not history:
        write_csv(path, {"iteration": []})
        return
    write_csv(path, {key: [row[key] for row in history] for key in history[0]})


def read_reactions(path):
    """Consistent reaction forces a body worker wrote: {label number: (R1, R2)}."""
    reactions = {}
    for line in Path(path).read_text().split("\n"):
        if line.strip():
            label, r1, r2 = line.split()
            reactions[int(label)] = (float(r1), float(r2))
    return reactions


def write_shell_vtu(fields_csv, y_midline, path):
    """The shell's mid-line as a VTU polyline with v, w, gamma and its forces."""
    data = np.genfromtxt(fields_csv, delimiter=",", names=True)
    points = np.column_stack([data["x1"], np.full(len(data), y_midline), np.zeros(len(data))])
    lines = np.column_stack([np.arange(len(data) - 1), np.arange(1, len(data))])
    keep = np.diff(data["x1"]) > 0       # samples repeat the nodes: skip zero-length cells
    point_data = {"displacement": np.column_stack([data["v"], data["w"], np.zeros(len(data))])}
    for name in ("gamma", "T11", "T13", "M11"):
        point_data[name] = data[name]
    path, partial = _atomic(path)
    meshio.write(partial, meshio.Mesh(points, [("line", lines[keep])], point_data=point_data),
                 file_format="vtu")
    os.replace(partial, path)
