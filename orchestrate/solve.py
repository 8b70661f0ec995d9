"""One run: validate, mesh, start the workers, iterate, write the results.

Results of a run in its output folder:
    contact.csv    x1, sigma_n on S12 (sigma_12n / E, compression negative)
    interface.csv  x1, sigma_n on S23 (sigma_23n / E), sigma_t
    traces.csv     x1 and the interface displacements: u1n and w on S12 (outward normals),
                   (u1, u2) of the coating's bottom and of Omega3's top on S23
    history.csv    one row per Robin iteration
    summary.json   scene, settings, outcome, forces, timings (written last)
    omega1.vtu, omega3.vtu, coating.vtu   displacement (and stress) fields for ParaView
    omega1.csv, omega3.csv  x1, x2, u1, u2, sigma_eq at the P2 nodes of each body
    coating.csv    the same in the 2D coating (model elastic); coating_fields.csv holds
                   the shell's v, w, gamma, T11, T13, M11 (model shell)
Numbers that did not converge are never written as results: a run that diverges or
stagnates writes only history.csv and a summary.json that says why.
"""

import os
import tempfile
import time

import numpy as np

from . import freefem
from .contact import contact_half_width
from .labels import LABELS
from .outputs import read_reactions, write_csv, write_history, write_json, write_shell_vtu
from .robin import run_robin_loop
from .scene import to_dict
from .state import StateLayout
from .subdomains import start_subdomains, write_inputs


class RunFailed(RuntimeError):
    """The Robin loop diverged, stagnated or hit its iteration limit."""

    def __init__(self, summary):
        super().__init__(f"{summary['status']}: {summary['reason']}")
        self.summary = summary


def solve(scene, settings, out_dir, progress=None):
    """Solve the scene; write results into ``out_dir``; return the summary dict.

    Raises RunFailed (after writing the report) if the loop does not converge."""
    freefem.executable()             # a missing FreeFEM is reported before any work
    out_dir = os.path.abspath(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="robin-") as workdir:
        files, contact_points, bond_points = write_inputs(scene, settings, workdir)
        layout = StateLayout(contact_points.size)
        with start_subdomains(scene, settings, files, workdir, out_dir) as subdomains:
            setup_seconds = time.perf_counter() - start
            loop = run_robin_loop(subdomains.solve, layout, contact_points, scene, settings,
                                  progress)
            if loop.converged:
                subdomains.write_outputs()   # the workers hold the fields of the last solve
            dofs = subdomains.dofs
    wall_time = time.perf_counter() - start

    write_history(os.path.join(out_dir, "history.csv"), loop.history)
    summary = {
        "scene": to_dict(scene),
        "settings": to_dict(settings),
        "status": loop.status,
        "reason": loop.reason,
        "converged": loop.converged,
        "iterations": loop.iterations,
        "final_relative_change": loop.history[-1]["relative_change"],
        "wall_time_s": wall_time,
        "setup_time_s": setup_seconds,
        "time_per_iteration_s": (loop.history[-1]["seconds"] / loop.iterations),
        "active_set_changes": sum(row["active_set_changed"] for row in loop.history),
        "dofs": dofs,
    }
    if not loop.converged:
        write_json(os.path.join(out_dir, "summary.json"), summary)
        raise RunFailed(summary)

    summary.update(_write_results(scene, settings, layout, loop, contact_points,
                                  bond_points, out_dir))
    write_json(os.path.join(out_dir, "summary.json"), summary)
    return summary


def interface_stresses(layout, state, psi):
    """sigma_12n on S12 and the traction (sigma_t, sigma_n) on S23 (on Omega3's top).

    Each side's traction is what its own Robin condition imposed in the last solve; the
    two sides agree at convergence, and their mean is written. Off the contact set Psi
    the law says zero; the loop's residual traction there (the active-set loop holds
    inactive points with a Robin term) is of the order of eps_u and is not a stress."""
    sigma_12n = 0.5 * (layout.get(state, "t_upper_n") + layout.get(state, "t_coating_n"))
    sigma_12n = np.where(psi > 0, sigma_12n, 0.0)
    traction_23 = 0.5 * (layout.get(state, "t_lower_bond") - layout.get(state, "t_coating_bond"))
    return sigma_12n, traction_23


def _write_results(scene, settings, layout, loop, contact_points, bond_points, out_dir):
    """Interface stresses and forces of the converged state; return summary entries."""
    state = loop.state
    sigma_12n, traction_23 = interface_stresses(layout, state, loop.psi)
    write_csv(os.path.join(out_dir, "contact.csv"), {"x1": contact_points.x, "sigma_n": sigma_12n})
    write_csv(os.path.join(out_dir, "traces.csv"), {
        "x1": contact_points.x,
        "upper_n": layout.get(state, "upper_n"), "coating_n": layout.get(state, "coating_n"),
        "coating_u1": layout.get(state, "coating_bond")[0],
        "coating_u2": layout.get(state, "coating_bond")[1],
        "lower_u1": layout.get(state, "lower_bond")[0],
        "lower_u2": layout.get(state, "lower_bond")[1]})
    write_csv(os.path.join(out_dir, "interface.csv"),
              {"x1": bond_points.x, "sigma_n": traction_23[1], "sigma_t": traction_23[0]})
    if settings.model == "shell":
        write_shell_vtu(os.path.join(out_dir, "coating_fields.csv"),
                        scene.height + scene.h2 / 2, os.path.join(out_dir, "coating.vtu"))
    upper = read_reactions(os.path.join(out_dir, "omega1_reactions.txt"))
    lower = read_reactions(os.path.join(out_dir, "omega3_reactions.txt"))
    return {
        "contact_force": -contact_points.integrate(sigma_12n),
        "interface_force": -bond_points.integrate(traction_23[1]),
        "stamp_reaction": -upper[LABELS["Stamp"]][1],
        "base_reaction": lower[LABELS["Clamped"]][1],
        "peak_contact_stress": float(np.min(sigma_12n)),
        "peak_interface_stress": float(np.min(traction_23[1])),
        "contact_half_width": contact_half_width(contact_points.x, sigma_12n),
    }
