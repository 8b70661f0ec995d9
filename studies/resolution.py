"""How many interface elements a contact needs: the answers' error against the elements
across the contact zone, the study behind the resolution limits of
orchestrate/run/validity.py (``python -m studies.resolution``, results/resolution.csv).

Each scene is solved with interface elements of decreasing length (element_size), so
that its a priori contact width 2a (orchestrate/model/estimate.py's estimate, mirrored in
a half model) spans from 2 to 48 elements; the answers (peak contact pressure, the
bond's peak compression and shear away from the patch ends, the coating's largest
stress) are compared with those of the finest run, 96 elements across. The scenes: the
paper's (a parabolic indenter on a 2 b patch, both coating models) and a cylinder of
radius 20 b on a stiff patch under a force (orchestrate/scenes/cylinder.toml).
"""

import argparse
import math
import os
import sys

import pandas as pd

from orchestrate.model import contact_half_width
from studies.paths import RESULTS_DIR
from orchestrate.model import Settings
from orchestrate.paths import SCENES_DIR
from orchestrate.model import load_scene, paper_scene

ACROSS = (2, 3, 4, 6, 8, 10, 12, 16, 24, 32, 48)
REFERENCE_ACROSS = 96
ANSWERS = {"peak_pressure": ("contact", None, "peak_pressure"),
           "bond_compression": ("bonds", "bond-coating1", "compression"),
           "bond_shear": ("bonds", "bond-coating1", "shear")}


def scenes():
    cylinder, _ = load_scene(SCENES_DIR / "cylinder.toml")
    return {"paper, shell": paper_scene(model="shell"),
            "paper, 2D coating": paper_scene(model="elastic"),
            "cylinder R = 20 b, shell": cylinder}


def _value(answers, group, owner, quantity):
    found = answers[group] if owner is None else answers[group][owner]
    extreme = found.get(quantity)
    return abs(extreme["value"]) if extreme else math.nan


def _coating_stress(answers):
    values = [abs(e["value"]) for q, e in answers["coatings"]["coating1"].items()
              if q != "at_patch_ends" and e]
    return max(values) if values else math.nan


def study(out, progress=print):
    import orchestrate

    rows = []
    for name, scene in scenes().items():
        width = 2.0 * contact_half_width(scene)         # the whole contact (mirrored)
        found = {}
        for across in (REFERENCE_ACROSS,) + ACROSS:
            settings = Settings(element_size=width / across)
            result = orchestrate.solve(scene, settings)
            answers = result.answers
            found[across] = {key: _value(answers, *where) for key, where in ANSWERS.items()}
            found[across]["coating_stress"] = _coating_stress(answers)
            found[across]["measured_across"] = (2.0 * result.summary["contact_half_width"]
                                                / (width / across))
            progress(f"{name}: {across} elements across, {result.summary['iterations']} "
                     f"iterations")
        reference = found.pop(REFERENCE_ACROSS)
        for across, values in found.items():
            row = {"scene": name, "elements_across": across,
                   "measured_elements_across": values["measured_across"]}
            for key in (*ANSWERS, "coating_stress"):
                row[f"{key}_error"] = abs(values[key] / reference[key] - 1.0)
            rows.append(row)
    table = pd.DataFrame(rows)
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    table.to_csv(out, index=False)
    return table


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULTS_DIR / "resolution.csv"))
    args = parser.parse_args(argv)
    table = study(args.out, progress=lambda text: print(text, file=sys.stderr))
    with pd.option_context("display.width", 200, "display.float_format", "{:.2e}".format):
        print(table.to_string(index=False))
    print(args.out)


if __name__ == "__main__":
    main()
