"""A rigid sphere on a coated half-space: the tool's axisymmetric runs against Hertz and
against the independent layered reference (studies/layered_indentation.py: the
bonded layer's Hankel-transform kernel, the contact solved on rings).

1. Hertz. A rigid sphere (a paraboloid of radius R = 50 a, as the reference's) on an
   uncoated cylinder as wide and deep as L = 10, 20, 40 a, pressed with the force that
   gives Hertz's contact radius a = 1 b. The peak pressure and the contact radius
   against Hertz's; the approach, measured to the clamped bottom, against a^2 / R: it
   is short of it by c P / (E L) (the far field a half-space would have below depth L,
   which the clamp holds), so the body-size correction is that term, c measured on the
   largest body pair by extrapolating the trend, 2 d(2L) - d(L).
2. Layered. The same sphere on the cylinder L = 40 a whose whole top carries a bonded
   2D coating (E2/E3 from 0.1 to 10, h2 from 0.1 to 2 contact radii, nu = 0.3 in
   both), pressed with the force the reference needs for a contact radius of 1 b: the
   tool's contact radius, peak pressure and approach (corrected by the same c P / (E3 L):
   the far field is the substrate's) against the reference's.
3. Winkler. A thin compliant layer on a much stiffer substrate (E3 / E2 = 10^3, 10^4;
   h2 = a/10, a/20, a/40; a cylinder L = 10 a: the layer carries the contact): the force
   against the confined-layer limit P = pi M a^4 / (4 R h2), M = E2 (1 - nu2) /
   ((1 + nu2)(1 - 2 nu2)), at the tool's contact radius, beside the reference's distance
   from that limit (the limit's own error, of order h2 / a), and the contact radius
   against the reference's.

Writes results/sphere_layered.csv and .md.

    python -m studies.sphere_layered
"""

import argparse
import math
import os
import time

import pandas as pd

from studies import layered_indentation as reference
from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds, signed_percent
from orchestrate.model import Base, Coating, Indenter, Load, Scene, Settings
import orchestrate

RADIUS, NU = 50.0, 0.3
SIZES = (10.0, 20.0, 40.0)            # the uncoated cylinder's radius and height, in a
LAYERED_SIZE = 40.0
MODULUS_RATIOS = (0.1, 0.3, 3.0, 10.0)   # E2 / E3
THICKNESSES = (0.1, 0.5, 1.0, 2.0)        # h2 / a
WINKLER_SIZE = 10.0
WINKLER_RATIOS = (1e-3, 1e-4)           # E2 / E3
WINKLER_THICKNESSES = (0.1, 0.05, 0.025)  # h2 / a
RINGS = 400                           # the reference's: a to 0.04 %, p0 and delta to 1e-6
EPS_U = 1e-6                          # the default: tighter, a thin soft layer's iteration
                                      # stalls near 1e-8 and falls back to a direct solve
TOLERANCE = 0.01                      # the 1 %


def sphere_scene(size, force, coating=None):
    """A rigid paraboloid of radius RADIUS on a cylinder of radius and height ``size``
    (E = 1), optionally coated over its whole top by ``coating`` (E2, h2)."""
    coatings = () if coating is None else (
        Coating(start=0.0, end=size, thickness=coating[1], E=coating[0], nu=NU,
                model="elastic"),)
    # the face spans the base: a coating may not reach beyond it
    return Scene(indenter=Indenter(radius=RADIUS, profile="parabola", width=size,
                                   height=size, rigid=True),
                 base=Base(width=size, height=size, E=1.0, nu=NU), coatings=coatings,
                 load=Load(force=force), axisymmetric=True)


def run(scene):
    """(summary, seconds) of the tool on a scene."""
    start = time.perf_counter()
    summary = orchestrate.solve(scene, Settings(eps_u=EPS_U)).summary
    return summary, time.perf_counter() - start


def hertz_rows():
    """The uncoated cylinders against Hertz (a = 1)."""
    modulus = reference.reduced_modulus(1.0, NU)
    force = reference.hertz_force(1.0, RADIUS, modulus)
    a, p0, approach = reference.hertz(force, RADIUS, modulus)
    rows = []
    for size in SIZES:
        summary, took = run(sphere_scene(size, force))
        rows.append({"case": "hertz", "size": size, "E2/E3": math.nan, "h2/a": math.nan,
                     "force": force, "a_error": summary["contact_half_width"] / a - 1,
                     "p0_error": -summary["peak_contact_stress"] / p0 - 1,
                     "raw_approach_error": summary["descent"] / approach - 1,
                     "descent": summary["descent"], "reference_approach": approach,
                     "iterations": summary["iterations"],
                     "unknowns": sum(summary["dofs"].values()), "seconds": took})
    return rows


def far_field(rows, size):
    """c / (E L) of the cylinder ``size`` (E = 1): the approach a clamp at depth L
    takes off per unit force, from the two largest bodies' trend (it halves as L
    doubles), 2 d(2L) - d(L) being the half-space's approach."""
    by_size = {row["size"]: row for row in rows}
    large, small = by_size[SIZES[-1]], by_size[SIZES[-2]]
    unbounded = 2.0 * large["descent"] - small["descent"]
    return (unbounded - by_size[size]["descent"]) / by_size[size]["force"]


def peak(exact):
    """The reference's largest pressure: at the centre (extrapolated to r = 0), or on a
    ring off the axis, where a stiff coating moves it."""
    return max(exact.peak_pressure, float(exact.pressure.max()))


def layered_rows(shift):
    """The coated cylinders against the layered reference; ``shift``: the approach per
    unit force the clamp takes off (far_field)."""
    rows = []
    for ratio in MODULUS_RATIOS:
        for thickness in THICKNESSES:
            body = reference.CoatedHalfSpace(ratio, NU, thickness, 1.0, NU)
            exact = reference.indent_to_radius(body, RADIUS, 1.0, rings=RINGS)
            scene = sphere_scene(LAYERED_SIZE, exact.force, (ratio, thickness))
            summary, took = run(scene)
            approach = summary["descent"] + shift * exact.force
            rows.append({"case": "layered", "size": LAYERED_SIZE, "E2/E3": ratio,
                         "h2/a": thickness, "force": exact.force,
                         "a_error": summary["contact_half_width"] / exact.contact_radius - 1,
                         "p0_error": -summary["peak_contact_stress"] / peak(exact) - 1,
                         "approach_error": approach / exact.approach - 1,
                         "descent": summary["descent"], "reference_approach": exact.approach,
                         "iterations": summary["iterations"],
                         "unknowns": sum(summary["dofs"].values()), "seconds": took})
    return rows


def winkler_force(contact_radius, E2, thickness):
    """The confined-layer limit's force at a contact radius."""
    modulus = E2 * (1 - NU) / ((1 + NU) * (1 - 2 * NU))
    return math.pi * modulus * contact_radius ** 4 / (4.0 * RADIUS * thickness)


def winkler_rows():
    """Thin compliant layers on a stiff substrate against the Winkler limit."""
    rows = []
    for ratio in WINKLER_RATIOS:
        for thickness in WINKLER_THICKNESSES:
            body = reference.CoatedHalfSpace(ratio, NU, thickness, 1.0, NU)
            exact = reference.indent_to_radius(body, RADIUS, 1.0, rings=RINGS)
            summary, took = run(sphere_scene(WINKLER_SIZE, exact.force, (ratio, thickness)))
            a = summary["contact_half_width"]
            rows.append({"case": "winkler", "size": WINKLER_SIZE, "E2/E3": ratio,
                         "h2/a": thickness, "force": exact.force,
                         "a_error": a / exact.contact_radius - 1,
                         "p0_error": -summary["peak_contact_stress"] / peak(exact) - 1,
                         "winkler_error": exact.force / winkler_force(a, ratio, thickness) - 1,
                         "reference_winkler_error": exact.force / winkler_force(
                             exact.contact_radius, ratio, thickness) - 1,
                         "iterations": summary["iterations"],
                         "unknowns": sum(summary["dofs"].values()), "seconds": took})
    return rows


def study():
    hertz = hertz_rows()
    shift = far_field(hertz, LAYERED_SIZE)
    for row in hertz:
        row["approach_error"] = ((row["descent"] + far_field(hertz, row["size"]) * row["force"])
                                 / row["reference_approach"] - 1)
    return pd.DataFrame(hertz + layered_rows(shift) + winkler_rows()), shift


ERRORS = [Column("a_error", "contact radius", signed_percent, "the tool's / the reference's - 1"),
          Column("p0_error", "peak pressure", signed_percent,
                 "the tool's largest / the reference's - 1 (off the axis under a stiff coating)"),
          Column("approach_error", "approach", signed_percent,
                 "the tool's descent plus the far field a clamp at depth L holds, / the "
                 "reference's - 1")]
COST = [Column("iterations", "iterations", "{:g}"), Column("unknowns", "unknowns", "{:g}"),
        Column("seconds", "wall time", seconds)]


def write_report(table, shift, out, argv=None):
    report = Report("A rigid sphere on a coated half-space against Hertz and the layered "
                    "reference", command_line("studies.sphere_layered", argv),
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text(f"A rigid paraboloid of radius R = {RADIUS:g} a on a cylinder as wide and deep "
                f"as L, E3 = 1, nu = {NU:g} everywhere, axisymmetric runs to eps_u = "
                f"{EPS_U:g} at mesh level 1, each under the force that gives a contact radius "
                f"a = 1 b (Hertz's, or the reference's: studies/layered_indentation.py, "
                f"{RINGS} rings).")
    hertz = table[table.case == "hertz"]
    report.section("Hertz: an uncoated cylinder L wide and deep")
    report.table(hertz, [Column("size", "L / a", "{:g}"), *ERRORS[:2],
                         Column("raw_approach_error", "approach to the clamp", signed_percent,
                                "the descent / a^2 / R - 1: short by the clamp's far field"),
                         ERRORS[2], *COST])
    report.finding(f"The clamp at depth L takes c P / (E L) off the approach, c = "
                   f"{shift * LAYERED_SIZE:.3g} (2 d(2L) - d(L) of the two largest bodies): the "
                   "approaches to the clamp fall short by "
                   + ", ".join(f"{100 * -e:.2f} %" for e in hertz.raw_approach_error)
                   + f" at L = {', '.join(f'{s:g}' for s in hertz['size'])} a, halving as L "
                   "doubles.")
    layered = table[table.case == "layered"]
    report.section(f"The coated cylinder (L = {LAYERED_SIZE:g} a) against the layered reference")
    report.table(layered, [Column("E2/E3", "E2/E3", "{:g}"), Column("h2/a", "h2/a", "{:g}"),
                           Column("force", "P", "{:.4g}", "E3 a^2"), *ERRORS, *COST])
    worst = layered[["a_error", "p0_error", "approach_error"]].abs().max()
    report.finding(f"{int((layered[['a_error', 'p0_error', 'approach_error']].abs().max(axis=1) < TOLERANCE).sum())} "
                   f"of {len(layered)} coated cases within {100 * TOLERANCE:g} % in all three; "
                   f"largest errors: contact radius {100 * worst.a_error:.2f} %, peak pressure "
                   f"{100 * worst.p0_error:.2f} %, approach {100 * worst.approach_error:.2f} %.")
    winkler = table[table.case == "winkler"]
    report.section(f"A thin compliant layer on a stiff substrate (L = {WINKLER_SIZE:g} a) against "
                   "the Winkler limit")
    report.table(winkler, [
        Column("E2/E3", "E2/E3", "{:g}"), Column("h2/a", "h2/a", "{:g}"),
        Column("winkler_error", "P / Winkler's", signed_percent,
               "the force over pi M a^4 / (4 R h2) at the tool's contact radius, - 1"),
        Column("reference_winkler_error", "reference's P / Winkler's", signed_percent,
               "the same for the layered reference: the limit's own error"),
        ERRORS[0], ERRORS[1], *COST])
    report.finding("Against the Winkler limit the force is "
                   + ", ".join(f"{100 * r.winkler_error:+.2f} %" for r in winkler.itertuples())
                   + " (rows in order); the exact layered solution's own distance from the "
                   "limit is " + ", ".join(f"{100 * r.reference_winkler_error:+.2f} %"
                                          for r in winkler.itertuples())
                   + ": the limit's error, of order h2 / a, which the tool follows (its contact "
                   f"radius within {100 * winkler.a_error.abs().max():.2f} % of the reference's).")
    report.write(os.path.splitext(out)[0] + ".md")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join(RESULTS_DIR, "sphere_layered.csv"))
    args = parser.parse_args(argv)
    table, shift = study()
    table.to_csv(args.out, index=False)
    write_report(table, shift, args.out, argv)
    print(table.to_string(index=False))


if __name__ == "__main__":
    main()
