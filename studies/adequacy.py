"""Where each coating model is adequate (not a test): ``make adequacy``.

Two sets of scenes, each measured by studies/model_errors.py (every coating model on
the paper's mesh against the mesh-converged 2D coating model):

    calibration   the paper's scene over h2 x E2 (and coating Poisson ratios from 0.1 to
                  0.49), and 38 development scenes (other heights, moduli, loads, radii,
                  cylinders, patches, a coated roller) on which the estimate's forms were
                  chosen: the map of model error over (h2 / a) x (E2 / E), and the data
                  orchestrate/model/estimate.py's estimate is fitted on (--fit prints its constants)
    held-out      36 scenes neither the forms nor the constants saw: other heights,
                  moduli and Poisson ratios, loads, bases, radii, cylinders (one off
                  centre, a full model), coated rollers (curved coatings), discrete and
                  shortened patches

For the held-out scenes the automatic choice (``model = "auto"``) is also run through the
Robin loop, timed against the model it chose run directly.

Writes results/adequacy/{calibration,held_out}.csv, calibration_judged.csv,
validation.csv, adequacy.png and the report report.md (the held-out verdict, where each
1D model is within the tolerance on the calibration grid, the estimate's misses).

    python -m studies.adequacy            # both sets, the map and the validation
    python -m studies.adequacy --fit      # the estimate's constants from calibration
"""

import argparse
import json
import time
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap, LogNorm  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from orchestrate.model import estimate  # noqa: E402
from orchestrate.run import plan  # noqa: E402
from studies.model_errors import measure_all, with_model  # noqa: E402
from studies.paths import RESULTS_DIR  # noqa: E402
from orchestrate.model import Settings, scene_from_dict  # noqa: E402
from orchestrate.paths import SCENES_DIR
from orchestrate.model import apply_overrides, load_scene, paper_scene  # noqa: E402
from orchestrate.run import solve_into as solve  # noqa: E402
from studies.report import (Column, Report, command_line, fraction_of_E,  # noqa: E402
                            listing, percent_g, span)

OUT_DIR = RESULTS_DIR / "adequacy"
GRID_HEIGHTS = (1 / 32, 1 / 16, 1 / 8, 1 / 4, 1 / 2, 1.0)
GRID_MODULI = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0)
GRID_POISSON = (0.1, 0.4, 0.45, 0.49)
JUDGED = 0.002         # the estimate is judged where the measured error exceeds this
FACTOR = 2.0           # ... and must lie within this factor of it
ONE_D = ("shell", "stretch_shell")


def calibration_scenes():
    """The grid, a smaller one over the coating's Poisson ratio (which the swelling
    term of the estimate needs to be told apart), and the development scenes."""
    grid = [(f"paper h2={h2:g} E2={E2:g}", paper_scene(h2=h2, E2=E2))
            for h2 in GRID_HEIGHTS for E2 in GRID_MODULI]
    poisson = [(f"paper h2={h2:g} E2={E2:g} nu2={nu2:g}", paper_scene(h2=h2, E2=E2, nu2=nu2))
               for nu2 in GRID_POISSON for h2 in (1 / 16, 1 / 4) for E2 in (0.2, 1.0, 5.0)]
    return grid + poisson + development_scenes()


def _from_file(name, **overrides):
    scene, _ = load_scene(SCENES_DIR / f"{name}.toml")
    return apply_overrides(scene, overrides)


def _paper(cases, **common):
    """Paper scenes from (h2, E2, {more shorthands}) cases."""
    scenes = []
    for h2, E2, *more in cases:
        extra = dict(common, **(more[0] if more else {}))
        label = " ".join([f"h2={h2:g}", f"E2={E2:g}"] + [f"{k}={v:g}" for k, v in extra.items()])
        scenes.append((f"paper {label}", paper_scene(h2=h2, E2=E2, **extra)))
    return scenes


def _cylinders(cases, name="cylinder", **common):
    """Scene-file scenes from (R or None, h2, E2, force) cases."""
    scenes = []
    for R, h2, E2, F in cases:
        radius = {} if R is None else {"indenter.radius": R}
        label = (f"R={R:g} " if R is not None else "") + f"h2={h2:g} E2={E2:g} F={F:g}"
        scenes.append((f"{name} {label}",
                       _from_file(name, h2=h2, E2=E2, force=F, **radius, **common)))
    return scenes


def development_scenes():
    """The first held-out set: the estimate's forms were revised on it (its patch ends
    and Poisson ratios), so that it now belongs to calibration."""
    paper = [(3 / 16, 0.3), (3 / 8, 3.0), (3 / 4, 0.5), (0.09, 2.0), (1 / 64, 0.2),
             (1 / 64, 1.0), (1 / 128, 0.1), (0.3, 0.15), (0.05, 7.0),
             (1 / 48, 0.7), (1 / 96, 3.0), (1 / 64, 0.05), (0.8, 3.0), (0.9, 8.0),
             (0.125, 0.5, {"nu2": 0.2}),
             (0.125, 1.0, {"E3": 0.5}), (0.0625, 0.3, {"E1": 3.0})]
    scenes = _paper(paper)
    shallow = [(1 / 16, 0.2), (1 / 8, 1.0), (1 / 4, 5.0), (1 / 32, 0.5)]
    scenes += [(f"paper stamp/4 h2={h2:g} E2={E2:g}",
                paper_scene(h2=h2, E2=E2, stamp=2.778999e-3 / 4)) for h2, E2 in shallow]
    scenes += [("paper l2=1.5 h2=0.2 E2=0.4", paper_scene(h2=0.2, E2=0.4, coating_length=1.5,
                                                          stamp=2.0e-3))]
    scenes += _cylinders([(10.0, 0.125, 5.0, 0.02), (50.0, 0.0625, 0.3, 0.02),
                          (100.0, 0.25, 1.0, 0.02), (20.0, 1 / 32, 0.2, 0.02),
                          (20.0, 0.125, 2.0, 0.005), (30.0, 1 / 64, 0.5, 0.01)])
    scenes += [(f"discrete h2={h2:g} E2={E2:g}", _from_file("discrete", h2=h2, E2=E2))
               for h2, E2 in [(0.125, 5.0), (0.0625, 0.3), (0.125, 1.0), (1 / 32, 0.2)]]
    scenes += _cylinders([(None, 0.125, 5.0, 0.02), (None, 0.0625, 0.3, 0.02),
                          (None, 0.25, 1.0, 0.02), (None, 1 / 32, 0.2, 0.02),
                          (None, 0.125, 2.0, 0.005), (None, 1 / 64, 1.5, 0.02)], name="roller")
    return scenes


def held_out_scenes():
    """(label, scene): scenes neither the estimate's forms nor its constants saw."""
    scenes = _paper([(0.15, 0.25), (0.04, 0.15), (0.6, 1.5), (0.07, 4.0), (1 / 40, 0.3),
                     (0.45, 0.3), (0.35, 6.0), (0.012, 0.08), (1 / 80, 2.0), (1 / 56, 0.4),
                     (0.2, 0.7, {"nu2": 0.35}), (0.1, 2.0, {"nu2": 0.47}),
                     (0.06, 0.5, {"nu2": 0.25}), (0.18, 1.2, {"nu2": 0.15}),
                     (0.03, 0.3, {"nu2": 0.45}),
                     (0.1, 0.5, {"E3": 2.0}), (0.05, 1.5, {"E3": 0.4}),
                     (0.15, 0.4, {"nu3": 0.2}), (0.12, 0.8, {"E1": 0.5}),
                     (0.1, 0.3, {"stamp": 5.5e-3}), (0.3, 2.0, {"stamp": 5.5e-3}),
                     (0.08, 0.6, {"stamp": 1.4e-3}),
                     (0.1, 0.5, {"coating_length": 1.3}), (0.1, 0.5, {"coating_length": 1.0})])
    scenes += _cylinders([(15.0, 0.05, 0.4, 0.015), (40.0, 0.1, 3.0, 0.03),
                          (70.0, 0.02, 0.25, 0.01), (25.0, 0.2, 0.6, 0.02)])
    off_centre = {"symmetric": False, "coating.start": -2.0, "indenter.centre": 0.3}
    scenes += [("cylinder off centre h2=0.08 E2=0.5 F=0.02",
                _from_file("cylinder", h2=0.08, E2=0.5, force=0.02, **off_centre))]
    scenes += _cylinders([(None, 0.05, 0.5, 0.01), (None, 0.2, 3.0, 0.03),
                          (None, 0.1, 0.25, 0.02), (None, 1 / 48, 0.6, 0.02)], name="roller")
    scenes += _cylinders([(None, 0.0625, 2.0, 0.02), (None, 0.1, 0.5, 0.02),
                          (None, 0.0625, 0.4, 0.003)], name="discrete")
    return scenes


# ---- the estimate's constants -------------------------------------------------------------

QUANTITIES = {"contact": "peak", "bond": "bond_peak"}   # estimate's name: model_errors' column


def model_part(table, model, quantity="contact"):
    """The model's error with the 2D model's own mesh error on the same mesh taken out:
    what the coating model adds (the fit's target)."""
    column = QUANTITIES[quantity]
    return (1 + table[f"{model}_error_{column}"]) / (1 + table[f"elastic_error_{column}"]) - 1


def worst_model_part(table, model):
    """The larger of the model's two errors, as auto judges it."""
    return np.maximum(*(model_part(table, model, q).abs() for q in QUANTITIES))


def _scenes(table):
    """The scene of every row."""
    return [scene_from_dict(json.loads(text)) for text in table.scene]


def features(table):
    """x, c, q, g (estimate.scene_ratios) of every row's first patch, and whether
    its errors are estimated at all."""
    scenes = _scenes(table)
    ratios = np.array([estimate.scene_ratios(s, s.coatings[0]) for s in scenes]).T
    estimated = np.array([estimate.not_estimated(s, s.coatings[0]) is None for s in scenes])
    return ratios, estimated


def _shell_constants(x, c, q, error):
    """The shell's K1..K4 by least squares relative to max(|error|, JUDGED)."""
    weight = 1.0 / np.maximum(np.abs(error), JUDGED)
    columns = np.array([x * c, x * q, x ** 2, x ** 2 * c]).T
    return tuple(float(k) for k in
                 np.linalg.lstsq(columns * weight[:, None], error * weight, rcond=None)[0])


def fit(table):
    """The constants of model_choice's estimate from the calibration rows it covers
    (estimate.not_estimated): the shell's K1..K4 per quantity (_shell_constants);
    the stretch shell's contact S, s by least squares on log error over the rows above
    JUDGED (the model too stiff: soft coatings), its plateau P as the median |error| of
    the rows below -JUDGED (too soft: stiff thick coatings) and T = P / x^2 at the
    smallest x among them; its bond B as the geometric mean of |error| / x^2 over the
    rows above JUDGED."""
    (x, c, q, g), estimated = features(table)
    table, x, c, q, g = table[estimated], x[estimated], c[estimated], q[estimated], g[estimated]
    constants = {f"SHELL_{quantity.upper()}":
                 _shell_constants(x, c, q, model_part(table, "shell", quantity).to_numpy())
                 for quantity in QUANTITIES}
    stretch = model_part(table, "stretch_shell").to_numpy()
    soft_coating, stiff_coating = stretch > JUDGED, stretch < -JUDGED
    log_fit = np.linalg.lstsq(np.array([np.ones(soft_coating.sum()), np.log(g[soft_coating])]).T,
                              np.log(stretch[soft_coating] / x[soft_coating] ** 2), rcond=None)[0]
    plateau = float(np.median(-stretch[stiff_coating]))
    bond = model_part(table, "stretch_shell", "bond").abs().to_numpy()
    judged = bond > JUDGED
    constants.update({
        "STRETCH_SOFT_COATING": (float(np.exp(log_fit[0])), float(log_fit[1])),
        "STRETCH_STIFF_COATING": (plateau / float(x[stiff_coating].min()) ** 2, plateau),
        "STRETCH_BOND": float(np.exp(np.mean(np.log(bond[judged] / x[judged] ** 2))))})
    return constants


# ---- the validation ----------------------------------------------------------------------

def estimates(table, model, quantity):
    """The estimate of every row's first patch (NaN: not estimated)."""
    values = []
    for scene in _scenes(table):
        errors = estimate.estimated_errors(scene, scene.coatings[0])[model]
        values.append(np.nan if errors is None else errors[quantity])
    return pd.Series(values, index=table.index)


def judge(table):
    """Per row, 1D model and quantity: the estimate against the measured model error
    (against the 2D model on the same mesh: model_part), and whether it is within FACTOR
    where that error exceeds JUDGED (NaN: not judged, or not estimated). mesh_error: the
    2D model's own error there (against the converged mesh), which every model shares."""
    out = table[["label"]].copy()
    out["mesh_error"] = table.elastic_error_peak
    for model in ONE_D:
        for quantity in QUANTITIES:
            name = f"{model}_{quantity}"
            measured = model_part(table, model, quantity).abs()
            estimated = estimates(table, model, quantity)
            out[f"{name}_measured"] = measured
            out[f"{name}_estimated"] = estimated
            out[f"{name}_ratio"] = estimated / measured
            out[f"{name}_within"] = np.where((measured > JUDGED) & estimated.notna(),
                                             (estimated / measured).between(1 / FACTOR, FACTOR),
                                             np.nan)
    return out


def timed_choice(scene, settings):
    """Solve with "auto" and with the model it chose (Robin loop, default settings):
    (chosen models, the estimate, seconds auto, seconds direct)."""
    auto_scene = with_model(scene, plan.AUTO)
    with tempfile.TemporaryDirectory() as auto_out, tempfile.TemporaryDirectory() as direct_out:
        start = time.perf_counter()
        summary = solve(auto_scene, settings, auto_out + "/run")
        seconds_auto = time.perf_counter() - start
        chosen = scene_from_dict(summary["scene"])
        start = time.perf_counter()
        solve(chosen, settings, direct_out + "/run")
        seconds_direct = time.perf_counter() - start
    patches = summary["model_choice"]["patches"]
    return ([p["model"] for p in patches], max(p["estimated_error"] for p in patches),
            seconds_auto, seconds_direct)


def validate(held_out, settings=Settings()):
    """The held-out table with the choice, its measured error (the larger of the
    contact and bond errors, of every model chosen) and the timings."""
    table = judge(held_out)
    for i, row in held_out.iterrows():
        scene = scene_from_dict(json.loads(row.scene))
        models, estimate, seconds_auto, seconds_direct = timed_choice(scene, settings)
        measured = max(0.0 if model == "elastic" else
                       float(worst_model_part(held_out.loc[[i]], model).iloc[0])
                       for model in set(models))
        table.loc[i, "chosen"] = "/".join(models)
        table.loc[i, "chosen_estimate"] = estimate
        table.loc[i, "chosen_measured"] = measured
        table.loc[i, "seconds_auto"] = seconds_auto
        table.loc[i, "seconds_direct"] = seconds_direct
        print(f"{row.label}: auto chose {'/'.join(models)}, measured {100 * measured:.2f} % "
              f"(estimate {100 * estimate:.2f} %), {seconds_auto:.2f} s against "
              f"{seconds_direct:.2f} s", flush=True)
    table["meets_tolerance"] = table.chosen_measured <= settings.model_tolerance
    table["cost_ratio"] = table.seconds_auto / table.seconds_direct
    return table


def _within_columns(table):
    return [f"{model}_{quantity}_within" for model in ONE_D for quantity in QUANTITIES]


def verdict(validation):
    """The held-out verdict (report.md's findings), from the validation."""
    within = pd.concat([validation[column] for column in _within_columns(validation)]).dropna()
    not_estimated = validation.shell_contact_estimated.isna()
    return {"scenes": len(validation),
            "meets_tolerance": float(validation.meets_tolerance.mean()),
            "worst_chosen_error": float(validation.chosen_measured.max()),
            "estimates_judged": len(within), "estimates_within_2x": float(within.mean()),
            "scenes_not_estimated": int(not_estimated.sum()),
            "worst_cost_ratio": float(validation.cost_ratio.max()),
            "median_cost_ratio": float(validation.cost_ratio.median())}


# ---- the map ------------------------------------------------------------------------------

def choice_map(heights, moduli):
    """The model auto chooses on the paper's scene over heights x moduli (index into
    plan.FIDELITY)."""
    choice = np.zeros((len(moduli), len(heights)), dtype=int)
    for j, E2 in enumerate(moduli):
        for i, h2 in enumerate(heights):
            scene = paper_scene(h2=h2, E2=E2, model=plan.AUTO)
            chosen, _ = plan.choose_models(scene, Settings())
            choice[j, i] = plan.FIDELITY.index(chosen.coatings[0].model)
    return choice


def draw_map(calibration, path):
    grid = {f"paper h2={h2:g} E2={E2:g}" for h2 in GRID_HEIGHTS for E2 in GRID_MODULI}
    calibration = calibration[calibration.label.isin(grid)].copy()
    patches = [scene.coatings[0] for scene in _scenes(calibration)]
    calibration["h2"] = [p.thickness for p in patches]
    calibration["E2"] = [p.E for p in patches]
    a = estimate.contact_half_width(paper_scene())
    heights = np.geomspace(1 / 128, 1.0, 43)
    moduli = np.geomspace(0.1, 10.0, 31)
    choice = choice_map(heights, moduli)
    scenes = [[paper_scene(h2=h2, E2=E2) for h2 in heights] for E2 in moduli]
    estimated = {model: np.array([[estimate.worst_error(
        estimate.estimated_errors(scene, scene.coatings[0])[model])
        for scene in row] for row in scenes]) for model in ONE_D}
    colours = ListedColormap(["#d6e9fb", "#ddf0dd", "#eeeeee"])
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for axis, model in zip(axes, ONE_D):
        axis.pcolormesh(heights / a, moduli, choice, cmap=colours, vmin=-0.5, vmax=2.5,
                        shading="nearest")
        measured = worst_model_part(calibration, model).clip(lower=1e-5)
        points = axis.scatter(calibration.h2 / a, calibration.E2, c=measured, s=90,
                              norm=LogNorm(1e-4, 1.0), cmap="magma_r", edgecolors="k")
        for h2, E2, value in zip(calibration.h2, calibration.E2, measured):
            axis.annotate(f"{100 * value:.2g}", (h2 / a, E2), textcoords="offset points",
                          xytext=(0, 8), ha="center", fontsize=6)
        axis.contour(heights / a, moduli, estimated[model], levels=[0.01], colors="k",
                     linestyles="--")
        axis.set(xscale="log", yscale="log", xlabel="h2 / a (a: estimated contact half-width)",
                 title=f"{model}: labels in %")
    axes[0].set_ylabel("E2 / E")
    figure.colorbar(points, ax=axes, label="measured |model error|, the larger of the peak contact\nand bond stresses' (against the 2D model)")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in colours.colors]
    handles.append(plt.Line2D([], [], color="k", linestyle="--"))
    figure.legend(handles, [f"auto chooses {m}" for m in plan.FIDELITY]
                  + ["estimated model error 1 %"], loc="lower center", ncol=4, fontsize=8,
                  bbox_to_anchor=(0.45, -0.06))
    figure.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(figure)


# ---- the report ---------------------------------------------------------------------------

MODEL_NAMES = {"shell": "Timoshenko shell", "stretch_shell": "stretch shell",
               "elastic": "2D coating"}


def _reasons(table):
    """Why each row's first patch is not estimated (None: it is)."""
    return [estimate.not_estimated(s, s.coatings[0]) for s in _scenes(table)]


def within_tolerance_up_to(calibration, tolerance):
    """Per grid E2 and 1D model: the largest h2/a of the grid up to which (it and every
    thinner h2) the model's measured error is within ``tolerance``."""
    grid = {f"paper h2={h2:g} E2={E2:g}": (h2, E2) for h2 in GRID_HEIGHTS for E2 in GRID_MODULI}
    rows = calibration[calibration.label.isin(grid)]
    a = estimate.contact_half_width(paper_scene())
    out = []
    for E2 in GRID_MODULI:
        line = {"E2": E2}
        for model in ONE_D:
            found = None
            for h2 in GRID_HEIGHTS:                       # thinnest first
                row = rows[rows.label == f"paper h2={h2:g} E2={E2:g}"]
                if row.empty:
                    break
                if float(worst_model_part(row, model).iloc[0]) > tolerance:
                    break
                found = h2
            line[model] = None if found is None else found / a
        out.append(line)
    return out


def write_report(calibration, held_out, validation, out, command="python -m studies.adequacy"):
    tolerance = Settings().model_tolerance
    report = Report("Where each coating model is adequate, and model = \"auto\"", command,
                    data=["calibration.csv", "held_out.csv", "validation.csv"])
    report.text("Every coating model on the paper's mesh against the mesh-converged 2D model "
                "(studies/model_errors.py; peaks away from the patches' ends). A 1D model's "
                "error is the larger of the peak contact and bond stresses' relative errors, "
                "with the 2D model's own error on the same mesh taken out; the tolerance is "
                f"the default {percent_g(tolerance)}. Map: adequacy.png.")
    if validation is not None and len(validation):
        report.section("The held-out scenes")
        reasons = _reasons(held_out) if held_out is not None else [None] * len(validation)
        chosen = validation.chosen.map(
            lambda models: "/".join(MODEL_NAMES.get(m, m) for m in sorted(set(models.split("/"))))
        ).value_counts()
        not_made = [(label, why) for label, why in zip(validation.label, reasons) if why]
        found = verdict(validation)
        report.finding(
            f"{found['scenes']} scenes neither the forms nor the constants saw: auto took "
            + listing(f"the {models} model in {n}" for models, n in chosen.items())
            + (f"; the estimate is not made in {len(not_made)} (" + "; ".join(
                f"{label}: {why}" for label, why in not_made) + "), where auto takes the 2D "
               "model" if not_made else "") + ".")
        report.finding(
            f"The chosen model is within the {percent_g(tolerance)} tolerance in "
            f"{int(validation.meets_tolerance.sum())} of {len(validation)} scenes (largest "
            f"measured error {percent_g(found['worst_chosen_error'])}). Auto's wall time over "
            f"the chosen model's run directly: median {found['median_cost_ratio']:.2f}, worst "
            f"{found['worst_cost_ratio']:.2f} (one run each on a shared machine: noise).")
        rows, misses = [], []
        for model in ONE_D:
            for quantity in QUANTITIES:
                name = f"{model}_{quantity}"
                judged = validation[f"{name}_within"].dropna()
                rows.append({"model": model, "quantity": quantity, "judged": len(judged),
                             "within": int(judged.sum())})
                for i in judged.index[judged == 0]:
                    misses.append(f"{validation.label[i]} ({MODEL_NAMES[model]}, {quantity} "
                                  f"stress): {percent_g(validation[f'{name}_measured'][i])} "
                                  f"measured, {percent_g(validation[f'{name}_estimated'][i])} "
                                  "estimated")
        report.table(rows, [
            Column("model", "model", MODEL_NAMES.get), Column("quantity", "quantity"),
            Column("judged", "judged", "{:g}", f"scenes where the measured error exceeds "
                   f"{percent_g(JUDGED)} and the estimate is made"),
            Column("within", f"within {FACTOR:g}x", "{:g}",
                   "of those, the estimate within a factor of the measured error")])
        report.finding(f"The estimate is within {FACTOR:g}x of the measured model error in "
                       f"{sum(r['within'] for r in rows)} of {sum(r['judged'] for r in rows)} "
                       f"judged cases" + ("; the misses: " + "; ".join(misses) if misses
                                          else "") + ".")
    if calibration is not None and len(calibration):
        report.section("The calibration grid: where each 1D model is within the tolerance")
        up_to = within_tolerance_up_to(calibration, tolerance)
        report.table(up_to, [Column("E2", "E2", fraction_of_E)] + [
            Column(model, f"{MODEL_NAMES[model]}: h2/a up to",
                   lambda v: "none" if v is None else f"{v:.3g}",
                   "the thickest grid h2 (over a, the estimated half-width) up to which "
                   "every thinner one is within the tolerance" if model == ONE_D[0] else "")
            for model in ONE_D])
        report.finding("Within the tolerance on the paper's scene: " + "; ".join(
            f"the {MODEL_NAMES[model]} up to h2/a = " + ", ".join(
                f"{'none' if r[model] is None else f'{r[model]:.2g}'} ({fraction_of_E(r['E2'])})"
                for r in up_to) for model in ONE_D) + ".")
        reasons = _reasons(calibration)
        kinds = {}
        for i, why in zip(calibration.index, reasons):
            if why:
                kind = ("a coating Poisson ratio outside the calibrated range"
                        if why.startswith("coating Poisson") else
                        "a patch end within the contact" if why.startswith("patch end") else why)
                kinds.setdefault(kind, []).append(i)
        for kind, index in kinds.items():
            part = calibration.loc[index]
            contact = model_part(part, "shell", "contact")
            report.finding(f"Where the estimate is not made ({kind}: {len(index)} calibration "
                           f"scenes), the Timoshenko shell's contact-stress error is "
                           f"{span(contact, lambda v: f'{100 * v:+.2g} %')}.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--only", choices=("calibration", "held_out"),
                        help="measure one set only")
    parser.add_argument("--fit", action="store_true",
                        help="print the estimate's constants fitted on the calibration set")
    args = parser.parse_args(argv)
    OUT_DIR.mkdir(parents=True, exist_ok=True)
    calibration = held_out = None
    if args.only in (None, "calibration") or args.fit:
        calibration = measure_all(calibration_scenes(), OUT_DIR / "calibration.csv", args.jobs)
    if args.fit:
        for name, constants in fit(calibration).items():
            print(f"{name} = " + (f"({', '.join(f'{value:.4g}' for value in constants)})"
                                  if isinstance(constants, tuple) else f"{constants:.4g}"))
        return
    if args.only in (None, "held_out"):
        held_out = measure_all(held_out_scenes(), OUT_DIR / "held_out.csv", args.jobs)
    if args.only is None:
        draw_map(calibration, OUT_DIR / "adequacy.png")
        judge(calibration).to_csv(OUT_DIR / "calibration_judged.csv", index=False)
        validation = validate(held_out)
        validation.to_csv(OUT_DIR / "validation.csv", index=False)
        print(validation[["label", "shell_contact_measured", "shell_contact_estimated",
                          "stretch_shell_contact_measured", "stretch_shell_contact_estimated",
                          "chosen", "chosen_measured", "cost_ratio"]].to_string(index=False))
        print(write_report(calibration, held_out, validation, OUT_DIR / "report.md",
                           command_line("studies.adequacy", argv)))


if __name__ == "__main__":
    main()
