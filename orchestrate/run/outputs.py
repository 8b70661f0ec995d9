"""A run's output files: checked whole after the workers wrote them (FreeFEM does not
report a failed write), the bodies' and shells' VTU fields written from their CSV, the
loop's history, the reactions, and every file expressed in the scene's units once the
run is written (express_run: each number scaled by the kind of its column,
orchestrate/model/units.py's KINDS)."""

import os
from pathlib import Path

import meshio
import numpy as np
import pandas as pd

from orchestrate.errors import SystemFailure
from orchestrate.files.writing import write_csv, write_text, write_vtu
from orchestrate.model.units import FORCE, Scales, kind_of
from orchestrate.run.answers import fibre_stresses


def check_written(prefix, kind, counts, fields=True):
    """Raise SystemFailure unless a worker's files next to ``prefix`` are whole: as many
    rows and lines as it reported writing (body: nodal CSV rows, cell rows, reaction
    lines; shell: field rows; without ``fields`` a body's reactions alone). FreeFEM does
    not report a failed write; a full disk or a file size limit leaves its files short."""
    if kind == "body":
        expected = {f"{prefix}_reactions.txt": counts[2]}
        if fields:
            expected.update({f"{prefix}.csv": counts[0] + 1, f"{prefix}_cells.csv": counts[1] + 1})
    else:
        expected = {f"{prefix}_fields.csv": counts[0] + 1} if fields else {}
    for path, lines in expected.items():
        found = _line_count(path)
        if found != lines:
            raise SystemFailure(f"{os.path.basename(path)} is incomplete ({found} of {lines} "
                                "lines): the disk is full or a file size limit was reached")


def _line_count(path):
    try:
        with open(path, "rb") as f:
            return sum(1 for _ in f)
    except OSError:
        return 0


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


# The stress components of a body's nodal CSV (and VTU), after x1, x2, u1, u2, sigma_eq.
STRESS_COMPONENTS = ("s11", "s22", "s12", "s33")


def write_body_fields(prefix):
    """Write ``prefix.vtu`` for ParaView from a body worker's ``prefix.csv`` (the P2 nodes:
    x1, x2, u1, u2, sigma_eq, s11, s22, s12, s33) and ``prefix_cells.csv`` (six nodes per
    triangle, VTK's triangle6 order): quadratic triangles in double precision with the
    displacement, the stress tensor (3 x 3, plane strain: s13 = s23 = 0; ParaView's
    tensor), its components and sigma_eq."""
    nodes = pd.read_csv(f"{prefix}.csv")
    cells = pd.read_csv(f"{prefix}_cells.csv").to_numpy(dtype=np.int64)
    column = {name: nodes[name].to_numpy(dtype=np.float64) for name in nodes.columns}
    zero = np.zeros(len(nodes))
    s11, s22, s12, s33 = (column[name] for name in STRESS_COMPONENTS)
    point_data = {
        "displacement": np.column_stack([column["u1"], column["u2"], zero]),
        "stress": np.column_stack([s11, s12, zero, s12, s22, zero, zero, zero, s33]),
        "sigma_eq": column["sigma_eq"],
        **{name: column[name] for name in STRESS_COMPONENTS},
    }
    mesh = meshio.Mesh(np.column_stack([column["x1"], column["x2"], zero]),
                       [("triangle6", cells)], point_data=point_data)
    write_vtu(f"{prefix}.vtu", mesh)


def write_shell_fields(fields_csv, spec, vtu_path):
    """Complete a shell worker's fields file (xi, v, w, gamma, epsilon, T11, T13, M11, T33
    along the mid-line) with the mid-line's place x1, x2, and write it as a VTU polyline
    with the displacement v t + w n in global components, gamma, epsilon, the forces and
    the fibre stresses: sigma11_top, sigma11_bottom = T11/h2 +- 6 M11/h2^2 at the top face
    (the contact side, xi3 = +h2/2 along the face's outward normal: M11 > 0 stretches it)
    and the bottom face (the bond), and sigma13_mean = T13/h2 (answers.fibre_stresses)."""
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
    for name in ("gamma", "epsilon", "T11", "T13", "M11", "T33"):
        point_data[name] = data[name].to_numpy()
    top, bottom, shear = fibre_stresses(data, spec.thickness)
    point_data.update(sigma11_top=top, sigma11_bottom=bottom, sigma13_mean=shear)
    mesh = meshio.Mesh(points, [("line", lines[keep])], point_data=point_data)
    write_vtu(vtu_path, mesh)


def column_units(folder, units):
    """{file: {column: unit}} of the run's CSV files, for the summary."""
    names = units.names()
    table = {}
    for name in sorted(os.listdir(folder)):
        if name.endswith(".csv"):
            with open(os.path.join(folder, name)) as f:     # plain names, no quotes
                columns = f.readline().strip().split(",")
            table[name] = {c: names[kind_of(c, name)] for c in columns if c != "interface"}
    return table


def _scaled_column(values, column, file, scales):
    if column == "interface":                # the interfaces' names
        return values
    scale = scales.of(kind_of(column, file))
    return values if scale == 1.0 else values * scale


def express_run(folder, scales):
    """Express every file of a finished run's FOLDER in the scene's units: CSV columns,
    reactions (forces) and VTU points and fields, by kind, each rewritten atomically; a
    run in b and E has nothing to do."""
    if scales == Scales():
        return
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name.endswith(".csv"):
            table = pd.read_csv(path)
            write_csv(path, {c: _scaled_column(table[c].to_numpy(), c, name, scales)
                             for c in table.columns})
        elif name.endswith("_reactions.txt"):
            force = scales.of(FORCE)
            lines = [line.split() for line in open(path).read().split("\n") if line.strip()]
            write_text(path, "".join(f"{label} {float(r1) * force!r} {float(r2) * force!r}\n"
                                     for label, r1, r2 in lines))
        elif name.endswith(".vtu"):
            mesh = meshio.read(path)
            mesh.points = mesh.points * scales.length
            mesh.point_data = {field: np.asarray(data) * scales.of(kind_of(field, name))
                               for field, data in mesh.point_data.items()}
            write_vtu(path, mesh)


def summary_units(folder, units, scales):
    """The summary's "units" entry: the unit of each kind, what b and E are in the
    scene's units, and the unit of every column of every CSV file."""
    scale = {} if units.dimensionless else {"b": f"{scales.length!r} {units.length}",
                                            "E": f"{scales.stress!r} {units.stress}"}
    return {**units.names(), **scale, "columns": column_units(folder, units)}
