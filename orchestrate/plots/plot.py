"""Plot of one run for a coating engineer: the contact and bond stresses along the
surface, where the contact is.

Reads only the run's files (summary.json, contact.csv, interface.csv), so a plot never
recomputes anything. The x range is the contact zones, each widened by a margin
(``zone_margin``), within the base's face; a run without contact shows the whole face.
Coating patches are a grey strip along the bottom. A bonded patch end off the symmetry
axis is a corner of two bonded materials: its stresses grow without bound as the mesh is
refined. Such ends are marked, and the values within their end zones
(orchestrate/run/answers.py's ``near_patch_ends``) are drawn but kept out of the y scale,
which they would otherwise set. The title names the scene and the axes the run's units.
The peak contact pressure and the bond's largest peel and shear away from the ends are
marked. The summary's warnings are listed in red under the axes."""

import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from orchestrate.run.answers import near_patch_ends  # noqa: E402
from orchestrate.errors import ParameterError  # noqa: E402
from orchestrate.model.scene import scene_from_dict  # noqa: E402
from orchestrate.model.units import force_label, force_name, modulus_text  # noqa: E402

# A contact zone's margin on each side: the bond's stresses reach beyond the contact by
# about the contact's half-width (the base's elastic field) and, under a stiff coating
# that spreads the load, by a few coating thicknesses (its shear lag); the larger of the
# two, never beyond the face. On the example scenes the bond's stresses beyond it, away
# from patch ends, are within a tenth of their peak (tests/run/test_plot.py).
HALF_WIDTHS = 1.0        # of the contact's half-width
THICKNESSES = 3.0        # of the thickest patch
Y_PAD = 0.08             # of the y range, above and below
MODEL_NAMES = {"shell": "shell model", "stretch_shell": "shell with stretch",
               "elastic": "2D model"}
END_ZONE_COLOUR = "tab:red"
PATCH_COLOUR = "0.6"
PATCH_STRIP = 0.025      # the patches' strip: its height, a fraction of the axes'


def finished_summary(run_dir):
    """The summary of the converged run in ``run_dir``; ParameterError, in one line, if
    there is none (no such folder, no summary.json: an unfinished run, a run that did
    not converge or failed)."""
    if not os.path.isdir(run_dir):
        raise ParameterError(f"{run_dir}: no such folder")
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            summary = json.load(f)
    except OSError:
        raise ParameterError(f"{run_dir} holds no finished run (no summary.json)") from None
    except ValueError:
        raise ParameterError(f"{run_dir}: its summary.json is not readable JSON") from None
    if not isinstance(summary, dict):
        raise ParameterError(f"{run_dir}: its summary.json is not a run's summary")
    if not summary.get("converged"):
        status = summary.get("status")
        reason = (str(summary.get("reason") or "").splitlines() or [""])[0]  # one line
        outcome = (f"failed: {reason}" if status == "error" else
                   f"did not converge ({status}{': ' + reason if reason else ''})")
        raise ParameterError(f"{run_dir}: the run {outcome}; there are no stresses to plot")
    return summary


def _read_stresses(run_dir, name):
    try:
        return pd.read_csv(os.path.join(run_dir, name))
    except (OSError, ValueError, pd.errors.EmptyDataError):
        raise ParameterError(f"{run_dir}: {name} is missing or unreadable") from None


def run_units(summary):
    """The names of the run's units of length, stress and force (per unit width); a
    run older than units: b and E."""
    units = summary.get("units", {})
    length, stress = units.get("length", "b"), units.get("stress", "E")
    force = units.get("force", force_name(stress, length))
    return {"length": length, "stress": stress, "force": force_label(force)}


def face_extent(scene):
    """(low, high): x1 of the ends of the base's top face (a half model: from the axis)."""
    return (0.0 if scene.symmetric else -scene.base.top), scene.base.top


def zone_margin(zone, scene):
    """How far beyond a contact zone (start, end) the plot reaches on each side."""
    width = zone[1] - zone[0]
    if scene.symmetric and zone[0] == 0.0:       # half of a contact that is twice as wide
        width *= 2.0
    thickest = max((c.thickness for c in scene.coatings), default=0.0)
    return max(HALF_WIDTHS * width / 2.0, THICKNESSES * thickest)


def x_range(summary, scene):
    """(low, high) of the plot: the contact zones with their margins, within the face;
    the whole face without contact."""
    low, high = face_extent(scene)
    zones = summary.get("contact_zones") or []
    if not zones:
        return low, high
    return (max(low, min(start - zone_margin((start, end), scene) for start, end in zones)),
            min(high, max(end + zone_margin((start, end), scene) for start, end in zones)))


def y_range(curves, scene, x_limits):
    """(low, high) covering every value shown within ``x_limits`` outside the patches'
    end zones, and zero; None if there is none. ``curves``: (x1, values) pairs."""
    kept = []
    for x1, values in curves:
        x1, values = np.asarray(x1, dtype=float), np.asarray(values, dtype=float)
        shown = (x1 >= x_limits[0]) & (x1 <= x_limits[1]) & ~near_patch_ends(scene, x1)
        kept.append(values[shown])
    kept = np.concatenate(kept) if kept else np.array([])
    if kept.size == 0:
        return None
    low, high = min(0.0, kept.min()), max(0.0, kept.max())
    if high == low:
        return None
    pad = Y_PAD * (high - low)
    return low - pad, high + pad


def singular_ends(scene):
    """x1 of every bonded patch end off the symmetry axis of a half model."""
    return [end for coating in scene.coatings for end in scene.patch_ends(coating)]


def end_zones(scene, x_limits, samples=2001):
    """[(start, end)] of the stretches of [x_limits] within a patch's end zone, as
    ``near_patch_ends`` decides them, to a 1/(samples - 1) of the range."""
    x1 = np.linspace(*x_limits, samples)
    near = near_patch_ends(scene, x1)
    zones, i = [], 0
    while i < samples:
        if near[i]:
            j = i
            while j + 1 < samples and near[j + 1]:
                j += 1
            zones.append((x1[i], x1[j]))
            i = j
        i += 1
    return zones


def _mark_singular_ends(axes, scene, limits, length):
    """A dotted line at each singular end in view; those beyond it named at the side."""
    beyond = {"left": [], "right": []}
    for x1 in singular_ends(scene):
        if limits[0] <= x1 <= limits[1]:
            axes.axvline(x1, color=END_ZONE_COLOUR, linewidth=0.8, linestyle=":")
        else:
            beyond["left" if x1 < limits[0] else "right"].append(x1)
    for side, ends in beyond.items():
        if ends:
            text = (f"bonded end{'s' if len(ends) > 1 else ''} at "
                    f"{', '.join(f'{x1:g}' for x1 in sorted(ends))} {length}")
            axes.annotate(f"← {text}" if side == "left" else f"{text} →",
                          (0.0 if side == "left" else 1.0, PATCH_STRIP),
                          xycoords="axes fraction", xytext=(3 if side == "left" else -3, 3),
                          textcoords="offset points", ha=side, va="bottom", fontsize=7,
                          color=END_ZONE_COLOUR)


def scene_title(summary, scene, units):
    """Two lines: the indenter, the base, the load; the coating patches."""
    length, stress = units["length"], units["stress"]
    indenter, base, load = scene.indenter, scene.base, scene.load
    if np.isinf(indenter.radius):
        shape = "flat indenter"
    else:
        round_face = "sphere" if scene.axisymmetric else "cylinder"
        shape = (f"{round_face if indenter.profile == 'circle' else 'parabolic indenter'} "
                 f"R = {indenter.radius:g} {length}")
    on = ("cylinder" if scene.axisymmetric else "block" if base.shape == "block"
          else f"roller R = {base.radius:g} {length}")
    base_E = modulus_text(base.E, stress)
    moduli = (f"rigid indenter, E = {base_E}" if indenter.rigid
              else f"E = {base_E}" if indenter.E == base.E
              else f"E = {modulus_text(indenter.E, stress)} / {base_E}")
    if load.force is not None:
        loading = f"force {load.force:g} {units['force']}"
    else:
        total = summary.get("total_force")
        loading = f"descent {load.displacement:.4g} {length}" + (
            f" (force {total:.4g} {units['force']})" if total is not None else "")
    first = f"{shape} on a {on}, {moduli}; {loading}"
    kinds = {}
    for coating in scene.coatings:
        kind = (coating.thickness, coating.E, coating.model)
        kinds[kind] = kinds.get(kind, 0) + 1
    patches = "; ".join(
        f"{f'{count} patches' if count > 1 else 'coating'} h = {thickness:g} {length}, "
        f"E = {modulus_text(E, stress)} ({MODEL_NAMES.get(model, model)})"
        for (thickness, E, model), count in kinds.items()) or "uncoated"
    view = ("; axisymmetric" if scene.axisymmetric else "; half model" if scene.symmetric
            else "")
    return f"{first}\n{patches}{view}"


def _answer_marks(summary, interface, units, axisymmetric=False):
    """(x1, y, marker, label) of the peak contact pressure and of the bond's largest
    peel and shear away from the patches' ends (the summary's answers); a position is
    x1, or r on a body of revolution."""
    answers = summary.get("answers")
    if not answers:
        return []
    stress, length = units["stress"], units["length"]
    along = "$r$" if axisymmetric else "$x_1$"

    def where(extreme):
        return f"{extreme['value']:.4g} {stress} at {along} = {extreme['x1']:.3g} {length}"
    marks = []
    peak = answers["contact"].get("peak_pressure")
    if peak:
        marks.append((peak["x1"], -peak["value"], "*", f"peak pressure {where(peak)}"))
    for quantity, column, marker in (("peel", "sigma_n", "^"), ("shear", "sigma_t", "D")):
        found = [(name, values[quantity]) for name, values in answers["bonds"].items()
                 if values.get(quantity)]
        if not found:
            continue
        name, extreme = max(found, key=lambda item: abs(item[1]["value"]))
        rows = interface[interface.interface == name]
        if rows.empty:
            continue
        # the shear's answer is |sigma_t|: its sign from the bond's table
        nearest = rows.iloc[int(np.argmin(np.abs(rows.x1.to_numpy() - extreme["x1"])))]
        marks.append((extreme["x1"], np.sign(nearest[column]) * abs(extreme["value"]),
                      marker, f"largest bond {quantity} {where(extreme)}"))
    return marks


def plot_run(run_dir, path=None):
    """Write ``run_dir/stresses.png`` (or ``path``) and return its path."""
    figure = stresses_figure(run_dir)
    path = path or os.path.join(run_dir, "stresses.png")
    try:
        figure.savefig(path, dpi=150, bbox_inches="tight")
    finally:
        plt.close(figure)
    return path


def stresses_figure(run_dir):
    """The figure of a finished run: the contact stress of every contact interface and
    the bond stresses (normal, shear) of every patch against x1, in the run's units,
    where the contact is."""
    summary = finished_summary(run_dir)
    contact = _read_stresses(run_dir, "contact.csv")
    interface = _read_stresses(run_dir, "interface.csv")
    scene = scene_from_dict(summary["scene"])
    units = run_units(summary)
    limits = x_range(summary, scene)
    figure, axes = plt.subplots(figsize=(7.2, 4.6))
    for coating in scene.coatings:       # a strip along the bottom: the patches
        axes.axvspan(coating.start, coating.end, ymax=PATCH_STRIP, color=PATCH_COLOUR,
                     linewidth=0, zorder=0)
    bands = end_zones(scene, limits)
    for start, end in bands:
        axes.axvspan(start, end, color=END_ZONE_COLOUR, alpha=0.12, linewidth=0, zorder=0)
    _mark_singular_ends(axes, scene, limits, units["length"])
    curves = []
    for k, (_, part) in enumerate(contact.groupby("interface", sort=False)):
        axes.plot(part.x1, part.sigma_n, color="C0",
                  label=r"contact $\sigma_n$" if k == 0 else None)
        curves.append((part.x1, part.sigma_n))
    for k, (_, part) in enumerate(interface.groupby("interface", sort=False)):
        axes.plot(part.x1, part.sigma_n, "--", color="C1",
                  label=r"bond $\sigma_n$ (peel > 0)" if k == 0 else None)
        axes.plot(part.x1, part.sigma_t, ":", color="C2",
                  label=r"bond $\sigma_t$" if k == 0 else None)
        curves += [(part.x1, part.sigma_n), (part.x1, part.sigma_t)]
    for x1, y, marker, label in _answer_marks(summary, interface, units, scene.axisymmetric):
        in_view = limits[0] <= x1 <= limits[1]     # else its legend entry alone
        axes.plot([x1] if in_view else [], [y] if in_view else [], marker, color="k",
                  markersize=8 if marker == "*" else 5, linestyle="none", zorder=5,
                  clip_on=False, label=label + ("" if in_view else ", beyond the view"))
    axes.axhline(0.0, color="0.7", linewidth=0.8)
    axes.set_xlim(*limits)
    y_limits = y_range(curves, scene, limits)
    if y_limits:
        axes.set_ylim(*y_limits)
    handles, _ = axes.get_legend_handles_labels()
    if scene.coatings:
        handles.append(Patch(color=PATCH_COLOUR, label="coating patch"))
    if any(limits[0] <= x1 <= limits[1] for x1 in singular_ends(scene)):
        handles.append(Line2D([], [], color=END_ZONE_COLOUR, linewidth=0.8, linestyle=":",
                              label="bonded patch end: singular stresses"))
    if bands:
        handles.append(Patch(color=END_ZONE_COLOUR, alpha=0.12,
                             label="patch end zone: drawn, out of the y scale"))
    axes.legend(handles=handles, fontsize=7)
    axes.set_xlabel(f"$r$ ({units['length']})" if scene.axisymmetric else
                    f"$x_1$ ({units['length']})"
                    + (" from the symmetry axis" if scene.symmetric else ""))
    axes.set_ylabel(f"stress ({units['stress']}; compression < 0)")
    axes.set_title(scene_title(summary, scene, units), fontsize=9)
    codes = [str(w.get("code", "?")) for w in summary.get("warnings") or []]
    if codes:                                  # under the x label
        axes.annotate("warnings: " + ", ".join(
            code + (f" (x{codes.count(code)})" if codes.count(code) > 1 else "")
            for code in dict.fromkeys(codes)), (0.0, 0.0), xycoords="axes fraction",
            xytext=(0, -40), textcoords="offset points", va="top", fontsize=7, color="red")
    figure.tight_layout()
    return figure
