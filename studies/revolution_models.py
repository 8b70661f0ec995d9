"""The coating models of an axisymmetric scene against each other as the coating thins:
the shell of revolution and the stretch shell of revolution against the 2D coating.

The sphere scene (orchestrate/scenes/sphere.toml: a sphere of radius 20 b on a cylinder,
a coating disc of radius 3 b, contact radius about 1 b) with a stiff coating (E2 = 4 E)
and a compliant one (E2 = E/4), h2 from b/4 down to b/64, each solved with the three
models at mesh level 1: the shells' peak pressure, contact radius, bond compression and
bond shear (their largest away from the patch's end) against the 2D coating's.

Writes results/revolution_models.csv and .md.

    python -m studies.revolution_models
"""

import argparse
import os
import time

import pandas as pd

from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds, signed_percent
from orchestrate.model import apply_overrides, load_scene
from orchestrate.paths import SCENES_DIR
import orchestrate

THICKNESSES = (1 / 4, 1 / 8, 1 / 16, 1 / 32, 1 / 64)
MODULI = (4.0, 0.25)
MODELS = ("elastic", "shell", "stretch_shell")
QUANTITIES = ("peak_pressure", "contact_radius", "bond_compression", "bond_shear")


def answers(model, thickness, modulus):
    """The quantities of one run, and its time."""
    scene, _ = load_scene(SCENES_DIR / "sphere.toml")
    scene = apply_overrides(scene, {"coating.model": model, "coating.thickness": thickness,
                                    "coating.E": modulus})
    start = time.perf_counter()
    result = orchestrate.solve(scene)
    took = time.perf_counter() - start
    bond = result.answers["bonds"]["bond-coating1"]
    return {"peak_pressure": result.answers["contact"]["peak_pressure"]["value"],
            "contact_radius": result.summary["contact_half_width"],
            "bond_compression": -bond["compression"]["value"],
            "bond_shear": bond["shear"]["value"],
            "iterations": result.summary["iterations"], "seconds": took}


def study():
    rows = []
    for modulus in MODULI:
        for thickness in THICKNESSES:
            reference = answers("elastic", thickness, modulus)
            for model in MODELS:
                found = reference if model == "elastic" else answers(model, thickness, modulus)
                row = {"E2": modulus, "h2": thickness, "model": model, **found}
                for name in QUANTITIES:
                    row[f"{name}_difference"] = found[name] / reference[name] - 1
                rows.append(row)
    return pd.DataFrame(rows)


def write_report(table, out, argv=None):
    report = Report("Shells of revolution against the 2D coating as the coating thins",
                    command_line("studies.revolution_models", argv),
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text("The sphere scene (orchestrate/scenes/sphere.toml: R = 20 b, a coating disc of "
                "radius 3 b, contact radius about 1 b), default settings, mesh level 1; each "
                "shell's answers against the 2D coating's of the same thickness.")
    shells = table[table.model != "elastic"]
    for modulus in MODULI:
        for model in MODELS[1:]:
            rows = shells[(shells.E2 == modulus) & (shells.model == model)]
            report.finding(
                f"{model}, E2 = {modulus:g} E, as h2 halves from b/4: peak pressure "
                + ", ".join(f"{100 * v:+.2f} %" for v in rows.peak_pressure_difference)
                + "; bond shear "
                + ", ".join(f"{100 * v:+.1f} %" for v in rows.bond_shear_difference) + ".")
    report.table(table, [
        Column("E2", "E2 (E)", "{:g}"), Column("h2", "h2 (b)", lambda v: f"1/{1 / v:g}"),
        Column("model", "model"),
        Column("peak_pressure_difference", "peak pressure", signed_percent,
               "against the 2D coating's"),
        Column("contact_radius_difference", "contact radius", signed_percent),
        Column("bond_compression_difference", "bond compression", signed_percent),
        Column("bond_shear_difference", "bond shear", signed_percent,
               "the largest away from the patch's end"),
        Column("iterations", "iterations", "{:g}"), Column("seconds", "time", seconds)])
    report.write(os.path.splitext(out)[0] + ".md")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join(RESULTS_DIR, "revolution_models.csv"))
    args = parser.parse_args(argv)
    table = study()
    table.to_csv(args.out, index=False)
    write_report(table, args.out, argv)
    print(table.to_string(index=False))


if __name__ == "__main__":
    main()
