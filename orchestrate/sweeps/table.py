"""A sweep's table, runs.csv: one row per point, in the sweep file's order, from the run
folders' summaries; and sweep.pvd, the converged runs' fields in ParaView."""

from dataclasses import fields
import json
import os
from pathlib import Path

import pandas as pd

from orchestrate.model.scene import Settings, scene_from_dict, to_dict
from orchestrate.model.scene_file import shorthand_values
from orchestrate.run.paraview import SWEEP_COLLECTION, write_sweep_collection


# a run's outcome in its row, from its summary.json; the other columns say what was run
SUMMARY_COLUMNS = ("status", "reason", "converged", "iterations", "final_relative_change",
                   "error_estimate", "active_set_changes", "inner_solve_used", "contact_force",
                   "total_force",
                   "descent", "interface_force", "peak_contact_stress",
                   "peak_interface_stress", "contact_half_width", "wall_time_s",
                   "setup_time_s", "loop_time_s", "outputs_time_s", "time_per_iteration_s")
OUTCOME_COLUMNS = SUMMARY_COLUMNS + ("model_chosen", "model_error_estimate", "warnings",
                                     "forms_digest")


def _model_choice_columns(choice):
    """A run with "auto" patches: the models chosen (one per auto patch, "/"-joined) and
    the largest estimated model error among them."""
    if not choice:
        return {"model_chosen": None, "model_error_estimate": None}
    estimates = [p["estimated_error"] for p in choice["patches"]
                 if p["estimated_error"] is not None]
    return {"model_chosen": "/".join(p["model"] for p in choice["patches"]),
            "model_error_estimate": max(estimates, default=None)}


def gather(sweep_dir, runs):
    """One row per (name, values) run, in their order: the run folder's name ("id"), the
    point's values, the scene and settings, outcome and figures."""
    rows = []
    for name, values in runs:
        path = Path(sweep_dir) / "runs" / name / "summary.json"
        if not path.exists():
            continue
        summary = json.loads(path.read_text())
        row = {"id": name, **values}
        if summary.get("scene"):
            scene = scene_from_dict(summary["scene"])
            row.update(shorthand_values(scene))
            row.update(_flatten(to_dict(scene)))
            row.update(_every_patch_values(values, row))
        # a run that could not run has no settings: its values over the defaults
        settings = summary.get("settings") or {f.name: values.get(f.name, f.default)
                                               for f in fields(Settings)}
        # a run older than a setting has no value for it: an empty cell
        row.update({f.name: settings.get(f.name) for f in fields(Settings)})
        row.update({key: summary.get(key) for key in SUMMARY_COLUMNS})
        row["started_from"] = Path(summary["started_from"]).name if summary.get(
            "started_from") else None
        row.update(_model_choice_columns(summary.get("model_choice")))
        # the forces' unit, which the scene's units leave to its kind: per unit width in
        # plane strain (N/mm), whole on a body of revolution (N)
        row["units.force"] = (summary.get("units") or {}).get("force")
        row["warnings"] = "; ".join(w["code"] for w in summary.get("warnings") or ())
        row["forms_digest"] = (summary.get("provenance") or {}).get("forms_digest")
        row.update(_answer_columns(summary.get("answers")))
        rows.append(row)
    return pd.DataFrame(rows)


def _every_patch_values(values, row):
    """A swept key of every patch (coating.E) as the scene holds it, a number in the
    scene's units, as every other swept key's column is (the scene's own, or a setting's):
    the first patch's (coating[1].E), which the key set to the same value as the others.
    The text given ("300 GPa") stays in the run's folder name."""
    first = {key: "coating[1]." + key.removeprefix("coating.") for key in values
             if key.startswith("coating.")}
    return {key: row[column] for key, column in first.items() if column in row}


def _answer_columns(answers):
    """orchestrate/run/answers.py's values away from the patches' ends, a column for each
    value and its x1: peak_pressure, bond-coating1.peel, coating1.von_mises, ..."""
    if not answers:
        return {}
    columns = {}
    found = {"": answers["contact"], **answers["bonds"], **answers["coatings"],
             "substrate": answers.get("substrate") or {}}
    for owner, values in found.items():
        for quantity, extreme in values.items():
            if quantity == "at_patch_ends":
                continue
            name = f"{owner}.{quantity}" if owner else quantity
            columns[name] = extreme["value"] if extreme else None
            columns[f"{name}_x1"] = extreme["x1"] if extreme else None
    return columns


def _flatten(data, prefix=""):
    """A scene's dict as dotted keys: indenter.radius, coating[1].E, ..."""
    flat = {}
    for key, value in data.items():
        if isinstance(value, dict):
            flat.update(_flatten(value, f"{prefix}{key}."))
        elif key == "coatings":
            for number, coating in enumerate(value, start=1):
                flat.update(_flatten(coating, f"{prefix}coating[{number}]."))
        elif isinstance(value, list):
            flat[prefix + key] = str(value)
        else:
            flat[prefix + key] = value
    return flat


def write_table(sweep_dir, runs):
    """runs.csv, and sweep.pvd: the finished runs' fields in ParaView, one time step per
    run in the file's order (its time slider steps through them)."""
    table = gather(sweep_dir, runs)
    path = Path(sweep_dir) / "runs.csv"
    partial = path.with_name(".runs.csv.partial")
    table.to_csv(partial, index=False)
    os.replace(partial, path)
    table.attrs["path"] = str(path)
    write_sweep_collection(Path(sweep_dir) / SWEEP_COLLECTION,
                           [Path(sweep_dir) / "runs" / name for name, _ in runs])
    return table
