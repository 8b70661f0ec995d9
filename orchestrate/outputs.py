"""Files of a run. Every file is written to a temporary name and renamed, so a file
that exists is complete; summary.json, written last, marks a finished run."""

import csv
import json
import os
from pathlib import Path

import meshio
import numpy as np
import pandas as pd


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


def write_shell_fields(fields_csv, spec, vtu_path):
    """Complete a shell worker's fields file (xi, v, w, gamma, T11, T13, M11 along the
    mid-line) with the mid-line's place x1, x2, and write it as a VTU polyline with the
    displacement v t + w n in global components, gamma and the forces."""
    data = pd.read_csv(fields_csv)
    s = spec.s_start + data["xi"].to_numpy() / spec.stretch
    place = spec.face.point(s, 0.5 * spec.thickness)
    tangent, normal = spec.face.tangent(s), spec.face.normal(s)
    data.insert(1, "x1", place[:, 0])
    data.insert(2, "x2", place[:, 1])
    write_csv(fields_csv, {name: data[name].to_numpy() for name in data.columns})
    displacement = data["v"].to_numpy()[:, None] * tangent + data["w"].to_numpy()[:, None] * normal
    points = np.column_stack([place, np.zeros(len(data))])
    lines = np.column_stack([np.arange(len(data) - 1), np.arange(1, len(data))])
    keep = np.diff(data["xi"].to_numpy()) > 0   # samples repeat the nodes: skip zero-length cells
    point_data = {"displacement": np.column_stack([displacement, np.zeros(len(data))])}
    for name in ("gamma", "T11", "T13", "M11"):
        point_data[name] = data[name].to_numpy()
    path, partial = _atomic(vtu_path)
    meshio.write(partial, meshio.Mesh(points, [("line", lines[keep])], point_data=point_data),
                 file_format="vtu")
    os.replace(partial, path)
