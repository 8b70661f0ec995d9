"""Instrumented indentation of coated steel by a rigid ball: the indentation curve, the
pressure and the stresses on the bond, in the coating and in the substrate, for several
coatings, against the uncoated Hertz curve.

A rigid ball (R = 2 mm: a tungsten carbide or diamond ball, far stiffer than the part)
pressed on a steel cylinder (E 210 GPa, 1 mm radius and height, clamped at its bottom)
whose top carries a coating disc of the whole radius. The force rises in steps to
P_max = 20 N, which gives Hertz's contact radius a_max = 0.05 mm on bare steel; each
step is solved from the previous one's answer in kept workers (one mesh for the whole
curve, elements of a_max / 16 at the contact). The coatings: a compliant one (an
aluminium-like 70 GPa) and a hard one (TiN-like 450 GPa), each 5 um and 25 um thick
(a tenth and half of a_max), and the bare steel.

The approach is the ball's descent to the clamped bottom plus the far field a clamp at
depth L holds (c P / (E L), c measured on the bare steel, whose half-space approach is
Hertz's a^2 / R: studies/sphere_layered.py shows that correction holds to 0.01 %).
Hertz's curve for the bare steel: P = (4/3) E* sqrt(R) delta^(3/2), E* = E/(1 - nu^2).

Writes results/indentation.csv (one row per coating and load) and results/indentation.md.

    python -m studies.indentation
"""

import argparse
import math
import os
import time

import numpy as np
import pandas as pd

from studies.paths import RESULTS_DIR
from studies.report import Column, Report, command_line, seconds, signed_percent
from orchestrate.model import Base, Coating, Indenter, Load, Scene, Settings, Units

import orchestrate

BALL_RADIUS = 2.0                 # mm
STEEL_E, NU = 210e3, 0.3          # MPa
BODY = 1.0                        # mm: the cylinder's radius and height, 20 a_max
MAX_FORCE = 20.0                  # N
STEPS = (0.125, 0.25, 0.5, 0.75, 1.0)        # of MAX_FORCE
COATINGS = {"bare steel": None,
            "70 GPa, 5 um": (70e3, 0.005), "70 GPa, 25 um": (70e3, 0.025),
            "450 GPa, 5 um": (450e3, 0.005), "450 GPa, 25 um": (450e3, 0.025)}
COATING_NU = 0.25
UNITS = Units(length="mm", stress="MPa", b=0.05)


def hertz_radius(force):
    """Hertz's contact radius of the rigid ball on bare steel."""
    return (0.75 * force * BALL_RADIUS * (1 - NU ** 2) / STEEL_E) ** (1.0 / 3.0)


def hertz_approach(force):
    return hertz_radius(force) ** 2 / BALL_RADIUS


ELEMENT = hertz_radius(MAX_FORCE) / 16.0     # mm: one mesh for the whole curve


def hertz_subsurface(force):
    """(the largest von Mises stress under Hertz's sphere, its depth): on the axis,
    sigma_z = -p0 / (1 + z^2/a^2), sigma_r = sigma_theta = -p0 ((1 + nu)(1 - (z/a)
    arctan(a/z)) - 1 / (2 (1 + z^2/a^2))) (Johnson, Contact Mechanics, eq. 3.45), von
    Mises |sigma_r - sigma_z|, maximised over z."""
    a = hertz_radius(force)
    p0 = 1.5 * force / (math.pi * a ** 2)
    z = np.linspace(1e-4, 2.0, 200001) * a
    ratio = z / a
    sigma_z = -p0 / (1 + ratio ** 2)
    sigma_r = -p0 * ((1 + NU) * (1 - ratio * np.arctan(1 / ratio)) - 0.5 / (1 + ratio ** 2))
    mises = np.abs(sigma_r - sigma_z)
    k = int(np.argmax(mises))
    return float(mises[k]), float(z[k])


def ball_scene(force, coating):
    """The rigid ball on the steel cylinder, with a coating disc (E, thickness) or bare."""
    coatings = () if coating is None else (
        Coating(start=0.0, end=BODY, thickness=coating[1], E=coating[0], nu=COATING_NU,
                model="elastic"),)
    # the ball's face spans the cylinder: a coating may not reach beyond it
    return Scene(indenter=Indenter(radius=BALL_RADIUS, profile="circle", width=0.9 * BALL_RADIUS,
                                   height=BALL_RADIUS, rigid=True),
                 base=Base(width=BODY, height=BODY, E=STEEL_E, nu=NU), coatings=coatings,
                 load=Load(force=force), axisymmetric=True, units=UNITS)


def _value(entry):
    return None if entry is None else entry["value"]


def curve(name, coating, session):
    """One coating's rows, the force stepped up from the previous step's answer."""
    rows, previous = [], None
    settings = Settings(element_size=ELEMENT / UNITS.b)     # in b
    for step in STEPS:
        force = step * MAX_FORCE
        start = time.perf_counter()
        result = orchestrate.solve(ball_scene(force, coating), settings, session=session,
                                   start_from=previous)
        took = time.perf_counter() - start
        summary, answers = result.summary, result.answers
        bond = answers["bonds"].get("bond-coating1", {})
        coating_stress = answers["coatings"].get("coating1", {}).get("von_mises")
        substrate = answers["substrate"]["von_mises"]
        rows.append({"coating": name, "force": force, "descent": summary["descent"],
                     "contact_radius": summary["contact_half_width"],
                     "peak_pressure": -summary["peak_contact_stress"],
                     "bond_compression": _value(bond.get("compression")),
                     "bond_shear": _value(bond.get("shear")),
                     "bond_peel": _value(bond.get("peel")),
                     "coating_von_mises": _value(coating_stress),
                     "substrate_von_mises": substrate["value"],
                     "substrate_depth": substrate["depth"],
                     "hertz_radius": hertz_radius(force), "hertz_approach": hertz_approach(force),
                     "iterations": summary["iterations"], "seconds": took})
        previous = result
    return rows


def study():
    rows = []
    with orchestrate.Session() as session:
        for name, coating in COATINGS.items():
            rows += curve(name, coating, session)
    table = pd.DataFrame(rows)
    bare = table[table.coating == "bare steel"]
    clamp = float(np.mean((bare.hertz_approach - bare.descent) / bare.force))
    table["approach"] = table.descent + clamp * table.force
    table["hertz_force"] = (4.0 / 3.0 * STEEL_E / (1 - NU ** 2) * math.sqrt(BALL_RADIUS)
                            * table.approach ** 1.5)
    return table, clamp


def write_report(table, clamp, out, argv=None):
    report = Report("Indentation of coated steel by a rigid ball",
                    command_line("studies.indentation", argv),
                    data=[os.path.basename(os.path.splitext(out)[0]) + ".csv"])
    report.text(f"A rigid ball of radius {BALL_RADIUS:g} mm on a steel cylinder (E = "
                f"{STEEL_E / 1e3:g} GPa, nu = {NU:g}) {BODY:g} mm in radius and height, its top "
                f"coated (nu = {COATING_NU:g}), the force stepped to {MAX_FORCE:g} N, each step "
                f"from the last in kept workers; one mesh, interface elements of "
                f"{1e3 * ELEMENT:.3g} um; axisymmetric, 2D coating, default settings otherwise.")
    bare = table[table.coating == "bare steel"]
    report.finding("Bare steel against Hertz: contact radius "
                   + ", ".join(f"{100 * (r.contact_radius / r.hertz_radius - 1):+.2f} %"
                               for r in bare.itertuples())
                   + "; peak pressure at the largest force "
                   f"{100 * (bare.peak_pressure.iloc[-1] / (1.5 * MAX_FORCE / (math.pi * bare.hertz_radius.iloc[-1] ** 2)) - 1):+.2f} %; "
                   f"the clamp's far field c P / (E L) = {clamp:.4g} mm/N, added to every approach.")
    largest, depth = hertz_subsurface(MAX_FORCE)
    report.finding(f"Bare steel's largest von Mises stress at {MAX_FORCE:g} N: "
                   f"{bare.substrate_von_mises.iloc[-1]:.4g} MPa at {1e3 * bare.substrate_depth.iloc[-1]:.3g} um "
                   f"deep, Hertz's {largest:.4g} MPa at {1e3 * depth:.3g} um "
                   f"({100 * (bare.substrate_von_mises.iloc[-1] / largest - 1):+.2f} %; the depth is "
                   "a mesh node's).")
    report.table(table, [
        Column("coating", "coating"), Column("force", "P (N)", "{:g}"),
        Column("approach", "approach (um)", lambda v: f"{1e3 * v:.4g}",
               "the ball's descent plus the clamp's far field"),
        Column(lambda r: r["force"] / r["hertz_force"] - 1, "P / Hertz's P", signed_percent,
               "the force over bare steel's Hertz force at the same approach, - 1: the "
               "coating's stiffening (+) or softening (-)"),
        Column("contact_radius", "a (um)", lambda v: f"{1e3 * v:.4g}"),
        Column("peak_pressure", "p0 (MPa)", "{:.4g}"),
        Column("bond_compression", "bond compression (MPa)", "{:.4g}"),
        Column("bond_shear", "bond shear (MPa)", "{:.4g}"),
        Column("coating_von_mises", "coating von Mises (MPa)", "{:.4g}"),
        Column("substrate_von_mises", "substrate von Mises (MPa)", "{:.4g}"),
        Column("substrate_depth", "its depth (um)", lambda v: f"{1e3 * v:.3g}",
               "below the substrate's top face"),
        Column("iterations", "iterations", "{:g}"), Column("seconds", "time", seconds)])
    report.write(os.path.splitext(out)[0] + ".md")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join(RESULTS_DIR, "indentation.csv"))
    args = parser.parse_args(argv)
    table, clamp = study()
    table.to_csv(args.out, index=False)
    write_report(table, clamp, args.out, argv)
    print(table.to_string(index=False))


if __name__ == "__main__":
    main()
