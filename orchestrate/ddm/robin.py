"""The Robin domain decomposition loop (21)-(24) on the interface state.

Each iteration turns the interface state x (orchestrate/ddm/state.py) into the Robin
coefficient alpha and data g of every subdomain, lets the workers solve (each solves
sigma_n(u) + alpha u = alpha g on its interfaces), and forms the new state from their
traces and tractions. The paper's loop solves all subdomains at once (Jacobi); the
active-set loop solves the bodies at once, then the coating patches from the bodies'
new traces (a Gauss-Seidel sweep, Problem.sweep). Two loops are offered
(Settings.method); which one, and every number it reads, is the run's Strategy
(orchestrate/ddm/strategy.py), decided before it starts:

``paper``: the paper's loop. Robin coefficient gamma = 1/theta, contact set Psi12 from
    the current iterate at every iteration (20), fixed relaxation (24):
    x^{k+1} = rho x~^{k+1} + (1 - rho) x^k. Relaxing the traces is the paper's
    relaxation of the whole fields: every right-hand side depends on the fields through
    their traces only, linearly. Stops when the relative change of the displacement
    traces (discrete L2 over S12 and S23) is below eps_u.

``active-set`` (default): the same Robin solves with a free Robin parameter gamma, the
    Robin coefficient on all of S12 (inactive points get their own trace as data, so
    no matrix ever changes), and two nested loops. Inside, Psi is frozen, so the map
    x -> x~ is affine, and Anderson acceleration (orchestrate/ddm/acceleration.py) drives it
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
penalised problem (16) (tests/ddm/test_monolithic.py checks it).
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np

from orchestrate.ddm.acceleration import Anderson
from orchestrate.ddm.contact import penetration, updated_active_set
from orchestrate.ddm.first_contact import (held_indenter_state, predicted_contact,
                                           predicted_friction_states)
from orchestrate.ddm.force_balance import ForceBalance
from orchestrate.faults import checkpoint
from orchestrate.ddm.interface_system import InterfaceSystem
from orchestrate.ddm.state import StateLayout
from orchestrate.model.scene import Settings

# A loop whose sides are split (robin_parameters.py) updates its contact set only once
# the tractions' change is below the update tolerance times this, besides the
# displacements': the split's small-coefficient side settles its tractions behind its
# displacements, and updates made while they had not begun to settle (changes near 1)
# walked the paper's scene at mesh level 3 iterated on one level through 18 sets, 226
# iterations (3 sets, 74 iterations with it; at a factor 1, the gallery's 30 um patches
# of then at mesh level 2 took 27 more). Where a side has a stiff neighbour its tractions
# lag by nature and waiting cost the gallery's stiff indenters 1-8 iterations: not there.
LAGGING_TRACTIONS = 30.0
# A contact set that recurs tightens its updates' tolerance tenfold per cycle, down to
# eps_u or this, whichever is smaller; only a cycle there stops the loop. The updates'
# precision is not the answer's: under eps_u = 1e-3 the gallery's pads at mesh level 2
# cycled once the tolerance had reached it (20 iterations), and the direct solve they
# fell back to took 33 s, against 5.5 s for the 34 iterations of the default eps_u.
SET_TOLERANCE_FLOOR = 1e-6

@dataclass
class RobinLaw:
    """One side's Robin condition sigma_n(u) + alpha u = alpha g, its data affine in the
    state: g = own u + other_u u' + other_t t' + constant, with u the side's own trace and
    u', t' the other side's trace and traction (coefficients per point, the same for
    every component; ``constant`` of shape (components, points)). The loop evaluates it
    (``robin_data``) and the direct solve of a frozen contact set assembles it
    (orchestrate/ddm/interface_system.py): one law for both."""
    alpha: np.ndarray
    own: np.ndarray
    other_u: np.ndarray
    other_t: np.ndarray
    constant: np.ndarray
    # a friction side's data also takes its contact's normal stress (the mean of the
    # contact's two tractions) times ``by_pressure``: contact, its interface index
    contact: int = None
    by_pressure: np.ndarray = None

    def data(self, u, u_other, t_other, t_contact=None):
        """g for the side's trace u and the other side's u', t' (shape (points,) or
        (components, points)), and a friction side's contact stress, of shape
        (components, points)."""
        g = self.own * u + self.other_u * u_other + self.other_t * t_other + self.constant
        if self.contact is not None:
            g = g + self.by_pressure * t_contact
        return np.atleast_2d(g)


def robin_laws(problem, layout, psi, theta, sides, direct=False, inside=(), slip_origin=None):
    """The Robin law of every side of every interface for the contact set Psi
    (concatenated over the contact interfaces): ``{(i, side): RobinLaw}``. ``sides``:
    every side's Robin parameter gamma and whether it holds its inactive points, in
    interface order, sides A then B (robin_parameters.side_parameters); ``direct``: every
    side holds them (a solve from the subdomains' maps needs fixed matrices); ``inside``:
    the bonds inside a worker (Strategy.bonds_inside), which take no Robin term (alpha =
    0: their penalty is in the worker's matrix) and whose tractions follow from the
    traces (with_bond_tractions).

    Interface laws (16): on a contact where Psi = 1, t = (d - u_A - u_B)/theta on both
    sides (normal tractions, compression negative), elsewhere t = 0; on a bond the
    traction on side B is (u_A - u_B)/theta and on side A (u_B - u_A)/theta. Solving each
    law for one side's Robin combination t + gamma u (gamma the side's own), with
    c = 1 - gamma theta:
        contact, side A:  alpha = gamma Psi,  g = d - u_B + c t_B / gamma
        contact, side B:  alpha = gamma Psi,  g = d - u_A + c t_A / gamma
        bond, side A:     alpha = gamma,      g = u_B - c t_B / gamma
        bond, side B:     alpha = gamma,      g = u_A - c t_A / gamma
    For gamma = 1/theta these are (21), (22), (23) with Psi u^k + (d - u1n - w)^- =
    Psi (d - neighbour) (METHOD.md, global components). At a fixed point the two sides'
    tractions t_A, t_B and the law's t satisfy (t_A - t_B) + gamma_A theta (t_B - t) = 0
    and (t_B - t_A) + gamma_B theta (t_A - t) = 0, whose only solution is t_A = t_B = t
    unless gamma_B theta - gamma_B / gamma_A = 1 (with one gamma: gamma theta = 2); so
    every gamma theta must stay below 1 (Settings refuses gamma theta >= 1.5 for the
    largest, and gamma_B / gamma_A > 0 keeps the second term away).

    Friction: on a friction interface both sides feel, along their tangents, the
    traction q = -phi mu sigma_n where their contact's Psi = 1 and the point slips
    (phi = +-1; full sliding: phi = 1 throughout; sigma_n the contact's normal stress,
    compression negative: q = phi mu p), else 0. A traction is a Neumann condition,
    which a Robin side takes as its own trace plus the traction over its gamma_f:
        friction, slipping:  alpha = gamma_f (held), g = u + Psi q / gamma_f,
                             sigma_n = (t_A + t_B) / 2 of the contact,
    so that t = alpha (g - u) = q at the fixed point, where the contact's two tractions
    equal its law's: the discrete problem the monolithic solve assembles, q with the
    penalty's sigma_n (freefem/monolithic.edp). A point that sticks (phi = 0, partial
    slip) has the penalty law t = -(u_A + u_B)/theta, a contact's with no gap, and its
    Robin-Robin exchange at the contact side's gamma (``sides`` of the contact):
        friction, sticking:  alpha = gamma,  g = -u' + c t' / gamma.
    The friction states follow the contact set Psi, after its points (StateLayout's
    friction_slices). On a load path (Scene.load.path) a point sticks where it stood at
    the step before: t = (s0 - u_A - u_B)/theta, ``slip_origin`` s0 its slip then (in
    friction_slices' order; None: 0), the contact's law with s0 for the gap.

    A side that holds its inactive points: alpha = gamma on all of the contact, and
    where Psi = 0 the data is the side's own trace, g = u^k. The fixed point is the same
    (there t = gamma (u - u) = 0), but its matrix does not depend on Psi: its worker
    factorises once per run (robin_parameters.py says where that pays)."""
    laws = {}
    psi_of = dict((i, psi[where]) for i, where in layout.contact_slices())
    origin_of = {i: (np.zeros(where.stop - where.start) if slip_origin is None
                     else slip_origin[where.start - layout.contact_points:
                                      where.stop - layout.contact_points])
                 for i, where in layout.friction_slices()}
    for i, interface in enumerate(problem.interfaces):
        n, ones, zeros = interface.size, np.ones(interface.size), np.zeros(interface.size)
        for side in (0, 1):
            parameter = sides[2 * i + side]
            gamma = parameter.gamma
            c = 1.0 - gamma * theta
            if i in inside:
                law = RobinLaw(zeros, zeros, zeros, zeros, np.zeros((2, n)))
            elif interface.kind == "friction":
                active = psi_of[interface.contact] > 0
                phi = layout.friction_state(psi, i)
                stick, slip = active & (phi == 0), active & (phi != 0)
                held = parameter.hold_inactive or direct
                # the stick law's exchange: the contact side's gamma
                gamma_s = sides[2 * interface.contact + side].gamma
                c_s = 1.0 - gamma_s * theta
                alpha = np.full(n, gamma) if held else gamma * psi_of[interface.contact]
                law = RobinLaw(np.where(stick, gamma_s, alpha), np.where(stick, 0.0, 1.0),
                               np.where(stick, -1.0, 0.0), np.where(stick, c_s / gamma_s, 0.0),
                               np.where(stick, origin_of[i], 0.0)[None, :], interface.contact,
                               np.where(slip, -phi * interface.friction / gamma, 0.0))
            elif interface.kind == "contact":
                active = psi_of[i] > 0
                if parameter.hold_inactive or direct:
                    law = RobinLaw(np.full(n, gamma), np.where(active, 0.0, 1.0),
                                   np.where(active, -1.0, 0.0), np.where(active, c / gamma, 0.0),
                                   np.where(active, interface.gap, 0.0)[None, :])
                else:
                    law = RobinLaw(gamma * psi_of[i], zeros, -ones, np.full(n, c / gamma),
                                   np.asarray(interface.gap, dtype=float)[None, :])
            else:
                law = RobinLaw(np.full(n, gamma), zeros, ones, np.full(n, -c / gamma),
                               np.zeros((2, n)))
            laws[i, side] = law
    return laws


def robin_data(layout, x, laws):
    """Robin coefficients and data of every side for the state x^k under ``laws``
    (robin_laws): ``{(i, side): (alpha, g)}``, g of shape (components, points)."""
    data = {}
    for (i, side), law in laws.items():
        other = 1 - side
        t_contact = (None if law.contact is None else
                     0.5 * (layout.get(x, "t", law.contact, 0) + layout.get(x, "t", law.contact, 1)))
        g = law.data(layout.get(x, "u", i, side), layout.get(x, "u", i, other),
                     layout.get(x, "t", i, other), t_contact)
        data[i, side] = (law.alpha, g)
    return data


def state_after_solve(layout, data, traces, before):
    """The state ``before`` with every side in ``traces`` replaced by its new trace and
    the traction of its Robin condition, t = alpha (g - u), which is exactly what that
    side felt in its solve."""
    x = before.copy()
    for i, side in traces:
        alpha, g = data[i, side]
        u = traces[i, side]
        x[layout.slices["u", i, side]] = np.ravel(u)
        x[layout.slices["t", i, side]] = np.ravel(alpha * (g - u))
    return x


def with_bond_tractions(layout, x, inside, theta):
    """The state x with the tractions of the bonds ``inside`` a worker from their traces by
    the bond's law: (u_A - u_B)/theta on side B, its opposite on side A (a worker solves
    them with their penalty in its matrix: no Robin condition tells their traction)."""
    if not inside:
        return x
    x = x.copy()
    for i in inside:
        jump = x[layout.slices["u", i, 0]] - x[layout.slices["u", i, 1]]
        x[layout.slices["t", i, 0]] = -jump / theta
        x[layout.slices["t", i, 1]] = jump / theta
    return x


def contact_traction(layout, x):
    """The mean of both sides' normal tractions at every contact point."""
    return 0.5 * (layout.contact(x, "t", 0) + layout.contact(x, "t", 1))


def state_penetration(layout, x):
    """d - u_A - u_B at every contact point of the state x (negative: interpenetration)."""
    return penetration(layout.gap, layout.contact(x, "u", 0), layout.contact(x, "u", 1))


def updated_contact_set(layout, psi, x, partial_slip=False, slip_origin=None):
    """The semi-smooth Newton update of Psi from the state x solved with it
    (contact.updated_active_set), and under partial slip of the friction states after
    it (updated_friction_states, the slips from ``slip_origin``: robin_laws'); under
    full sliding they stay 1."""
    n = layout.contact_points
    contact = updated_active_set(psi[:n], state_penetration(layout, x),
                                 contact_traction(layout, x))
    if len(psi) == n:
        return contact
    if not partial_slip:
        return np.concatenate([contact, psi[n:]])
    states = []
    slices = dict(layout.contact_slices())
    for i, where in layout.friction_slices():
        face = layout.interfaces[i]
        c = face.contact
        pressure = -0.5 * (layout.get(x, "t", c, 0) + layout.get(x, "t", c, 1))
        slip = layout.get(x, "u", i, 0) + layout.get(x, "u", i, 1)
        if slip_origin is not None:
            slip = slip - slip_origin[where.start - n:where.stop - n]
        states.append(updated_friction_states(
            psi[slices[c]] > 0, contact[slices[c]] > 0, psi[where],
            0.5 * (layout.get(x, "t", i, 0) + layout.get(x, "t", i, 1)), slip,
            face.friction * pressure))
    return np.concatenate([contact] + states)


def decided_entries(layout, psi, new_psi, x, image):
    """``new_psi`` without the points it lets into contact, unless the iterate ``image``
    decides one of them: some point's penetration exceeds its change from ``x`` to
    ``image``. Next to a contact's edge the gap is nearly closed, and a penetration
    within its last change rests on the iterate's error: the coated roller at mesh level
    2 took in the point beside its a priori set on a penetration of 4e-5 (of the largest
    displacement) that had just changed by 2e-4, then let it go again, 25 iterations in
    three sets against 16 in one (docs/method.md, "The Robin loop"). One decided entry
    takes the others along: an edge that moves moves at several points. The points
    leaving keep the update's judgement, their tension: held back alike, a first set
    too wide shrank slower (the anodised aluminium at mesh level 3: 28 iterations
    against 24). As the iterates converge their changes vanish, and every entry
    counts."""
    n = layout.contact_points
    entering = (psi[:n] == 0) & (new_psi[:n] > 0)
    depth = -state_penetration(layout, image)
    depth_change = np.abs(depth + state_penetration(layout, x))
    if not entering.any() or np.any(entering & (depth > depth_change)):
        return new_psi
    decided = new_psi.copy()
    decided[:n][entering] = 0.0
    return decided


def slipping_at_flips(layout, psi, new_psi, x, slip_origin=None):
    """``new_psi`` with every friction point whose contact the update flips while it
    sticks kept in contact and slipping instead (phi the sign of its friction traction,
    or against its slip where it has none yet); None if there is none. At the first or
    last touch a point's friction limit mu p is near zero, so slipping is the state its
    law allows there; the update has it stick, and under a pull an edge point can then
    flip for ever between sticking, with a tension that releases it, and released,
    penetrating (the fretting example, pulled from the pressed state)."""
    n = layout.contact_points
    slices = dict(layout.contact_slices())
    changed, new_psi = False, new_psi.copy()
    for i, where in layout.friction_slices():
        c = slices[layout.interfaces[i].contact]
        q = 0.5 * (layout.get(x, "t", i, 0) + layout.get(x, "t", i, 1))
        slip = layout.get(x, "u", i, 0) + layout.get(x, "u", i, 1)
        if slip_origin is not None:
            slip = slip - slip_origin[where.start - n:where.stop - n]
        direction = np.where(q != 0, np.sign(q), -np.sign(slip))
        released = (psi[c] > 0) & (new_psi[c] == 0) & (psi[where] == 0)
        entering = (psi[c] == 0) & (new_psi[c] > 0) & (new_psi[where] == 0)
        flips = (released | entering) & (direction != 0)
        if flips.any():                 # new_psi[c], new_psi[where]: views of new_psi
            new_psi[c][flips], new_psi[where][flips] = 1.0, direction[flips]
            changed = True
    return new_psi if changed else None


def updated_friction_states(active, active_next, phi, traction, slip, limit):
    """The semi-smooth update of the friction states phi from a state solved with them
    (freefem/monolithic.edp updates its own alike): at a point in contact, one that
    sticks slips where its traction exceeds the limit mu p (phi the traction's sign),
    one that slips sticks where its slip turns with phi (the traction must oppose it);
    a point out of contact in the next set sticks (so it enters)."""
    stuck = np.where(np.abs(traction) > limit, np.sign(traction), 0.0)
    kept = np.where(phi * slip > 0, 0.0, phi)
    new = np.where(active, np.where(phi == 0, stuck, kept), phi)
    return np.where(active_next, new, 0.0)


@dataclass
class LoopResult:
    state: np.ndarray           # traces and tractions of the last solve
    psi: np.ndarray             # contact set of the last solve
    iterations: int             # Robin iterations (parallel subdomain solves)
    converged: bool
    status: str                 # converged, diverged, stagnated, max_iterations
    reason: str
    history: list = field(default_factory=list)
    descent: float = None       # the stamp's descent in the last solve
    error_estimate: float = None  # estimated relative error of the state (loops' docstrings)


class ConvergenceMonitor:
    """Stops a loop that diverges or stagnates, and one that hits its iteration limit.

    Diverged: a non-finite value; displacements (the entries ``displacement_mask`` picks;
    tractions scale with the moduli and follow the displacements) beyond ``growth_limit``
    times the scene's scale (stamp displacement plus largest gap); or a relative change
    ``growth_limit`` times above the smallest seen since the last ``restart``. Stagnated:
    no new smallest relative change (smaller by the share ``progress``) in ``window``
    iterations. ``growth_limit`` and ``progress`` are by default the settings'
    divergence_growth and stagnation_progress."""

    def __init__(self, max_iterations, displacement_scale, window,
                 growth_limit=Settings.divergence_growth, displacement_mask=None,
                 progress=Settings.stagnation_progress):
        self.max_iterations = max_iterations
        self.displacement_mask = displacement_mask
        self.displacement_scale = displacement_scale
        self.window = window
        self.growth_limit = growth_limit
        self.progress = progress
        self.restart(0)

    def restart(self, iteration):
        self.best_change, self.best_iteration = math.inf, iteration

    def check(self, iteration, x, change):
        """``(status, reason)`` when the loop must stop for failure, else None."""
        if not (np.all(np.isfinite(x)) and math.isfinite(change)):
            return "diverged", f"non-finite values at iteration {iteration}"
        displacements = x if self.displacement_mask is None else x[self.displacement_mask]
        largest = float(np.max(np.abs(displacements), initial=0.0))
        if largest > self.growth_limit * self.displacement_scale:
            return "diverged", (f"a displacement reached {largest:.3g}, over "
                                f"{self.growth_limit:g} times the scene's scale "
                                f"{self.displacement_scale:.3g}, at iteration {iteration}")
        if change > self.growth_limit * self.best_change:
            return "diverged", (f"relative change grew from {self.best_change:.3g} "
                                f"(iteration {self.best_iteration}) to {change:.3g} "
                                f"(iteration {iteration})")
        if change < (1.0 - self.progress) * self.best_change:
            self.best_change, self.best_iteration = change, iteration
        elif iteration - self.best_iteration >= self.window:
            return "stagnated", (f"relative change stuck near {self.best_change:.3g} for "
                                 f"{self.window} iterations")
        if iteration >= self.max_iterations:
            return "max_iterations", (f"relative change {change:.3g} after {iteration} "
                                      "iterations")
        return None


def run_robin_loop(solve, problem, strategy, progress=None, start=None, robin_maps=None,
                   coarse=None, slip_origin=None):
    """Iterate until converged or stopped; the workers keep the fields of the last solve.

    ``strategy``: the loop, its laws' parameters and knobs (orchestrate/ddm/strategy.py).
    ``solve(data, names)`` performs the solves of the subdomains ``names`` at once and
    returns the traces of their sides, each worker's CPU seconds and the stamp's descent
    (orchestrate/workers/subdomains.py).
    ``start``: the active-set loop's first iterate (orchestrate/run/warm_start.py), else
    zero; the paper's loop always starts from zero, as the paper's does.
    ``robin_maps(data)``: every subdomain's Robin map at the coefficients of ``data``, or
    None (Subdomains.robin_maps); with them the active-set loop solves each contact
    set's fixed point directly (orchestrate/ddm/interface_system.py). ``coarse``: a
    CoarseCorrection (orchestrate/ddm/coarse.py) for the iterated active-set loop.
    ``slip_origin``: on a load path, every friction point's slip at the step before
    (robin_laws), else None."""
    if strategy.loop == "paper":
        return _PaperLoop(solve, problem, strategy, progress).run()
    loop = _ActiveSetLoop(solve, problem, strategy, progress)
    loop.start_state = start
    loop.robin_maps = robin_maps
    loop.coarse = coarse
    loop.slip_origin = slip_origin
    return loop.run()


def displacement_scale(problem):
    """The scene's scale of displacements: the largest initial gap plus the stamp's
    descent (or, under a force, the force over the softest modulus)."""
    scene = problem.scene
    gap = max((float(np.max(i.gap)) for i in problem.contacts), default=0.0)
    if scene.load.displacement is not None:
        return scene.load.displacement + gap
    moduli = ([] if scene.indenter.rigid else [scene.indenter.E]) + [scene.base.E] + [
        c.E for c in scene.coatings]
    return scene.load.force / min(moduli) + gap


class _Loop:
    """What both loops share: one Robin iteration, its history row, the monitor. What
    the loop is (its sweep, its laws, its numbers) is the strategy's."""

    def __init__(self, solve, problem, strategy, progress):
        self.solve, self.problem, self.strategy, self.progress = solve, problem, strategy, progress
        self.knobs = strategy.knobs
        self.sweep = strategy.sweep
        self.layout = StateLayout(problem.interfaces)
        self.theta, self.gamma = strategy.theta.solver_value, strategy.gamma.solver_value
        self.monitor = ConvergenceMonitor(self.knobs.max_iterations, displacement_scale(problem),
                                          strategy.stagnation_window,
                                          self.knobs.divergence_growth,
                                          self.layout.displacement_mask,
                                          self.knobs.stagnation_progress)
        self.history = []
        self.start = time.perf_counter()
        self.descent = None
        self.estimate = math.inf
        self.direct = False       # whether this iteration solved its contact set directly
        partner = strategy.force_balance
        self.balance = (ForceBalance(problem, partner, strategy.sides_of(problem, partner))
                        if partner is not None else None)

    slip_origin = None        # a load path's slips at the step before (robin_laws)

    def laws(self, psi, direct=False):
        return robin_laws(self.problem, self.layout, psi, self.theta, self.strategy.sides,
                          direct, self.strategy.bonds_inside, self.slip_origin)

    def iterate(self, x, psi):
        """Solve every subdomain for the state x and the contact set psi; return x~. The
        groups of ``sweep`` solve one after the other, each from the state the groups
        before it left."""
        laws, image, seconds = self.laws(psi, self.direct), x, {"wait": 0.0}
        for group in self.sweep:
            data = robin_data(self.layout, image, laws)
            balance = (self.balance if self.balance is not None and not self.direct
                       and self.balance.applies(group) else None)
            if balance is not None:
                data = balance.balanced(data)
            traces, group_seconds, descent = self.solve(data, group)
            if balance is not None:
                data, traces = balance.settled(data, traces, self.solve)
            image = with_bond_tractions(self.layout,
                                        state_after_solve(self.layout, data, traces, image),
                                        self.strategy.bonds_inside, self.theta)
            seconds = {**seconds, **group_seconds,
                       "wait": seconds["wait"] + group_seconds["wait"]}
            self.descent = descent if descent is not None else self.descent
        self.seconds = seconds
        return image

    def record(self, image, psi, previous_psi, change, update, status=None):
        layout = self.layout
        traction = layout.contact(image, "t", 0) + layout.contact(image, "t", 1)
        row = {
            "iteration": len(self.history) + 1,
            "relative_change": max(change[:2]),
            "displacement_change": change[0],
            "traction_change": change[1],
            "traction_component_change": change[2],
            "error_estimate": self.estimate,
            "active_points": int(psi[:layout.contact_points].sum()),
            "active_set_changed": previous_psi is not None and bool(np.any(psi != previous_psi)),
            "active_set_update": update,
            "contact_force": -0.5 * float(np.dot(layout.contact_weight,
                                                 traction * layout.contact_normal_x2)),
            "descent": self.descent,
            "direct": self.direct,
            "seconds": time.perf_counter() - self.start,
            "wait": self.seconds["wait"],
        }
        workers = [name for group in self.sweep for name in group]
        for name in workers:
            row[f"cpu_{name}"] = self.seconds[name]
        for name in workers:
            row[f"back_{name}"] = self.seconds[f"back_{name}"]
        self.history.append(row)
        if len(self.history) == 3:
            checkpoint("iterating")
        if self.progress is not None:
            self.progress(row, status or "running")

    def relative_change(self, new, old):
        """(displacements, tractions, traction components): the change from old to new
        relative to new, in the discrete L2 norms of the interfaces; the tractions as a
        whole, and the largest over their components (a bond's shear is read apart from
        its peel stress, and is often much smaller: its relative change jumps with every
        new contact set, so the monitor watches the first two only). Tractions are
        measured against at least traction_floor gamma ||u||: without contact they are
        zero up to round-off, and their relative change would be noise."""
        norms, changes = self.layout.part_norms(new), self.layout.part_norms(new - old)
        sizes = self.part_sizes(norms)
        parts = changes / sizes
        whole = np.linalg.norm(changes[1:]) / max(np.linalg.norm(norms[1:]),
                                                  self.traction_floor(norms[0]))
        return float(parts[0]), float(whole), float(np.max(parts[1:], initial=0.0))

    def traction_floor(self, u):
        """traction_floor gamma ||u||, the least a traction is measured against."""
        return max(self.knobs.traction_floor * self.gamma * u, 1e-300)

    def part_sizes(self, norms):
        """What the relative errors of the parts (StateLayout.parts) with these norms are
        measured against: a traction component's at least traction_floor and
        component_floor times the largest component."""
        sizes = norms.copy()
        floor = max(self.traction_floor(norms[0]),
                    self.knobs.component_floor * np.max(norms[1:], initial=0.0))
        sizes[1:] = np.maximum(sizes[1:], floor)
        sizes[0] = max(sizes[0], 1e-300)
        return sizes

    def part_errors(self, image, x, anderson, scale):
        """Each part's estimated relative error (_ActiveSetLoop's docstring):
        ||r|| max ||dx_part|| / ||dr|| / ||x_part||, and at least the part's own residual
        ||r_part|| / ||x_part||, in the scaled norm of the acceleration (displacements as
        they are, tractions over gamma); displacements first. A part no iterate has
        moved (the pressure of a contact with no point in contact: zero throughout) has
        no error, not the whole residual's: measured against component_floor of the
        largest traction, that had asked the other parts for a thousand times their
        tolerance."""
        residuals = (image - x) * scale
        own = np.array([np.linalg.norm(residuals[part]) for part in self.layout.parts])
        return (np.maximum(anderson.amplification() * np.linalg.norm(residuals), own)
                / self._scaled_sizes(image))

    def _scaled_sizes(self, image):
        """part_sizes in the acceleration's scaling (tractions over gamma)."""
        sizes = self.part_sizes(self.layout.part_norms(image))
        sizes[1:] /= self.gamma
        return sizes

    def error_estimate(self, image, x, anderson, scale):
        """The largest relative error of a part of the state, with estimate_margin."""
        return self.knobs.estimate_margin * float(np.max(self.part_errors(image, x, anderson,
                                                                          scale)))

    def confirmed(self, estimate, image, anderson):
        """``estimate``, and where it would stop the run, at least the history's bound of
        each part's error (Anderson.answer_errors) with estimate_margin: the pairs'
        amplification is a lower bound, which a dip of the residual had taken below the
        error. Made only here: it costs a dense solve per part."""
        if estimate >= self.knobs.eps_u:
            return estimate
        bounds = anderson.answer_errors()
        if bounds is None:
            return estimate
        return max(estimate, self.knobs.estimate_margin
                   * float(np.max(bounds / self._scaled_sizes(image))))

    def converged(self, error):
        eps = self.knobs.eps_u
        return error < eps, (f"estimated error {error:.3g} < eps_u = {eps:g} in the "
                             "interface displacements and tractions")

    def result(self, image, psi, status, reason):
        return LoopResult(image, psi, len(self.history), status == "converged", status,
                          reason, self.history, self.descent, self.estimate)


class _PaperLoop(_Loop):
    """(21)-(24): Psi from every iterate, fixed relaxation rho.

    A fixed-point iteration that contracts by q per step is still ||x_k - x_{k-1}|| q /
    (1 - q) away from its limit: the paper's stopping test, the change alone, stops a
    slow loop far from its answer. The error is estimated as the active-set loop's is
    (error_estimate), from the last paper_amplification_window pairs of iterates, and
    from the contraction q read off the last paper_contraction_window changes; the larger
    counts. (The contraction alone, over as many iterations, was fooled by the jumps of a
    contact set that changes every iteration: it called converged a run far off in
    force.)"""

    def run(self):
        knobs, layout = self.knobs, self.layout
        scale = np.where(layout.displacement_mask, 1.0, 1.0 / self.gamma)
        scale = scale * np.sqrt(layout.entry_weight)
        history = Anderson(scale, memory=knobs.paper_amplification_window, parts=layout.parts)
        x, previous_psi, changes = layout.zeros(), None, []
        for iteration in range(1, knobs.max_iterations + 1):
            psi = (state_penetration(self.layout, x) < 0).astype(float)
            image = self.iterate(x, psi)
            history.record(x, image)
            x_new = knobs.rho * image + (1.0 - knobs.rho) * x
            change = self.relative_change(x_new, x)
            changes.append(max(change))
            amplified = (self.error_estimate(image, x, history, scale)
                         if history.secants >= knobs.min_secants else math.inf)
            x = x_new
            self.estimate = self.confirmed(
                max(changes[-1], amplified,
                    _contraction_bound(changes, knobs.paper_contraction_window)),
                image, history)
            done, reason = self.converged(self.estimate)
            if done:
                self.record(image, psi, previous_psi, change, 0, "converged")
                return self.result(image, psi, "converged", reason)
            failure = self.monitor.check(iteration, x, max(change[:2]))
            self.record(image, psi, previous_psi, change, 0, failure and failure[0])
            if failure:
                return self.result(image, psi, *failure)
            previous_psi = psi
        raise AssertionError("the monitor stops at max_iterations")


def _contraction_bound(changes, window):
    """q/(1 - q) times the last change, q the mean contraction over the last ``window``
    changes (infinite while there are too few, or without contraction)."""
    if len(changes) < window + 1 or changes[-1 - window] <= 0:
        return math.inf
    q = (changes[-1] / changes[-1 - window]) ** (1.0 / window)
    return changes[-1] * q / (1.0 - q) if q < 1 else math.inf


def first_contact_set(scene, layout, x, supported=False, predicted=None):
    """Psi of the state x: where the bodies interpenetrate; where none do, the points
    within ``predicted`` (the contact points' distances from the contact's centre, over
    the a priori half-width: at most 1; under a descent too, where the first solve would
    push the indenter through the whole overlap, about sqrt(2) wider than the answer's
    set), else under a force, or when ``supported``, the points the indenter touches first
    (without a support the problem of a force is singular, and so is the whole interface
    system of a body held only by its contact: interface_system.py). A set near the
    answer's saves the semi-smooth updates that grow one from a point
    (Strategy.first_contact; ddm/first_contact.py)."""
    psi = (state_penetration(layout, x) < 0).astype(float)
    if (scene.load.force is not None or supported or predicted is not None) and not psi.any():
        if predicted is not None and np.any(predicted <= 1.0):
            return (predicted <= 1.0).astype(float)
        psi = (layout.gap <= np.min(layout.gap) + 1e-12 * np.max(layout.gap)).astype(float)
    return psi


class _ActiveSetLoop(_Loop):
    """Anderson-accelerated Robin iterations for a frozen Psi, Psi updated in between.

    Psi is updated once the inner residual is below active_set_tolerance (the first,
    predicted set below predicted_set_tolerance), its entries where the iterate decides
    one (decided_entries). Should Psi return to a set already tried, the updates were
    too inexact to tell the edge points apart: from then on they wait for a tolerance
    ten times tighter at each cycle, down to eps_u or SET_TOLERANCE_FLOOR, whichever is
    smaller, and for the displacements' estimated error within it; only a cycle there
    stops the loop.
    Under partial slip a cycle first keeps the sticking points whose contact it flips in
    contact, slipping (slipping_at_flips), unless that set was tried too.

    Stopping test. The residual r = x~ - x of an iterate underestimates its distance to
    the fixed point by up to ||(I - J)^-1|| (1/(1 - q) for a map that contracts by q): a
    slow map has a small residual far from its answer. The history of the frozen set
    shows that factor: every pair of iterates gives dr = (J - I) dx, and the largest
    ||dx|| / ||dr|| (Anderson.amplification) bounds it from below. Each quantity a user
    reads apart gets its own factor, max ||dx_part|| / ||dr||: the interface
    displacements, and each traction component of each interface (a contact's pressure,
    a bond's peel and shear stress): a small component such as a soft coating's bond
    shear may hide a much larger part of the distance than its share of the residual
    (measured: 5.7 % off in shear at E2 = 1e-6 E under a test on the whole state). The
    loop stops when Psi is settled and, for every part, the residual's norm times its
    factor is below eps_u times the part's norm (tractions: at least traction_floor
    gamma ||u|| and component_floor times the largest component), with at least
    min_secants pairs seen in the final set. Psi is updated on the displacements' change,
    and after a cycle on the tractions' too (they can lag behind the displacements under
    a stiff Robin parameter: an edge point flipped on their error at mesh level 3). A stop
    is confirmed by the history's bound of each part's error (Anderson.answer_errors):
    the pairs' amplification is a lower bound, which a dip of the residual had taken
    below the error. The estimate carries estimate_margin. (The names are the strategy's
    knobs, LoopKnobs.)"""

    start_state = None        # the first iterate (warm start), else zero
    robin_maps = None         # the subdomains' maps, when all have one (interface_system.py)
    coarse = None             # a CoarseCorrection (coarse.py): first iterate, preconditioner

    def run(self):
        knobs, layout, eps = self.knobs, self.layout, self.knobs.eps_u
        measure = np.where(layout.displacement_mask, 1.0, 1.0 / self.gamma)
        measure = measure * np.sqrt(layout.entry_weight)
        # the bonds inside a worker are its solve's answer to the contact state, not
        # iterated on: left out of the residual (their tractions, from the penalty of a
        # trace jump, carry rounding far above the contacts'), measured by their images
        scale = measure * ~self.inside_mask()
        anderson = Anderson(scale, knobs.anderson_depth, knobs.anderson_filter,
                            knobs.anderson_first_relaxation, layout.parts, measure)
        if self.start_state is not None:
            x = self.start_state.copy()
        elif self.coarse is not None:
            x = self.coarse.first_state(self.strategy.first_contact)
        else:
            x = held_indenter_state(self.problem, layout)
        system = self.interface_system(x)
        touching = layout.zeros() if self.strategy.first_contact_over_start else x
        psi = first_contact_set(self.problem.scene, layout, touching,
                                supported=system is not None,
                                predicted=predicted_contact(self.problem, layout,
                                                            self.strategy.first_contact))
        predicted = (self.strategy.first_contact is not None
                     and not np.any(state_penetration(layout, touching) < 0))
        # the friction states after the contact points: under partial slip Cattaneo's
        # (predicted_friction_states) from a cold start, else all stick; all slip (full
        # sliding) otherwise
        partial_slip = self.problem.scene.partial_slip
        friction_points = sum(layout.interfaces[i].size for i in layout.friction_indices)
        states = np.full(friction_points, 0.0 if partial_slip else 1.0)
        if partial_slip and self.start_state is None and self.coarse is None:
            states = predicted_friction_states(self.problem, layout, self.strategy.first_contact)
        psi = np.concatenate([psi, states])
        previous_psi, update, seen, cycled = None, 0, {psi.tobytes()}, False
        flipped = np.zeros(layout.contact_points, dtype=bool)   # since the last return
        loose = None        # the tolerance before returns tightened it
        tractions_lag = self.split_tractions_lag()
        floor = min(eps, SET_TOLERANCE_FLOOR)      # the updates' tightest tolerance
        tolerance = max(eps, knobs.predicted_set_tolerance if predicted
                        else knobs.active_set_tolerance)
        for iteration in range(1, knobs.max_iterations + 1):
            self.direct = system is not None
            displacement_error = 0.0        # a direct solve's iterate is its set's answer
            if system is not None:
                x, refined = system.fixed_point(self.laws(psi, direct=True))
                rounding = max(self.relative_change(refined, x))
            image = self.iterate(x, psi)
            change = self.relative_change(image, x)
            failure = self.monitor.check(iteration, image, max(change[:2]))
            new_psi = updated_contact_set(layout, psi, image, partial_slip, self.slip_origin)
            psi_settled = np.array_equal(new_psi, psi)
            if system is not None:
                # image is x up to rounding; the refinement step sizes the rounding
                self.estimate = knobs.estimate_margin * max(rounding, max(change))
                x_next = image
            else:
                # Anderson on x + M (image - x), M the coarse correction's (or I): the
                # same fixed point, and the estimate from that map's own secants
                target = (image if self.coarse is None
                          else image + self.coarse.correction(psi, image - x))
                x_next = anderson.step(x, target)
                self.estimate = displacement_error = math.inf
                if anderson.secants >= knobs.min_secants:
                    errors = self.part_errors(target, x, anderson, scale)
                    self.estimate = knobs.estimate_margin * float(np.max(errors))
                    displacement_error = float(errors[0])
                    if psi_settled:
                        self.estimate = self.confirmed(self.estimate, target, anderson)
            done, reason = self.converged(self.estimate)
            if system is not None and psi_settled and not done:
                system = None     # too ill-conditioned to solve directly: iterate on
            if done and psi_settled:
                self.record(image, psi, previous_psi, change, update, "converged")
                return self.result(image, psi, "converged", f"contact set settled, {reason}")
            self.record(image, psi, previous_psi, change, update, failure and failure[0])
            if failure:
                return self.result(image, psi, *failure)
            previous_psi = psi
            # after a cycle, the tractions too (under a stiff Robin parameter they can lag
            # behind the displacements, and an edge point flips on their error), and the
            # displacements' estimated error (a slow contraction's change hides its
            # distance: a rigid stamp's sets cycled on changes of 1e-5, errors of 0.1)
            inexact = max(change[:2]) if cycled else change[0]
            if not cycled and tractions_lag:
                inexact = max(inexact, change[1] / LAGGING_TRACTIONS)
            if cycled:
                inexact = max(inexact, displacement_error)
            if (predicted or self.start_state is not None) and update == 0:
                # the predicted set is left only once the displacements' estimated error
                # is below the tolerance too: a slow map's change hides its distance (a
                # soft layer two contact radii thick under a rigid sphere: the set
                # wandered from 33 points to 3, then 110, and back in 21 updates, 1194
                # iterations; kept, 1 set, 112); so is a warm start's set (a frictional
                # scene from a frictionless neighbour: updated after three iterations, its
                # sets cycled, 129 iterations against 75 cold; held, 52; frictionless
                # gallery scenes from a neighbour: the same or 3 more)
                inexact = max(inexact, displacement_error)
            if inexact < tolerance and not psi_settled and not partial_slip:
                new_psi = decided_entries(layout, psi, new_psi, x, image)
                if np.array_equal(new_psi, psi):
                    x = x_next      # entries within their last change only: iterate on
                    continue
                turning = new_psi[:layout.contact_points] != psi[:layout.contact_points]
                returning = np.any(flipped & turning)
                if loose is None and tolerance > floor and returning:
                    # a point would return to the state an earlier update took it from:
                    # the updates wait for a tolerance ten times tighter while they
                    # return points (a zone that barely touches enters and leaves whole
                    # on inexact iterates: the gallery's pads walked through 28 sets,
                    # 221 iterations; so, 9 and 141). The first that returns none
                    # restores it: held for good, a contact then zipping open a point an
                    # update paid it on each (copper pads on PEEK: 94 iterations without
                    # the wait, 400 held for good, 157 so)
                    loose, tolerance = tolerance, max(floor, 0.1 * tolerance)
                    x = x_next
                    continue
                flipped |= turning
                if loose is not None and not returning:
                    tolerance, loose = loose, None
            if inexact < tolerance and not psi_settled:
                if new_psi.tobytes() in seen and partial_slip:
                    # a cycle: the sticking points whose contact flips
                    # stay in contact slipping instead, once (slipping_at_flips)
                    slipping = slipping_at_flips(layout, psi, new_psi, image, self.slip_origin)
                    if slipping is not None and slipping.tobytes() not in seen:
                        new_psi = slipping
                if new_psi.tobytes() in seen:
                    if tolerance <= floor:
                        return self.result(image, psi, "stagnated",
                                           f"the contact set cycles (update {update + 1} "
                                           "returns to an earlier set)")
                    tolerance, seen, cycled = max(floor, 0.1 * tolerance), set(), True
                seen.add(new_psi.tobytes())
                psi, x, update = new_psi, image, update + 1
                if update == 1 and predicted and tolerance > eps:
                    # the predicted set left, the next are updated as any (a rigid
                    # cylinder sliding at mu 0.5, its set shrinking a point an update:
                    # 88 iterations down to 63; the gallery's the same within a set)
                    tolerance = max(eps, knobs.active_set_tolerance)
                anderson.reset()
                self.monitor.restart(iteration)
            else:
                x = x_next
        raise AssertionError("the monitor stops at max_iterations")

    def split_tractions_lag(self):
        """Whether some side's gamma is split (robin_parameters: contact_split, bond_split)
        and no side has a stiff neighbour, so that a set's update waits for its tractions
        too (LAGGING_TRACTIONS)."""
        sides = self.strategy.sides
        return (any(side.gamma != side.direct_gamma for side in sides)
                and not any(side.stiff_neighbour for side in sides))

    def inside_mask(self):
        """The state's entries of the bonds inside a worker (Strategy.bonds_inside)."""
        mask = np.zeros(self.layout.size, dtype=bool)
        for i in self.strategy.bonds_inside:
            for kind in ("u", "t"):
                for side in (0, 1):
                    mask[self.layout.slices[kind, i, side]] = True
        return mask

    def interface_system(self, x):
        """The frozen-set system of the subdomains' Robin maps, or None where some
        subdomain has none (its solves are then iterated). The maps do not depend on the
        contact set (hold_inactive): they are asked with an empty one."""
        if self.robin_maps is None:
            return None
        empty = np.zeros_like(self.layout.gap)
        maps = self.robin_maps(robin_data(self.layout, x, self.laws(empty, direct=True)))
        if maps is None:
            return None
        sides = {name: self.strategy.sides_of(self.problem, name) for name in maps}
        return InterfaceSystem(self.layout, sides, maps, lambda state: with_bond_tractions(
            self.layout, state, self.strategy.bonds_inside, self.theta))
