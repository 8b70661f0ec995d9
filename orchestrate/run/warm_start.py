"""A run's start from a finished neighbour: its interface state as the first iterate.

The active-set loop starts from zero traces and tractions, and spends a third of its
iterations finding the contact set. A finished run of a nearby scene (another h2 or E2,
say) knows both closely: its traces and tractions (traces.csv, contact.csv,
interface.csv, in its scene's units: from its folder, or from memory for a Result of
the Python API) are the first iterate of the next run, interface by interface (matched
by name), at this run's points (interpolated along the face's arc length s where the
points differ). The loop, its stopping test and its answer are unchanged: only the path
to the fixed point is shorter. Measured on the paper's scene, 2D coating h2 = b/8,
E2 = 5E: 113 iterations from zero, 74 from the run with E2 = E, 77 from the one with
h2 = b/4. The first contact set is the neighbour's where its state touches, or, where
the neighbour touched in one zone and the scene is frictionless, the run's a priori set
calibrated by the neighbour (calibrated_half_width).
"""

import json
import math
from pathlib import Path

import numpy as np

from orchestrate.errors import ParameterError
from orchestrate.model.scene import scene_from_dict
from orchestrate.model.units import dimensionless


def state_from_tables(summary, traces, contact, interface, layout):
    """The state vector (StateLayout ``layout``, in b and E) from a finished run's
    summary and tables; None if the run did not converge or shares no interface."""
    if not summary.get("converged"):
        return None
    scales = dimensionless(scene_from_dict(summary["scene"]))[1]
    blocks, matched = {}, 0
    for i, face in enumerate(layout.interfaces):
        # a friction interface's traces and traction are its contact's a_t, b_t, sigma_t
        name = (face.name if face.kind != "friction"
                else layout.interfaces[face.contact].name)
        rows = traces[traces.interface == name]
        stresses = (interface if face.kind == "bond" else contact)
        stress_rows = stresses[stresses.interface == name]
        if face.kind == "friction" and ("sigma_t" not in stress_rows
                                        or rows.a_t.isna().all()):
            rows = stress_rows = rows.iloc[:0]      # a frictionless run: nothing to start
        if rows.empty or stress_rows.empty:
            for kind in ("u", "t"):
                for side in (0, 1):
                    blocks[kind, i, side] = np.zeros((face.components, face.size))
            continue
        matched += 1

        def at(table, column, scale):                # the files are in the run's units
            return np.interp(face.s, table.s.to_numpy() / scales.length,
                             table[column].to_numpy()) / scale
        if face.kind == "friction":
            blocks["u", i, 0] = at(rows, "a_t", scales.length)
            blocks["u", i, 1] = at(rows, "b_t", scales.length)
            blocks["t", i, 0] = blocks["t", i, 1] = at(stress_rows, "sigma_t", scales.stress)
        elif face.kind == "contact":
            blocks["u", i, 0] = at(rows, "a_n", scales.length)
            blocks["u", i, 1] = at(rows, "b_n", scales.length)
            pressure = at(stress_rows, "sigma_n", scales.stress)
            blocks["t", i, 0] = blocks["t", i, 1] = pressure
        else:
            blocks["u", i, 0] = np.array([at(rows, "a_t", scales.length),
                                          at(rows, "a_n", scales.length)])
            blocks["u", i, 1] = np.array([at(rows, "b_t", scales.length),
                                          at(rows, "b_n", scales.length)])
            on_base = np.array([at(stress_rows, "sigma_t", scales.stress),
                                at(stress_rows, "sigma_n", scales.stress)])
            blocks["t", i, 1], blocks["t", i, 0] = on_base, -on_base
    return layout.pack(blocks) if matched else None


# The columns a start reads, by table
_COLUMNS = {"traces": ("interface", "s", "a_t", "a_n", "b_t", "b_n"),
            "contact": ("interface", "s", "sigma_n"),
            "interface": ("interface", "s", "sigma_n", "sigma_t")}


def start_state(start_from, layout):
    """The first iterate from the finished run ``start_from``, its folder or a run in
    memory (the API's Result: its summary and tables), by state_from_tables, checked
    before any work: ParameterError naming ``start_from`` if the folder is missing or not
    a run's, the run did not converge, a table is missing, unreadable or not finite, or
    the run's interfaces are not this scene's (another layout of bodies and patches)."""
    in_memory = hasattr(start_from, "summary")
    where = "(a Result)" if in_memory else Path(start_from)

    def refuse(why):
        raise ParameterError(f"start_from {where}: {why}", "start_from")
    if not in_memory:
        folder = Path(start_from)
        if not folder.exists():
            refuse("no such folder")
        if not folder.is_dir():
            refuse("not a folder (a run's output folder is due)")
    try:
        summary = _summary(start_from)
    except (OSError, ValueError):
        refuse("holds no finished run (no readable summary.json)")
    if not isinstance(summary, dict) or not isinstance(summary.get("scene"), dict):
        refuse("its summary.json is not a run's")
    if not summary.get("converged"):
        refuse(f"its run did not converge ({summary.get('status')}): nothing to start from")
    try:
        scene_from_dict(summary["scene"])
    except (ParameterError, KeyError, TypeError, ValueError) as error:
        refuse(f"its summary's scene is not readable ({error})")
    import pandas as pd     # here: a run that starts from none needs no pandas

    tables = {}
    for name, columns in _COLUMNS.items():
        try:
            table = (getattr(start_from, name) if in_memory
                     else pd.read_csv(folder / f"{name}.csv"))
        except (OSError, ValueError, pd.errors.EmptyDataError):
            refuse(f"{name}.csv is missing or unreadable")
        missing = [c for c in columns if c not in table.columns]
        if missing:
            refuse(f"{name}.csv lacks the column(s) {', '.join(missing)}")
        numbers = table[list(columns[1:])]
        if name == "traces":        # a contact's tangential traces are empty by design
            numbers = numbers[["s", "a_n", "b_n"]]
        if not np.isfinite(numbers.to_numpy(dtype=float)).all():
            refuse(f"{name}.csv holds values that are not finite numbers")
        tables[name] = table
    found = set(tables["traces"].interface)
    expected = {face.name for face in layout.interfaces if face.kind != "friction"}
    if found != expected:
        refuse(f"its run has the interfaces {sorted(found)}, this scene "
               f"{sorted(expected)}: a run of another layout of bodies and patches cannot "
               "start it")
    return state_from_tables(summary, tables["traces"], tables["contact"],
                             tables["interface"], layout)


def _summary(start_from):
    """The summary of ``start_from``: a Result's, or its folder's summary.json."""
    if hasattr(start_from, "summary"):
        return start_from.summary
    return json.loads((Path(start_from) / "summary.json").read_text())


def calibrated_half_width(start_from, first_contact):
    """The half-width a warm start's first contact set is drawn to: this run's a priori
    one (Strategy.first_contact, b) times the neighbour's answer over its own a priori
    one, where the neighbour made one and touched in one zone; else None (its set is the
    start's). The neighbour's own set can be far from this run's: from the answer at
    half the force the near-rigid cylinder's set grew for 8 updates, 30 iterations
    against a cold start's 10; the calibrated estimate took 10 (and 4 from its own
    answer, 9-18 from a neighbour in a coating's modulus or thickness, against 11-21
    cold). ``start_from``: as start_state's, already checked by it."""
    summary = _summary(start_from)
    own = (summary.get("strategy") or {}).get("first_contact")
    answer, zones = summary.get("contact_half_width"), summary.get("contact_zones") or []
    if not own or not answer or len(zones) != 1:
        return None
    length = dimensionless(scene_from_dict(summary["scene"]))[1].length
    return first_contact * answer / (own * length)


def nearest(values, candidates):
    """The candidate point (name, values) nearest to ``values``: the fewest differing
    keys, then the smallest sum of |log(a/b)| over differing positive numbers (other
    differences count 1), then the earliest; None without candidates."""
    def distance(other):
        keys = set(values) | set(other)
        differing = [k for k in keys if values.get(k) != other.get(k)]
        spread = 0.0
        for key in differing:
            a, b = values.get(key), other.get(key)
            numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0
                          for v in (a, b))
            spread += abs(math.log(a / b)) if numbers else 1.0
        return len(differing), spread
    ranked = sorted(enumerate(candidates), key=lambda item: (distance(item[1][1]), item[0]))
    return ranked[0][1] if ranked else None
