"""Where each coating model is adequate (not a test): ``make adequacy``.

Two sets of scenes, each measured by orchestrate/model_errors.py (every coating model on
the paper's mesh against the mesh-converged 2D coating model):

    calibration   the paper's scene over h2 x E2 (and a few coating Poisson ratios):
                  the map of model error over (h2 / a) x (E2 / E), and the data
                  model_choice.py's estimate was fitted on (--fit prints its constants)
    held-out      39 scenes the estimate never saw: other heights, moduli and Poisson
                  ratios, loads, radii, moduli of the bodies, cylinders under a force,
                  patches, a coated roller (a curved coating)

For the held-out scenes the automatic choice (``model = "auto"``) is also run through the
Robin loop, timed against the model it chose run directly.

Writes results/adequacy/{calibration,held_out}.csv, validation.csv and adequacy.png.

    python -m orchestrate.adequacy            # both sets, the map and the validation
    python -m orchestrate.adequacy --fit      # the estimate's constants from calibration
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

from . import model_choice  # noqa: E402
from .model_errors import measure_all, with_model  # noqa: E402
from .paths import RESULTS_DIR  # noqa: E402
from .scene import Settings, scene_from_dict  # noqa: E402
from .scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene  # noqa: E402
from .solve import solve  # noqa: E402

OUT_DIR = RESULTS_DIR / "adequacy"
GRID_HEIGHTS = (1 / 32, 1 / 16, 1 / 8, 1 / 4, 1 / 2, 1.0)
GRID_MODULI = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0)
GRID_POISSON = (0.1, 0.4)
JUDGED = 0.002         # the estimate is judged where the measured error exceeds this
FACTOR = 2.0           # ... and must lie within this factor of it
ONE_D = ("shell", "stretch_shell")


def calibration_scenes():
    """The grid, and a smaller one over the coating's Poisson ratio (which the
    swelling term of the estimate needs to be told apart)."""
    grid = [(f"paper h2={h2:g} E2={E2:g}", paper_scene(h2=h2, E2=E2))
            for h2 in GRID_HEIGHTS for E2 in GRID_MODULI]
    poisson = [(f"paper h2={h2:g} E2={E2:g} nu2={nu2:g}", paper_scene(h2=h2, E2=E2, nu2=nu2))
               for nu2 in GRID_POISSON for h2 in (1 / 16, 1 / 4) for E2 in (0.2, 1.0, 5.0)]
    return grid + poisson


def _from_file(name, **overrides):
    scene, _ = load_scene(SCENES_DIR / f"{name}.toml")
    return apply_overrides(scene, overrides)


def held_out_scenes():
    """(label, scene): none of them in the calibration grid."""
    scenes = []
    paper = [(3 / 16, 0.3), (3 / 8, 3.0), (3 / 4, 0.5), (0.09, 2.0), (1 / 64, 0.2),
             (1 / 64, 1.0), (1 / 128, 0.1), (0.3, 0.15), (0.05, 7.0),
             # where auto takes a 1D model: thinner than b/32, or thick and stiff
             (1 / 48, 0.7), (1 / 96, 3.0), (1 / 64, 0.05), (0.8, 3.0), (0.9, 8.0)]
    scenes += [(f"paper h2={h2:g} E2={E2:g}", paper_scene(h2=h2, E2=E2)) for h2, E2 in paper]
    shallow = [(1 / 16, 0.2), (1 / 8, 1.0), (1 / 4, 5.0), (1 / 32, 0.5)]
    scenes += [(f"paper stamp/4 h2={h2:g} E2={E2:g}",
                paper_scene(h2=h2, E2=E2, stamp=2.778999e-3 / 4)) for h2, E2 in shallow]
    scenes += [("paper h2=0.125 E2=0.5 nu2=0.2", paper_scene(h2=0.125, E2=0.5, nu2=0.2)),
               ("paper h2=0.25 E2=1 nu2=0.45", paper_scene(h2=0.25, E2=1.0, nu2=0.45)),
               ("paper h2=0.125 E2=1 E3=0.5", paper_scene(h2=0.125, E2=1.0, E3=0.5)),
               ("paper h2=0.0625 E2=0.3 E1=3", paper_scene(h2=0.0625, E2=0.3, E1=3.0)),
               ("paper l2=1.5 h2=0.2 E2=0.4", paper_scene(h2=0.2, E2=0.4, coating_length=1.5,
                                                          stamp=2.0e-3))]
    cylinder = [(10.0, 0.125, 5.0, 0.02), (50.0, 0.0625, 0.3, 0.02), (100.0, 0.25, 1.0, 0.02),
                (20.0, 1 / 32, 0.2, 0.02), (20.0, 0.125, 2.0, 0.005), (30.0, 1 / 64, 0.5, 0.01)]
    scenes += [(f"cylinder R={R:g} h2={h2:g} E2={E2:g} F={F:g}",
                _from_file("cylinder", h2=h2, E2=E2, force=F, **{"indenter.radius": R}))
               for R, h2, E2, F in cylinder]
    discrete = [(0.125, 5.0), (0.0625, 0.3), (0.125, 1.0), (1 / 32, 0.2)]
    scenes += [(f"discrete h2={h2:g} E2={E2:g}", _from_file("discrete", h2=h2, E2=E2))
               for h2, E2 in discrete]
    roller = [(0.125, 5.0, 0.02), (0.0625, 0.3, 0.02), (0.25, 1.0, 0.02), (1 / 32, 0.2, 0.02),
              (0.125, 2.0, 0.005), (1 / 64, 1.5, 0.02)]
    scenes += [(f"roller h2={h2:g} E2={E2:g} F={F:g}", _from_file("roller", h2=h2, E2=E2, force=F))
               for h2, E2, F in roller]
    return scenes


# ---- the estimate's constants -------------------------------------------------------------

def model_part(table, model):
    """The model's error with the 2D model's own mesh error on the same mesh taken out:
    what the coating model adds (the fit's target)."""
    return (1 + table[f"{model}_error_peak"]) / (1 + table.elastic_error_peak) - 1


def _scenes(table):
    """The scene of every row."""
    return [scene_from_dict(json.loads(text)) for text in table.scene]


def features(table):
    """x, c, q (model_choice.scene_ratios) of every row's first patch."""
    return np.array([model_choice.scene_ratios(scene, scene.coatings[0])
                     for scene in _scenes(table)]).T


def fit(table):
    """The constants of model_choice's estimate from the calibration table:
    the shell's four by least squares relative to max(|error|, JUDGED); the stretch
    shell's S, s by least squares on log error over the rows above JUDGED (the model too
    stiff: soft coatings), its plateau P as the median |error| of the rows below -JUDGED
    (too soft: stiff thick coatings) and T = P / x^2 at the smallest x among them."""
    x, c, q = features(table)
    shell = model_part(table, "shell").to_numpy()
    weight = 1.0 / np.maximum(np.abs(shell), JUDGED)
    columns = np.array([x * c, x * q, x ** 2, x ** 2 * c]).T
    shell_constants = np.linalg.lstsq(columns * weight[:, None], shell * weight, rcond=None)[0]
    stretch = model_part(table, "stretch_shell").to_numpy()
    soft_coating, stiff_coating = stretch > JUDGED, stretch < -JUDGED
    log_fit = np.linalg.lstsq(np.array([np.ones(soft_coating.sum()), np.log(c[soft_coating])]).T,
                              np.log(stretch[soft_coating] / x[soft_coating] ** 2), rcond=None)[0]
    plateau = float(np.median(-stretch[stiff_coating]))
    return {"SHELL": tuple(float(k) for k in shell_constants),
            "STRETCH_SOFT_COATING": (float(np.exp(log_fit[0])), float(log_fit[1])),
            "STRETCH_STIFF_COATING": (plateau / float(x[stiff_coating].min()) ** 2, plateau)}


# ---- the validation ----------------------------------------------------------------------

def estimates(table):
    return pd.DataFrame([model_choice.estimated_errors(scene, scene.coatings[0])
                         for scene in _scenes(table)], index=table.index)


def judge(table):
    """Per row and 1D model: the estimate against the measured model error (against the
    2D model on the same mesh: model_part), and whether it is within FACTOR where that
    error exceeds JUDGED. mesh_error: the 2D model's own error there (against the
    converged mesh), which every model shares."""
    estimated = estimates(table)
    out = table[["label"]].copy()
    out["mesh_error"] = table.elastic_error_peak
    for model in ONE_D:
        measured = model_part(table, model).abs()
        out[f"{model}_measured"] = measured
        out[f"{model}_estimated"] = estimated[model]
        ratio = estimated[model] / measured
        out[f"{model}_ratio"] = ratio
        out[f"{model}_within"] = np.where(measured > JUDGED,
                                          (ratio >= 1 / FACTOR) & (ratio <= FACTOR), np.nan)
    return out


def timed_choice(scene, settings):
    """Solve with "auto" and with the model it chose (Robin loop, default settings):
    (chosen models, the estimate, seconds auto, seconds direct)."""
    auto_scene = with_model(scene, model_choice.AUTO)
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
    """The held-out table with the choice, its measured error and the timings."""
    table = judge(held_out)
    for i, row in held_out.iterrows():
        scene = scene_from_dict(json.loads(row.scene))
        models, estimate, seconds_auto, seconds_direct = timed_choice(scene, settings)
        model = models[0]
        table.loc[i, "chosen"] = "/".join(models)
        table.loc[i, "chosen_estimate"] = estimate
        table.loc[i, "chosen_measured"] = (0.0 if model == "elastic" else
                                           abs(model_part(held_out.loc[[i]], model).iloc[0]))
        table.loc[i, "seconds_auto"] = seconds_auto
        table.loc[i, "seconds_direct"] = seconds_direct
        print(f"{row.label}: auto chose {model}, measured {100 * table.loc[i, 'chosen_measured']:.2f}"
              f" % (estimate {100 * estimate:.2f} %), {seconds_auto:.2f} s against "
              f"{seconds_direct:.2f} s", flush=True)
    table["meets_tolerance"] = table.chosen_measured <= settings.model_tolerance
    table["cost_ratio"] = table.seconds_auto / table.seconds_direct
    return table


def verdict(validation):
    """The targets of the README's table, from the validation."""
    within = pd.concat([validation[f"{m}_within"] for m in ONE_D]).dropna()
    return {"scenes": len(validation),
            "meets_tolerance": float(validation.meets_tolerance.mean()),
            "estimates_judged": len(within), "estimates_within_2x": float(within.mean()),
            "worst_cost_ratio": float(validation.cost_ratio.max()),
            "median_cost_ratio": float(validation.cost_ratio.median())}


# ---- the map ------------------------------------------------------------------------------

def choice_map(heights, moduli):
    """The model auto chooses on the paper's scene over heights x moduli (index into
    model_choice.FIDELITY)."""
    choice = np.zeros((len(moduli), len(heights)), dtype=int)
    for j, E2 in enumerate(moduli):
        for i, h2 in enumerate(heights):
            scene = paper_scene(h2=h2, E2=E2, model=model_choice.AUTO)
            chosen, _ = model_choice.choose_models(scene, Settings())
            choice[j, i] = model_choice.FIDELITY.index(chosen.coatings[0].model)
    return choice


def draw_map(calibration, path):
    calibration = calibration[~calibration.label.str.contains("nu2")].copy()   # nu2 = 0.3
    patches = [scene.coatings[0] for scene in _scenes(calibration)]
    calibration["h2"] = [p.thickness for p in patches]
    calibration["E2"] = [p.E for p in patches]
    a = model_choice.contact_half_width(paper_scene())
    heights = np.geomspace(1 / 128, 1.0, 43)
    moduli = np.geomspace(0.1, 10.0, 31)
    choice = choice_map(heights, moduli)
    scenes = [[paper_scene(h2=h2, E2=E2) for h2 in heights] for E2 in moduli]
    estimate = {model: np.array([[model_choice.estimated_errors(scene, scene.coatings[0])[model]
                                  for scene in row] for row in scenes]) for model in ONE_D}
    colours = ListedColormap(["#d6e9fb", "#ddf0dd", "#eeeeee"])
    figure, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for axis, model in zip(axes, ONE_D):
        axis.pcolormesh(heights / a, moduli, choice, cmap=colours, vmin=-0.5, vmax=2.5,
                        shading="nearest")
        measured = model_part(calibration, model).abs().clip(lower=1e-5)
        points = axis.scatter(calibration.h2 / a, calibration.E2, c=measured, s=90,
                              norm=LogNorm(1e-4, 1.0), cmap="magma_r", edgecolors="k")
        for h2, E2, value in zip(calibration.h2, calibration.E2, measured):
            axis.annotate(f"{100 * value:.2g}", (h2 / a, E2), textcoords="offset points",
                          xytext=(0, 8), ha="center", fontsize=6)
        axis.contour(heights / a, moduli, estimate[model], levels=[0.01], colors="k",
                     linestyles="--")
        axis.set(xscale="log", yscale="log", xlabel="h2 / a (a: estimated contact half-width)",
                 title=f"{model}: labels in %")
    axes[0].set_ylabel("E2 / E")
    figure.colorbar(points, ax=axes, label="measured |model error| of the peak contact stress\n(against the 2D model)")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in colours.colors]
    handles.append(plt.Line2D([], [], color="k", linestyle="--"))
    figure.legend(handles, [f"auto chooses {m}" for m in model_choice.FIDELITY]
                  + ["estimated model error 1 %"], loc="lower center", ncol=4, fontsize=8,
                  bbox_to_anchor=(0.45, -0.06))
    figure.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(figure)


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
            print(f"{name} = ({', '.join(f'{value:.4g}' for value in constants)})")
        return
    if args.only in (None, "held_out"):
        held_out = measure_all(held_out_scenes(), OUT_DIR / "held_out.csv", args.jobs)
    if args.only is None:
        draw_map(calibration, OUT_DIR / "adequacy.png")
        judge(calibration).to_csv(OUT_DIR / "calibration_judged.csv", index=False)
        validation = validate(held_out)
        validation.to_csv(OUT_DIR / "validation.csv", index=False)
        print(validation[["label", "shell_measured", "shell_estimated", "stretch_shell_measured",
                          "stretch_shell_estimated", "chosen", "chosen_measured",
                          "cost_ratio"]].to_string(index=False))
        print(verdict(validation))


if __name__ == "__main__":
    main()
