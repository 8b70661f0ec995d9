"""Where each coating model is adequate, and model = "auto" checked (not a test):
``make adequacy``.

Two families of scenes (studies/adequacy_scenes.py), plane strain and axisymmetric,
each with two sets, measured by studies/model_errors.py (every coating model on the
default mesh against the mesh-converged 2D coating model: the peak contact stress, the
bond's peak normal stress and its largest shear):

    calibration   a grid over h2 x E2 on the family's scene (the paper's; a sphere on a
                  coated cylinder), coating Poisson ratios and development scenes: the
                  map of model error over (h2 / a) x (E2 / E) and the data the
                  estimate's constants are fitted on (--fit prints the family's
                  Calibration for orchestrate/model/estimate.py)
    held-out      scenes neither the forms nor the constants saw

For the held-out scenes the automatic choice (``model = "auto"``) is made under each
answer set (model_answers "normal" and "all": the shells' bond shear left out or
judged), and under the default one also run through the Robin loop, timed against the
model it chose run directly.

Writes results/adequacy/{family}_{calibration,held_out}.csv, {family}_calibration_judged.csv,
{family}_validation.csv, {family}.png and the report report.md (per family: what each
model gives to what accuracy, the held-out verdict, where each 1D model is within the
tolerance on the grid, the estimate's misses).

    python -m studies.adequacy                      # both families
    python -m studies.adequacy --family revolution  # one
    python -m studies.adequacy --fit                # the estimate's constants
"""

import argparse
from dataclasses import replace
import functools
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
from orchestrate.run import edge_elements  # noqa: E402
from studies.adequacy_scenes import FAMILIES  # noqa: E402
from studies.model_errors import measure_all, with_model  # noqa: E402
from studies.paths import RESULTS_DIR  # noqa: E402
from orchestrate.model import Settings, scene_from_dict  # noqa: E402
from orchestrate.run import solve_into as solve  # noqa: E402
from studies.report import (Column, Report, command_line, fraction_of_E,  # noqa: E402
                            listing, percent_g, span)

OUT_DIR = RESULTS_DIR / "adequacy"
JUDGED = 0.002         # the estimate is judged where the measured error exceeds this
FACTOR = 2.0           # ... and must lie within this factor of it
SETTLED = 0.25         # a bond-shear error is also judged apart where the reference's own
                       # shear moved by at most this share of it at its last refinement
ELEMENT_BANDS = ((0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 4.0), (4.0, np.inf))
ONE_D = ("shell", "stretch_shell")


# ---- the estimate's constants -------------------------------------------------------------

QUANTITIES = {"contact": "peak", "bond": "bond_peak",      # estimate's name:
              "shear": "bond_shear"}                      # model_errors' column


def model_part(table, model, quantity="contact"):
    """The model's error with the 2D model's own mesh error on the same mesh taken out:
    what the coating model adds (the fit's target)."""
    column = QUANTITIES[quantity]
    return (1 + table[f"{model}_error_{column}"]) / (1 + table[f"elastic_error_{column}"]) - 1


def worst_model_part(table, model, answers="all"):
    """The largest of the model's errors in the ``answers`` (estimate.ANSWERS), as auto
    judges it."""
    return pd.concat([model_part(table, model, q).abs() for q in estimate.ANSWERS[answers]],
                     axis=1).max(axis=1)


def _scenes(table):
    """The scene of every row."""
    return [scene_from_dict(json.loads(text)) for text in table.scene]


def features(table):
    """x, c, q, g, p (estimate.scene_ratios) of every row's first patch, and whether
    its errors are estimated at all."""
    scenes = _scenes(table)
    ratios = np.array([estimate.scene_ratios(s, s.coatings[0]) for s in scenes]).T
    estimated = np.array([estimate.not_estimated(s, s.coatings[0], calibrated=False) is None
                          for s in scenes])
    return ratios, estimated


def _shell_constants(x, c, q, error):
    """The shell's K1..K4 by least squares relative to max(|error|, JUDGED)."""
    weight = 1.0 / np.maximum(np.abs(error), JUDGED)
    columns = np.array([x * c, x * q, x ** 2, x ** 2 * c]).T
    return tuple(float(k) for k in
                 np.linalg.lstsq(columns * weight[:, None], error * weight, rcond=None)[0])


def _saturating_constants(ratio, x, share, error):
    """S, s, t, r, u of the share S ratio^s x^t exp((r + u ln x) (share - 1/2)) whose
    share / (1 + share) is |error|: least squares on log share over the rows above
    JUDGED (the share of an error below 1)."""
    judged = (np.abs(error) > JUDGED) & (np.abs(error) < 1.0)
    target = np.abs(error[judged]) / (1.0 - np.abs(error[judged]))
    stiffening = share[judged] - 0.5
    columns = np.array([np.ones(judged.sum()), np.log(ratio[judged]), np.log(x[judged]),
                        stiffening, stiffening * np.log(x[judged])]).T
    log_S, s, t, r, u = np.linalg.lstsq(columns, np.log(target), rcond=None)[0]
    return float(np.exp(log_S)), float(s), float(t), float(r), float(u)


def fit(table):
    """The estimate's Calibration from the calibration rows it covers
    (estimate.not_estimated): the shell's K1..K4 for the contact and bond stresses
    (_shell_constants); the stretch shell's contact S, s by least squares on log error
    over the rows above JUDGED (the model too stiff: soft coatings), its plateau P as
    the median |error| of the rows below -JUDGED (too soft: stiff thick coatings) and
    T = P / x^2 at the smallest x among them; its bond B as the geometric mean of
    |error| / x^2 over the rows above JUDGED; both shells' bond shear
    (_saturating_constants, in p for the shell, g for the stretch shell, both in the
    indenter's share); and the spans of the indenter's share, h2/a and g the rows cover."""
    (x, c, q, g, p), estimated = features(table)
    table, x, c, q, g, p = (table[estimated], x[estimated], c[estimated], q[estimated],
                            g[estimated], p[estimated])

    def error(model, quantity):
        return model_part(table, model, quantity).to_numpy()

    stretch = error("stretch_shell", "contact")
    soft_coating, stiff_coating = stretch > JUDGED, stretch < -JUDGED
    log_fit = np.linalg.lstsq(np.array([np.ones(soft_coating.sum()), np.log(g[soft_coating])]).T,
                              np.log(stretch[soft_coating] / x[soft_coating] ** 2), rcond=None)[0]
    plateau = float(np.median(-stretch[stiff_coating]))
    bond = np.abs(error("stretch_shell", "bond"))
    judged = bond > JUDGED
    shares = np.array([estimate.indenter_share(scene) for scene in _scenes(table)])
    # the stretch shell's bond shear where its mesh sets it is not estimated: left out
    formed = ~np.array([estimate.stretch_shear_mesh_bound(
        _auto_patch(text)["stretch_shell_elements_thick"]) for text in table.scene])
    stretch_shear = np.where(formed, error("stretch_shell", "shear"), 0.0)  # 0: not judged
    return estimate.Calibration(
        shell_contact=_shell_constants(x, c, q, error("shell", "contact")),
        shell_bond=_shell_constants(x, c, q, error("shell", "bond")),
        shell_shear=_saturating_constants(p, x, shares, error("shell", "shear")),
        stretch_soft_coating=(float(np.exp(log_fit[0])), float(log_fit[1])),
        stretch_stiff_coating=(plateau / float(x[stiff_coating].min()) ** 2, plateau),
        stretch_bond=float(np.exp(np.mean(np.log(bond[judged] / x[judged] ** 2)))),
        stretch_shear=_saturating_constants(g, x, shares, stretch_shear),
        indenter_share=(float(min(shares)), float(max(shares))),
        thickest=float(x.max()),
        coating_compliance=(float(g.min()), float(g.max())))


def rounded(calibration, digits=4):
    """The Calibration with every constant to ``digits`` significant digits, as
    estimate.py keeps it."""
    def round_(value):
        return float(f"{value:.{digits}g}")
    return estimate.Calibration(**{
        name: (tuple(round_(v) for v in value) if isinstance(value, tuple) else round_(value))
        for name, value in vars(calibration).items()})


# ---- the validation ----------------------------------------------------------------------

def estimates(table, model, quantity):
    """The estimate of every row's first patch as auto makes it, on the mesh a run
    makes (NaN: not estimated)."""
    values = []
    for text in table.scene:
        errors = _auto_patch(text)["estimated_errors"][model]
        values.append(np.nan if errors is None or errors[quantity] is None
                      else errors[quantity])
    return pd.Series(values, index=table.index)


@functools.lru_cache(maxsize=None)
def _auto_patch(scene_text):
    """The model choice's report of the first patch of a scene (its JSON), as auto makes
    it (plan.model_choice: the stretch shell's bond shear judged on its mesh)."""
    scene = with_model(scene_from_dict(json.loads(scene_text)), plan.AUTO)
    return plan.model_choice(scene, Settings())["patches"][0]


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
            if quantity == "shear":      # the least converged answer of the reference
                settled = table.reference_bond_shear_change.abs() <= SETTLED * measured
                out[f"{name}_settled"] = settled
    return out


def timed_choice(auto_scene, settings):
    """Solve a scene of "auto" patches and the model it solved them with (Robin loop):
    (the models solved, those auto chose before any work, seconds auto, seconds direct).
    They differ where the run solved a shell patch again as the 2D coating (its pressure
    gathered at the contact's edges: orchestrate/run/solve.py)."""
    with tempfile.TemporaryDirectory() as auto_out, tempfile.TemporaryDirectory() as direct_out:
        start = time.perf_counter()
        summary = solve(auto_scene, settings, auto_out + "/run")
        seconds_auto = time.perf_counter() - start
        chosen = scene_from_dict(summary["scene"])
        start = time.perf_counter()
        solve(chosen, settings, direct_out + "/run")
        seconds_direct = time.perf_counter() - start
    patches = summary["model_choice"]["patches"]
    return ([p["model"] for p in patches], [p.get("fallback_from", p["model"]) for p in patches],
            seconds_auto, seconds_direct)


def chosen_error(row, models, answers):
    """The measured error of the chosen ``models`` in the ``answers``: the largest over
    the models chosen (the 2D coating's: 0, the reference's model)."""
    return max(0.0 if model == "elastic" else float(worst_model_part(row, model, answers).iloc[0])
               for model in set(models))


def validate(held_out, settings=Settings()):
    """The held-out table with auto's choice under each answer set (estimate.ANSWERS):
    the models chosen, their estimate and measured error in those answers
    ({answers}_chosen, _chosen_estimate, _chosen_measured, _meets_tolerance); under the
    settings' own answers also solved through the Robin loop and timed against the
    chosen model run directly (seconds_auto, seconds_direct, cost_ratio), the models the
    run solved with (solved: a shell solved again as the 2D coating where its pressure
    gathered at the contact's edges) and their measured error (solved_measured, which
    _meets_tolerance judges under those answers)."""
    table = judge(held_out)
    for i, row in held_out.iterrows():
        scene = with_model(scene_from_dict(json.loads(row.scene)), plan.AUTO)
        said = []
        for answers in estimate.ANSWERS:
            report = plan.model_choice(scene, replace(settings, model_answers=answers))
            models = [p["model"] for p in report["patches"]]
            measured = chosen_error(held_out.loc[[i]], models, answers)
            table.loc[i, f"{answers}_chosen"] = "/".join(models)
            table.loc[i, f"{answers}_chosen_estimate"] = max(p["estimated_error"]
                                                             for p in report["patches"])
            table.loc[i, f"{answers}_chosen_measured"] = measured
            said.append(f"on the {answers} answers {'/'.join(models)}, measured "
                        f"{100 * measured:.2f} %")
        solved, chosen, seconds_auto, seconds_direct = timed_choice(scene, settings)
        assert "/".join(chosen) == table.loc[i, f"{settings.model_answers}_chosen"]
        table.loc[i, "solved"] = "/".join(solved)
        table.loc[i, "solved_measured"] = chosen_error(held_out.loc[[i]], solved,
                                                       settings.model_answers)
        table.loc[i, "seconds_auto"] = seconds_auto
        table.loc[i, "seconds_direct"] = seconds_direct
        print(f"{row.label}: auto chose " + "; ".join(said) + f"; {seconds_auto:.2f} s "
              f"against {seconds_direct:.2f} s", flush=True)
    for answers in estimate.ANSWERS:
        measured = table["solved_measured" if answers == settings.model_answers
                         else f"{answers}_chosen_measured"]
        table[f"{answers}_meets_tolerance"] = measured <= settings.model_tolerance
    table["cost_ratio"] = table.seconds_auto / table.seconds_direct
    return table


def _within_columns(table):
    return [f"{model}_{quantity}_within" for model in ONE_D for quantity in QUANTITIES]


def verdict(validation):
    """The held-out verdict (report.md's findings), from the validation."""
    within = pd.concat([validation[column] for column in _within_columns(validation)]).dropna()
    not_estimated = validation.shell_contact_estimated.isna()
    found = {"scenes": len(validation),
             "estimates_judged": len(within), "estimates_within_2x": float(within.mean()),
             "scenes_not_estimated": int(not_estimated.sum()),
             "worst_cost_ratio": float(validation.cost_ratio.max()),
             "median_cost_ratio": float(validation.cost_ratio.median())}
    solved_with = Settings().model_answers          # the answers the runs were judged on
    for answers in estimate.ANSWERS:
        measured = validation["solved_measured" if answers == solved_with
                              else f"{answers}_chosen_measured"]
        found[f"{answers}_meets_tolerance"] = float(validation[f"{answers}_meets_tolerance"].mean())
        found[f"{answers}_worst_chosen_error"] = float(measured.max())
    found["solved_again"] = int((validation.solved
                                 != validation[f"{solved_with}_chosen"]).sum())
    return found


# ---- the map ------------------------------------------------------------------------------

def choice_map(family, heights, moduli):
    """The model auto chooses on the family's grid scene over heights x moduli (index
    into plan.FIDELITY)."""
    choice = np.zeros((len(moduli), len(heights)), dtype=int)
    for j, E2 in enumerate(moduli):
        for i, h2 in enumerate(heights):
            scene = with_model(family.grid_scene(h2, E2), plan.AUTO)
            chosen = plan.model_choice(scene, Settings())["patches"][0]["model"]
            choice[j, i] = plan.FIDELITY.index(chosen)
    return choice


def draw_map(family, calibration, path):
    grid = {family.grid_label(h2, E2) for h2 in family.heights for E2 in family.moduli}
    calibration = calibration[calibration.label.isin(grid)].copy()
    patches = [scene.coatings[0] for scene in _scenes(calibration)]
    calibration["h2"] = [p.thickness for p in patches]
    calibration["E2"] = [p.E for p in patches]
    a = estimate.contact_half_width(family.grid_scene(family.heights[0], 1.0))
    heights = np.geomspace(1 / 128, 1.0, 43)
    moduli = np.geomspace(0.1, 10.0, 31)
    choice = choice_map(family, heights, moduli)
    scenes = [[family.grid_scene(h2, E2) for h2 in heights] for E2 in moduli]
    answers = Settings().model_answers                  # what auto judges by default
    estimated = {model: np.array([[estimate.worst_error(
        estimate.estimated_errors(scene, scene.coatings[0])[model], answers)
        for scene in row] for row in scenes]) for model in ONE_D}
    colours = ListedColormap(["#d6e9fb", "#ddf0dd", "#eeeeee"])
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for axis, model in zip(axes, ONE_D):
        axis.pcolormesh(heights / a, moduli, choice, cmap=colours, vmin=-0.5, vmax=2.5,
                        shading="nearest")
        measured = worst_model_part(calibration, model, answers).clip(lower=1e-5)
        points = axis.scatter(calibration.h2 / a, calibration.E2, c=measured, s=90,
                              norm=LogNorm(1e-4, 1.0), cmap="magma_r", edgecolors="k")
        for h2, E2, value in zip(calibration.h2, calibration.E2, measured):
            axis.annotate(f"{100 * value:.2g}", (h2 / a, E2), textcoords="offset points",
                          xytext=(0, 8), ha="center", fontsize=6)
        axis.contour(heights / a, moduli, estimated[model], levels=[0.01], colors="k",
                     linestyles="--")
        axis.set(xscale="log", yscale="log", xlabel="h2 / a (a: estimated contact half-width)",
                 title=f"{family.name}, {model}: labels in %")
    axes[0].set_ylabel("E2 / E")
    figure.colorbar(points, ax=axes, label="measured |model error| in the default answers\n(against the 2D model)")
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


def within_tolerance_up_to(family, calibration, tolerance):
    """Per grid E2 and 1D model: the largest h2/a of the grid up to which (it and every
    thinner h2) the model's measured error is within ``tolerance``."""
    a = estimate.contact_half_width(family.grid_scene(family.heights[0], 1.0))
    out = []
    for E2 in family.moduli:
        line = {"E2": E2}
        for model in ONE_D:
            found = None
            for h2 in family.heights:                     # thinnest first
                row = calibration[calibration.label == family.grid_label(h2, E2)]
                if row.empty:
                    break
                if float(worst_model_part(row, model, Settings().model_answers).iloc[0]) > tolerance:
                    break
                found = h2
            line[model] = None if found is None else found / a
        out.append(line)
    return out


def write_report(parts, out, command="python -m studies.adequacy"):
    """The report of every family measured: parts, [(family, calibration, held_out,
    validation)]."""
    tolerance = Settings().model_tolerance
    report = Report("Where each coating model is adequate, and model = \"auto\"", command,
                    data=[f"{family.name}_{part}.csv" for family, *_ in parts
                          for part in ("calibration", "held_out", "validation")])
    report.text("Every coating model on the default mesh (level 1) against the mesh-converged "
                "2D model (studies/model_errors.py; peaks away from the patches' ends): the "
                "peak contact stress, the bond's peak normal stress under the contact and its "
                "largest shear. A 1D model's error in each is the relative error with the 2D "
                "model's own error on the same mesh taken out; auto judges the largest "
                f"against the default tolerance {percent_g(tolerance)}. Maps: "
                + ", ".join(f"{family.name}.png" for family, *_ in parts) + ".")
    for family, calibration, held_out, validation in parts:
        _family_sections(report, family, calibration, held_out, validation, tolerance)
    return report.write(out)


THICKNESS_BANDS = ((0.0, 0.1), (0.1, 0.3), (0.3, 1.0))   # h2 / a: thin, middle, thick


def answer_accuracy(table):
    """Per 1D model, answer and band of h2/a (THICKNESS_BANDS): the median and the
    largest measured |error| over the rows the estimate covers (what each model gives
    to what accuracy)."""
    (x, *_), estimated = features(table)
    rows = []
    for model in ONE_D:
        for quantity in QUANTITIES:
            error = model_part(table, model, quantity).abs().to_numpy()
            row = {"model": model, "answer": estimate.ANSWER_NAMES[quantity]}
            for low, high in THICKNESS_BANDS:      # NaN: no bond under the contact
                band = estimated & (x > low) & (x <= high) & ~np.isnan(error)
                row[f"median {low:g}"] = float(np.median(error[band])) if band.any() else None
                row[f"largest {low:g}"] = float(error[band].max()) if band.any() else None
                row[f"scenes {low:g}"] = int(band.sum())
            rows.append(row)
    return rows


def _accuracy_section(report, family, table):
    rows = answer_accuracy(table)
    report.section(f"What each model gives, {family.title}")
    report.text("Every scene of the family the estimate covers (calibration and held out), "
                "each 1D model's measured error against the 2D coating on the same mesh, by "
                "the coating's thickness over the estimated contact half-width a.")
    columns = [Column("model", "model", MODEL_NAMES.get), Column("answer", "answer")]
    for low, high in THICKNESS_BANDS:
        columns += [Column(f"median {low:g}", f"h2/a in ({low:g}, {high:g}]: median",
                           percent_g, "median |error| over the scenes of the band"),
                    Column(f"largest {low:g}", "largest", percent_g),
                    Column(f"scenes {low:g}", "scenes", "{:g}")]
    report.table(rows, columns)


def calibrated_range(calibration):
    """The span of each of the estimate's ratios (estimate.scene_ratios) over the
    calibration rows the estimate covers: where it is calibrated."""
    ratios, estimated = features(calibration)
    shares = np.array([estimate.indenter_share(scene) for scene in _scenes(calibration)])
    return {name: (float(values[estimated].min()), float(values[estimated].max()))
            for name, values in zip("xcqgps", (*ratios, shares))}


def elements_thick(table):
    """Per row: its first patch's thickness over the interface element at the predicted
    contact's edge on the 2D coating's default mesh (validity.edge_elements; NaN where
    no patch lies under an edge, away from its ends)."""
    values = []
    for scene in _scenes(table):
        problem = plan.prepare(with_model(scene, "elastic"), Settings()).problem
        found = edge_elements(problem, estimate.predicted_half_width(problem.scene))
        first = [element for n, _, element in found if n == 1]
        values.append(problem.scene.coatings[0].thickness / first[0] if first else np.nan)
    return np.array(values)


def bond_shear_and_mesh(table):
    """By bands of elements_thick (ELEMENT_BANDS): the scenes, the 2D coating's bond shear
    moved at its reference's last refinement (the default mesh against one of half its
    elements: median and largest), and each 1D model's measured bond-shear error (median)."""
    thick = elements_thick(table)
    moved = table.reference_bond_shear_change.abs().to_numpy()
    rows = []
    for low, high in ELEMENT_BANDS:
        band = (thick > low) & (thick <= high) & ~np.isnan(moved)
        row = {"band": f"{low:g}-{high:g}" if np.isfinite(high) else f"over {low:g}",
               "scenes": int(band.sum())}
        if band.any():
            row.update(moved_median=float(np.median(moved[band])),
                       moved_largest=float(moved[band].max()))
            for model in ONE_D:
                error = model_part(table, model, "shear").abs().to_numpy()[band]
                row[f"{model}_median"] = float(np.nanmedian(error))
        rows.append(row)
    return rows


def _bond_shear_mesh_section(report, family, table):
    rows = bond_shear_and_mesh(table)
    report.section(f"The bond shear and the mesh, {family.title}")
    report.text("Every scene of the family (calibration and held out) by its coating's "
                "thickness in interface elements at the predicted contact's edge on the 2D "
                "coating's default mesh (what the warning coarse_bond measures): how far the "
                "2D coating's largest bond shear moved when the reference halved the "
                "elements, and each 1D model's bond-shear error against that reference.")
    report.table(rows, [
        Column("band", "h2 / element"), Column("scenes", "scenes", "{:g}"),
        Column("moved_median", "2D moved: median", percent_g,
               "|change| of the 2D coating's largest bond shear, default mesh to half its "
               "elements"),
        Column("moved_largest", "largest", percent_g)] + [
        Column(f"{model}_median", f"{MODEL_NAMES[model]}: median", percent_g,
               "median measured bond-shear error against the reference" if model == ONE_D[0]
               else "") for model in ONE_D])


def _family_sections(report, family, calibration, held_out, validation, tolerance):
    if calibration is not None:
        spans = calibrated_range(calibration)
        report.section(f"Where the estimate is calibrated, {family.title}")
        report.finding(
            f"The constants (estimate.{family.name.upper()}) are fitted on "
            f"{len(calibration)} scenes, spanning h2/a = "
            f"{spans['x'][0]:.3g}-{spans['x'][1]:.3g}, E*/M2 (c) = "
            f"{spans['c'][0]:.3g}-{spans['c'][1]:.3g}, E*/G2 (g) = "
            f"{spans['g'][0]:.3g}-{spans['g'][1]:.3g} and the Poisson share p = "
            f"{spans['p'][0]:.3g}-{spans['p'][1]:.3g} (estimate.py's ratios; the "
            "coating's Poisson ratio within the estimate's 0.1-0.4), with the indenter's "
            f"stiffness against the base's (estimate.indenter_share) "
            f"{spans['s'][0]:.3g}-{spans['s'][1]:.3g}. Outside the spans of h2/a, of g and "
            "of the indenter's stiffness the estimate is not made (auto takes the 2D "
            "coating); c and p follow g within the calibrated Poisson ratios, and outside "
            "the span of q it is an extrapolation.")
    if calibration is not None and held_out is not None:
        both = pd.concat([calibration, held_out], ignore_index=True)
        _accuracy_section(report, family, both)
        _bond_shear_mesh_section(report, family, both)
    if validation is not None and len(validation):
        report.section(f"The held-out scenes, {family.title}")
        reasons = _reasons(held_out) if held_out is not None else [None] * len(validation)
        not_made = [(label, why) for label, why in zip(validation.label, reasons) if why]
        found = verdict(validation)
        report.finding(
            f"{found['scenes']} scenes neither the forms nor the constants saw"
            + (f"; the estimate is not made in {len(not_made)} (" + "; ".join(
                f"{label}: {why}" for label, why in not_made) + "), where auto takes the 2D "
               "model" if not_made else "") + ".")
        for answers, names in estimate.ANSWERS.items():
            chosen = validation[f"{answers}_chosen"].map(
                lambda models: "/".join(MODEL_NAMES.get(m, m)
                                        for m in sorted(set(models.split("/"))))
            ).value_counts()
            report.finding(
                f"With model_answers = \"{answers}\" (the tolerance on the "
                + listing(estimate.ANSWER_NAMES[name] for name in names) + ") auto takes "
                + listing(f"the {models} model in {n}" for models, n in chosen.items())
                + f"; the chosen model is within the {percent_g(tolerance)} tolerance in "
                f"{int(validation[f'{answers}_meets_tolerance'].sum())} of {len(validation)} "
                f"scenes (largest measured error "
                f"{percent_g(found[f'{answers}_worst_chosen_error'])}).")
        report.finding(
            f"Runs that solved a shell patch again as the 2D coating, its pressure gathered "
            f"at the contact's edges (default answers): {found['solved_again']} of "
            f"{len(validation)}; the tolerance above is judged on the model each run solved "
            "with.")
        report.finding(
            f"Auto's wall time over the chosen model's run directly (default answers): median "
            f"{found['median_cost_ratio']:.2f}, worst {found['worst_cost_ratio']:.2f} (one run "
            "each on a shared machine: noise).")
        rows, misses = [], []
        for model in ONE_D:
            for quantity in QUANTITIES:
                name = f"{model}_{quantity}"
                judged = validation[f"{name}_within"].dropna()
                settled = (judged[validation[f"{name}_settled"][judged.index].astype(bool)]
                           if quantity == "shear" else judged)
                rows.append({"model": model, "quantity": quantity, "judged": len(judged),
                             "within": int(judged.sum()), "settled": len(settled),
                             "settled_within": int(settled.sum())})
                for i in judged.index[judged == 0]:
                    # the bond shear's reference is the least converged answer: how far
                    # it moved at its last refinement bounds what a miss can say
                    moved = (f" (the reference moved "
                             f"{percent_g(abs(held_out.reference_bond_shear_change[i]))} at "
                             "its last refinement)"
                             if quantity == "shear" and held_out is not None else "")
                    misses.append(f"{validation.label[i]} ({MODEL_NAMES[model]}, {quantity} "
                                  f"stress): {percent_g(validation[f'{name}_measured'][i])} "
                                  f"measured, {percent_g(validation[f'{name}_estimated'][i])} "
                                  f"estimated{moved}")
        report.table(rows, [
            Column("model", "model", MODEL_NAMES.get), Column("quantity", "quantity"),
            Column("judged", "judged", "{:g}", f"scenes where the measured error exceeds "
                   f"{percent_g(JUDGED)} and the estimate is made"),
            Column("within", f"within {FACTOR:g}x", "{:g}",
                   "of those, the estimate within a factor of the measured error"),
            Column("settled", "reference settled", "{:g}",
                   f"of the judged, those whose reference moved by at most {SETTLED:g} of "
                   "the measured error at its last refinement (the bond shear's: the other "
                   "answers' references settle far below the errors judged)"),
            Column("settled_within", f"within {FACTOR:g}x", "{:g}")])
        report.finding(f"The estimate is within {FACTOR:g}x of the measured model error in "
                       f"{sum(r['within'] for r in rows)} of {sum(r['judged'] for r in rows)} "
                       f"judged cases, {sum(r['settled_within'] for r in rows)} of "
                       f"{sum(r['settled'] for r in rows)} where the reference settled"
                       + ("; the misses: " + "; ".join(misses) if misses else "") + ".")
    if calibration is not None and len(calibration):
        report.section(f"The calibration grid, {family.title}: where each 1D model is "
                       "within the tolerance in the default answers")
        up_to = within_tolerance_up_to(family, calibration, tolerance)
        report.table(up_to, [Column("E2", "E2", fraction_of_E)] + [
            Column(model, f"{MODEL_NAMES[model]}: h2/a up to",
                   lambda v: "none" if v is None else f"{v:.3g}",
                   "the thickest grid h2 (over a, the estimated half-width) up to which "
                   "every thinner one is within the tolerance" if model == ONE_D[0] else "")
            for model in ONE_D])
        report.finding("Within the tolerance on the grid's scene: " + "; ".join(
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


def measure_family(family, jobs, only=None):
    """The family's calibration and held-out tables (None: not asked for), measured
    where not yet in results/adequacy/."""
    tables = {}
    for part, scenes in (("calibration", family.calibration), ("held_out", family.held_out)):
        if only in (None, part):
            tables[part] = measure_all(scenes(), OUT_DIR / f"{family.name}_{part}.csv", jobs)
    return tables.get("calibration"), tables.get("held_out")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--family", choices=tuple(FAMILIES), action="append",
                        help="measure this family only (repeatable; default: every one)")
    parser.add_argument("--only", choices=("calibration", "held_out"),
                        help="measure one set only")
    parser.add_argument("--fit", action="store_true",
                        help="print the estimate's constants fitted on the calibration set")
    args = parser.parse_args(argv)
    OUT_DIR.mkdir(parents=True, exist_ok=True)
    parts = []
    for family in (FAMILIES[name] for name in args.family or FAMILIES):
        if args.fit:
            calibration, _ = measure_family(family, args.jobs, "calibration")
            print(f"{family.name.upper()} = {rounded(fit(calibration))!r}")
            continue
        calibration, held_out = measure_family(family, args.jobs, args.only)
        if args.only is not None:
            continue
        draw_map(family, calibration, OUT_DIR / f"{family.name}.png")
        judge(calibration).to_csv(OUT_DIR / f"{family.name}_calibration_judged.csv", index=False)
        validation = validate(held_out)
        validation.to_csv(OUT_DIR / f"{family.name}_validation.csv", index=False)
        parts.append((family, calibration, held_out, validation))
    if parts:
        print(write_report(parts, OUT_DIR / "report.md", command_line("studies.adequacy", argv)))


if __name__ == "__main__":
    main()
