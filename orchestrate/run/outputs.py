"""A run's output files, each written once, in the scene's units.

The run computes in b and E; each table, mesh or text is expressed in the scene's units
as it is rendered (every number scaled by the kind of its column, field or key:
orchestrate/model/units.py's kind_of) and written whole into the run's scratch folder
(RunFiles). The files: the tables of the converged state and the loop's history
(orchestrate/run/solve.py), and each subdomain's fields as its worker sent them
(orchestrate/workers/exchange.py's BodyOutput, ShellOutput): a body's nodal table, its
cells, its reactions and its VTU; a shell's table along its mid-line (with the
mid-line's place x1, x2) and its VTU with the fibre stresses (a shell of revolution's
radial and hoop ones); run.pvd; summary.json
last. The tables stay in memory, in the scene's units, for the Python API's Result
(orchestrate/run/api.py), and so, when asked, do the files' bytes.
"""

import json
import os

import meshio
import numpy as np

from orchestrate.files.writing import csv_bytes, vtu_bytes, write_bytes
from orchestrate.model.units import FORCE, Scales, kind_of
from orchestrate.run.answers import fibre_stresses, revolution_fibre_stresses
from orchestrate.run.paraview import RUN_COLLECTION, collection_text
from orchestrate.workers.exchange import CELL_NODES, REVOLUTION_SHELL_COLUMNS, SHELL_COLUMNS

# The stress components of a body's nodal table (and VTU), after x1, x2, u1, u2, sigma_eq
# (exchange.py's BODY_COLUMNS)
STRESS_COMPONENTS = ("s11", "s22", "s12", "s33")
CELL_COLUMNS = tuple(f"n{corner}" for corner in range(CELL_NODES))  # rows of NAME.csv
# A shell's columns its VTU holds as they are (besides its place and displacement); a
# shell of revolution's
SHELL_VTU_FIELDS = ("gamma", "epsilon", "T11", "T13", "M11", "T33")
REVOLUTION_VTU_FIELDS = ("beta", "epsilon", "N_r", "N_theta", "Q", "M_r", "M_theta", "N_z")
SUMMARY = "summary.json"


def _scaled(values, scale):
    values = np.asarray(values)
    if scale == 1.0:
        return values
    if values.dtype == object:               # a history column with gaps (None)
        return np.array([v if v is None else v * scale for v in values], dtype=object)
    return values * scale


def in_units(columns, file, scales):
    """``{column: values}`` of ``file`` in the scene's units, each column scaled by its
    kind (the interfaces' names as they are)."""
    return {name: values if name == "interface"
            else _scaled(values, scales.of(kind_of(name, file)))
            for name, values in columns.items()}


def mesh_in_units(mesh, file, scales):
    """A meshio mesh in b and E in the scene's units: its points and every field by kind."""
    if scales.length == 1.0 and scales.stress == 1.0:
        return mesh
    return meshio.Mesh(mesh.points * scales.length, mesh.cells,
                       point_data={field: np.asarray(data) * scales.of(kind_of(field, file))
                                   for field, data in mesh.point_data.items()})


def history_table(history):
    """The loop's history as columns: one row per iteration."""
    if not history:
        return {"iteration": []}
    return {key: [row[key] for row in history] for key in history[0]}


def body_mesh(columns, cells):
    """A body's fields for ParaView: quadratic triangles (VTK's triangle6) in double
    precision with the displacement, the stress tensor (3 x 3, plane strain: s13 = s23
    = 0; ParaView's tensor), its components and sigma_eq, from its nodal ``columns``
    (BODY_COLUMNS) and ``cells`` (six rows of them each)."""
    zero = np.zeros(len(columns["x1"]))
    s11, s22, s12, s33 = (np.asarray(columns[name], dtype=np.float64)
                          for name in STRESS_COMPONENTS)
    point_data = {
        "displacement": np.column_stack([columns["u1"], columns["u2"], zero]),
        "stress": np.column_stack([s11, s12, zero, s12, s22, zero, zero, zero, s33]),
        "sigma_eq": np.asarray(columns["sigma_eq"], dtype=np.float64),
        **{name: np.asarray(columns[name], dtype=np.float64) for name in STRESS_COMPONENTS},
    }
    return meshio.Mesh(np.column_stack([columns["x1"], columns["x2"], zero]),
                       [("triangle6", np.asarray(cells, dtype=np.int64))], point_data=point_data)


def shell_table(columns, spec):
    """A shell's fields along its mid-line (SHELL_COLUMNS, a shell of revolution's
    REVOLUTION_SHELL_COLUMNS) with the mid-line's place x1, x2 after xi (``spec``: its
    ShellSpec, orchestrate/mesh/discretization.py)."""
    s = spec.s_start + np.asarray(columns["xi"]) / spec.stretch
    place = spec.face.point(s, 0.5 * spec.thickness)
    table = {"xi": columns["xi"], "x1": place[:, 0], "x2": place[:, 1]}
    names = REVOLUTION_SHELL_COLUMNS if spec.revolution else SHELL_COLUMNS
    table.update((name, columns[name]) for name in names if name != "xi")
    return table


def shell_mesh(table, spec):
    """A shell's fields for ParaView (``table``: shell_table's): a polyline along its
    mid-line with the displacement v t + w n in global components, gamma, epsilon, the
    forces and the fibre stresses: sigma11_top, sigma11_bottom = T11/h2 +- 6 M11/h2^2 at
    the top face (the contact side, xi3 = +h2/2 along the face's outward normal: M11 > 0
    stretches it) and the bottom face (the bond), and sigma13_mean = T13/h2
    (answers.fibre_stresses). A shell of revolution's: u e_r + w e_z, beta, epsilon, its
    forces, the radial and hoop fibre stresses sigma_r_top, sigma_r_bottom,
    sigma_theta_top, sigma_theta_bottom and sigma_rz_mean = Q/h2
    (answers.revolution_fibre_stresses)."""
    xi = np.asarray(table["xi"])
    s = spec.s_start + xi / spec.stretch
    tangent, normal = spec.face.tangent(s), spec.face.normal(s)
    zero = np.zeros(len(xi))
    along, fields = ("u", REVOLUTION_VTU_FIELDS) if spec.revolution else ("v", SHELL_VTU_FIELDS)
    displacement = (np.asarray(table[along])[:, None] * tangent
                    + np.asarray(table["w"])[:, None] * normal)
    points = np.column_stack([table["x1"], table["x2"], zero])
    lines = np.column_stack([np.arange(len(xi) - 1), np.arange(1, len(xi))])
    keep = np.diff(xi) > 0       # samples repeat the nodes: skip zero-length cells
    point_data = {"displacement": np.column_stack([displacement, zero])}
    point_data.update((name, np.asarray(table[name])) for name in fields)
    point_data.update(_fibre_stress_fields(table, spec))
    return meshio.Mesh(points, [("line", lines[keep])], point_data=point_data)


def _fibre_stress_fields(table, spec):
    """The VTU's fibre stresses of a shell (shell_mesh)."""
    if spec.revolution:
        names = ("sigma_r_top", "sigma_r_bottom", "sigma_theta_top", "sigma_theta_bottom",
                 "sigma_rz_mean")
        return dict(zip(names, revolution_fibre_stresses(table, spec.thickness)))
    return dict(zip(("sigma11_top", "sigma11_bottom", "sigma13_mean"),
                    fibre_stresses(table, spec.thickness)))


class RunFiles:
    """The files of one run, each rendered once in the scene's units (``scales``) and
    written whole into ``folder`` (the run's scratch folder) as soon as it is made.
    ``tables``: every CSV file's columns, in the scene's units, and ``fields`` those of
    each subdomain's fields by its name; ``contents``: every file's bytes, kept only if
    ``keep`` (the Python API's Result saves them); ``summary``: summary.json's, once
    written."""

    def __init__(self, folder, scales, keep=False):
        self.folder = folder
        self.scales = scales
        self.summary = None
        self.tables, self.fields = {}, {}
        self.names = []
        self.contents = {} if keep else None

    def add(self, name, data):
        write_bytes(os.path.join(self.folder, name), data)
        self.names.append(name)
        if self.contents is not None:
            self.contents[name] = data

    def table(self, name, columns):
        """A CSV file of ``{column: values}`` in b and E."""
        self.tables[name] = in_units(columns, name, self.scales)
        self.add(name, csv_bytes(self.tables[name]))

    def mesh(self, name, mesh):
        """A VTU file of a meshio mesh in b and E."""
        self.add(name, vtu_bytes(mesh_in_units(mesh, name, self.scales), name))

    def body(self, name, output):
        """A body's files from its worker's BodyOutput (in b and E): with its fields
        NAME.csv (BODY_COLUMNS at its P2 nodes), NAME_cells.csv and NAME.vtu; always
        NAME_reactions.txt, "label R1 R2" per support (labels of freefem/labels.idp)."""
        if len(output.columns["x1"]):
            self.table(f"{name}.csv", output.columns)
            self.fields[name] = self.tables[f"{name}.csv"]
            self.table(f"{name}_cells.csv", dict(zip(CELL_COLUMNS, np.asarray(output.cells).T)))
            self.mesh(f"{name}.vtu", body_mesh(output.columns, output.cells))
        force = self.scales.of(FORCE)
        self.add(f"{name}_reactions.txt",
                 "".join(f"{label} {r1 * force!r} {r2 * force!r}\n"
                         for label, (r1, r2) in output.reactions.items()).encode())

    def shell(self, name, table, spec):
        """A shell's files from its shell_table (in b and E): NAME_fields.csv and NAME.vtu."""
        self.table(f"{name}_fields.csv", table)
        self.fields[name] = self.tables[f"{name}_fields.csv"]
        self.mesh(f"{name}.vtu", shell_mesh(table, spec))

    def collection(self, names):
        """run.pvd: the VTU files of the subdomains ``names`` (those written) together in
        ParaView."""
        vtu = [f"{name}.vtu" for name in names if f"{name}.vtu" in self.names]
        self.add(RUN_COLLECTION, collection_text(vtu).encode())

    def write_summary(self, summary, units):
        """summary.json, last, with its "units" entry: the unit of each kind, what b and
        E are in the scene's ``units``, and the unit of every column of every CSV file.
        ``summary``: in the scene's units already (units.scaled_summary)."""
        names = units.names(self.scales.revolution)
        scale = {} if units.dimensionless else {
            "b": f"{self.scales.length!r} {units.length}",
            "E": f"{self.scales.stress!r} {units.stress}"}
        columns = {file: {c: names[kind_of(c, file)] for c in self.tables[file]
                          if c != "interface"}
                   for file in sorted(self.tables)}
        summary["units"] = {**names, **scale, "columns": columns}
        self.add(SUMMARY, (json.dumps(summary, indent=2) + "\n").encode())
        self.summary = summary
