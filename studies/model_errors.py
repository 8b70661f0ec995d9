"""The measured model error of the coating models on any scene (not a test).

For a scene, the 2D coating model is solved monolithically (freefem/monolithic.edp, the
discrete problem the Robin loop solves) on meshes 1, 2, ... with the penalty scaled like
the mesh, until its peak contact stress changes by less than REFERENCE_TOLERANCE: the
mesh-converged reference. Each coating model is then solved on the paper's mesh (level 1,
the default run) and compared with it:

    error_peak         peak contact stress / the reference's - 1 (signed: + too stiff)
    error_bond_peak    the same for the bond's peak normal stress under the contact (the
                       bond points within the contact's span)
    error_bond_shear   the same for the bond's largest |shear| (anywhere on the bond: it
                       peaks near the contact's edge, often just outside it)
Both peaks are taken away from the patches' ends (farther than EDGE_DISTANCE thicknesses):
where the indenter presses on the step at a patch's end, or the bond ends, the stress is
singular and no mesh converges (measured on the discrete scene: the 2D model 11-42 %
from its own finer mesh at the step).

Scenes are measured in parallel and appended to a CSV as they finish, so that an
interrupted study resumes where it stopped (studies/adequacy.py runs the studies).
"""

from concurrent.futures import ProcessPoolExecutor, as_completed
import json
import os
import time

import numpy as np
import pandas as pd

from orchestrate.run import END_ZONE, near_patch_ends
from orchestrate.run import monolithic_solution
from studies.reference import refinement_settings
from orchestrate.model import MODELS, to_dict

REFERENCE_TOLERANCE = 1e-3     # well below the 0.2 % where model errors are judged
REFERENCE_LEVELS = (1, 2, 3, 4)
EDGE_DISTANCE = END_ZONE       # thicknesses from a patch's end


def with_model(scene, model):
    """The scene with every coating patch modelled by ``model``."""
    return scene.with_models([model] * len(scene.coatings))


def away_from_patch_ends(scene, x):
    """Which of the points x1 lie outside every patch's end zone: EDGE_DISTANCE
    thicknesses from the end, at most a quarter of the patch (the answers' end zones,
    orchestrate/run/answers.py; uncapped, a coating as thick as half its patch left no
    point to measure)."""
    return ~near_patch_ends(scene, x, EDGE_DISTANCE)   # capped, as the answers are


def peaks(scene, level):
    """Peak contact stress and bond peak (under the contact) of the monolithic solve,
    away from the patches' ends; and the contact's span."""
    problem, _, stresses = monolithic_solution(scene, refinement_settings(level))
    x = np.concatenate([c.position[:, 0] for c in problem.contacts])
    sigma = np.concatenate([stresses[problem.interfaces.index(c)] for c in problem.contacts])
    loaded = x[sigma < 0]
    bond, shear = [], []
    for b in problem.bonds:
        bx = b.position[:, 0]
        away = away_from_patch_ends(scene, bx)
        under = (bx >= loaded.min()) & (bx <= loaded.max()) & away
        tangential, normal = stresses[problem.interfaces.index(b)]
        bond.append(normal[under])
        shear.append(np.abs(tangential[away]))
    bond = np.concatenate(bond) if bond else np.array([])
    shear = np.concatenate(shear) if shear else np.array([])
    return {"peak": float(sigma[away_from_patch_ends(scene, x)].min()),
            "bond_peak": float(bond.min()) if bond.size else float("nan"),
            "bond_shear": float(shear.max()) if shear.size else float("nan"),
            "contact_span": float(loaded.max() - loaded.min())}


def reference_peaks(scene):
    """The 2D coating model's peaks, refined until the peak contact stress converges;
    with the levels used and how much the bond shear moved at the last refinement (it
    is not converged alone: its spike at the contact's edge costs finer meshes)."""
    elastic, previous = with_model(scene, "elastic"), None
    for level in REFERENCE_LEVELS:
        current = peaks(elastic, level)
        if previous is not None:
            current["bond_shear_change"] = current["bond_shear"] / previous["bond_shear"] - 1
            if abs(current["peak"] / previous["peak"] - 1) < REFERENCE_TOLERANCE:
                break
        previous = current
    current["levels"] = level
    return current


def measure(label, scene):
    """One row: the reference's peaks and each coating model's errors against them."""
    start = time.perf_counter()
    ref = reference_peaks(scene)
    row = {"label": label, "scene": json.dumps(to_dict(scene)),
           "reference_peak": ref["peak"], "reference_bond_peak": ref["bond_peak"],
           "reference_bond_shear": ref["bond_shear"],
           "reference_bond_shear_change": ref["bond_shear_change"],
           "contact_span": ref["contact_span"], "reference_levels": ref["levels"]}
    for model in MODELS:
        result = peaks(with_model(scene, model), 1)
        row[f"{model}_error_peak"] = result["peak"] / ref["peak"] - 1.0
        row[f"{model}_error_bond_peak"] = result["bond_peak"] / ref["bond_peak"] - 1.0
        row[f"{model}_error_bond_shear"] = result["bond_shear"] / ref["bond_shear"] - 1.0
    row["seconds"] = time.perf_counter() - start
    return row


def measure_all(scenes, csv_path, jobs=2, progress=print):
    """Measure every (label, scene) not yet in ``csv_path``, appending rows as they
    finish; return the whole table. A row measured on another scene under the same label
    (a scene file edited since) is dropped and measured again."""
    done = set()
    if os.path.exists(csv_path):
        table = pd.read_csv(csv_path)
        current = {label: json.dumps(to_dict(scene)) for label, scene in scenes}
        stale = table.label.isin(current) & (table.scene != table.label.map(current))
        if stale.any():
            progress(f"{csv_path}: measuring again {', '.join(table.label[stale])} (its "
                     "scene changed)")
            table = table[~stale]
            partial = f"{csv_path}.partial"
            table.to_csv(partial, index=False)
            os.replace(partial, csv_path)           # whole, or the old table
        done = set(table.label)
    todo = [(label, scene) for label, scene in scenes if label not in done]
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(measure, label, scene): label for label, scene in todo}
        for future in as_completed(futures):
            if future.exception() is not None:       # not the rest, unrecorded
                pool.shutdown(wait=True, cancel_futures=True)
                raise RuntimeError(f"measuring {futures[future]!r} failed") \
                    from future.exception()
            row = future.result()
            header = not os.path.exists(csv_path)
            text = pd.DataFrame([row]).to_csv(header=header, index=False)
            with open(csv_path, "a") as out:    # one write: a row is whole or absent
                out.write(text)
            progress(f"{row['label']}: shell {100 * row['shell_error_peak']:+.2f} %, stretch "
                     f"{100 * row['stretch_shell_error_peak']:+.2f} %, 2D "
                     f"{100 * row['elastic_error_peak']:+.2f} % ({row['seconds']:.0f} s)")
    table = pd.read_csv(csv_path)
    labels = [label for label, _ in scenes]
    return table[table.label.isin(labels)]
