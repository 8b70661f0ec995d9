"""The bond's peak shear against the interface elements (not a test): what the warning
coarse_bond (orchestrate/run/validity.py) rests on, and what the shells do as the mesh
resolves the coating.

At a contact's edge the pressure drops to zero with an unbounded slope (Hertz: like the
square root of the distance). A 2D coating spreads that drop over about its thickness,
and the bond's shear peaks there; on interface elements longer than the thickness the
peak is the mesh's. So the peak should settle once the elements are a fraction of h2,
whatever h2 is. A shell's bond shear carries the slope of its membrane force, which
(with the coating's Poisson stress, docs/findings.md) follows the pressure's slope at a
point: nothing spreads it over the thickness.

On the paper's scene (h2 = b/16 and b/64; E2 = E/5, E, 5E), the interface elements
sized so that the coating is ELEMENT_THICKNESSES of them thick at the contact (contact_elements
= a y / h2, graded back to the default away from the contact), each coating model: the
bond's largest shear away from the patch's end zones, where it is, and the peak contact
pressure; each against the 2D coating's on the finest mesh.

Writes results/bond_shear_mesh.csv (a row per run, appended as it finishes: an
interrupted study resumes) and the report results/bond_shear_mesh.md.

    python -m studies.bond_shear_mesh
    python -m studies.bond_shear_mesh --heights 0.0625 --moduli 1     # shorter
"""

import argparse
import os

import numpy as np
import pandas as pd

import orchestrate
from orchestrate.model import Settings, contact_half_width, estimate
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, fraction_of_b, signed_percent

HEIGHTS = (1 / 16, 1 / 64)
MODULI = (0.2, 1.0, 5.0)
ELEMENT_THICKNESSES = (0.5, 1.0, 2.0, 4.0, 8.0)   # h2 over the interface element at the contact
MODELS = ("elastic", "shell", "stretch_shell")


def solve(h2, E2, thick, model, session):
    scene = orchestrate.paper_scene(h2=h2, E2=E2, model=model)
    a = contact_half_width(scene)
    settings = Settings(contact_elements=a * thick / h2)
    summary = orchestrate.solve(scene, settings, session=session).summary
    bond = summary["answers"]["bonds"]["bond-coating1"]
    return {"h2": h2, "E2": E2, "elements_thick": thick, "model": model,
            "element": summary["interface_element_size"],
            "bond_shear": bond["shear"]["value"], "bond_shear_x1": bond["shear"]["x1"],
            "peak_pressure": -summary["peak_contact_stress"],
            "contact_half_width": summary["contact_half_width"]}


def study(out, heights=HEIGHTS, moduli=MODULI, thicks=ELEMENT_THICKNESSES, progress=print):
    """Every run's row, appended to the CSV ``out`` as it finishes (a run already there
    is not solved again: an interrupted study resumes); the table with each row's
    errors against the 2D coating's on the finest mesh."""
    done = pd.read_csv(out) if os.path.exists(out) else pd.DataFrame()
    key = ["h2", "E2", "elements_thick", "model"]
    finished = set(map(tuple, done[key].to_numpy())) if len(done) else set()
    with orchestrate.Session() as session:
        for h2 in heights:
            for E2 in moduli:
                for thick in thicks:
                    for model in MODELS:
                        if (h2, E2, thick, model) in finished:
                            continue
                        row = pd.DataFrame([solve(h2, E2, thick, model, session)])
                        row.to_csv(out, mode="a", header=not os.path.exists(out), index=False)
                    progress(f"h2 = {h2:g} b, E2 = {E2:g} E, {thick:g} elements thick: done")
    return with_errors(pd.read_csv(out))


def with_errors(table):
    """The table with each row's bond shear and peak pressure against the 2D coating's
    on the finest mesh of its scene."""
    table = table.copy()
    elastic = table[table.model == "elastic"]
    finest = (elastic.loc[elastic.groupby(["h2", "E2"]).elements_thick.idxmax()]
              .set_index(["h2", "E2"]))
    for quantity in ("bond_shear", "peak_pressure"):
        table[f"{quantity}_error"] = [
            row[quantity] / finest.loc[(row["h2"], row["E2"]), quantity] - 1.0
            for _, row in table.iterrows()]
    return table


def _trend(table, model, h2, E2):
    rows = table[(table.model == model) & (table.h2 == h2) & (table.E2 == E2)]
    return ", ".join(signed_percent(e, 1) for e in rows.sort_values("elements_thick")
                     .bond_shear_error)


def settled_from(table, tolerance=0.01):
    """The fewest elements through the thickness from which the 2D coating's bond shear
    stays within ``tolerance`` of its finest value, in every scene (NaN if never)."""
    elastic = table[table.model == "elastic"]
    settled = []
    for _, rows in elastic.groupby(["h2", "E2"]):
        rows = rows.sort_values("elements_thick")
        within = (rows.bond_shear_error.abs() <= tolerance).to_numpy()
        first = next((i for i in range(len(within)) if within[i:].all()), None)
        settled.append(np.nan if first is None else rows.elements_thick.iloc[first])
    return max(settled)


def poisson_shares(table):
    """((h2, E2), the Timoshenko shell's bond-shear error on the finest mesh, p) of every
    scene: p = E* nu2 (1 + nu2) / E2 (estimate.scene_ratios), the layer's Poisson stress
    against its stretch."""
    found = []
    for (h2, E2), rows in table[table.model == "shell"].groupby(["h2", "E2"]):
        scene = orchestrate.paper_scene(h2=h2, E2=E2)
        share = estimate.scene_ratios(scene, scene.coatings[0])[4]
        finest = rows.loc[rows.elements_thick.idxmax(), "bond_shear_error"]
        found.append(((h2, E2), float(finest), share))
    return found


def write_report(table, out, command="python -m studies.bond_shear_mesh"):
    report = Report("The bond's peak shear against the interface elements", command,
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    thicks = sorted(table.elements_thick.unique())
    report.text("The paper's scene, the interface elements at the contact sized so that the "
                f"coating is {', '.join(f'{t:g}' for t in thicks)} of them thick; the bond's "
                "largest shear away from the patch's end zones (it lies at the contact's "
                "edge) of each coating model, against the 2D coating's on the finest mesh.")
    report.finding(f"The 2D coating's peak bond shear stays within 1 % of its finest value "
                   f"from {settled_from(table):g} elements through the thickness on, in every "
                   f"scene.")
    report.finding("The Timoshenko shell's bond shear on the finest mesh against the share "
                   "-p/(1 + p) its membrane leaves out, p = E* nu2 (1 + nu2) / E2 (the layer's "
                   "Poisson stress, docs/findings.md): " + "; ".join(
                       f"h2 = {fraction_of_b(h2)}, E2 = {E2:g} E: {signed_percent(error, 1)} "
                       f"against {signed_percent(-share / (1 + share), 1)}"
                       for (h2, E2), error, share in poisson_shares(table)) + ".")
    for model, name in (("elastic", "2D coating"), ("shell", "Timoshenko shell"),
                        ("stretch_shell", "stretch shell")):
        for (h2, E2), _ in table.groupby(["h2", "E2"]):
            report.finding(f"{name}, h2 = {fraction_of_b(h2)}, E2 = {E2:g} E, as the coating "
                           f"is {', '.join(f'{t:g}' for t in thicks)} elements thick: "
                           f"{_trend(table, model, h2, E2)}.")
    report.table(table, [
        Column("model", "model"), Column("h2", "h2", fraction_of_b),
        Column("E2", "E2 (E)", "{:g}"), Column("elements_thick", "h2 / element", "{:g}"),
        Column("element", "element (b)", "{:.3g}", "the interface element at the contact"),
        Column("bond_shear_error", "bond shear", signed_percent,
               "largest bond shear away from the end zones, against the 2D coating's on "
               "the finest mesh"),
        Column("bond_shear_x1", "at x1 (b)", "{:.3g}"),
        Column("contact_half_width", "a (b)", "{:.3g}", "the contact's half-width"),
        Column("peak_pressure_error", "peak pressure", signed_percent)])
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "bond_shear_mesh.csv"))
    parser.add_argument("--heights", type=float, nargs="+", default=list(HEIGHTS))
    parser.add_argument("--moduli", type=float, nargs="+", default=list(MODULI))
    args = parser.parse_args(argv)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    table = study(args.out, args.heights, args.moduli)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print(write_report(table, os.path.splitext(args.out)[0] + ".md",
                       command_line("studies.bond_shear_mesh", argv)))


if __name__ == "__main__":
    main()
