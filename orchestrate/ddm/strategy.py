"""The strategy of a run: how its scene is solved, decided once before any work and
handed to the loop, as preCICE's configuration is handed to its coupling scheme.

``plan_strategy`` (called by orchestrate/run/plan.py's prepare) resolves the settings
against the discrete problem into a frozen Strategy: the loop, the order of the
subdomains' solves in an iteration, how the active-set loop reaches each contact set's
fixed point (the inner solve), the penalty theta and the Robin parameter gamma, the
coarse level, and the loop's knobs. robin.run_robin_loop reads it and decides nothing
about itself; summary.json records it under "strategy" (Strategy.record), every default
resolved.

One decision needs the workers: where "auto" may solve directly, whether probing their
Robin maps pays depends on their sizes, known once they started
(orchestrate/workers/subdomains.py). The plan says so (InnerSolve.pending, and the rule
it will be decided by) and the run records the decision (Strategy.decided).

To extend it: another inner solve is another value of InnerSolve.planned, resolved in
_inner_solve and acted on by the loop; another Robin parameter (per interface, say) is
another Parameter beside ``gamma``, resolved here, that the loop's laws read.
"""

from dataclasses import asdict, dataclass, fields, replace
from typing import Optional

from orchestrate.ddm.coarse import coarse_element_size, paired
from orchestrate.ddm.robin_parameters import side_parameters
from orchestrate.mesh.problem_size import (GIB, estimated_dofs, interface_system_memory,
                                            memory_limit)

PAPER, ACTIVE_SET = "paper", "active-set"
COATED_BASE = "coated_base"          # the worker of the base with its coatings
# The tightest eps_u the loop reaches with the bonds inside a worker: their penalty in one
# matrix rounds the contact state to about 1e-10, which the stopping test's amplification
# and margin lift to 1e-9 - 2e-8 (measured: runs at eps_u 1e-10 stagnated near relative
# changes of 5e-13). A tighter tolerance keeps them exchanged. "auto" takes them inside
# only down to AUTO_INSIDE_TIGHTEST_EPS_U: at 1e-8 the gallery's near-rigid cylinder and
# steel on a coated polymer stagnated, their estimates stuck near 1.7e-8 and 1.9e-8,
# where exchanged they reached 9e-9 in as many iterations (at 1e-7 the latter converged
# inside at mesh levels 1-3).
INSIDE_TIGHTEST_EPS_U = 1e-8
AUTO_INSIDE_TIGHTEST_EPS_U = 1e-7
DIRECT, ITERATE, TWO_LEVEL = "direct", "iterate", "two-level"
NO_INNER_SOLVE = "none"              # the paper's loop: no frozen contact set
DIRECT_OR_ITERATE = "direct or iterate"   # auto below two levels: decided by the workers


@dataclass(frozen=True)
class LoopKnobs:
    """The numbers the loops read (robin.py, acceleration.py, coarse.py): the Settings'
    fields of the same names, whose comments give their meanings and units."""

    eps_u: float
    max_iterations: int
    rho: float
    active_set_tolerance: float
    predicted_set_tolerance: float
    estimate_margin: float
    min_secants: int
    traction_floor: float
    component_floor: float
    divergence_growth: float
    stagnation_progress: float
    stagnation_window: int
    paper_stagnation_window: int
    paper_contraction_window: int
    paper_amplification_window: int
    anderson_depth: int
    anderson_filter: float
    anderson_first_relaxation: float
    coarse_newton_steps: int

    @classmethod
    def of(cls, settings):
        return cls(**{f.name: getattr(settings, f.name) for f in fields(cls)})


@dataclass(frozen=True)
class Parameter:
    """A parameter of the interface laws as resolved: in the solver's units (b and E),
    as the loop uses it (the discrete problem's: Problem.penalty, Problem.robin; its
    scene is in b and E, so the same number), and the rule that gave it."""

    value: float
    unit: str
    solver_value: float
    rule: str


@dataclass(frozen=True)
class InnerSolve:
    """How the active-set loop reaches each contact set's fixed point: ``planned`` is
    DIRECT (from the subdomains' Robin maps), ITERATE (Anderson), TWO_LEVEL (Anderson
    with a coarse correction), DIRECT_OR_ITERATE (auto, decided once the workers
    started: ``decided``, ``decided_on``) or NO_INNER_SOLVE (the paper's loop)."""

    asked: str                      # Settings.inner_solve
    planned: str
    rule: str                       # why, in words, with the knobs it read
    fallback: Optional[str]         # DIRECT where an iteration auto chose stalls or
                                    # diverges (orchestrate/run/solve.py), else None
    decided: Optional[str] = None   # the inner solve the run starts with
    decided_on: Optional[dict] = None   # what the workers' decision weighed

    @property
    def pending(self):
        return self.decided is None


@dataclass(frozen=True)
class CoarseMesh:
    """The coarse level of two levels: the scene at ``mesh_level`` with interface
    elements ``element_size`` long (b) at that level, solved directly."""

    mesh_level: int
    element_size: float
    rule: str


@dataclass(frozen=True)
class Strategy:
    """How a run is solved, decided once (plan_strategy)."""

    loop: str                       # PAPER or ACTIVE_SET (Settings.method)
    sweep: tuple                    # groups of subdomains solved one after the other in
                                    # an iteration, each from the state the ones before
                                    # left (Problem.sweep), or one group: all at once
    sides: tuple                    # every interface side's gamma (E/b) and whether it
                                    # holds its inactive points where the loop iterates
                                    # (orchestrate/ddm/robin_parameters.py)
    inner_solve: InnerSolve
    theta: Parameter                # the penalty, b/E
    gamma: Parameter                # the Robin parameter, E/b
    coarse: Optional[CoarseMesh]    # with two levels, else None
    knobs: LoopKnobs
    # the first contact set: the points within this a priori contact half-width (b;
    # model/estimate.py, under a descent from the force it takes) where the first state
    # interpenetrates nowhere (robin.py's first_contact_set), or where those lie on
    # several contact faces under a force, the half-planes' contact across the faces'
    # gap (ddm/first_contact.py); None: the points touched first (under a descent, those
    # the first solve pushes through)
    first_contact: Optional[float] = None
    # whether the first set is drawn to first_contact even from a start state that
    # touches elsewhere: a warm start whose neighbour calibrated it (run/warm_start.py)
    first_contact_over_start: bool = False
    # the workers, ((worker, (its subdomains, ...)), ...): every subdomain its own, or
    # (where Settings.bonds takes them inside) the base and its coatings one, COATED_BASE
    # (freefem/coated_base.edp); and the interfaces inside a worker (its bonds), which
    # the loop does not exchange
    workers: tuple = ()
    bonds_inside: tuple = ()
    # under a force, the worker that carries the stamp's force on its contact sides at
    # every iteration (ddm/force_balance.py; Settings.force_balance), else None
    force_balance: Optional[str] = None

    def sides_of(self, problem, worker):
        """(interface index, side index) of every side of a worker's subdomains, in their
        order: what it is asked and answers (Subdomains)."""
        return problem.sides_of(*dict(self.workers)[worker])

    @property
    def two_levels(self):
        return self.inner_solve.planned == TWO_LEVEL

    @property
    def stagnation_window(self):
        """The monitor's window of the planned loop."""
        return (self.knobs.paper_stagnation_window if self.loop == PAPER
                else self.knobs.stagnation_window)

    def decided(self, direct, weighed):
        """The strategy with auto's pending inner solve decided by the workers:
        ``direct``, whether every worker gives its map (Subdomains.solves_directly);
        ``weighed``, what that was decided on."""
        if not self.inner_solve.pending:
            return self
        return replace(self, sides=_solved_directly(self.sides, direct),
                       inner_solve=replace(self.inner_solve, decided=DIRECT if direct
                                           else ITERATE, decided_on=weighed),
                       force_balance=None if direct else self.force_balance)

    def record(self, scales, units):
        """summary.json's "strategy": in b and E, theta and gamma also in the scene's
        units (``scales``: what b and E are in them; ``units``: their names)."""
        length, stress = units.length, units.stress
        in_scene = {"theta": (scales.length / scales.stress, f"{length}/{stress}"),
                    "gamma": (scales.stress / scales.length, f"{stress}/{length}")}
        record = asdict(self)
        for name, (factor, unit) in in_scene.items():
            # from the solver's value: a scene in b and E may have a stiffer body's
            # modulus other than 1
            record[name].update(scene_value=getattr(self, name).solver_value * factor,
                                scene_unit=unit)
        record["gamma_theta"] = self.gamma.value * self.theta.value
        record["sweep"] = [list(group) for group in self.sweep]
        record["workers"] = {worker: list(names) for worker, names in self.workers}
        record["bonds_inside"] = list(self.bonds_inside)
        factor, unit = in_scene["gamma"]
        record["sides"] = [{**side, "scene_gamma": side["gamma"] * factor, "scene_unit": unit}
                           for side in record["sides"]]
        return record


def _solved_directly(sides, direct):
    """The sides' parameters where each contact set is solved directly (``direct``):
    every side's unsplit (robin_parameters.SideParameter.direct_gamma)."""
    return tuple(side.solved_directly() for side in sides) if direct else sides


def plan_strategy(settings, problem, coarse=None, half_width=None, coarse_left_out=None,
                  first_contact=None):
    """The Strategy of ``problem`` (a run's discrete problem, in b and E) under
    ``settings``; ``coarse``: the coarse level's problem where two levels are asked
    (Settings.two_levels), else None; ``half_width``: the a priori contact half-width
    (b), if known; ``coarse_left_out``: why auto left out the coarse level its mesh
    level would take (run/plan.py), or None; ``first_contact``: the half-width the first
    contact set is drawn to (b; estimate.first_contact_half_width), by default
    ``half_width``."""
    paper = settings.method == PAPER
    theta, default_rule = settings.default_theta()
    inner_solve = _inner_solve(settings, problem, coarse, coarse_left_out)
    gamma, gamma_rule = settings.robin_choice()
    inside = _bonds_inside(settings, problem, inner_solve, half_width)
    if inside and inner_solve.pending:
        # chosen where the maps would not pay: the loop iterates
        inner_solve = replace(
            inner_solve, planned=ITERATE, decided=ITERATE,
            decided_on={"auto_direct_unknowns": settings.auto_direct_unknowns,
                        "weighted_unknowns": _weighted_unknowns(problem), "estimated": True},
            rule=(f"{inner_solve.rule}. Decided before the workers started: iterate, the "
                  "coatings inside the base's worker (bonds 'inside'), for the maps of each "
                  "worker apart would not pay (weighted by their estimated dofs)"))
    workers = _workers(problem, inside)
    balanced = _force_balance(settings, problem, inner_solve, workers)
    return Strategy(
        loop=settings.method,
        # the active-set loop solves the coatings from the bodies' fresh traces (a
        # Gauss-Seidel sweep; theirs are the cheap solves): fewer iterations; with the
        # coatings inside the base's worker, its workers at once
        sweep=((tuple(problem.subdomains),) if paper
               else (tuple(name for name, _ in workers),) if inside else problem.sweep),
        # two levels: the coarse level models the fine iteration with every side held
        # (its maps need fixed matrices), so the fine loop holds them too
        sides=_solved_directly(side_parameters(problem, problem.robin, settings.robin_sides,
                                               settings.hold_contrast, paper,
                                               hold_all=inner_solve.planned == TWO_LEVEL,
                                               split_sides=inner_solve.planned != TWO_LEVEL,
                                               balanced=balanced is not None),
                               inner_solve.planned == DIRECT),
        inner_solve=inner_solve,
        theta=Parameter(settings.theta, "b/E", problem.penalty,
                        default_rule if settings.theta == theta else "given (theta)"),
        gamma=Parameter(gamma, "E/b", problem.robin, gamma_rule),
        coarse=(CoarseMesh(1, coarse_element_size(settings), _coarse_rule(settings))
                if inner_solve.planned == TWO_LEVEL else None),
        knobs=LoopKnobs.of(settings),
        first_contact=(first_contact or half_width) if half_width and not paper else None,
        workers=workers,
        bonds_inside=(tuple(i for i, interface in enumerate(problem.interfaces)
                            if interface.kind == "bond") if inside else ()),
        force_balance=balanced)


def _force_balance(settings, problem, inner_solve, workers):
    """The worker that carries the stamp's force at every iteration (Settings.force_balance
    "auto"), or None. Under a force, where the active-set loop iterates on one level (its
    offset is a correction of the iterates: a contact set solved directly from the maps
    is solved at once, and two levels' coarse level models the loop unbalanced), without
    friction (whose slip also answers the stamp's tangential force), and where one
    worker, not the stamp's, holds every contact's side B. Measured on the gallery's and
    the contrast study's scenes (docs/method.md, "The Robin loop")."""
    scene = problem.scene
    if (settings.force_balance == "off" or scene.load.force is None
            or inner_solve.planned not in (ITERATE, DIRECT_OR_ITERATE)
            or any(interface.kind == "friction" for interface in problem.interfaces)):
        return None
    partners = {worker for worker, names in workers for i, side in problem.sides_of(*names)
                if problem.interfaces[i].kind == "contact" and side == 1}
    if len(partners) != 1:
        return None
    partner = partners.pop()
    if any(problem.subdomains[name].stamp for name in dict(workers)[partner]):
        return None
    return partner


def _bonds_inside(settings, problem, inner_solve, half_width):
    """Whether the base and its coatings are solved by one worker (Settings.bonds):
    "inside" where the active-set loop iterates, on one level (asked, or auto where the
    maps of each worker apart would not pay for a direct solve: they are kept from scene
    to scene, a coated base is new with every coating) or, asked, two (the coarse level
    models the one worker from its parts' maps: the paper's three patches at mesh level 2
    took 34 iterations against 37 exchanged, TiN at level 3 26 against 27; under auto's
    contrast, the rigid cylinder at level 2 took 366 against 212), and every patch is
    thinner than the a priori contact half-width (a thicker one is a body of its own under the
    contact, whose exchange with the base converges as fast: measured on the gallery,
    one worker was slower there), within the tolerance it reaches
    (INSIDE_TIGHTEST_EPS_U, under "auto" AUTO_INSIDE_TIGHTEST_EPS_U); "auto" there too:
    with no bond to exchange, the contact's far split (robin_parameters.py) keeps the
    final contact set's iterations about level with the mesh, where a thin coating's
    bond, exchanged, would not (at a contact split of 4 and between bodies alike, one
    worker had taken fewer iterations but more time, its requests and replies carrying
    both sides of every bond). Never with a fresh process per solve: each factorises
    anew, its last digits differ from process to process, and with the penalty in one
    matrix that noise (measured: relative changes stuck near 4e-9 under a near-rigid
    indenter) kept the stopping test above eps_u."""
    if (settings.method == PAPER or settings.bonds == "exchanged" or not problem.bonds
            or inner_solve.planned not in (ITERATE, DIRECT_OR_ITERATE, TWO_LEVEL)
            or settings.eps_u < (INSIDE_TIGHTEST_EPS_U if settings.bonds == "inside"
                                 else AUTO_INSIDE_TIGHTEST_EPS_U)
            or settings.workers == "fresh"):
        return False
    if half_width and any(c.thickness > half_width for c in problem.scene.coatings):
        return False
    if inner_solve.planned == TWO_LEVEL and settings.bonds != "inside":
        return False    # auto takes them inside under a contrast: no place for two levels
    return (inner_solve.planned in (ITERATE, TWO_LEVEL)
            or not maps_would_pay(problem, settings))


def maps_would_pay(problem, settings):
    """Subdomains._maps_pay before any worker started, every worker new: each one's
    interface unknowns weighted by its estimated dofs over the largest's, against
    auto_direct_unknowns."""
    return all(weighted <= settings.auto_direct_unknowns
               for weighted in _weighted_unknowns(problem).values())


def _unknowns_and_dofs(problem):
    """{subdomain: (its interface unknowns, its estimated dofs)}."""
    dofs = estimated_dofs(problem)
    return {name: (sum(problem.interfaces[i].size * problem.interfaces[i].components
                       for i, _ in problem.sides_of(name)), dofs[name]) for name in dofs}


def probe_work(problem):
    """What probing every worker's Robin map costs: its interface unknowns (a
    back-substitution each) times its estimated dofs, summed (dof-columns)."""
    return float(sum(n * dofs for n, dofs in _unknowns_and_dofs(problem).values()))


def _weighted_unknowns(problem):
    """{subdomain: its interface unknowns times its estimated dofs over the largest's}."""
    sizes = _unknowns_and_dofs(problem)
    largest = max(dofs for _, dofs in sizes.values())
    return {name: float(n * dofs / largest) for name, (n, dofs) in sizes.items()}


def _workers(problem, inside):
    """The workers and their subdomains: each subdomain its own, or (``inside``) the base
    and its coatings one (COATED_BASE), after the indenter's. Under two levels the
    coarse level models that worker from its parts' maps (coarse.py).

    Why inside: a thin coating and its base, exchanged across their bond, have
    Dirichlet-to-Neumann responses no Robin parameter matches at once (a membrane's grows
    as k^2, the base's as k), and their exchange was most of the loop's iterations
    (docs/method.md, "The coated base")."""
    names = list(problem.subdomains)
    if not inside:
        return tuple((name, (name,)) for name in names)
    subdomains = problem.subdomains.items()
    base = tuple(name for name, sub in subdomains if not (sub.coating or sub.stamp))
    coated = base + tuple(name for name, sub in subdomains if sub.coating)   # the base first
    others = tuple((name, (name,)) for name in names if name not in coated)
    return others + ((COATED_BASE, coated),)


def _inner_solve(settings, problem, coarse, coarse_left_out=None):
    """The InnerSolve the settings ask of the active-set loop, where the scene allows it
    (two levels need interfaces that pair up with the coarse level's)."""
    asked = settings.inner_solve
    if settings.method == PAPER:
        return InnerSolve(asked, NO_INNER_SOLVE, "the paper's loop updates its contact set "
                          "at every iteration: no fixed point to solve", None, NO_INNER_SOLVE)
    if problem.scene.partial_slip:
        return InnerSolve(asked, ITERATE, f"{'asked' if asked == ITERATE else 'auto'}: "
                          "iterate, as the workers' maps do not carry the stamp's shift "
                          "(partial slip)", None, ITERATE)
    fallback, affordable = None, ""
    if asked == "auto" and settings.workers == "persistent":
        work, memory = probe_work(problem), interface_system_memory(problem)
        limit, what = memory_limit(settings)
        if work > settings.auto_fallback_work:
            affordable = (f"; no direct fallback: probing every worker's map would cost "
                          f"{work:.3g} dof-columns, above auto_fallback_work "
                          f"{settings.auto_fallback_work:.3g}")
        elif limit is not None and memory > limit:
            affordable = (f"; no direct fallback: its dense interface system would take "
                          f"{memory / GIB:.1f} GiB, above {what}")
        else:
            fallback = DIRECT
    if settings.two_levels:
        rule = ("asked" if asked == TWO_LEVEL else
                f"auto: mesh_level {settings.mesh_level} >= auto_two_level_mesh_level "
                f"{settings.auto_two_level_mesh_level}")
        if coarse is not None and paired(problem.interfaces, coarse.interfaces):
            return InnerSolve(asked, TWO_LEVEL, rule + affordable, fallback, TWO_LEVEL)
        return InnerSolve(asked, ITERATE, rule + ", but the coarse level's interfaces do not "
                          "pair up with the fine ones" + affordable, fallback, ITERATE)
    if asked in (DIRECT, ITERATE):
        return InnerSolve(asked, asked, "asked", None, asked)
    if settings.workers == "fresh":
        return InnerSolve(asked, ITERATE, "auto with a fresh process per solve, which keeps "
                          "no factorisation to probe a map with", None, ITERATE)
    without_coarse = f"no coarse level ({coarse_left_out}); " if coarse_left_out else ""
    return InnerSolve(asked, DIRECT_OR_ITERATE,
                      f"auto: {without_coarse}direct where every new worker's interface unknowns, weighted by "
                      f"its dofs over the largest worker's, are at most auto_direct_unknowns "
                      f"{settings.auto_direct_unknowns}, else iterate; decided once the "
                      "workers started" + affordable, fallback)


def _coarse_rule(settings):
    if settings.mesh_level == 1:
        return (f"the paper's mesh with interface elements coarse_element_factor "
                f"{settings.coarse_element_factor:g} times as long")
    return "the paper's mesh (mesh level 1)"
