"""The monolithic solve of the discrete penalised problem (freefem/monolithic.edp).

Every subdomain in one matrix, built by the workers' own FreeFEM includes, the contact
set iterated to a fixed point. It solves the same discrete problem as the Robin loop
(same forms, same interface points), which makes it the yardstick of the loop's
correctness."""

from dataclasses import replace
import os

import numpy as np

from orchestrate.files.folders import WorkFolder
from orchestrate.workers import freefem
from orchestrate.ddm.contact import bond_traction, contact_stress, limits_on_axis
from orchestrate.ddm.first_contact import predicted_contact
from orchestrate.ddm.state import StateLayout
from orchestrate.workers.problem_file import write_problem
from orchestrate.workers.subdomains import (geometry_arguments, tangential_arguments,
                                            write_inputs)
from orchestrate.run.plan import prepare


def solve_monolithic(problem, workdir, slip_origin=None, half_width=None):
    """The monolithic solution's traces, {(interface index, side): trace} (shapes as the
    Robin loop's), with "solves" and "descent". ``half_width``: the a priori contact
    half-width (b; Strategy.first_contact), whose points start the contact set's
    iteration, as they start the Robin loop's; else it starts from the points touched
    first. The answer is the same, in fewer solves (the gallery at mesh level 1: 8-29
    from the first point)."""
    files = write_inputs(problem, workdir)
    problem_file = os.path.join(workdir, "problem.txt")
    output = os.path.join(workdir, "monolithic_traces.txt")
    write_problem(problem, files, problem_file, slip_origin=slip_origin)
    first_set = _write_first_set(problem, half_width, os.path.join(workdir, "first_set.txt"))
    freefem.run_script("monolithic.edp", ["-problem", problem_file, "-output", output,
                                          *(["-firstset", first_set] if first_set else []),
                                          *geometry_arguments(problem.scene),
                                          *tangential_arguments(problem.scene.load)],
                       os.path.join(workdir, "monolithic.log"))
    tokens = open(output).read().split()
    traces, k = {}, 0
    for i, interface in enumerate(problem.interfaces):
        for side in (0, 1):
            arrays = []
            for _ in range(interface.components):
                n = int(tokens[k])
                arrays.append(np.array(tokens[k + 1:k + 1 + n], dtype=float))
                k += 1 + n
            traces[i, side] = arrays[0] if interface.components == 1 else np.array(arrays)
    solves, settled, descent = int(tokens[k]), int(tokens[k + 1]), float(tokens[k + 2])
    if not settled:
        raise RuntimeError(f"the monolithic contact set did not settle in {solves} solves")
    traces["solves"], traces["descent"], traces["shift"] = solves, descent, float(tokens[k + 3])
    k += 4
    for i, interface in enumerate(problem.interfaces):   # the friction states phi
        if interface.kind == "friction":
            n = int(tokens[k])
            traces["phi", i] = np.array(tokens[k + 1:k + 1 + n], dtype=float)
            k += 1 + n
    return traces


def _write_first_set(problem, half_width, path):
    """The a priori contact set of every contact interface (monolithic.edp's -firstset),
    written to ``path``; None where there is no estimate or no point within it."""
    layout = StateLayout(problem.interfaces)
    predicted = predicted_contact(problem, layout, half_width)
    if predicted is None or not np.any(predicted <= 1.0):
        return None
    with open(path, "w") as f:
        for _, rows in layout.contact_slices():
            psi = predicted[rows] <= 1.0
            f.write(f"{psi.size} " + " ".join("1" if p else "0" for p in psi) + "\n")
    return path


def interface_stresses(problem, traces):
    """{interface index: stress} from the traces by the penalty laws: a contact's
    sigma_n = (d - u_A - u_B)^- / theta, a bond's traction on the base (u_A - u_B)/theta
    as (sigma_t, sigma_n), a friction interface's -mu sigma_n of its contact."""
    theta, stresses = problem.penalty, {}
    for i, interface in enumerate(problem.interfaces):
        a, b = traces[i, 0], traces[i, 1]
        if interface.kind == "contact":
            stresses[i] = contact_stress(interface.gap, a, b, theta)
        elif interface.kind == "friction":
            # slipping (phi = +-1): phi mu p; sticking: the penalty's -(u_A + u_B)/theta
            contact = problem.interfaces[interface.contact]
            sigma_n = contact_stress(contact.gap, traces[interface.contact, 0],
                                     traces[interface.contact, 1], theta)
            phi = traces["phi", i]
            origin = traces.get(("origin", i), 0.0)
            stresses[i] = np.where(sigma_n < 0, np.where(
                phi != 0, -phi * interface.friction * sigma_n, (origin - a - b) / theta), 0.0)
        else:
            stresses[i] = bond_traction(a, b, theta)
        stresses[i] = limits_on_axis(interface, stresses[i])
    return stresses


def monolithic_of(problem, before=(), half_width=None):
    """The monolithic solution of a discrete problem (a run's plan's, say), in a private
    folder: its traces (solve_monolithic) and interface stresses, in b and E; its contact
    set started from the points within ``half_width`` (b), if given. On a load path
    (Scene.load.path), ``before``: the (problem, half_width) of its earlier steps, in
    order, each solved from the friction slips of the one before (its sticking points
    keep them)."""
    # removed after a killed process too (a study killed by SIGTERM left them)
    with WorkFolder(WorkFolder.MONOLITHIC_PREFIX) as workdir:
        origin = None
        for number, (step, step_half_width) in enumerate(before, start=1):
            step_dir = os.path.join(workdir, f"step{number}")
            os.makedirs(step_dir)
            solved = solve_monolithic(step, step_dir, origin, step_half_width)
            origin = {i: solved[i, 0] + solved[i, 1] for i, f in enumerate(step.interfaces)
                      if f.kind == "friction"}
        traces = solve_monolithic(problem, workdir, origin, half_width)
        traces.update({("origin", i): value for i, value in (origin or {}).items()})
    return traces, interface_stresses(problem, traces)


def monolithic_solution(scene, settings):
    """The monolithic solution of a scene: the problem a run of it solves (its plan's:
    in b and E, every "auto" patch's model chosen), its traces and interface stresses;
    its contact set started from the run's a priori set (Strategy.first_contact)."""
    plan = prepare(scene, settings)
    before, step = [], scene.step_before()
    while step is not None:          # a load path's earlier steps, last first
        step_plan = prepare(step, settings)
        before.insert(0, (step_plan.problem, step_plan.strategy.first_contact))
        step = step.step_before()
    return (plan.problem, *monolithic_of(plan.problem, before, plan.strategy.first_contact))


def monolithic_curves(scene, settings):
    """x1, sigma_12n and sigma_23n of the monolithic solve of a scene of the paper's kind
    (one contact interface, one bond), and its number of solves."""
    problem, traces, stresses = monolithic_solution(scene, settings)
    contact, bond = problem.contacts[0], problem.bonds[0]
    return (contact.position[:, 0], stresses[problem.interfaces.index(contact)],
            stresses[problem.interfaces.index(bond)][1], traces["solves"])
