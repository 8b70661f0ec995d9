"""A cylinder on an uncoated block under a force load against plane-strain Hertz (not a
test; tests/studies/test_hertz.py checks one size).

Two bodies of the same material (E = 1, nu = 0.3): the indenter, whose lower face is a
circle of radius R = 40 b, pressed with the total force F per unit width (both halves;
the half model carries F/2) on a flat block clamped at its bottom; no coating. Both
bodies have half-width W and height H = W. For two half-spaces plane-strain Hertz gives

    E* = E / (2 (1 - nu^2))            (same E and nu on both sides)
    a  = sqrt(4 F R / (pi E*))         contact half-width
    p0 = 2 F / (pi a)                  peak pressure, on the axis
    p(x) = p0 sqrt(1 - x^2/a^2)

F is chosen so that a = 1 b (F = pi E* / (4 R), p0 = 2 F / pi). The finite bodies come
closer to half-spaces as W grows; the script separates that from the discretisation
(mesh levels 1-3) and from the penalty (theta). R = 40 so that the circular face spans
every size up to W = 32 (a circle's face cannot be wider than R); a/R = 1/40, and the
circle departs from Hertz's parabola by x^4/(8 R^3), 6e-4 of the gap at x = a.

Reported for every run, as relative errors against Hertz:
    peak        the solver's peak_contact_stress: the largest nodal contact pressure
    half_width  the solver's contact_half_width (edge of the loaded points, p^2 linear)
    axis        the pressure at x1 = 0, where the Hertz peak lies
    fit p0, fit a   p^2 = p0^2 (1 - x^2/a^2) fitted (least squares) to the loaded points
                with x < 0.8 a: the smooth part of the pressure, without the node-to-node
                noise of a single nodal value
The contact zone is [0, 2 a]: the interface (and the fine face mesh) stays short; a
contact that reached its end would fail the run.

The Robin loop is run to eps_u = 1e-9: at the default 1e-6 the nodal pressures carry
the loop's own error (the pressure is a difference of displacements over theta), a few
tenths of a per cent node to node, and on fine meshes a single node near the axis stood
up to 3 % above its neighbours (W = 8, level 3: peak +3.3 % at eps_u = 1e-6, +0.55 %
and smooth at 1e-10). The measured numbers are in results/hertz.csv and docs/findings.md.

    python -m studies.hertz                  # the study: prints a table, writes CSV
    python -m studies.hertz --sizes 4 8 --levels 1 --thetas 1e-3
"""

import argparse
import math
import os
import tempfile
import time

import numpy as np
import pandas as pd

from studies.paths import RESULTS_DIR
from orchestrate.model import Base, Indenter, Load, Scene, Settings
from orchestrate.run import solve_into as solve

E, NU = 1.0, 0.3
RADIUS = 40.0
HALF_WIDTH = 1.0                  # the Hertz half-width a the force is chosen for
ZONE = 2.0                        # contact_zone [0, ZONE a]
SIZES = (4.0, 8.0, 16.0, 32.0)
FIT_RANGE = 0.8                   # fit p^2 on x < FIT_RANGE a
EPS_U = 1e-9                      # the Robin loop's tolerance: see the docstring


def effective_modulus(E=E, nu=NU):
    """E* of two bodies of the same E and nu (plane strain)."""
    return E / (2.0 * (1.0 - nu ** 2))


def hertz_force(a=HALF_WIDTH, radius=RADIUS):
    """The total force per unit width that gives the half-width a."""
    return math.pi * effective_modulus() * a ** 2 / (4.0 * radius)


def hertz(force, radius=RADIUS):
    """(a, p0) of plane-strain Hertz for the total force per unit width."""
    a = math.sqrt(4.0 * force * radius / (math.pi * effective_modulus()))
    return a, 2.0 * force / (math.pi * a)


def hertz_scene(size, radius=RADIUS, force=None, zone=ZONE * HALF_WIDTH):
    """The half model: a cylinder face of ``radius`` on an uncoated block, both bodies
    ``size`` wide (half model) and high, under ``force`` (default: a = 1)."""
    force = hertz_force(radius=radius) if force is None else force
    return Scene(indenter=Indenter(radius=radius, profile="circle", width=size, height=size,
                                   E=E, nu=NU),
                 base=Base(shape="block", width=size, height=size, E=E, nu=NU),
                 coatings=(), load=Load(force=force), symmetric=True,
                 contact_zone=(0.0, zone))


def pressure_fit(x, pressure, a_estimate):
    """(p0, a) of p^2 = p0^2 (1 - x^2/a^2) fitted to the loaded points x < FIT_RANGE a."""
    keep = (pressure > 0) & (x < FIT_RANGE * a_estimate)
    slope, intercept = np.polyfit(x[keep] ** 2, pressure[keep] ** 2, 1)
    return math.sqrt(intercept), math.sqrt(-intercept / slope)


def compare(summary, contact, force, radius=RADIUS):
    """Relative errors against Hertz of a run's summary and contact.csv table."""
    a, p0 = hertz(force, radius)
    x, pressure = contact["x1"].to_numpy(), -contact["sigma_n"].to_numpy()
    order = np.argsort(x)
    x, pressure = x[order], pressure[order]
    fit_p0, fit_a = pressure_fit(x, pressure, summary["contact_half_width"])
    return {
        "peak_error": -summary["peak_contact_stress"] / p0 - 1.0,
        "half_width_error": summary["contact_half_width"] / a - 1.0,
        "axis_error": pressure[0] / p0 - 1.0,
        "fit_p0_error": fit_p0 / p0 - 1.0,
        "fit_a_error": fit_a / a - 1.0,
        "force_error": summary["total_force"] / force - 1.0,
    }


def run(size, mesh_level=1, theta=1e-3, radius=RADIUS, eps_u=EPS_U):
    """Solve the scene of ``size``; one row: settings, errors, cost."""
    scene = hertz_scene(size, radius)
    settings = Settings(mesh_level=mesh_level, theta=theta, eps_u=eps_u)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        summary = solve(scene, settings, out)
        contact = pd.read_csv(os.path.join(out, "contact.csv"))
    seconds = time.perf_counter() - start
    return {"size": size, "mesh_level": mesh_level, "theta": theta,
            **compare(summary, contact, scene.load.force, radius),
            "iterations": summary["iterations"], "dofs": sum(summary["dofs"].values()),
            "seconds": seconds}


def study_cases(sizes, levels, thetas):
    """Every size at level 1 and the first theta; the finer levels and other thetas on
    the two largest sizes."""
    cases = [(size, 1, thetas[0]) for size in sizes]
    for size in sizes[-2:]:
        cases += [(size, level, theta) for level in levels for theta in thetas
                  if (level, theta) != (1, thetas[0])]
    return cases


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=float, nargs="+", default=list(SIZES),
                        help="W = H of both bodies (b), at most below the radius 40")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2, 3],
                        help="mesh levels, on the two largest sizes")
    parser.add_argument("--thetas", type=float, nargs="+", default=[1e-3, 1e-4],
                        help="penalties; the first for the size trend")
    parser.add_argument("--out", default=str(RESULTS_DIR / "hertz.csv"))
    args = parser.parse_args(argv)
    a, p0 = hertz(hertz_force())
    print(f"R = {RADIUS:g}, F = {hertz_force():.6g}, Hertz a = {a:.6g}, p0 = {p0:.6g}")
    rows = []
    for size, level, theta in study_cases(args.sizes, args.levels, args.thetas):
        rows.append(run(size, level, theta))
        print({k: (f"{v:+.4%}" if k.endswith("_error") else v) for k, v in rows[-1].items()},
              flush=True)
    table = pd.DataFrame(rows)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    table.to_csv(args.out, index=False)
    shown = table.copy()
    for column in [c for c in shown.columns if c.endswith("_error")]:
        shown[column] = shown[column].map(lambda v: f"{100 * v:+.3f}%")
    shown["seconds"] = shown["seconds"].map(lambda v: f"{v:.1f}")
    with pd.option_context("display.width", 200):
        print(shown.to_string(index=False))
    print(f"\nwritten to {args.out}")


if __name__ == "__main__":
    main()
