"""The Robin domain decomposition loop (21)-(24) on the interface state.

Each iteration turns the interface state x (orchestrate/state.py) into the Robin
coefficient alpha and data g of every subdomain, lets the three workers solve at once
(each solves sigma_n(u) + alpha u = alpha g on its interfaces), and forms the new state
from their traces and tractions. Two loops are offered (Settings.method):

``paper``: the paper's loop. Robin coefficient gamma = 1/theta, contact set Psi12 from
    the current iterate at every iteration (20), fixed relaxation (24):
    x^{k+1} = rho x~^{k+1} + (1 - rho) x^k. Relaxing the traces is the paper's
    relaxation of the whole fields: every right-hand side depends on the fields through
    their traces only, linearly. Stops when the relative change of the displacement
    traces (discrete L2 over S12 and S23) is below eps_u.

``active-set`` (default): the same Robin solves with a free Robin parameter gamma, the
    Robin coefficient on all of S12 (inactive points get their own trace as data, so
    no matrix ever changes), and two nested loops. Inside, Psi is frozen, so the map
    x -> x~ is affine, and Anderson acceleration (orchestrate/acceleration.py) drives it
    to its fixed point. Outside, Psi is updated from that fixed point (a semi-smooth
    Newton step: an active point is released where the contact traction turns tensile,
    an inactive one enters where the bodies interpenetrate), the history restarts, and
    the loop goes on until Psi no longer changes and the fixed-point residual
    ||x~ - x|| / ||x~|| is below eps_u.

Robin parameter. The paper's Robin coefficient is the penalty itself, gamma = 1/theta;
its loop then contracts like 1 - O(theta E / b) per iteration (hundreds of thousands of
iterations at a penalty small enough to be accurate). A free gamma uses the Robin-Robin
exchange of Lions for the penalised laws: each side receives gamma times the
displacement the interface law asks of it, plus the neighbour's traction weighted by
(1 - gamma theta). For gamma = 1/theta the neighbour's traction drops out and the data
are exactly those of (21)-(23); for any gamma the fixed point is the same discrete
penalised problem (16) (tests/test_monolithic.py checks it).
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .acceleration import Anderson
from .contact import active_set, updated_active_set


def robin_data(layout, x, gap, theta, gamma, psi, hold_inactive=False):
    """Robin coefficients and data of every subdomain for the state x^k and contact set Psi.

    Interface laws (16): on S12 where Psi = 1, t = (d - u1n - w)/theta on both sides
    (normal tractions, compression negative), elsewhere t = 0; on S23 the traction on
    Omega3 is (f - u3)/theta and on the coating (u3 - f)/theta. Solving each law for
    one side's Robin combination t + gamma u, with c = 1 - gamma theta:
        Omega1  on S12: alpha = gamma Psi,  g = d - w + c t_w / gamma
        coating on S21: alpha = gamma Psi,  g = d - u1n + c t_u1n / gamma
        coating on S23: alpha = gamma,      g = u3 - c t_3 / gamma
        Omega3  on S32: alpha = gamma,      g = f - c t_f / gamma
    For gamma = 1/theta these are (21), (22), (23) with Psi u^k + (d - u1n - w)^- =
    Psi (d - neighbour) (METHOD.md, global components). At a fixed point the two sides'
    tractions t1, t2 satisfy (2 - gamma theta)(t1 + t2) = 0 and then the law; so
    gamma theta must stay away from 2 (Settings refuses gamma theta >= 1.5).

    ``hold_inactive``: alpha = gamma on all of S12, and where Psi = 0 the data is the
    side's own trace, g = u^k. The fixed point is the same (there t = gamma (u - u) = 0),
    but no matrix depends on Psi any more: the workers factorise once per run."""
    get = lambda name: layout.get(x, name)  # noqa: E731
    c = 1.0 - gamma * theta
    alpha_contact = gamma * psi
    alpha_bond = np.full(layout.points, gamma)
    g_upper = gap - get("coating_n") + c * get("t_coating_n") / gamma
    g_coating_n = gap - get("upper_n") + c * get("t_upper_n") / gamma
    if hold_inactive:
        alpha_contact = np.full(layout.points, gamma)
        g_upper = np.where(psi > 0, g_upper, get("upper_n"))
        g_coating_n = np.where(psi > 0, g_coating_n, get("coating_n"))
    g_coating_bond = get("lower_bond") - c * get("t_lower_bond") / gamma
    g_lower = get("coating_bond") - c * get("t_coating_bond") / gamma
    return {
        "upper": [alpha_contact, g_upper],
        "coating": [alpha_contact, g_coating_n, alpha_bond, *g_coating_bond],
        "lower": [alpha_bond, *g_lower],
    }


def state_after_solve(layout, data, traces):
    """The new state: each side's traces and the traction of its Robin condition,
    t = alpha (g - u), which is exactly what that side felt in its solve."""
    upper_n, coating_n, coating_bond, lower_bond = traces
    alpha_c, g_upper = data["upper"]
    _, g_coating_n, alpha_b, g_cb1, g_cb2 = data["coating"]
    _, g_lower1, g_lower2 = data["lower"]
    return layout.pack(
        upper_n=upper_n, coating_n=coating_n, coating_bond=coating_bond, lower_bond=lower_bond,
        t_upper_n=alpha_c * (g_upper - upper_n),
        t_coating_n=alpha_c * (g_coating_n - coating_n),
        t_coating_bond=alpha_b * (np.array([g_cb1, g_cb2]) - coating_bond),
        t_lower_bond=alpha_b * (np.array([g_lower1, g_lower2]) - lower_bond))


# Inner tolerance of the active-set loop while Psi may still change: enough for the
# tractions to tell tension from compression at most points. Measured on the figure
# scenes (total iterations of 8 runs): 1e-4: 760, 3e-3: 512, 1e-2: 449, 3e-2: 428 with one
# run cycling (caught, finished at eps_u: 94). The final answer does not depend on it.
ACTIVE_SET_TOLERANCE = 1e-2


@dataclass
class LoopResult:
    state: np.ndarray           # traces and tractions of the last solve
    psi: np.ndarray             # contact set of the last solve
    iterations: int             # Robin iterations (parallel subdomain solves)
    converged: bool
    status: str                 # converged, diverged, stagnated, max_iterations
    reason: str
    history: list = field(default_factory=list)


class ConvergenceMonitor:
    """Stops a loop that diverges or stagnates, and one that hits its iteration limit.

    Diverged: a non-finite value; displacements beyond ``growth_limit`` times the scene's
    scale (stamp displacement plus largest gap); or a relative change ``growth_limit``
    times above the smallest seen since the last ``restart``. Stagnated: no new smallest
    relative change (by 10 %) in ``window`` iterations."""

    def __init__(self, max_iterations, displacement_scale, window, growth_limit=1e3):
        self.max_iterations = max_iterations
        self.displacement_scale = displacement_scale
        self.window = window
        self.growth_limit = growth_limit
        self.restart(0)

    def restart(self, iteration):
        self.best_change, self.best_iteration = math.inf, iteration

    def check(self, iteration, x, change):
        """``(status, reason)`` when the loop must stop for failure, else None."""
        if not (np.all(np.isfinite(x)) and math.isfinite(change)):
            return "diverged", f"non-finite values at iteration {iteration}"
        largest = float(np.max(np.abs(x)))
        if largest > self.growth_limit * self.displacement_scale:
            return "diverged", (f"a displacement or traction reached {largest:.3g}, over "
                                f"{self.growth_limit:g} times the scene's scale "
                                f"{self.displacement_scale:.3g}, at iteration {iteration}")
        if change > self.growth_limit * self.best_change:
            return "diverged", (f"relative change grew from {self.best_change:.3g} "
                                f"(iteration {self.best_iteration}) to {change:.3g} "
                                f"(iteration {iteration})")
        if change < 0.9 * self.best_change:
            self.best_change, self.best_iteration = change, iteration
        elif iteration - self.best_iteration >= self.window:
            return "stagnated", (f"relative change stuck near {self.best_change:.3g} for "
                                 f"{self.window} iterations")
        if iteration >= self.max_iterations:
            return "max_iterations", (f"relative change {change:.3g} after {iteration} "
                                      "iterations")
        return None


def run_robin_loop(solve, layout, contact, scene, settings, progress=None):
    """Iterate until converged or stopped; the workers keep the fields of the last solve.

    ``solve(data)`` performs the three subdomain solves and returns the traces and each
    worker's CPU seconds (orchestrate/subdomains.py); ``contact`` is the S12 quadrature."""
    loop = _PaperLoop if settings.method == "paper" else _ActiveSetLoop
    return loop(solve, layout, contact, scene, settings, progress).run()


class _Loop:
    """What both loops share: one Robin iteration, its history row, the monitor."""

    window = 500

    def __init__(self, solve, layout, contact, scene, settings, progress):
        self.solve, self.layout, self.contact = solve, layout, contact
        self.settings, self.progress = settings, progress
        self.gamma = settings.robin_parameter
        self.monitor = ConvergenceMonitor(settings.max_iterations,
                                          scene.stamp + float(np.max(contact.gap)),
                                          self.window)
        self.history = []
        self.start = time.perf_counter()

    hold_inactive = False

    def iterate(self, x, psi):
        """Solve every subdomain for the state x and the contact set psi; return x~."""
        data = robin_data(self.layout, x, self.contact.gap, self.settings.theta, self.gamma,
                          psi, self.hold_inactive)
        traces, seconds = self.solve(data)
        self.seconds = seconds
        return state_after_solve(self.layout, data, traces)

    def record(self, image, psi, previous_psi, change, update, status=None):
        traction = self.layout.get(image, "t_upper_n") + self.layout.get(image, "t_coating_n")
        row = {
            "iteration": len(self.history) + 1,
            "relative_change": change,
            "active_points": int(psi.sum()),
            "active_set_changed": previous_psi is not None and bool(np.any(psi != previous_psi)),
            "active_set_update": update,
            "contact_force": -0.5 * self.contact.integrate(traction),
            "seconds": time.perf_counter() - self.start,
            "cpu_upper": self.seconds["upper"], "cpu_coating": self.seconds["coating"],
            "cpu_lower": self.seconds["lower"], "wait": self.seconds["wait"],
            "back_upper": self.seconds["back_upper"], "back_coating": self.seconds["back_coating"],
            "back_lower": self.seconds["back_lower"],
        }
        self.history.append(row)
        if self.progress is not None:
            self.progress(row, status or "running")

    def relative_change(self, new, old):
        weight = self.contact.weight
        return (self.layout.displacement_norm(new - old, weight)
                / max(self.layout.displacement_norm(new, weight), 1e-300))

    def result(self, image, psi, status, reason):
        return LoopResult(image, psi, len(self.history), status == "converged", status,
                          reason, self.history)


class _PaperLoop(_Loop):
    """(21)-(24): Psi from every iterate, fixed relaxation rho."""

    def run(self):
        layout, gap, rho = self.layout, self.contact.gap, self.settings.rho
        x, previous_psi = layout.zeros(), None
        for iteration in range(1, self.settings.max_iterations + 1):
            psi = active_set(gap, layout.get(x, "upper_n"), layout.get(x, "coating_n"))
            image = self.iterate(x, psi)
            x_new = rho * image + (1.0 - rho) * x
            change = self.relative_change(x_new, x)
            x = x_new
            if change < self.settings.eps_u:
                self.record(image, psi, previous_psi, change, 0, "converged")
                return self.result(image, psi, "converged",
                                   f"relative change {change:.3g} < eps_u = {self.settings.eps_u:g}")
            failure = self.monitor.check(iteration, x, change)
            self.record(image, psi, previous_psi, change, 0, failure and failure[0])
            if failure:
                return self.result(image, psi, *failure)
            previous_psi = psi
        raise AssertionError("the monitor stops at max_iterations")


class _ActiveSetLoop(_Loop):
    """Anderson-accelerated Robin iterations for a frozen Psi, Psi updated in between.

    Psi is updated once the inner residual is below ACTIVE_SET_TOLERANCE. Should Psi
    return to a set already tried, the updates were too inexact to tell the edge points
    apart: from then on they wait for the full tolerance eps_u, and only a cycle under
    that tolerance stops the loop."""

    window = 200
    hold_inactive = True      # constant matrices: each worker factorises once (measured:
                              # +5-10 iterations, -40 % wall time on the figure scenes)

    def run(self):
        layout, gap, eps = self.layout, self.contact.gap, self.settings.eps_u
        scale = np.where(layout.displacement_mask(), 1.0, 1.0 / self.gamma)
        scale = scale * np.sqrt(np.tile(self.contact.weight, layout.size // layout.points))
        anderson = Anderson(scale)
        x = layout.zeros()
        psi = active_set(gap, layout.get(x, "upper_n"), layout.get(x, "coating_n"))
        previous_psi, update, seen = None, 0, {psi.tobytes()}
        tolerance = max(eps, ACTIVE_SET_TOLERANCE)
        for iteration in range(1, self.settings.max_iterations + 1):
            image = self.iterate(x, psi)
            change = self.relative_change(image, x)
            failure = self.monitor.check(iteration, image, change)
            new_psi = updated_active_set(psi, gap, layout.get(image, "upper_n"),
                                         layout.get(image, "coating_n"),
                                         0.5 * (layout.get(image, "t_upper_n")
                                                + layout.get(image, "t_coating_n")))
            psi_settled = np.array_equal(new_psi, psi)
            if change < eps and psi_settled:
                self.record(image, psi, previous_psi, change, update, "converged")
                return self.result(image, psi, "converged",
                                   f"contact set settled and relative change {change:.3g} "
                                   f"< eps_u = {eps:g}")
            self.record(image, psi, previous_psi, change, update, failure and failure[0])
            if failure:
                return self.result(image, psi, *failure)
            previous_psi = psi
            if change < tolerance and not psi_settled:
                if new_psi.tobytes() in seen:
                    if tolerance <= eps:
                        return self.result(image, psi, "stagnated",
                                           f"the contact set cycles (update {update + 1} "
                                           "returns to an earlier set)")
                    tolerance, seen = eps, set()
                seen.add(new_psi.tobytes())
                psi, x, update = new_psi, image, update + 1
                anderson.reset()
                self.monitor.restart(iteration)
            else:
                x = anderson.step(x, image)
        raise AssertionError("the monitor stops at max_iterations")
