"""A cylinder sliding over a discrete coating: the bonds' peel and shear against the
indenter's position, for several friction coefficients (not a test: the loop's
correctness under friction is tests/ddm/test_monolithic.py's).

The cylinder scene's bodies (R = 20 b, blocks 8 b wide and high, force 0.02 E b, a
contact about 1.4 b wide) as a full model, over three patches 0.5 b long, 0.25 b apart,
0.125 b thick, of 5 E (2D coatings), the indenter's lowest point at x1 = POSITIONS and
sliding towards +x1 with mu = FRICTIONS (mu = 0: pressed without friction). The
positions of one mu are a sweep that keeps what does not move: the interface elements
of one size everywhere (element_size, not sized to the contact, which would follow it)
and one contact zone over the whole traverse, so that the base and its patches keep
their workers from position to position (a Session) and each position starts from the
one before (start_from): only the indenter, the gap and the tractions change. Measured
on three positions: the base's and the patches' workers kept, 51-53 iterations against
100-106 and 1.4-1.9 s against 2.5-2.6 s as separate runs.

Reported per run: the peak pressure, the largest peel (tensile normal stress) and shear
on any bond, away from the patches' ends and within their end zones (where a bond's
stresses are singular and grow with the mesh: they say where, not how much;
orchestrate/run/answers.py), and the base's largest tension along its face.

Writes results/sliding/sliding.csv, sliding.png and results/sliding/sliding.md.

    python -m studies.sliding_patches
"""

import argparse
from dataclasses import replace
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from orchestrate import Session, solve  # noqa: E402
from orchestrate.model import DEFAULT_ELEMENT_SIZE, Coating, Settings, load_scene  # noqa: E402
from orchestrate.paths import SCENES_DIR  # noqa: E402
from studies.paths import RESULTS_DIR  # noqa: E402
from studies.report import Column, Report, command_line, seconds  # noqa: E402

PATCHES = ((-1.0, -0.5), (-0.25, 0.25), (0.5, 1.0))
POSITIONS = tuple(np.round(np.arange(-1.5, 1.5 + 1e-9, 0.125), 6))
FRICTIONS = (0.0, 0.2, 0.5)
TRAVERSE_ZONE = (-2.5, 2.5)      # the contact zone of every position
SETTINGS = Settings(element_size=DEFAULT_ELEMENT_SIZE)


def sliding_scene(centre, friction):
    scene, _ = load_scene(SCENES_DIR / "cylinder.toml")
    patch = scene.coatings[0]
    coatings = tuple(Coating(start=start, end=end, thickness=patch.thickness, E=patch.E,
                             nu=patch.nu, model="elastic") for start, end in PATCHES)
    return replace(scene, symmetric=False, coatings=coatings, contact_zone=TRAVERSE_ZONE,
                   indenter=replace(scene.indenter, centre=float(centre)),
                   friction=friction, sliding=friction > 0)


def _largest(answers, quantity, at_ends):
    """The largest value of ``quantity`` over every bond, away from the ends or within
    their end zones (0 where none)."""
    values = []
    for found in answers["bonds"].values():
        extreme = (found.get("at_patch_ends", {}) if at_ends else found).get(quantity)
        values.append(extreme["value"] if extreme else 0.0)
    return max(values)


def traverse(friction):
    """The rows of every position under ``friction``, one sweep (the module's text)."""
    rows, previous = [], None
    with Session() as session:
        for centre in POSITIONS:
            result = solve(sliding_scene(centre, friction), SETTINGS, session=session,
                           start_from=previous)
            rows.append(_row(centre, friction, result.summary))
            previous = result
    return rows


def _row(centre, friction, summary):
    answers = summary["answers"]
    tension = answers["substrate"].get("face_tension")
    return {"centre": centre, "mu": friction,
            "peak_pressure": answers["contact"]["peak_pressure"]["value"],
            "peel": _largest(answers, "peel", False),
            "shear": _largest(answers, "shear", False),
            "peel_at_ends": _largest(answers, "peel", True),
            "shear_at_ends": _largest(answers, "shear", True),
            "face_tension": tension["value"] if tension else 0.0,
            "iterations": summary["iterations"], "seconds": summary["wall_time_s"],
            "workers_kept": len(summary["workers_kept"])}


def plot(table, path):
    figure, axes = plt.subplots(1, 3, figsize=(13, 3.8), sharex=True)
    panels = (("peel", "peel_at_ends", "largest peel on a bond (E)"),
              ("shear", "shear_at_ends", "largest bond shear (E)"),
              ("face_tension", None, "base's largest face tension (E)"))
    for axis, (away, ends, label) in zip(axes, panels):
        for mu, rows in table.groupby("mu"):
            line, = axis.plot(rows.centre, rows[away], "-o", ms=3, label=f"mu = {mu:g}")
            if ends:
                axis.plot(rows.centre, rows[ends], "--", color=line.get_color(), lw=1)
        for start, end in PATCHES:
            axis.axvspan(start, end, color="0.9", zorder=0)
        axis.set_xlabel("indenter position x1 (b)")
        axis.set_ylabel(label)
    axes[0].legend(title="solid: away from patch ends\ndashed: in their end zones",
                   fontsize=8, title_fontsize=8)
    figure.suptitle("A cylinder sliding towards +x1 over three 2D coating patches (shaded)")
    figure.tight_layout()
    figure.savefig(path, dpi=130)
    plt.close(figure)


def write_report(table, out, command="python -m studies.sliding_patches"):
    report = Report("A cylinder sliding over three patches", command,
                    data=["sliding.csv"])
    report.text("The cylinder scene as a full model over three 2D coating patches "
                f"{', '.join(f'[{s:g}, {e:g}] b' for s, e in PATCHES)} (0.125 b, 5 E), the "
                "indenter's lowest point at each x1, sliding towards +x1 (mu = 0: pressed "
                "without friction); the positions of one mu a sweep that keeps the base's "
                "and the patches' workers and starts each position from the one before; "
                "stresses in E. Figure: `sliding.png`.")
    worst = table.groupby("mu").agg(
        peel=("peel", "max"), shear=("shear", "max"), peel_at_ends=("peel_at_ends", "max"),
        shear_at_ends=("shear_at_ends", "max"), face_tension=("face_tension", "max"),
        iterations=("iterations", "median"), seconds=("seconds", "median"),
        kept=("workers_kept", "median")).reset_index()
    report.table(worst, [
        Column("mu", "mu", "{:g}"),
        Column("peel", "peel", "{:.4g}", "the largest over every position and bond, away "
               "from the patches' ends"),
        Column("shear", "shear", "{:.4g}"),
        Column("peel_at_ends", "peel at ends", "{:.4g}", "within the end zones "
               "(mesh-dependent: a singular corner)"),
        Column("shear_at_ends", "shear at ends", "{:.4g}"),
        Column("face_tension", "face tension", "{:.4g}", "the base's largest tension along "
               "its face"),
        Column("iterations", "iterations", "{:g}", "the median over the positions"),
        Column("seconds", "time", seconds, "the median run's"),
        Column("kept", "workers kept", "{:g}", "the median run's workers kept from the "
               "position before (of 5)")])
    dry = worst[worst.mu == 0].iloc[0]
    for _, row in worst[worst.mu > 0].iterrows():
        report.finding(
            f"With mu = {row.mu:g}, over all positions, the largest bond shear away from "
            f"the patches' ends is {row.shear / dry.shear:.2f} times the frictionless one, "
            f"the largest peel within their end zones {row.peel_at_ends / dry.peel_at_ends:.2f}"
            f" times (a singular corner: the ratio, not the value, is the answer), and the "
            f"base's largest face tension {row.face_tension / dry.face_tension:.2f} times.")
    return report.write(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "sliding"))
    args = parser.parse_args(argv)
    table = pd.DataFrame([row for mu in FRICTIONS for row in traverse(mu)])
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    os.makedirs(args.out, exist_ok=True)
    table.to_csv(os.path.join(args.out, "sliding.csv"), index=False)
    plot(table, os.path.join(args.out, "sliding.png"))
    print(write_report(table, os.path.join(args.out, "sliding.md"),
                       command_line("studies.sliding_patches", argv)))


if __name__ == "__main__":
    main()
