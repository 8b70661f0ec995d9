"""One run: validate, mesh, start the workers, iterate, write the results.

Results of a run in its output folder, each file written once, in the scene's units (b
and E unless its file has a [units] table; summary.json's "units" names the unit of
every column; orchestrate/run/outputs.py):
    contact.csv    every contact interface's points: interface, x1, x2, s (arc length
                   along the base's face), sigma_n (normal stress, compression negative),
                   sigma_t (the friction traction on the base along the face's tangent:
                   mu p under sliding, 0 without friction)
    interface.csv  every bond's points: interface, x1, x2, s, sigma_n, sigma_t (the
                   traction on the base, in the face's normal and tangential components)
    traces.csv     interface, x1, x2, s and each side's displacement trace: a_n, b_n (a
                   contact: along each side's outward normal; under friction also a_t,
                   b_t, along each side's tangent, -t and t), a_t, a_n, b_t, b_n (a bond:
                   the coating's and the base's, in the face's components)
    history.csv    one row per Robin iteration
    summary.json   scene, settings, outcome, answers, forces, peaks, contact zones, units
                   (written last)
    NAME.csv, NAME_cells.csv, NAME_reactions.txt, NAME.vtu   each body's fields (indenter,
                   base, 2D coating patches coatingI): x1, x2, u1, u2, sigma_eq, s11, s22,
                   s12, s33 at the P2 nodes (recovered stresses, freefem/recovery.idp), the
                   P2 triangles as six node rows each, the consistent reactions on its
                   supports (label, R1, R2), and all of it as quadratic VTU
    coatingI_fields.csv, coatingI.vtu   a shell patch's xi, x1, x2, v, w, gamma, epsilon,
                   T11, T13, M11, T33 along its mid-line (a shell of revolution's xi = r,
                   x1, x2, u, w, beta, epsilon, N_r, N_theta, Q, M_r, M_theta, N_z); the
                   VTU adds its fibre stresses
    run.pvd        opens every VTU of the run together in ParaView
Numbers that did not converge are never written as results: a run that diverges or
stagnates writes only history.csv and a summary.json that says why.
"""

import contextlib
from dataclasses import replace
import math
from pathlib import Path
import time
from types import SimpleNamespace

import numpy as np

from orchestrate.ddm.contact import (contact_half_width, contact_zones, limits_on_axis,
                                     stick_zones)
from orchestrate.ddm.robin import run_robin_loop
from orchestrate.ddm.state import StateLayout
from orchestrate.errors import RunFailed, WarnedBeforeWork  # noqa: F401  (callers import them here)
from orchestrate.faults import checkpoint
from orchestrate.files.folders import RunFolder, WorkFolder
from orchestrate.mesh.labels import LABELS
from orchestrate.model.scene import to_dict
from orchestrate.model.units import scaled_summary
from orchestrate.run import answers
from orchestrate.run.coarse_level import CoarseLevel
from orchestrate.run.outputs import RunFiles, history_table, shell_table
from orchestrate.run.plan import prepare
from orchestrate.run.validity import (Say, edge_peak, elements_across, forms_edited_warning,
                                      run_warnings)
from orchestrate.run.warm_start import calibrated_half_width, start_state
from orchestrate.workers import freefem
from orchestrate.workers.provenance import forms_hashes, provenance
from orchestrate.workers.session import Session
from orchestrate.workers.subdomains import start_subdomains, written_inputs


def solve(scene, settings, out_dir, progress=None, overwrite=False, start_from=None,
          session=None, sweep_point=None, start_name=None, strict=False):
    """Solve the scene; write results into ``out_dir``; return the summary dict
    (solve_run's, which says the rest)."""
    return solve_run(scene, settings, out_dir, progress=progress, overwrite=overwrite,
                     start_from=start_from, session=session, sweep_point=sweep_point,
                     start_name=start_name, strict=strict).summary


def solve_run(scene, settings, out_dir, progress=None, overwrite=False, start_from=None,
              session=None, sweep_point=None, start_name=None, strict=False, keep=False):
    """Solve the scene; write results into ``out_dir``; return the run's files
    (outputs.py's RunFiles: its summary and tables in memory, and with ``keep`` every
    file's bytes).
    ``start_from``: a finished run (its folder, or the API's Result) whose interface state
    is the first iterate (orchestrate/run/warm_start.py: a run of this layout of bodies
    and interfaces, checked before any work; not used where a coarse level starts the
    run from its own solution of the scene); ``start_name``: what the summary calls it
    (default: its path). ``session``: a Session (orchestrate/workers/session.py) that
    keeps workers from scene to scene; without one, the run's workers stop with it.
    ``sweep_point``: the sweep and inputs a sweep's run records (orchestrate/sweeps/
    sweep.py), or None. ``strict``: WarnedBeforeWork for the warnings known before any
    work (validity.py).

    Before any work: ParameterError for a scene the settings cannot solve, a problem
    too large for the machine, or an output folder another run holds or is writing
    (``overwrite`` replaces an earlier run's folder whole). Then RunFailed (after
    writing the report) if the loop does not converge, SystemFailure if a worker or a
    file fails. The folder appears only once complete (orchestrate/files/folders.py).

    A patch whose model auto chose as a shell, on which the run finds the contact
    pressure peaking at its zone's edge (validity.edge_peak: an answer the shells'
    estimate does not cover), is solved again with the 2D coating before anything is
    written; summary.json's model_choice says so in its entry (fallback_from, _reason)."""
    freefem.executable()             # a missing FreeFEM is reported before any work
    fallbacks, before = [], None
    step_before = scene.step_before()
    with (Session(map_kept=False) if step_before is not None and session is None
          else contextlib.nullcontext(session)) as session:
        if step_before is not None:  # a load path: the steps before, workers kept between
            before = _step_before(step_before, settings, progress, start_from, session)
            start_from, start_name = before, "the load path's step before (load.path)"
        while True:
            try:
                return _solve_once(scene, settings, out_dir, progress, overwrite, start_from,
                                   session, sweep_point, start_name, strict, keep, fallbacks,
                                   before)
            except _ModelFallback as fallback:
                fallbacks.append(fallback.record)
                scene = scene.with_models(["elastic" if n == fallback.record["patch"]
                                           else c.model
                                           for n, c in enumerate(scene.coatings, start=1)])


def _step_before(scene, settings, progress, start_from, session):
    """A load path's step before the scene's own (Scene.step_before: solved, in a folder
    of its own, from the steps before it in turn): its summary and tables, which start
    the next step, whose sticking points stay where they stood at its end (robin.
    robin_laws' slip_origin). RunFailed where it does not converge, saying which step."""
    with WorkFolder() as scratch:
        try:
            files = solve_run(scene, settings, Path(scratch) / "step", progress=progress,
                              start_from=start_from, session=session, keep=True)
        except RunFailed as failed:
            number = len(scene.load.earlier_steps) + 1
            raise RunFailed(dict(failed.summary, reason=(
                f"the load path's step {number} (load.path: force {scene.load.force:g}, "
                f"{scene.load.tangential_kind.replace('_', ' ')} {scene.load.tangential:g}): "
                f"{failed.summary['reason']}"))) from None
    import pandas as pd     # here: a run without a load path needs no pandas

    tables = {name: pd.DataFrame(files.tables.get(f"{name}.csv", {}))
              for name in ("contact", "interface", "traces")}
    return SimpleNamespace(summary=files.summary, **tables)


def _load_steps(before):
    """summary.json's load_steps: every earlier step of a load path (``before``: the
    last of them, solved), in the scene's units."""
    if before is None:
        return None
    summary = before.summary
    return (summary.get("load_steps") or []) + [dict(
        force=summary["scene"]["load"]["force"],
        **{key: summary[key] for key in ("tangential_force", "stamp_shift", "iterations",
                                         "descent", "stick_zones", "wall_time_s")})]


class _ModelFallback(Exception):
    """An "auto" patch whose shell the run found outside its estimate (its record)."""

    def __init__(self, record):
        super().__init__(record["reason"])
        self.record = record


def _auto_fallback(model_choice, problem, results, contact_x1, contact_stress):
    """The record of an "auto" patch to solve again with the 2D coating (None: none):
    the contact pressure peaks at its zone's edge on a shell auto chose."""
    if model_choice is None:
        return None
    found = edge_peak(problem, results["answers"]["contact"].get("peak_pressure"),
                      results["contact_zones"], contact_x1, contact_stress)
    chosen = {patch["patch"]: patch for patch in model_choice["patches"]}
    if not found or found[0] not in chosen:
        return None
    return {"patch": found[0], "model": chosen[found[0]]["model"], "report": model_choice,
            "reason": "the contact pressure peaks near the edge of its contact zone on the "
                      "patch, where the shells' estimate does not hold (edge_contact_peak)"}


def _with_fallbacks(report, fallbacks):
    """The model choice's report of a run solved again (``report``: its own choice of
    the patches still "auto", or None): the first choice's, every patch as solved, a
    fallen-back patch's entry saying the model auto chose first, its estimate and why it
    was left, its estimated_error the 2D coating's (summary.json's wall_time_s counts the
    runs left)."""
    first = fallbacks[0]["report"]
    patches = {patch["patch"]: patch for patch in first["patches"]}
    patches.update((patch["patch"], patch) for patch in (report or {}).get("patches", []))
    for fallback in fallbacks:
        chosen = patches[fallback["patch"]]
        patches[fallback["patch"]] = dict(chosen, model="elastic", estimated_error=0.0,
                                          fallback_from=fallback["model"],
                                          fallback_estimated_error=chosen["estimated_error"],
                                          fallback_reason=fallback["reason"])
    return dict(first, patches=[patches[n] for n in sorted(patches)])


def _solve_once(scene, settings, out_dir, progress, overwrite, start_from, session,
                sweep_point, start_name, strict, keep, fallbacks, before=None):
    """solve_run's run of one choice of models (``fallbacks``: the patches solved again
    with the 2D coating so far; ``before``: a load path's step before, whose state
    ``start_from`` is): _ModelFallback for a patch to solve again, before its folder is
    written."""
    plan = prepare(scene, settings)
    if strict and plan.warnings:
        raise WarnedBeforeWork(list(plan.warnings))
    scene, problem, model_choice, scales = plan.scene, plan.problem, plan.model_choice, plan.scales
    strategy = plan.strategy         # how it is solved, decided once (ddm/strategy.py)
    start = (start_state(start_from, StateLayout(problem.interfaces))
             if start_from is not None else None)         # checked before any work
    if (start is not None and strategy.first_contact and not scene.frictional
            and not strategy.two_levels):
        # the neighbour's answer calibrates this run's a priori set (friction keeps the
        # neighbour's set: its states and slips go with it; two levels start from their
        # coarse level's solution, not from the neighbour)
        calibrated = calibrated_half_width(start_from, strategy.first_contact)
        if calibrated is not None:
            strategy = replace(strategy, first_contact=calibrated,
                               first_contact_over_start=True)
    slip_origin = None
    if before is not None:           # the slips the step before left (robin_laws)
        layout = StateLayout(problem.interfaces)
        slip_origin = np.concatenate([np.zeros(0)] + [
            layout.get(start, "u", i, 0) + layout.get(start, "u", i, 1)
            for i in layout.friction_indices])
    forms = forms_hashes()           # what the workers started now will compile
    started = time.perf_counter()
    with (RunFolder(out_dir, overwrite) as folder, WorkFolder() as workdir,
          contextlib.nullcontext(session) if session is not None else Session() as workers,
          workers.lock,                          # one scene at a time per session
          CoarseLevel(problem, plan.coarse, strategy.knobs.coarse_newton_steps)  # probes
          if strategy.two_levels else contextlib.nullcontext() as coarse_level):  # meanwhile
        scratch = str(folder.scratch)
        # each worker starts once its files are written: it assembles while the next mesh is made
        files = written_inputs(problem, workdir, strategy.workers)
        with start_subdomains(problem, settings, files, workers, strategy.workers,
                              strategy.inner_solve.planned == "iterate") as subdomains:
            if strategy.inner_solve.pending:    # auto: whether the maps pay, on the workers' sizes
                strategy = strategy.decided(subdomains.solves_directly, subdomains.map_costs())
            setup_seconds = time.perf_counter() - started
            checkpoint("setup")
            coarse = None
            if coarse_level is not None:        # a fine mesh: iterated with two levels
                coarse = coarse_level.correction(strategy.bonds_inside)
                coarse_level.close()
            # a coarse level solves this very scene's contact problem: a better start than
            # a neighbour's answer (fewer contact sets: measured 1-2 against 0-9 at level 3)
            first_iterate = start if coarse is None else None
            loop = run_robin_loop(subdomains.solve, problem, strategy, progress, first_iterate,
                                  subdomains.robin_maps, coarse, slip_origin)
            inner_solve_used = _inner_solve_used(loop.history, coarse is not None)
            fallback = None
            if (not loop.converged and loop.status in FALLBACK_STATUSES
                    and strategy.inner_solve.fallback == "direct"
                    and inner_solve_used != "direct"):
                # auto chose to iterate, and the iteration stalled or diverged (extreme
                # moduli): each contact set solved directly from the maps instead
                fallback = {"inner_solve": inner_solve_used, "status": loop.status,
                            "reason": loop.reason, "iterations": loop.iterations}
                subdomains.solve_directly()
                earlier = loop.history
                loop = run_robin_loop(subdomains.solve, problem, strategy, progress,
                                      first_iterate, subdomains.robin_maps,
                                      slip_origin=slip_origin)
                for row in loop.history:
                    row["iteration"] += len(earlier)
                loop.history = earlier + loop.history
                loop.iterations = len(loop.history)
                inner_solve_used = f"{fallback['inner_solve']} ({fallback['status']}), then direct"
            loop_seconds = time.perf_counter() - started - setup_seconds
            if loop.converged:
                reached = zone_end_reached(problem, loop.psi)
                if reached is not None:
                    loop.converged, loop.status = False, "contact_zone"
                    loop.reason = (f"the contact reaches the end of contact_zone at x1 = "
                                   f"{reached:g}: contact beyond it was assumed away; widen it")
            # the workers hold the fields of the last solve
            outputs = subdomains.outputs() if loop.converged else None
            stamp_shift = subdomains.shift
            dofs = subdomains.dofs
            kept = subdomains.kept
        summary = {
            "scene": to_dict(scene),         # as solved: "auto" patches with their model
            "settings": to_dict(settings),
            "strategy": strategy.record(scales, scene.units),
            "model_choice": (_with_fallbacks(model_choice, fallbacks) if fallbacks
                             else model_choice),
            "status": loop.status,
            "reason": loop.reason,
            "converged": loop.converged,
            "stamp_shift": stamp_shift if scene.partial_slip else None,
            # a load path's earlier steps, in the scene's units
            "load_steps": _load_steps(before),
            "iterations": loop.iterations,
            "final_relative_change": loop.history[-1]["relative_change"],
            "error_estimate": loop.error_estimate,
            "wall_time_s": None,
            "setup_time_s": setup_seconds,
            "loop_time_s": loop_seconds,
            "outputs_time_s": None,
            "time_per_iteration_s": (loop.history[-1]["seconds"] / loop.iterations),
            "active_set_changes": sum(row["active_set_changed"] for row in loop.history),
            "inner_solve_used": inner_solve_used,
            "inner_solve_fallback": fallback,
            "started_from": (start_name or str(start_from) if first_iterate is not None
                             and settings.method != "paper" else None),
            "dofs": dofs,
            # the interface elements as sized (Settings.sized_to), at the contact and away
            # (a thin 2D coating refines its face further: contact_element_size)
            "interface_element_size": problem.settings.element_size / problem.settings.mesh_level,
            "interface_element_size_far": ((problem.settings.element_size_far or
                                            problem.settings.element_size)
                                           / problem.settings.mesh_level),
            "workers_kept": kept,
            "provenance": provenance(forms),
            "sweep_point": sweep_point,
            "warnings": list(plan.warnings),
        }
        run_files = RunFiles(scratch, scales, keep)
        run_files.table("history.csv", history_table(loop.history))
        if loop.converged:
            results, contact_x1, contact_stress = _write_results(problem, loop, outputs,
                                                                 run_files)
            model_fallback = _auto_fallback(model_choice, problem, results, contact_x1,
                                            contact_stress)
            if model_fallback is not None:    # the folder is discarded, not committed
                model_fallback["seconds"] = time.perf_counter() - started
                raise _ModelFallback(model_fallback)
            summary.update(results)
            summary["warnings"] += run_warnings(problem, results, contact_x1, contact_stress,
                                                Say(scales, scene.units))
        if forms_hashes() != forms:
            summary["warnings"].append(forms_edited_warning())
        summary = scaled_summary(summary, scales)
        summary["outputs_time_s"] = time.perf_counter() - started - setup_seconds - loop_seconds
        summary["wall_time_s"] = (time.perf_counter() - started    # with the runs left
                                  + sum(fallback["seconds"] for fallback in fallbacks)
                                  + (before.summary["wall_time_s"] if before else 0.0))
        run_files.write_summary(summary, scene.units)
        checkpoint("committing")
        folder.commit()
    if not loop.converged:
        raise RunFailed(run_files.summary)
    return run_files


# An iterated inner solve that auto chose and that ended so falls back to the direct solve
FALLBACK_STATUSES = ("diverged", "stagnated")


def _inner_solve_used(history, two_levels):
    """How the loop reached its contact sets' fixed points: "direct", "iterate" or
    "two-level" (iterated with a coarse correction), or "direct, then ..." (a system too
    ill-conditioned to solve directly)."""
    direct = [row["direct"] for row in history]
    if all(direct):
        return "direct"
    iterated = "two-level" if two_levels else "iterate"
    return f"direct, then {iterated}" if direct[0] else iterated


def zone_end_reached(problem, psi):
    """x1 of an end of the user's contact_zone that the contact set reaches, if that end
    is not also the end of a face (there contact stops anyway), else None."""
    scene = problem.scene
    if scene.contact_zone is None or not len(psi) or not problem.contacts:
        return None
    contacts = problem.contacts
    last = sum(c.size for c in contacts) - 1       # the friction states come after
    ends = [(contacts[0].position[0, 0], psi[0]), (contacts[-1].position[-1, 0], psi[last])]
    indenter, base = scene.indenter, scene.base
    low = 0.0 if scene.symmetric else max(indenter.centre - indenter.width, -base.top)
    high = min(indenter.width if scene.symmetric else indenter.centre + indenter.width, base.top)
    for (x1, active), face_end in zip(ends, (low, high)):
        if active > 0 and abs(x1 - face_end) > 1e-9 * (1.0 + abs(face_end)):
            return float(x1)
    return None


def interface_stresses(layout, state, psi):
    """{interface index: stress} of the state: on a contact sigma_n (points,), on a bond
    the traction on the base (sigma_t, sigma_n) (2, points), on a friction interface
    the friction traction on the base along the face's tangent (points,).

    Each side's traction is what its own Robin condition imposed in the last solve; the
    two sides agree at convergence, and their mean is written. Off the contact set Psi
    the law says zero; the loop's residual traction there (the active-set loop holds
    inactive points with a Robin term) is of the order of eps_u and is not a stress."""
    stresses = {}
    psi_of = dict((i, psi[where]) for i, where in layout.contact_slices())
    for i, interface in enumerate(layout.interfaces):
        t_a, t_b = layout.get(state, "t", i, 0), layout.get(state, "t", i, 1)
        if interface.kind in ("contact", "friction"):
            active = psi_of[i if interface.kind == "contact" else interface.contact] > 0
            stresses[i] = np.where(active, 0.5 * (t_a + t_b), 0.0)
        else:
            stresses[i] = 0.5 * (t_b - t_a)
        stresses[i] = limits_on_axis(interface, stresses[i])
    return stresses



def _write_results(problem, loop, outputs, run_files):
    """Write the interface stresses and traces of the converged state and every
    subdomain's fields (``outputs``: Subdomains.outputs()) into ``run_files``; return
    (summary entries: answers, forces, peaks, the contact zones, ...; the contact points'
    x1 and normal stresses), in b and E."""
    layout = StateLayout(problem.interfaces)
    state = loop.state
    stresses = interface_stresses(layout, state, loop.psi)
    contact_rows, bond_rows, trace_rows = [], [], []
    friction_of = {f.contact: i for i, f in enumerate(problem.interfaces) if f.kind == "friction"}
    for i, interface in enumerate(problem.interfaces):
        where = {"interface": [interface.name] * interface.size,
                 "x1": interface.position[:, 0], "x2": interface.position[:, 1], "s": interface.s}
        u_a, u_b = layout.get(state, "u", i, 0), layout.get(state, "u", i, 1)
        if interface.kind == "contact":
            k = friction_of.get(i)
            none = np.full(interface.size, np.nan)
            contact_rows.append({**where, "sigma_n": stresses[i], "sigma_t": (
                np.zeros(interface.size) if k is None else stresses[k])})
            trace_rows.append({
                **where, "a_t": none if k is None else layout.get(state, "u", k, 0), "a_n": u_a,
                "b_t": none if k is None else layout.get(state, "u", k, 1), "b_n": u_b})
        elif interface.kind == "friction":
            continue                    # the contact's rows carry it
        else:
            bond_rows.append({**where, "sigma_n": stresses[i][1], "sigma_t": stresses[i][0]})
            trace_rows.append({**where, "a_t": u_a[0], "a_n": u_a[1], "b_t": u_b[0], "b_n": u_b[1]})
    where = ("interface", "x1", "x2", "s")
    run_files.table("contact.csv", _stack(contact_rows, where + ("sigma_n", "sigma_t")))
    run_files.table("interface.csv", _stack(bond_rows, where + ("sigma_n", "sigma_t")))
    run_files.table("traces.csv", _stack(trace_rows, where + ("a_t", "a_n", "b_t", "b_n")))
    fields = {}                          # what the answers read of each patch
    for name, subdomain in problem.subdomains.items():
        if subdomain.kind == "shell":
            fields[name] = shell_table(outputs[name].columns, subdomain.plan)
            run_files.shell(name, fields[name], subdomain.plan)
        else:
            fields[name] = outputs[name].columns
            run_files.body(name, outputs[name])
    run_files.collection(problem.subdomains)

    per_interface, contact_force, interface_force, tangential_force = {}, 0.0, 0.0, 0.0
    for i, interface in enumerate(problem.interfaces):
        if interface.kind == "contact":
            # the traction on the base: sigma_n n + sigma_t t (friction's sigma_t)
            k = friction_of.get(i)
            sigma_t = np.zeros(interface.size) if k is None else stresses[k]
            force = -interface.integrate(stresses[i] * interface.normal[:, 1]
                                         + sigma_t * interface.tangent[:, 1])
            tangential_force += interface.integrate(stresses[i] * interface.normal[:, 0]
                                                    + sigma_t * interface.tangent[:, 0])
            contact_force += force
            peak = float(np.min(stresses[i]))
        elif interface.kind == "friction":
            continue
        else:
            sigma_t, sigma_n = stresses[i]
            force = -interface.integrate(sigma_n * interface.normal[:, 1]
                                         + sigma_t * interface.tangent[:, 1])
            interface_force += force
            peak = float(np.min(sigma_n))
        per_interface[interface.name] = {"force": force, "peak_normal_stress": peak}
    contact = [stresses[i] for i in layout.contact_indices]
    x_contact = np.concatenate([problem.interfaces[i].position[:, 0] for i in layout.contact_indices])
    sigma_contact = np.concatenate(contact)
    bonds = [stresses[i][1] for i, f in enumerate(problem.interfaces) if f.kind == "bond"]
    scene = problem.scene
    zones = contact_zones(x_contact, sigma_contact)
    across = elements_across(x_contact, scene.symmetric, zones)
    return ({
        "answers": _answers(problem, contact_rows, bond_rows, fields),
        "contact_force": contact_force,
        # the x1 force of the indenter on the base (friction drags it towards +x1; the
        # halves of a half model cancel)
        "tangential_force": 0.0 if problem.scene.symmetric else tangential_force,
        "interface_force": interface_force,
        "stamp_reaction": -outputs["indenter"].reactions[LABELS["Stamp"]][1],
        # the x1 force the stamp carries (a given shift's answer; the halves of a half
        # model cancel; a rigid indenter carries the contact's, its only load)
        "stamp_tangential_force": (0.0 if problem.scene.symmetric else tangential_force
                                   if problem.scene.indenter.rigid else
                                   outputs["indenter"].reactions[LABELS["Stamp"]][0]),
        "base_reaction": outputs["base"].reactions[LABELS["Clamped"]][1],
        "peak_contact_stress": float(np.min(sigma_contact)),
        "peak_interface_stress": float(np.min(np.concatenate(bonds))) if bonds else None,
        "contact_half_width": _half_width(scene, x_contact, sigma_contact, zones),
        "contact_zones": [list(zone) for zone in zones],
        "elements_across_contact": [count for count, _ in across],
        # as meshed: finer than interface_element_size where a thin 2D coating refines
        # its face (its cells' aspect at the contact's edges)
        "contact_element_size": [length for _, length in across],
        "descent": loop.descent,
        "stick_zones": _stick_zones(problem, layout, loop.psi, stresses),
        "total_force": (2.0 if scene.symmetric and not scene.axisymmetric else 1.0) * contact_force,
        "interfaces": per_interface,
        # the faces' normals over the contact: the pairing assumes them opposite
        "normal_mismatch_deg": math.degrees(max(
            (float(np.max(problem.interfaces[i].mismatch[stresses[i] < 0]))
             for i in layout.contact_indices if np.any(stresses[i] < 0)), default=0.0)),
    }, x_contact, sigma_contact)


def _stick_zones(problem, layout, psi, stresses):
    """Under partial slip, the x1 intervals where the bodies stick (contact.stick_zones);
    else None."""
    if not problem.scene.partial_slip:
        return None
    contacts = dict(layout.contact_slices())
    x, stick, margin = [], [], []
    for i, where in layout.friction_slices():
        face = problem.interfaces[i]
        pressure = -stresses[face.contact]
        x.append(face.position[:, 0])
        stick.append((psi[contacts[face.contact]] > 0) & (psi[where] == 0))
        margin.append(face.friction * pressure - np.abs(stresses[i]))
    x, stick, margin = (np.concatenate(v) for v in (x, stick, margin))
    order = np.argsort(x, kind="stable")
    return [list(zone) for zone in stick_zones(x[order], stick[order], margin[order])]


def _answers(problem, contact_rows, bond_rows, fields):
    """orchestrate/run/answers.py's values of the run: the contact, every bond (by its
    interface's name) and every patch (by its subdomain's name; ``fields``: its nodes'
    or its mid-line's columns)."""
    scene = problem.scene
    contact = _stack(contact_rows, ("x1", "x2", "sigma_n"))
    bonds = {row["interface"][0]: answers.bond_answers(scene, row["x1"], row["x2"],
                                                       row["sigma_n"], row["sigma_t"])
             for row in bond_rows}
    coatings = {}
    for name, subdomain in problem.subdomains.items():
        if not name.startswith("coating"):
            continue
        patch = scene.coatings[int(name[len("coating"):]) - 1]
        if subdomain.kind == "shell":
            coatings[name] = answers.shell_answers(scene, patch, fields[name])
        else:
            coatings[name] = answers.coating_answers(scene, fields[name], patch)
    return {"contact": answers.contact_answers(scene, contact["x1"], contact["x2"],
                                               contact["sigma_n"]),
            "bonds": bonds, "coatings": coatings,
            "substrate": answers.substrate_answers(scene, fields["base"])}


def _half_width(scene, x, sigma, zones):
    """A half model: the end of the zone on the axis; a full model: half the length of
    the zone under the indenter's lowest point."""
    if scene.symmetric:
        return contact_half_width(x, sigma)
    for start, end in zones:
        if start <= scene.indenter.centre <= end:
            return 0.5 * (end - start)
    return 0.0


def _stack(rows, columns):
    """One table of the given columns from tables that have them."""
    return {name: np.concatenate([np.asarray(r[name]) for r in rows]) if rows else []
            for name in columns}
