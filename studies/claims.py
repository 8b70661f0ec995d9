"""The paper's claims about its figures 3-5 (METHOD.md, "What the figures show"),
measured on finished runs and judged: ``python -m studies.claims results/figures`` (after
`make fig3 fig4 fig5`) writes results/claims.md, each claim with the numbers it was
judged on and its verdict, and results/claims.csv, every measurement.
tests/studies/test_paper_claims.py turns each claim into a test.

Distances between two stress curves on an interface are relative L2 distances over
the coating, ||a - b|| / ||b||, with the nodal (Simpson) weights of the interface points.
"""

import argparse
import json
import os

import numpy as np
import pandas as pd

from orchestrate.files import written
from orchestrate.mesh import simpson
from studies.figure_scenes import FIGURE_HEIGHTS
from studies.figures import STRESS_UNIT, load_runs
from studies.paths import RESULTS_DIR
from studies.report import (Column, Report, fraction_of_b, fraction_of_E, listing, percent,
                            significant, signed_percent)


class Runs:
    """Finished runs indexed by (model, h2, E2)."""

    def __init__(self, folders):
        table = load_runs(folders)
        self.folders = {(r.model, r.h2, r.E2): r.folder for r in table.itertuples()}
        self.height = float(table.height.iloc[0])

    def curve(self, file, model, h2, E2):
        table = pd.read_csv(os.path.join(self.folders[(model, h2, E2)], file))
        return table.x1.to_numpy(), table.sigma_n.to_numpy()

    def summary(self, model, h2, E2):
        with open(os.path.join(self.folders[(model, h2, E2)], "summary.json")) as f:
            return json.load(f)

    def coating(self, h2, E2):
        return pd.read_csv(os.path.join(self.folders[("elastic", h2, E2)], "coating1.csv"))


def distance(a, b):
    """||a - b|| / ||b|| for two curves given at the same interface points."""
    (xa, ya), (xb, yb) = a, b
    assert np.allclose(xa, xb), "curves on different interface points"
    weight = simpson(xb[::2])[1]       # the element ends are every other point
    return float(np.sqrt(np.dot(weight, (ya - yb) ** 2) / np.dot(weight, yb ** 2)))


def left_edge(coating, height):
    """sigma_eq along the coating's left edge x1 = 0, by height above S23."""
    edge = coating[coating.x1 == 0.0].sort_values("x2")
    return (edge.x2 - height).to_numpy(), edge.sigma_eq.to_numpy()


def maximum(coating, height, h2):
    """Value of the largest sigma_eq and its place: x1 and relative height (x2 - h)/h2."""
    peak = coating.sigma_eq.idxmax()
    return (float(coating.sigma_eq[peak]), float(coating.x1[peak]),
            float((coating.x2[peak] - height) / h2))


def local_maxima(values):
    """Indices of the local maxima of a sequence (ends count when above their neighbour)."""
    padded = np.concatenate([[-np.inf], values, [-np.inf]])
    return [i for i in range(len(values))
            if padded[i + 1] > padded[i] and padded[i + 1] >= padded[i + 2]]


def measurements(runs):
    """Every number the claims are judged on, as (name, value) rows."""
    rows = []
    for E2 in (5.0, 1.0):
        for h2 in (1.0, 0.125):
            rows.append((f"fig3 model distance, h2={h2:g}, E2={E2:g}", distance(
                runs.curve("contact.csv", "shell", h2, E2),
                runs.curve("contact.csv", "elastic", h2, E2))))
    for model in ("shell", "elastic"):
        for h2 in (1.0, 0.125):
            rows.append((f"fig3 E2 distance, {model}, h2={h2:g}", distance(
                runs.curve("contact.csv", model, h2, 5.0), runs.curve("contact.csv", model, h2, 1.0))))
            for E2 in (5.0, 1.0):
                summary = runs.summary(model, h2, E2)
                rows.append((f"fig3 peak |sigma12n|, {model}, h2={h2:g}, E2={E2:g}",
                             -summary["peak_contact_stress"]))
                rows.append((f"fig3 half-width, {model}, h2={h2:g}, E2={E2:g}",
                             summary["contact_half_width"]))
    for h2 in (1.0, 0.5, 0.25, 0.125, 0.0625):
        for E2 in (5.0, 1.0):
            rows.append((f"fig4 model distance, h2={h2:g}, E2={E2:g}", distance(
                runs.curve("interface.csv", "shell", h2, E2),
                runs.curve("interface.csv", "elastic", h2, E2))))
        for model in ("shell", "elastic"):
            rows.append((f"fig4 E2 distance, {model}, h2={h2:g}", distance(
                runs.curve("interface.csv", model, h2, 5.0),
                runs.curve("interface.csv", model, h2, 1.0))))
            for E2 in (5.0, 1.0):
                rows.append((f"fig4 sigma23-sigma12 distance, {model}, h2={h2:g}, E2={E2:g}",
                             distance(runs.curve("interface.csv", model, h2, E2),
                                      runs.curve("contact.csv", model, h2, E2))))
    for E2 in (0.2, 1.0, 5.0):
        for h2 in (1.0, 0.5, 0.25, 0.125):
            value, x1, height = maximum(runs.coating(h2, E2), runs.height, h2)
            rows.append((f"fig5 max sigma_eq, h2={h2:g}, E2={E2:g}", value))
            rows.append((f"fig5 max x1, h2={h2:g}, E2={E2:g}", x1))
            rows.append((f"fig5 max relative height, h2={h2:g}, E2={E2:g}", height))
            heights, values = left_edge(runs.coating(h2, E2), runs.height)
            for i in local_maxima(values):
                rows.append((f"fig5 left-edge local max, h2={h2:g}, E2={E2:g}, "
                             f"height={heights[i] / h2:.2f}", values[i]))
    return rows


# ---- the claims, judged -------------------------------------------------------------------
# Each claim of the paper is checked case by case (a panel, a model, a modulus): a case
# holds or not, with the numbers it was judged on. The verdict follows from the cases.

FIG3_HEIGHTS = (1.0, 0.125)
FIG5_HEIGHTS = (1.0, 0.5, 0.25, 0.125)
MODEL_NAMES = {"shell": "shell", "elastic": "2D"}


def _b(h2):
    return fraction_of_b(h2)


def _E(E2):
    return fraction_of_E(E2)


def _stress(value):
    """A stress in the figures' unit, 1e-4 E."""
    return f"{value / STRESS_UNIT:.3g}"


def _decreasing(values):
    return all(b < a for a, b in zip(values, values[1:]))


def _sequence(values, show=significant):
    return " -> ".join(show(v) for v in values)


def _model_distance(runs, file, h2, E2):
    return distance(runs.curve(file, "shell", h2, E2), runs.curve(file, "elastic", h2, E2))


def _E2_distance(runs, file, model, h2):
    return distance(runs.curve(file, model, h2, 5.0), runs.curve(file, model, h2, 1.0))


def _peak(runs, model, h2, E2):
    return -runs.summary(model, h2, E2)["peak_contact_stress"]


def _half_width(runs, model, h2, E2):
    return runs.summary(model, h2, E2)["contact_half_width"]


def _edge_maxima(runs, h2, E2):
    """Local maxima of sigma_eq along the left edge: {relative height: value}."""
    heights, values = left_edge(runs.coating(h2, E2), runs.height)
    return {round(heights[i] / h2, 3): values[i] for i in local_maxima(values)}


def _place(height):
    """A relative height above S23 (0: on S23, 1: on S12)."""
    return {0.0: "on S23", 1.0: "on S12"}.get(height, f"{height:.3g} h2 above S23")


def fig3_claims(runs):
    thick, thin = FIG3_HEIGHTS
    contact = "contact.csv"
    yield "Fig. 3: the models differ more for E2 = E", [
        (f"h2 = {_b(h2)}", _model_distance(runs, contact, h2, 1.0)
         > _model_distance(runs, contact, h2, 5.0),
         f"h2 = {_b(h2)}: {significant(_model_distance(runs, contact, h2, 1.0))} (E) vs "
         f"{significant(_model_distance(runs, contact, h2, 5.0))} (5E)")
        for h2 in FIG3_HEIGHTS]
    yield "... they come closer as h2 decreases", [
        (_E(E2), _model_distance(runs, contact, thin, E2)
         < _model_distance(runs, contact, thick, E2),
         f"{_E(E2)}: " + _sequence([_model_distance(runs, contact, h2, E2)
                                    for h2 in FIG3_HEIGHTS]))
        for E2 in (1.0, 5.0)]
    cases = [(model, E2) for model in ("shell", "elastic") for E2 in (5.0, 1.0)]
    yield "a smaller h2 lowers the peak abs(sigma_12n)", [
        (f"{MODEL_NAMES[model]}, E2 = {_E(E2)}",
         _peak(runs, model, thin, E2) < _peak(runs, model, thick, E2),
         f"{MODEL_NAMES[model]} {_E(E2)}: " + _sequence(
             [_peak(runs, model, h2, E2) for h2 in FIG3_HEIGHTS], _stress) + " (1e-4 E)")
        for model, E2 in cases]
    yield "... and widens the contact", [
        (f"{MODEL_NAMES[model]}, E2 = {_E(E2)}",
         _half_width(runs, model, thin, E2) > _half_width(runs, model, thick, E2),
         f"{MODEL_NAMES[model]} {_E(E2)}: " + _sequence(
             [_half_width(runs, model, h2, E2) for h2 in FIG3_HEIGHTS]) + " b")
        for model, E2 in cases]
    yield "the thinner the coating, the less E2 matters", [
        (MODEL_NAMES[model], _E2_distance(runs, contact, model, thin)
         < _E2_distance(runs, contact, model, thick),
         f"{MODEL_NAMES[model]}: " + _sequence([_E2_distance(runs, contact, model, h2)
                                                for h2 in FIG3_HEIGHTS]))
        for model in ("shell", "elastic")]


def fig4_claims(runs):
    heights = FIGURE_HEIGHTS
    bond, contact = "interface.csv", "contact.csv"
    models = {E2: [_model_distance(runs, bond, h2, E2) for h2 in heights] for E2 in (5.0, 1.0)}
    yield "Fig. 4: the models agree better as h2 decreases (b ... b/16)", [
        (_E(E2), _decreasing(values), f"{_E(E2)}: " + ", ".join(map(significant, values)))
        for E2, values in models.items()]
    yield "... and better for the stiffer coating", [
        (f"h2 = {_b(h2)}", models[5.0][i] < models[1.0][i],
         f"h2 = {_b(h2)}: {significant(models[5.0][i])} (5E) vs {significant(models[1.0][i])} (E)")
        for i, h2 in enumerate(heights)]
    yield "the curves for different E2 converge as h2 decreases", [
        (MODEL_NAMES[model], _decreasing(values := [_E2_distance(runs, bond, model, h2)
                                                    for h2 in heights]),
         f"{MODEL_NAMES[model]}: " + _sequence(values))
        for model in ("shell", "elastic")]
    yield "sigma_23n approaches sigma_12n as h2 decreases", [
        (f"{MODEL_NAMES[model]}, E2 = {_E(E2)}",
         _decreasing(values := [distance(runs.curve(bond, model, h2, E2),
                                         runs.curve(contact, model, h2, E2))
                                for h2 in heights]),
         f"{MODEL_NAMES[model]} {_E(E2)}: " + _sequence(values))
        for model in ("shell", "elastic") for E2 in (5.0, 1.0)]


def fig5_claims(runs):
    heights = FIG5_HEIGHTS

    def top(h2, E2):
        return maximum(runs.coating(h2, E2), runs.height, h2)

    value, x1, height = top(1.0, 0.2)
    yield "Fig. 5, E2 = E/5: the maximum lies near the middle of the left edge at h2 = b", [
        ("h2 = b", x1 == 0.0 and 0.3 <= height <= 0.7,
         f"x1 = {x1:g}, {_place(round(height, 3))}")]
    soft = [top(h2, 0.2) for h2 in heights]
    places = [round(h, 3) for _, _, h in soft]
    yield "... it grows and moves to S23 as h2 drops", [
        ("grows", _decreasing([-v for v, _, _ in soft]),
         ", ".join(_stress(v) for v, _, _ in soft) + " (1e-4 E)"),
        ("moves to S23", all(b <= a for a, b in zip(places, places[1:])) and places[-1] == 0.0,
         ", ".join(_place(p) for p in places))]
    _, same_x1, same_height = top(1.0, 1.0)
    yield "E2 = E: the maximum lies on the left edge, nearer S23 than for E/5", [
        ("h2 = b", same_x1 == 0.0 and same_height < height,
         f"x1 = {same_x1:g}, {_place(round(same_height, 3))} (E/5: {_place(round(height, 3))})")]
    same = [top(h2, 1.0)[0] for h2 in heights]
    yield "... falling as h2 drops", [
        ("falls", _decreasing(same), ", ".join(map(_stress, same)) + " (1e-4 E)")]
    stiff = {h2: _edge_maxima(runs, h2, 5.0) for h2 in heights}
    yield "E2 = 5E: two local maxima on the left edge, near S23 and S12", [
        (f"h2 = {_b(h2)}", set(found) == {0.0, 1.0},
         f"h2 = {_b(h2)}: " + listing(_place(p) for p in sorted(found)))
        for h2, found in stiff.items()]
    both = [h2 for h2 in heights if {0.0, 1.0} <= set(stiff[h2])]

    def step(a, b):
        rise = {p: stiff[b][p] / stiff[a][p] - 1.0 for p in (1.0, 0.0)}
        return (f"{_b(a)} -> {_b(b)}", rise[1.0] > 0 and rise[0.0] < 0,
                f"{_b(a)} -> {_b(b)}: S12 {signed_percent(rise[1.0], 0)}, "
                f"S23 {signed_percent(rise[0.0], 0)}")
    cases = []
    if len(both) > 1:
        label, ok, data = step(both[0], both[-1])
        cases.append((label + " (overall)", ok, data + " (overall)"))
    if len(both) > 2:
        cases += [step(a, b) for a, b in zip(both, both[1:])]
    yield "... a smaller h2 raises the one near S12 and lowers the one near S23", cases
    yield "the maxima grow with E2 (E/5, E, 5E)", [
        (f"h2 = {_b(h2)}", _decreasing([-v for v in values]),
         f"h2 = {_b(h2)}: " + ", ".join(map(_stress, values)) + " (1e-4 E)")
        for h2 in heights for values in [[top(h2, E2)[0] for E2 in (0.2, 1.0, 5.0)]]]


def verdict(cases):
    """'holds' when every case does, 'contradicted' when none does, else for which."""
    failing = [label for label, ok, _ in cases if not ok]
    if not failing:
        return "holds"
    if len(failing) == len(cases):
        return "**contradicted**"
    others = len(cases) - len(failing)
    return (f"**contradicted** for {listing(failing)}; holds in the other "
            f"{others} case{'s' if others > 1 else ''}")


def judged(runs):
    """Every claim: (claim, the numbers it was judged on, verdict)."""
    rows = []
    for claims in (fig3_claims, fig4_claims, fig5_claims):
        for claim, cases in claims(runs):
            rows.append({"claim": claim, "data": "; ".join(data for _, _, data in cases),
                         "verdict": verdict(cases)})
    return rows


def _bond_shear(summary):
    return summary["answers"]["bonds"]["bond-coating1"]["shear"]["value"]


def shell_warnings(runs, folders):
    """Per shell run of the figures: its model_error warning (the estimate, or none) and
    the measured error it estimates: the larger of the peak contact and bond stresses'
    relative differences from the 2D model's run of the same scene; its bond_shear_model
    warning and the bond shear's measured difference."""
    table = load_runs(folders)
    rows = []
    for run in table[table.model == "shell"].sort_values(["E2", "h2"], ascending=False
                                                         ).itertuples():
        shell, elastic = runs.summary("shell", run.h2, run.E2), runs.summary("elastic", run.h2,
                                                                           run.E2)
        measured = max(abs(shell[key] / elastic[key] - 1.0)
                       for key in ("peak_contact_stress", "peak_interface_stress"))
        warning = [w for w in shell["warnings"] if w["code"] == "model_error"]
        shear = [w for w in shell["warnings"] if w["code"] == "bond_shear_model"]
        rows.append({"h2": run.h2, "E2": run.E2,
                     "estimate": warning[0]["value"] if warning else None,
                     "measured": measured,
                     "shear_estimate": shear[0]["value"] if shear else None,
                     "shear_measured": abs(_bond_shear(shell) / _bond_shear(elastic) - 1.0),
                     "tolerance": shell["settings"]["model_tolerance"],
                     "other_warnings": ", ".join(
                         w["code"] for w in shell["warnings"]
                         if w["code"] not in ("model_error", "bond_shear_model"))})
    return rows


def report(folders, out):
    """Write the claims' report (markdown) and the measurements behind it (CSV)."""
    runs = Runs(folders)
    measured = pd.DataFrame(measurements(runs), columns=["measurement", "value"])
    csv = os.path.splitext(out)[0] + ".csv"
    written(csv, lambda partial: measured.to_csv(partial, index=False))
    claims = judged(runs)
    text = Report("The paper's claims, on our data",
                  "python -m studies.claims " + " ".join(folders),
                  data=[os.path.join(f, "runs.csv") if os.path.isdir(f) else f
                        for f in folders])
    text.text("Each claim the paper makes about its figures 3-5 (METHOD.md), judged on the "
              "figure runs (both coating models, the paper's mesh), case by case. Distances "
              "are relative L2 distances between two stress curves over the coating, "
              "||a - b|| / ||b|| (dimensionless); stresses in 1e-4 E, half-widths and heights "
              "in b; 'h2 above S23' is a height in the coating over its thickness.")
    text.table(claims, [
        Column("claim", "claim (the paper's)"),
        Column("data", "our data", meaning="the numbers each case is judged on, "
               "thicker coating first (a -> b: from the thicker to the thinner)"),
        Column("verdict", "verdict", meaning="holds in every case, **contradicted** in "
               "every case, or contradicted in the cases named")])
    failing = [row["claim"] for row in claims if row["verdict"] != "holds"]
    text.finding(f"{len(claims) - len(failing)} of the paper's {len(claims)} claims hold in "
                 "every case"
                 + (f"; our data contradict {len(failing)}, in some cases or all: "
                    + "; ".join(f"\"{claim}\"" for claim in failing) if failing else "")
                 + ".")
    warnings = shell_warnings(runs, folders)
    text.section("The shell runs' model_error warnings")
    text.text("A shell run warns (`model_error`) where its estimated model error in the "
              "judged answers (the peak contact and bond stresses) exceeds the tolerance, and "
              "(`bond_shear_model`) where its bond shear's does; measured here against the 2D "
              "model's run of the same scene.")
    text.table(warnings, [
        Column("h2", "h2", _b), Column("E2", "E2", _E),
        Column("estimate", "estimated error", percent,
               "the warning's value (empty: no warning)"),
        Column("measured", "measured error", percent, "the larger of the peak contact and "
               "bond stresses' relative difference from the 2D model"),
        Column("shear_estimate", "bond shear: estimated", percent,
               "the bond_shear_model warning's value (empty: no warning)"),
        Column("shear_measured", "measured", percent,
               "the largest bond shear's relative difference from the 2D model"),
        Column("other_warnings", "other warnings")])
    agree = sum((row["estimate"] is not None) == (row["measured"] > row["tolerance"])
                for row in warnings)
    shear_agree = sum((row["shear_estimate"] is not None)
                      == (row["shear_measured"] > row["tolerance"]) for row in warnings)
    warned = [f"{_b(row['h2'])} ({_E(row['E2'])})" for row in warnings
              if row["estimate"] is not None]
    text.finding(f"The warning is given on {len(warned)} of {len(warnings)} shell runs"
                 + (f" (h2 = {listing(warned)})" if warned else "")
                 + f"; it is given exactly where the measured error exceeds the tolerance "
                 f"in {agree} of {len(warnings)}. The bond_shear_model warning is given "
                 f"exactly where the bond shear's measured difference exceeds it in "
                 f"{shear_agree} of {len(warnings)}.")
    return text.write(out), csv


def main(argv=None):
    parser = argparse.ArgumentParser(description="Judge the paper's claims on the figure runs "
                                     "(results/claims.md, claims.csv).")
    parser.add_argument("runs", nargs="+", help="run folders, or the figure sweep's folder "
                        "(results/figures)")
    parser.add_argument("--out", default=str(RESULTS_DIR / "claims.md"),
                        help="the report; the measurements go beside it (claims.csv)")
    args = parser.parse_args(argv)
    for path in report(args.runs, args.out):
        print(path)


if __name__ == "__main__":
    main()
