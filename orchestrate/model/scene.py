"""The scene (bodies, coatings, load) and the solver settings, as validated data.

A scene is an indenter pressed on a base that carries any number of coating patches:

    Indenter  the upper body: a block whose lower face has the profile of a circle or a
              parabola of radius R (flat without a radius), pushed down at its top by a
              rigid stamp
    Base      the lower body: a block with a flat top, clamped at its bottom, or a roller
              (a disk on a rigid shaft, clamped at its bore)
    Coating   a patch on the base's top face, between two abscissae x1, modelled as a
              Timoshenko-type shell (a shell of revolution in an axisymmetric scene) or
              as a 2D elastic body
    Load      the stamp's descent, or the total force per unit width
    Friction  Coulomb's coefficient mu on every contact, with the indenter sliding
              steadily towards +x1 (full sliding: the friction traction is mu p,
              against the indenter's motion, wherever the bodies touch) or pulled by a
              tangential force below mu P (partial slip: stick and slip zones)

Lengths are in units of b and moduli in units of E (METHOD.md); the scene files of
orchestrate/scenes/ write them out (orchestrate/model/scene_file.py reads them). Every object
is checked once, on creation; an error names the key (``coating[2].thickness``,
patches counted from 1) and the allowed range. Scene and settings are written next to
every result, so that any result can be reproduced.
"""

from contextlib import contextmanager
from dataclasses import asdict, dataclass, fields, replace
import math
import re
from typing import Optional

from orchestrate.errors import ParameterError
from orchestrate.model.units import FORCE, SCENE_KINDS, Units

MODELS = ("shell", "stretch_shell", "elastic")
SHELL_MODELS = ("shell", "stretch_shell")   # the coating on its mid-line
MODEL_CHOICES = MODELS + ("auto",)            # auto: chosen per patch (run/plan.py)
THETA_RANGE = (1e-6, 1.0)      # the penalty, b/E
ROBIN_RANGE = (1e-3, 1e3)      # the Robin parameter, E/b
MODULUS_RATIO = 1e6            # the largest over the smallest modulus of a scene
MODULUS_RANGE = (1e-20, 1e20)  # any unit of stress; beyond, squares and penalties overflow
LOOSEST_EPS_U = 1e-3           # the paper's; within it the stopping test holds (robin.py)
SMALLEST_LOAD = 1e-12          # a descent in b, a force in E b: below, results underflow
# Every length of a scene, in b (the solver's unit of length, units.b): within these, a
# scene can be meshed and its squares neither overflow nor lose their digits. A radius
# beyond its bound is a flat face (leave it out); loads beyond theirs are strains of
# millions.
LENGTH_RANGE = (1e-6, 1e6)     # b: sizes, positions (in absolute value), thicknesses
RADIUS_LIMIT = 1e12            # b
LARGEST_LOAD = 1e6             # a descent in b, a force in E b
SHEAR_FACTOR_RANGE = (1e-3, 1e3)   # k' of the shell
# Coulomb's mu: metals in air reach about 1, clean metals in vacuum more; beyond 2 the
# friction traction would exceed twice the pressure, no contact of coated parts does
FRICTION_RANGE = (0.0, 2.0)
LOAD_PATHS = ("at_once", "pressed_first")   # partial slip: the forces together, or in turn
                                            # (or a list of the states passed first: Load)
PROFILES = ("circle", "parabola")
FACE_MESHES = ("shaped", "flat")
SHAPES = ("block", "roller")
METHODS = ("active-set", "paper")
INNER_SOLVES = ("auto", "direct", "iterate", "two-level")   # a contact set's fixed point
ROBIN_SIDES = ("neighbour", "equal")   # each interface side's gamma (ddm/robin_parameters.py)
MODEL_ANSWERS = ("normal", "all")            # what auto's tolerance covers (estimate.ANSWERS)
BONDS = ("auto", "inside", "exchanged")  # the active-set loop's bonds (ddm/strategy.py)
FORCE_BALANCES = ("auto", "off")        # the stamp's partner balanced (ddm/force_balance.py)
WORKERS = ("persistent", "fresh")
PAPER_THETA = 1e-3     # b/E: the paper's penalty, the default of its loop
MESH_LEVEL_LIMIT = 16   # the paper's mesh refined 16 times: about 7 million unknowns
ELEMENT_SIZE_RANGE = (1e-4, None)   # b: the interface elements at mesh level 1
# b: the interface elements' length at mesh level 1 where the contact is wider than
# CONTACT_ELEMENTS of them (the paper's 32 on its coating of length 2), and away from it
DEFAULT_ELEMENT_SIZE = 0.0625
# Away from the contact, a face sized to it needs no more elements than twice the paper's
# density on its base (32 from the contact's centre to the base's end, 2 b away): the far
# elements are at least that reach over FAR_ELEMENTS, so that a large body costs little
# more than a small one
FAR_ELEMENTS = 64
# A contact set's update tolerance (active_set_tolerance, predicted_set_tolerance)
SET_TOLERANCE_RANGE = (1e-12, 1.0, "relative change", "below eps_u it is eps_u; above 1 "
                       "the iterates say nothing of the contact set")
# The strategy's knobs (Settings, from theta_per_length on): each one's range, inclusive,
# its unit and why beyond it the knob no longer does what it is for. An integer knob is
# one whose default is an integer.
KNOB_RANGES = {
    "theta_per_length": (1e-4, 1.0, "1/E", "the default theta, this times the element's "
                         "length, must stay within theta's range"),
    "robin_one_level": (*ROBIN_RANGE, "E/b", "beyond, the Robin exchange stops converging "
                        "(robin's own range)"),
    "robin_two_level_per_length": (*ROBIN_RANGE, "E", "gamma = robin_two_level_per_length "
                                   "/ element_size: beyond, the Robin exchange stops "
                                   "converging (robin's own range)"),
    "hold_contrast": (0.0, 1e12, "factor", "0: every side holds, and the inactive points "
                      "of a body as soft as its neighbour crawl; large: no side holds, and "
                      "every worker factorises again for each contact set"),
    "contact_split": (1.0, 1e3, "factor", "1: one coefficient each side's neighbour "
                      "offers; far above, the soft side's coefficient reaches 1/theta "
                      "and the other side's nears zero"),
    "bond_split": (1.0, 1e3, "factor", "1: the split of the coating's response against "
                   "the base's alone; above 16 the same as 16"),
    "auto_direct_unknowns": (0, 10 ** 6, "interface unknowns", "0: auto probes no new "
                             "worker's map; beyond, the dense interface system of the "
                             "maps outgrows any machine"),
    "auto_two_level_mesh_level": (1, MESH_LEVEL_LIMIT + 1, "mesh level", "1: two levels on "
                                  "every mesh; above mesh_level's limit: never"),
    "auto_fallback_work": (0.0, 1e12, "dof-columns", "0: a stalled iteration never falls "
                           "back; beyond, probing the maps takes hours and their dense "
                           "interface system outgrows the machine's memory"),
    "active_set_tolerance": SET_TOLERANCE_RANGE,
    "predicted_set_tolerance": SET_TOLERANCE_RANGE,
    "estimate_margin": (1.0, 1e3, "factor", "below 1 the estimate drops under the error "
                        "the iterates show; far above, runs iterate for nothing"),
    "min_secants": (1, 1000, "pairs of iterates", "without a pair there is no "
                    "amplification to estimate the error from"),
    "traction_floor": (1e-12, 1e-2, "of gamma ||u||", "zero: a run without contact "
                       "measures round-off; larger, real tractions count as zero"),
    "component_floor": (1e-12, 1.0, "of the largest traction component", "zero: a "
                        "vanishing component's round-off stalls the stopping test"),
    "divergence_growth": (10.0, 1e12, "factor", "smaller, an ordinary jump of a new "
                          "contact set reads as divergence"),
    "stagnation_progress": (1e-3, 0.9, "share of the smallest change", "zero: round-off "
                            "counts as progress; near 1, no loop progresses"),
    "stagnation_window": (10, 10 ** 6, "iterations", "fewer, a loop stops while its "
                          "contact set settles"),
    "paper_stagnation_window": (10, 10 ** 6, "iterations", "fewer, a loop stops while "
                                "its contact set settles"),
    "paper_contraction_window": (1, 1000, "changes", "the contraction is read from at "
                                 "least one pair of changes"),
    "paper_amplification_window": (1, 1000, "pairs of iterates", "at least one pair; a "
                                   "longer history costs more than it tells"),
    "anderson_depth": (1, 1000, "pairs of iterates", "at least one secant; more than the "
                       "interface has unknowns adds nothing but cost"),
    "anderson_filter": (1e-16, 1e-2, "of a secant's norm", "below round-off it filters "
                        "nothing; above, it drops secants that carry new directions"),
    "anderson_first_relaxation": (1e-3, 1.0, "factor", "0 does not move; above 1 the "
                                  "first step overshoots"),
    "coarse_element_factor": (1.5, 16.0, "factor", "a coarse level must be coarser, and "
                              "still see the contact"),
    "coarse_newton_steps": (1, 1000, "steps", "at least the first solve; it settles in "
                            "about ten"),
}


def _require(condition, key, message):
    if not condition:
        raise ParameterError(message, key)


def _finite(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


# A part's key (coating[1].thickness, load.path[2].force) and the number quoted after it
_QUOTED_VALUE = re.compile(r"\b((indenter|base|coating|load)(?:\[\d+\])?\.(?:path\[\d+\]\.)?"
                           r"(\w+) = -?(?:\d+\.?\d*(?:e[-+]?\d+)?|inf|nan))(?=[ :,)]|$)")


@contextmanager
def values_in_units(units, revolution=False):
    """A part's check whose message quotes values of a scene with units ("key = value")
    says each value's unit after it: a value given as "3 um", or overridden in another
    unit, is quoted in the file's unit (-0.003 mm), and a bare number is not read as b."""
    try:
        yield
    except ParameterError as error:
        if units.dimensionless:
            raise
        names = units.names(revolution)

        def with_unit(match):
            kind = SCENE_KINDS[match[2]].get(match[3])
            if kind is None or match.string.startswith(f" {names[kind]}", match.end()):
                return match[1]                 # no unit, or said already
            return f"{match[1]} {names[kind]}"
        raise ParameterError(_QUOTED_VALUE.sub(with_unit, str(error)), error.key) from None


def _positive(key, value):
    _require(_finite(value) and value > 0, key, f"{key} = {value!r} must be a positive number")


def _poisson(key, value):
    _require(_finite(value) and -1.0 < value < 0.5, key,
             f"{key} = {value!r} must lie in (-1, 0.5): outside it the body has no "
             "positive elastic energy")


def _friction(key, value):
    low, high = FRICTION_RANGE
    _require(_finite(value) and not isinstance(value, bool) and low <= value <= high, key,
             f"{key} = {value!r} must be a number in [{low:g}, {high:g}] (Coulomb's mu)")


def _choice(key, value, choices):
    _require(value in choices, key, f"{key} = {value!r} must be one of {choices}")


def _positive_int(key, value):
    _require(isinstance(value, int) and not isinstance(value, bool) and value >= 1, key,
             f"{key} = {value!r} must be a positive integer")


@dataclass(frozen=True)
class Indenter:
    """The upper body: x1 in [centre - width, centre + width] (a half model: [0, width]),
    its lower face touching the scene at its lowest point, its top ``height`` above it."""

    radius: float = math.inf       # R of the lower face; infinite: a flat face
    profile: str = "circle"        # gap above the lowest point: R - sqrt(R^2 - x^2), or x^2/(2R)
    face_mesh: str = "shaped"      # "shaped": meshed as it is; "flat": meshed flat, the
                                   # profile only in the initial gap (the paper's Omega1)
    width: float = 4.0             # half width (the whole width of a half model)
    height: float = 8.0
    centre: float = 0.0            # x1 of the lowest point (full models)
    E: float = 1.0
    nu: float = 0.3
    rigid: bool = False            # a rigid indenter: no body (E, nu and height unused),
                                   # its face pressed by the stamp as a whole

    def check(self, prefix):
        _require(isinstance(self.radius, (int, float)) and not isinstance(self.radius, bool)
                 and self.radius > 0 and not math.isnan(self.radius), prefix + "radius",
                 f"{prefix}radius = {self.radius!r} must be a positive number (or absent: "
                 "a flat face)")
        _choice(prefix + "profile", self.profile, PROFILES)
        _choice(prefix + "face_mesh", self.face_mesh, FACE_MESHES)
        for name in ("width", "height", "E"):
            _positive(prefix + name, getattr(self, name))
        _poisson(prefix + "nu", self.nu)
        _require(_finite(self.centre), prefix + "centre",
                 f"{prefix}centre = {self.centre!r} must be a number")
        _require(isinstance(self.rigid, bool), prefix + "rigid",
                 f"{prefix}rigid = {self.rigid!r} must be true or false")
        if self.profile == "circle" and math.isfinite(self.radius):
            _require(self.radius > self.width, prefix + "radius",
                     f"{prefix}radius = {self.radius!r} must exceed {prefix}width = "
                     f"{self.width!r}: a circular face cannot be wider than its circle")

    @property
    def flat(self):
        return math.isinf(self.radius)

    def sag(self, x):
        """Height of the face above its lowest point, at a distance x from it."""
        if self.flat:
            return 0.0 * x
        if self.profile == "parabola":
            return x ** 2 / (2.0 * self.radius)
        # R - sqrt(R^2 - x^2) without its cancellation (a large radius lost every digit)
        return x ** 2 / (self.radius + (self.radius ** 2 - x ** 2) ** 0.5)

    def slope(self, x):
        """d sag / dx."""
        if self.flat:
            return 0.0 * x
        if self.profile == "parabola":
            return x / self.radius
        return x / (self.radius ** 2 - x ** 2) ** 0.5


@dataclass(frozen=True)
class Base:
    """The lower body: a block [-width, width] x [0, height] (a half model: [0, width])
    clamped at its bottom, or a roller: a disk of ``radius`` about the origin on a rigid
    shaft of radius ``bore`` (default radius/2), clamped there."""

    shape: str = "block"
    width: float = 4.0             # block: half width (the whole width of a half model)
    height: float = 8.0            # block
    radius: Optional[float] = None  # roller
    bore: Optional[float] = None    # roller
    E: float = 1.0
    nu: float = 0.3

    def check(self, prefix):
        _choice(prefix + "shape", self.shape, SHAPES)
        _positive(prefix + "E", self.E)
        _poisson(prefix + "nu", self.nu)
        if self.shape == "block":
            _positive(prefix + "width", self.width)
            _positive(prefix + "height", self.height)
            for name in ("radius", "bore"):
                _require(getattr(self, name) is None, prefix + name,
                         f"{prefix}{name} = {getattr(self, name)!r} is for a roller; a "
                         "block has width and height")
        else:
            _require(self.radius is not None, prefix + "radius",
                     f"{prefix}radius is missing: a roller needs its radius")
            _positive(prefix + "radius", self.radius)
            if self.bore is not None:
                _positive(prefix + "bore", self.bore)
                _require(self.bore < 0.9 * self.radius, prefix + "bore",
                         f"{prefix}bore = {self.bore!r} must lie in (0, 0.9 {prefix}radius = "
                         f"{0.9 * self.radius:g})")

    @property
    def shaft_radius(self):
        return self.bore if self.bore is not None else 0.5 * self.radius

    @property
    def top(self):
        """x1 of the top face's ends on the side x1 > 0."""
        return self.width if self.shape == "block" else self.radius


@dataclass(frozen=True)
class Coating:
    """A patch on the base's top face between the abscissae ``start`` and ``end`` (on a
    roller: the x1 of its ends on the roller's surface)."""

    start: float = 0.0
    end: float = 2.0
    thickness: float = 0.125
    E: float = 1.0
    nu: float = 0.3
    model: str = "shell"           # "shell" (Timoshenko-type, the paper's; in an
                                   # axisymmetric scene a Mindlin shell of revolution),
                                   # "stretch_shell" (the same with thickness stretch),
                                   # "elastic" (2D) or "auto" (chosen per scene:
                                   # orchestrate/run/plan.py)
    shear_factor: float = 5.0 / 6.0  # k' of the shell
    friction: Optional[float] = None   # Coulomb's mu on its top (None: the scene's)

    def check(self, prefix):
        for name in ("start", "end"):
            _require(_finite(getattr(self, name)), prefix + name,
                     f"{prefix}{name} = {getattr(self, name)!r} must be a number")
        _require(self.end > self.start, prefix + "end",
                 f"{prefix}end = {self.end!r} must exceed {prefix}start = {self.start!r}")
        for name in ("thickness", "E", "shear_factor"):
            _positive(prefix + name, getattr(self, name))
        low, high = SHEAR_FACTOR_RANGE
        _require(low <= self.shear_factor <= high, prefix + "shear_factor",
                 f"{prefix}shear_factor = {self.shear_factor!r} must lie in [{low:g}, "
                 f"{high:g}] (Timoshenko's k', 5/6 for a rectangle): beyond, the shell's "
                 "shear stiffness leaves its matrix ill-conditioned")
        _poisson(prefix + "nu", self.nu)
        _choice(prefix + "model", self.model, MODEL_CHOICES)
        if self.friction is not None:
            _friction(prefix + "friction", self.friction)


@dataclass(frozen=True)
class LoadStep:
    """A state a load path passes through before the load's own (Load.path): the force
    per unit width and the stamp's tangential load, of the load's own kind (a tangential
    force, or a tangential displacement); one left None is the load's own."""

    force: Optional[float] = None
    tangential_force: Optional[float] = None
    tangential_displacement: Optional[float] = None


TANGENTIAL_LOADS = ("tangential_force", "tangential_displacement")


@dataclass(frozen=True)
class Load:
    """The stamp's descent from first touch, or the total force per unit width on the
    whole body (both halves of a half model); exactly one of them. Under partial slip
    also one of: the tangential force per unit width on the indenter (towards +x1;
    negative: towards -x1), below the friction's limit mu P in size, the stamp shifting
    along x1 to carry it; or the stamp's tangential displacement (its shift along x1,
    given; the tangential force its answer, mu P once the indenter slides).
    ``path``: how the tangential load is reached, "at_once" (with the force:
    proportional loading), "pressed_first" (the force alone, the tangential load zero,
    then the tangential load from that state), or the states it passes through first
    (LoadStep, or tables {force, tangential_force} or {force, tangential_displacement}),
    each solved from the one before (a fretting cycle: [{tangential_force = 0},
    {tangential_force = Q}, {tangential_force = -Q}] before Q)."""

    displacement: Optional[float] = None
    force: Optional[float] = None
    tangential_force: Optional[float] = None
    tangential_displacement: Optional[float] = None
    path: object = "at_once"

    def __post_init__(self):
        if isinstance(self.path, (list, tuple)):
            steps = []
            for number, step in enumerate(self.path, start=1):
                key = f"load.path[{number}]"
                if isinstance(step, dict):
                    allowed = [f.name for f in fields(LoadStep)]
                    unknown = [name for name in step if name not in allowed]
                    _require(not unknown, key, f"unknown key {key}.{unknown[0] if unknown else ''} "
                             f"(allowed: {', '.join(allowed)})")
                    step = LoadStep(**step)
                _require(isinstance(step, LoadStep), key,
                         f"{key} = {step!r} must be a table {{force, {self.tangential_kind}}}")
                steps.append(step)
            object.__setattr__(self, "path", tuple(steps))

    def check(self, prefix):
        given = [name for name in ("displacement", "force") if getattr(self, name) is not None]
        _require(len(given) == 1, prefix + "displacement",
                 f"{prefix.rstrip('.')} must give exactly one of displacement or force "
                 f"(given: {given or 'none'})")
        _require(_finite(getattr(self, given[0])) and getattr(self, given[0]) >= 0,
                 prefix + given[0],
                 f"{prefix}{given[0]} = {getattr(self, given[0])!r} must be a non-negative number")
        tangential = [name for name in TANGENTIAL_LOADS if getattr(self, name) is not None]
        _require(len(tangential) <= 1, prefix + "tangential_displacement",
                 f"{prefix.rstrip('.')} must give at most one of tangential_force or "
                 "tangential_displacement (the stamp's force along x1, or its shift)")
        for name in tangential:
            _require(_finite(getattr(self, name)), prefix + name,
                     f"{prefix}{name} = {getattr(self, name)!r} must be a number")
        if isinstance(self.path, str):
            _choice(prefix + "path", self.path, LOAD_PATHS)
        if self.path in ("at_once", ()):
            return
        _require(tangential, prefix + "path",
                 f"{prefix}path = {self.path!r} needs {prefix}tangential_force or "
                 f"{prefix}tangential_displacement: a path is the order of the force and "
                 "the tangential load")
        _require(self.force is not None, prefix + "path",
                 f"{prefix}path = {self.path!r} needs {prefix}force: a path's steps are "
                 "forces")
        for number, step in enumerate(self.path if isinstance(self.path, tuple) else (),
                                      start=1):
            key = f"{prefix}path[{number}]."
            if step.force is not None:
                _require(_finite(step.force) and step.force > 0, key + "force",
                         f"{key}force = {step.force!r} must be a positive number (a "
                         "tangential load needs the bodies pressed together)")
            other = next(n for n in TANGENTIAL_LOADS if n != self.tangential_kind)
            _require(getattr(step, other) is None, key + other,
                     f"{key}{other} with {prefix}{self.tangential_kind}: a path's steps give "
                     "the load's own kind of tangential load")
            value = getattr(step, self.tangential_kind)
            if value is not None:
                _require(_finite(value), key + self.tangential_kind,
                         f"{key}{self.tangential_kind} = {value!r} must be a number")

    @property
    def kind(self):
        return "force" if self.force is not None else "displacement"

    @property
    def tangential_kind(self):
        """"tangential_force", "tangential_displacement", or None (no tangential load)."""
        return ("tangential_displacement" if self.tangential_displacement is not None
                else "tangential_force" if self.tangential_force is not None else None)

    @property
    def tangential(self):
        """The tangential load's value, of its kind (None: none)."""
        return None if self.tangential_kind is None else getattr(self, self.tangential_kind)

    @property
    def earlier_steps(self):
        """The (force, tangential load of the load's kind) of every state the path passes
        through before the load's own, in order (none: "at_once")."""
        if self.path == "pressed_first":
            return ((self.force, 0.0),)
        if isinstance(self.path, str):
            return ()
        kind = self.tangential_kind
        return tuple((self.force if step.force is None else step.force,
                      self.tangential if getattr(step, kind) is None else getattr(step, kind))
                     for step in self.path)

    def step_before(self):
        """The load of the path's step before this one (None: none): its force and
        tangential load, the path up to it."""
        steps, kind = self.earlier_steps, self.tangential_kind
        if not steps:
            return None
        force, tangential = steps[-1]
        earlier = tuple(LoadStep(**{"force": f, kind: q}) for f, q in steps[:-1])
        return replace(self, force=force, **{kind: tangential}, path=earlier or "at_once")


@dataclass(frozen=True)
class Scene:
    """The indenter, the base, its coating patches (any number, none overlapping) and
    the load. ``symmetric``: a half model, x1 >= 0, with symmetry at x1 = 0.
    ``axisymmetric``: the bodies are bodies of revolution about x1 = 0 and the scene
    their meridian section, (x1, x2) = (r, z): a sphere (circle profile) or a
    paraboloid or a flat punch on a cylinder of radius base.width, coating patches are
    rings [start, end] in r (from 0: a disc; a shell model is a shell of revolution),
    the load a total force (E b^2).
    ``contact_zone``: the x1 range where the indenter may touch the coatings or the
    bare base (default: wherever its face is over the base); a run whose contact
    reaches an end of it that is not the end of a face fails. A patch may reach beyond
    it (a coating wider than the indenter's face): its top is a contact up to its last
    element end inside the zone and free beyond.
    ``friction``: Coulomb's coefficient mu on every contact (a patch's own
    ``friction``, where given, on its top); ``sliding``: the indenter
    slides steadily towards +x1 over the base (full sliding: the friction traction
    mu p wherever the bodies touch, the indenter dragging the surfaces it touches
    along), or load.tangential_force or load.tangential_displacement (partial slip).
    Friction needs one of them, and both a full plane model (symmetric = false):
    friction breaks the mirror symmetry."""

    indenter: Indenter
    base: Base
    load: Load
    coatings: tuple = ()
    symmetric: bool = True
    contact_zone: Optional[tuple] = None
    axisymmetric: bool = False
    units: Units = Units()         # the file's units (orchestrate/model/units.py); default b, E
    friction: float = 0.0          # Coulomb's mu on every contact
    sliding: bool = False          # the indenter slides towards +x1 (full sliding)

    def __post_init__(self):
        _require(isinstance(self.units, Units), "units",
                 f"units = {self.units!r} must be orchestrate.units.Units")
        _require(isinstance(self.coatings, (tuple, list)), "coating",
                 f"coating = {self.coatings!r} must be a list of patches ([[coating]] tables)")
        object.__setattr__(self, "coatings", tuple(self.coatings))
        if self.contact_zone is not None:
            _require(isinstance(self.contact_zone, (tuple, list)), "contact_zone",
                     f"contact_zone = {self.contact_zone!r} must be [x1_start, x1_end]")
            object.__setattr__(self, "contact_zone", tuple(self.contact_zone))
        _require(isinstance(self.symmetric, bool), "symmetric",
                 f"symmetric = {self.symmetric!r} must be true or false")
        _require(isinstance(self.axisymmetric, bool), "axisymmetric",
                 f"axisymmetric = {self.axisymmetric!r} must be true or false")
        with values_in_units(self.units, self.axisymmetric):
            self.indenter.check("indenter.")
            self.base.check("base.")
            self.load.check("load.")
            for number, coating in enumerate(self.coatings, start=1):
                coating.check(f"coating[{number}].")
            self._check_magnitudes()
            self._check_layout()
            self._check_friction()

    def _lengths(self):
        """(key, value) of every length of the scene, in its units."""
        yield from ((f"indenter.{name}", getattr(self.indenter, name))
                    for name in ("radius", "width", "height", "centre"))
        yield from ((f"base.{name}", getattr(self.base, name))
                    for name in ("width", "height", "radius", "bore"))
        for number, coating in enumerate(self.coatings, start=1):
            yield from ((f"coating[{number}].{name}", getattr(coating, name))
                        for name in ("start", "end", "thickness"))
        yield from (("contact_zone", z) for z in self.contact_zone or ())

    def _check_magnitudes(self):
        """Every length within LENGTH_RANGE b (a radius within RADIUS_LIMIT b), the load
        within LARGEST_LOAD: checked before any square of them is taken."""
        b, unit = self.units.b, self.units.length
        low, high = LENGTH_RANGE
        of_b = "" if unit == "b" else f" (b = {b:g} {unit}, units.b)"

        def given(key, value, size):
            return f"{key} = {value:g} {unit}" + ("" if unit == "b" else f" is {size:.3g} b")
        for key, value in self._lengths():
            if value is None or value == 0 or (key == "indenter.radius" and math.isinf(value)):
                continue
            _require(_finite(value), key, f"{key} = {value!r} must be a finite number")
            size = abs(value) / b
            limit = RADIUS_LIMIT if key.endswith("radius") else high
            _require(size <= limit, key,
                     f"{given(key, value, size)}: at most {limit:g} b{of_b}"
                     + (": a larger radius is a flat face (leave it out)"
                        if key == "indenter.radius" else ""))
            positions = key.endswith(("centre", "start", "end")) or key == "contact_zone"
            _require(positions or size >= low, key,
                     f"{given(key, value, size)}: at least {low:g} b{of_b}: "
                     "smaller, it cannot be meshed beside the others")
        load = self.load
        if load.force is not None:       # per unit width, or an axisymmetric scene's total
            per_b, force = ("b^2", b ** 2) if self.axisymmetric else ("b", b)
            limit = LARGEST_LOAD * self.modulus * force
            in_units = ("" if self.units.dimensionless else
                        f" = {limit:g} {self.units.names(self.axisymmetric)[FORCE]}")
            _require(load.force <= limit, "load.force",
                     f"load.force = {load.force:g} must be at most {LARGEST_LOAD:g} E {per_b}"
                     f"{in_units}: beyond, strains of millions")
        if load.displacement is not None:
            _require(load.displacement <= LARGEST_LOAD * b, "load.displacement",
                     f"load.displacement = {load.displacement:g} must be at most "
                     f"{LARGEST_LOAD:g} b = {LARGEST_LOAD * b:g}")

    def patch_ends(self, coating):
        """The x1 of a patch's ends (a half model's symmetry axis is no end)."""
        return [end for end in (coating.start, coating.end)
                if not (self.symmetric and end == 0.0)]

    def _check_layout(self):
        base, indenter = self.base, self.indenter
        low = 0.0 if self.symmetric else -base.top
        if self.axisymmetric:
            self._check_revolution()
        if self.symmetric:
            _require(indenter.centre == 0, "indenter.centre",
                     f"indenter.centre = {indenter.centre!r} must be 0 in a half model "
                     "(symmetric = true); off-centre loads need symmetric = false")
        for number, coating in enumerate(self.coatings, start=1):
            key = f"coating[{number}]."
            where = (f"the roller's upper half, |x1| < radius = {base.radius!r}"
                     if base.shape == "roller" else f"the base's top face [{low:g}, {base.top:g}]")
            limit = base.top
            inside = (low <= coating.start and coating.end <= limit if base.shape == "block"
                      else low <= coating.start and coating.end < limit and coating.start > -limit)
            name = "start" if coating.start < low or coating.start <= -limit else "end"
            _require(inside, key + name,
                     f"{key}{name} = {getattr(coating, name)!r} (the patch [{coating.start!r}, "
                     f"{coating.end!r}]) must lie on {where}"
                     + (" (a half model starts at the symmetry axis x1 = 0)"
                        if self.symmetric and coating.start < 0 else ""))
            if base.shape == "block":
                _require(coating.thickness < base.height, key + "thickness",
                         f"{key}thickness = {coating.thickness!r} must be below base.height "
                         f"= {base.height!r}")
            else:
                _require(coating.thickness < base.radius, key + "thickness",
                         f"{key}thickness = {coating.thickness!r} must be below base.radius "
                         f"= {base.radius!r}")
        ordered = sorted(enumerate(self.coatings, start=1), key=lambda item: item[1].start)
        for (n1, first), (n2, second) in zip(ordered, ordered[1:]):
            _require(second.start >= first.end, f"coating[{n2}].start",
                     f"coating[{n2}].start = {second.start!r} overlaps coating[{n1}] "
                     f"[{first.start!r}, {first.end!r}]: patches must not overlap")
        if self.contact_zone is not None:
            zone = self.contact_zone
            _require(len(zone) == 2 and all(_finite(z) for z in zone) and zone[0] < zone[1],
                     "contact_zone", f"contact_zone = {list(zone)!r} must be [x1_start, x1_end] "
                     "with x1_start < x1_end")
        if self.load.force is not None:
            _require(self.load.force >= SMALLEST_LOAD * self.modulus, "load.force",
                     f"load.force = {self.load.force!r} must be at least {SMALLEST_LOAD:g} "
                     f"E b = {SMALLEST_LOAD * self.modulus:g}: the indenter is pushed onto "
                     "the base")
        descent = self.load.displacement
        _require(descent is None or descent == 0 or descent >= SMALLEST_LOAD, "load.displacement",
                 f"load.displacement = {descent!r} must be 0 or at least {SMALLEST_LOAD:g} b: "
                 "smaller descents underflow")
        moduli = {"base.E": self.base.E} if self.indenter.rigid else {
            "indenter.E": self.indenter.E, "base.E": self.base.E}
        moduli.update((f"coating[{n}].E", c.E) for n, c in enumerate(self.coatings, start=1))
        for key, modulus in moduli.items():
            _require(MODULUS_RANGE[0] <= modulus <= MODULUS_RANGE[1], key,
                     f"{key} = {modulus!r} must lie in [{MODULUS_RANGE[0]:g}, "
                     f"{MODULUS_RANGE[1]:g}] (any unit of stress does: Pa, MPa, E): beyond, "
                     "squared stresses and penalties under- or overflow")
        softest, stiffest = min(moduli, key=moduli.get), max(moduli, key=moduli.get)
        _require(moduli[stiffest] <= MODULUS_RATIO * moduli[softest], softest,
                 f"{softest} = {moduli[softest]!r} must be at least {stiffest} / "
                 f"{MODULUS_RATIO:g} = {moduli[stiffest] / MODULUS_RATIO:g}: the coupled "
                 "problem's conditioning grows with the moduli's ratio")

    def _check_friction(self):
        """Friction on a full plane model, under full sliding or partial slip: what the
        solver covers."""
        _require(isinstance(self.sliding, bool), "sliding",
                 f"sliding = {self.sliding!r} must be true or false")
        _friction("friction", self.friction)
        moving = self.sliding or self.partial_slip
        for number, coating in enumerate(self.coatings, start=1):
            key = f"coating[{number}].friction"
            _require(not coating.friction or moving, "sliding",
                     f"{key} = {coating.friction!r} needs sliding = true (full sliding) or "
                     "load.tangential_force or load.tangential_displacement (partial slip)")
        _require(self.friction == 0 or moving, "sliding",
                 f"friction = {self.friction!r} needs sliding = true (full sliding: the "
                 "friction traction mu p wherever the bodies touch) or load.tangential_force "
                 "or load.tangential_displacement (partial slip under a tangential force "
                 "below mu P, or a given shift)")
        _require(not self.sliding or not self.symmetric, "symmetric",
                 "sliding = true needs symmetric = false: the friction traction breaks the "
                 "mirror symmetry of a half model (model the whole scene)")
        if not self.partial_slip:
            return
        kind, q = f"load.{self.load.tangential_kind}", self.load.tangential
        _require(not self.sliding, kind,
                 f"{kind} = {q!r} with sliding = true: a sliding indenter carries mu P; "
                 "leave one of them out")
        _require(not self.symmetric, "symmetric",
                 f"{kind} needs symmetric = false: the tangential load breaks the mirror "
                 "symmetry of a half model (model the whole scene)")
        # a rigid stamp's shift would be a second unknown of its Robin problem: tried, its
        # loop diverged where the stick zone's ends settle (not kept)
        _require(not self.indenter.rigid, "indenter.rigid",
                 f"{kind} with indenter.rigid = true: a rigid indenter's shift is not "
                 "modelled yet; give the indenter a modulus")
        if self.load.tangential_kind == "tangential_displacement":
            return                   # any shift: beyond the stick limit the indenter slides
        _require(self.load.force is not None, kind,
                 f"{kind} = {q!r} needs load.force: the stamp carries both forces (a "
                 "descent with a tangential force is not solved; give "
                 "load.tangential_displacement)")
        least = min([self.friction] + [c.friction for c in self.coatings
                                       if c.friction is not None])
        steps = [("load.", self.load.force, q)] + [
            (f"load.path[{n}].", force, tangential)
            for n, (force, tangential) in enumerate(self.load.earlier_steps, start=1)]
        for prefix, force, tangential in steps:
            _require(abs(tangential) < least * force, prefix + "tangential_force",
                     f"{prefix}tangential_force = {tangential!r} must be below mu P = "
                     f"{least:g} x {force!r} in size (the smallest friction on any "
                     "contact): at it the indenter slides (sliding = true, or "
                     "load.tangential_displacement)")

    def step_before(self):
        """The scene of its load path's step before this one (Load.step_before), each
        solved from the one before it; None: none."""
        load = self.load.step_before() if self.partial_slip else None
        return None if load is None else replace(self, load=load)

    @property
    def partial_slip(self):
        """Whether the stamp carries a tangential load (a force below the friction's
        limit, or a shift)."""
        return self.load.tangential_kind is not None

    @property
    def frictional(self):
        """Whether any contact carries a friction traction."""
        return (self.sliding or self.partial_slip) and any(mu > 0 for mu in [self.friction] + [
            c.friction for c in self.coatings if c.friction is not None])

    def friction_on(self, coating):
        """Coulomb's mu on a patch's top (None: the bare base's)."""
        if coating is not None and coating.friction is not None:
            return coating.friction
        return self.friction

    def _check_revolution(self):
        """What a scene of bodies of revolution (axisymmetric) cannot have."""
        _require(self.symmetric, "symmetric",
                 "symmetric = false with axisymmetric = true: a body of revolution is "
                 "modelled by its meridian section, r >= 0 (leave symmetric out)")
        _require(self.base.shape == "block", "base.shape",
                 f"base.shape = {self.base.shape!r} with axisymmetric = true: the base of "
                 "revolution is a cylinder (shape = \"block\": radius base.width, height "
                 "base.height); a roller is a plane scene")
        for number, coating in enumerate(self.coatings, start=1):
            key = f"coating[{number}]."
            _require(coating.start >= 0, key + "start",
                     f"{key}start = {coating.start!r}: a ring of an axisymmetric scene lies "
                     "at r >= 0 (a patch from 0 is a disc)")

    @property
    def modulus(self):
        """E, the scene's unit of stress: the stiffer body's modulus (the base's under a
        rigid indenter). The penalty and the Robin parameter are set in b/E and E/b, so
        that a scene behaves the same in any unit of stress."""
        return self.base.E if self.indenter.rigid else max(self.indenter.E, self.base.E)

    # ---- derived quantities -------------------------------------------------------
    @property
    def contact_centre(self):
        """x1 of the contact's centre before any load: under the indenter's lowest point
        (on the axis of a half model)."""
        return 0.0 if self.symmetric else self.indenter.centre

    @property
    def mirror_symmetric(self):
        """A full model whose geometry and materials are symmetric about x1 = 0: its
        meshes are made mirror-symmetric, so that it equals its half model."""
        if self.symmetric or self.indenter.centre != 0:
            return False
        if self.contact_zone is not None and self.contact_zone[0] != -self.contact_zone[1]:
            return False
        mirrored = {replace(c, start=-c.end, end=-c.start) for c in self.coatings}
        return mirrored == set(self.coatings)

    def with_models(self, models):
        """The scene with its patches modelled by ``models``, one per patch."""
        return replace(self, coatings=tuple(replace(c, model=m)
                                            for c, m in zip(self.coatings, models)))

    @property
    def half_force(self):
        """The stamp's force on the modelled part (half of it in a half model)."""
        if self.load.force is None:
            return None
        if self.axisymmetric:          # the meridian section carries the whole body
            return self.load.force
        return 0.5 * self.load.force if self.symmetric else self.load.force


class DefaultTheta(float):
    """Settings.theta where it was not given: the default of its mesh, worked out again
    by a Settings made from it with another mesh (dataclasses.replace), unlike a theta
    given, which is kept."""


@dataclass(frozen=True)
class Settings:
    """How the scene is solved: penalty, Robin loop, mesh; then the strategy's knobs,
    which tune the defaults, auto's choices and the loops (orchestrate/ddm/strategy.py
    resolves them, with the scene, into the run's Strategy)."""

    theta: Optional[float] = None  # penalty parameter of (16), in b/E (E: Scene.modulus);
                                   # None: PAPER_THETA for the paper's loop, else
                                   # theta_per_length times the interface element's length
    method: str = "active-set"     # Robin loop: "active-set" (accelerated) or "paper"
    inner_solve: str = "auto"      # active-set loop, each contact set's fixed point:
                                   # "direct" from the subdomains' Robin maps, "iterate"
                                   # (Anderson), "two-level" (Anderson with a coarse
                                   # correction: the scene at mesh level 1; on level 1
                                   # itself, with interface elements coarse_element_factor
                                   # times as long), "auto": two-level from mesh level
                                   # auto_two_level_mesh_level, below it direct where the
                                   # maps cost less (auto_direct_unknowns), else iterate
    robin: Optional[float] = None  # Robin parameter gamma, E/b; None: robin_parameter
    robin_sides: str = "neighbour"  # each side's gamma: "neighbour", gamma times the
                                   # neighbour's plane-strain modulus over the stiffer
                                   # body's (orchestrate/ddm/robin_parameters.py);
                                   # "equal", gamma on every side
    bonds: str = "auto"            # the active-set loop's: "inside", the base and its
                                   # coatings solved by one worker
                                   # (freefem/coated_base.edp), the bonds in its matrix,
                                   # where the loop iterates (on one level, or two);
                                   # "auto", so on one level under a contrast of the
                                   # bodies (hold_contrast); "exchanged", every coating
                                   # its own worker, the bonds Robin-exchanged as the
                                   # paper's loop exchanges them
    force_balance: str = "auto"    # under a force, where the active-set loop iterates on
                                   # one level without friction: "auto", the worker of
                                   # every contact's side B carries the stamp's force at
                                   # each iteration (orchestrate/ddm/force_balance.py),
                                   # and the stamp's sides release their inactive points;
                                   # "off", neither
    rho: float = 0.5               # relaxation (24), in (0, 1]
    eps_u: float = 1.0e-6          # the relative error at which a run stops (robin.py)
    max_iterations: int = 3000
    mesh_level: int = 1            # 1: the paper's mesh; L: every mesh size divided by L
    element_size: Optional[float] = None  # interface elements' length at mesh level 1 (b),
                                   # uniform; None: sized to the contact (sized_to)
    contact_elements: float = 16.0  # sized to the contact: at least this many interface
                                   # elements across the a priori contact half-width,
                                   # graded to element_size_far away from it
    element_size_far: Optional[float] = None  # b: the elements' length away from the
                                   # contact where sized_to refined it (None:
                                   # DEFAULT_ELEMENT_SIZE, or on a large body the contact
                                   # range's reach over FAR_ELEMENTS if longer)
    workers: str = "persistent"    # FreeFEM workers: persistent, or a fresh process per solve
    worker_timeout: float = 600.0  # seconds a worker may take to answer before the run fails
    memory_limit: Optional[float] = None  # GiB the run may take; None: 3/4 of what is free
    model_tolerance: float = 0.01  # model = "auto": the estimated error a chosen coating
                                   # model may have in each of the model_answers
    model_answers: str = "normal"  # the answers model_tolerance covers: "normal" (the
                                   # peak contact stress and the bond's normal stress,
                                   # the paper's) or "all" (and the bond's shear, which
                                   # the shells miss by several to tens of per cent,
                                   # docs/findings.md: all takes the 2D coating nearly
                                   # always, and on thin coatings it costs)
    body_fields: bool = True       # write the indenter's and base's nodal fields (CSV,
                                   # VTU); the interfaces' tables, the reactions and the
                                   # coatings' fields are written always

    # ---- the strategy's knobs (ranges: KNOB_RANGES; what was measured with them:
    # docs/method.md). The defaults of theta and gamma, where not given:
    theta_per_length: float = 4e-3  # 1/E: the active-set loop's theta per b of interface
                                    # element: the penalty's error stays below the mesh's
    robin_one_level: float = 8.0    # E/b: the active-set loop's gamma on one level at
                                    # mesh level 1, times sqrt(mesh_level) finer (on the
                                    # gallery's meshes, sized to the contact, 20-50 %
                                    # fewer iterations than 2, the best on the figures'
                                    # b/16, whose scenes the maps solve directly)
    robin_two_level_per_length: float = 4.0  # E: with two levels gamma is this over
                                    # element_size: the stiffness of the interface modes
                                    # the coarse mesh cannot see, which it damps fastest
    hold_contrast: float = 4.0      # a side holds its inactive contact points (a matrix
                                    # that never changes) only where its body is at least
                                    # this many times as stiff (E*) as its neighbour; the
                                    # others release them (robin_parameters.py); auto takes
                                    # no coarse level where a neighbour is more than this
                                    # many times as stiff
    contact_split: float = 256.0    # iterated on one level without friction, a contact's
                                    # stiffer side takes its neighbour-rule gamma over
                                    # this, the softer side its own times this: nearly
                                    # a Neumann and a Dirichlet side (at most 4 under an
                                    # indenter hold_contrast times as stiff as the
                                    # base; robin_parameters.py); 1: unsplit
    bond_split: float = 16.0        # and a bond's sides, split by the coating's response
                                    # against the base's, further by this (frictionless,
                                    # one level; at most 16 in all); 1: that split alone
    # auto's inner solve:
    auto_direct_unknowns: int = 250  # interface unknowns: auto solves each contact set
                                    # directly while every new worker has at most this
                                    # many, weighted by its dofs over the largest worker's
                                    # (probing costs a back-substitution per unknown);
                                    # on a finer mesh, two levels only where the coarse
                                    # level's workers have at most as many (run/plan.py)
    auto_two_level_mesh_level: int = 2  # auto iterates with two levels from this mesh
                                    # level up (there probing maps costs more)
    auto_fallback_work: float = 5e8  # dof-columns: an iteration auto chose that stalls
                                    # falls back to the direct solve only where probing
                                    # every worker's map costs at most this much (its
                                    # interface unknowns times its estimated dofs,
                                    # summed): a few minutes (the near-rigid cylinder at
                                    # mesh level 3, 3.2e8, took 111 s and 1 GB solved
                                    # directly; a 5 um 2D coating on a roller at level 3,
                                    # 2.4e9, ran a quarter of an hour and grew past
                                    # 12 GB; at level 2, 7.3e8, its dense system would
                                    # take 13.6 GB); beyond, the run stops stagnated and
                                    # says why
    # the active-set loop:
    active_set_tolerance: float = 1e-2  # relative change at which the contact set is
                                    # updated (eps_u once a set recurs): enough to tell
                                    # tension from compression at most points
    predicted_set_tolerance: float = 1e-3  # the same, where the first contact set is the
                                    # one predicted from the a priori half-width
                                    # (Strategy.first_contact): it is near the answer's,
                                    # and looser updates flip its edge points on the
                                    # iterates' error (docs/method.md)
    # the stopping test (both loops):
    estimate_margin: float = 5.0    # factor on the estimated error: the amplification the
                                    # iterates show bounds the true one from below
    min_secants: int = 3            # pairs of iterates of the final contact set before the
                                    # estimate counts
    traction_floor: float = 1e-6    # of gamma ||u||: tractions below it count as zero in
                                    # relative changes (their natural scale: 1e-2 to 1)
    component_floor: float = 1e-3   # of the largest traction component: the least each
                                    # component's error is measured against
    # the monitor (both loops):
    divergence_growth: float = 1e3  # diverged: a displacement this many times the scene's
                                    # scale, or a relative change this many times the
                                    # smallest since the last contact set
    stagnation_progress: float = 0.1   # relative: a new smallest change must be this much
                                    # below the last one to count as progress
    stagnation_window: int = 200    # iterations without progress: the active-set loop
                                    # stagnated
    paper_stagnation_window: int = 500  # the same for the paper's loop
    # the paper's loop's error estimate:
    paper_contraction_window: int = 10  # changes its contraction is read over (fewer are
                                    # fooled by a contact set that changes every iteration)
    paper_amplification_window: int = 50  # pairs of iterates whose amplification it reads
    # Anderson acceleration (the active-set loop):
    anderson_depth: int = 100       # pairs of iterates its secant model keeps
    anderson_filter: float = 1e-8   # relative: a secant whose QR diagonal is below this
                                    # times its norm adds no direction and is dropped
    anderson_first_relaxation: float = 1.0  # factor: its first step after a restart,
                                    # x + this (G(x) - x)
    # two levels:
    coarse_element_factor: float = 2.0  # on mesh level 1 the coarse level's interface
                                    # elements are this many times the fine ones
    coarse_newton_steps: int = 50   # semi-smooth Newton steps of the coarse contact
                                    # problem at most (it settles in about ten)

    def __post_init__(self):
        _choice("workers", self.workers, WORKERS)
        _choice("method", self.method, METHODS)
        _choice("inner_solve", self.inner_solve, INNER_SOLVES)
        _choice("robin_sides", self.robin_sides, ROBIN_SIDES)
        _choice("bonds", self.bonds, BONDS)
        _choice("force_balance", self.force_balance, FORCE_BALANCES)
        _choice("model_answers", self.model_answers, MODEL_ANSWERS)
        _require(not (self.method == "paper" and self.inner_solve == "direct"), "inner_solve",
                 "inner_solve = 'direct' needs method = 'active-set': the paper's loop "
                 "updates its contact set at every iteration and has no fixed point to solve")
        _require(not (self.method == "paper" and self.inner_solve == "two-level"),
                 "inner_solve", "inner_solve = 'two-level' needs method = 'active-set': "
                 "the paper's loop is not accelerated")
        _require(not (self.workers == "fresh" and self.inner_solve == "direct"), "inner_solve",
                 "inner_solve = 'direct' needs workers = 'persistent': a fresh process per "
                 "solve keeps no factorisation to probe the maps with")
        _positive_int("mesh_level", self.mesh_level)
        _require(self.mesh_level <= MESH_LEVEL_LIMIT, "mesh_level",
                 f"mesh_level = {self.mesh_level!r} must be at most {MESH_LEVEL_LIMIT}: each "
                 "level divides every mesh size, and the paper's mesh at level "
                 f"{MESH_LEVEL_LIMIT} already has millions of unknowns")
        for key in ("element_size", "element_size_far"):
            value = getattr(self, key)
            if value is None:
                continue
            _positive(key, value)
            _require(value >= ELEMENT_SIZE_RANGE[0], key,
                     f"{key} = {value!r} must be at least {ELEMENT_SIZE_RANGE[0]:g} b (a length "
                     "in b, or with its unit in a scene with [units]): smaller, the faces "
                     "need millions of elements")
        _require(self.element_size_far is None or self.element_size is None
                 or self.element_size_far >= self.element_size, "element_size_far",
                 f"element_size_far = {self.element_size_far!r} must be at least element_size "
                 f"= {self.element_size!r}: it is the elements' length away from the contact")
        _require(_finite(self.contact_elements) and 1.0 <= self.contact_elements <= 1e4,
                 "contact_elements", f"contact_elements = {self.contact_elements!r} must lie "
                 "in [1, 1e4]: interface elements across the a priori contact half-width")
        self._check_knobs()
        if self.theta is None or isinstance(self.theta, DefaultTheta):
            # the default, tied to the mesh: set here, and again where replace() changed
            # the mesh (a default kept from mesh level 1 had the gallery's level-2 runs
            # under level 1's penalty)
            theta, rule = self.default_theta()
            _require(THETA_RANGE[0] <= theta <= THETA_RANGE[1], "theta_per_length",
                     f"theta_per_length = {self.theta_per_length!r} gives the default theta = "
                     f"{rule} = {theta:g} b/E, beyond theta's range [{THETA_RANGE[0]:g}, "
                     f"{THETA_RANGE[1]:g}]: give another one, or theta")
            object.__setattr__(self, "theta", DefaultTheta(theta))
        _require(_finite(self.theta) and THETA_RANGE[0] <= self.theta <= THETA_RANGE[1], "theta",
                 f"theta = {self.theta!r} must lie in [{THETA_RANGE[0]:g}, {THETA_RANGE[1]:g}] "
                 "(b/E): a softer penalty is no contact law (the bodies pass through each "
                 "other), a stiffer one leaves the problem ill-conditioned")
        if self.robin is not None:
            _require(_finite(self.robin) and ROBIN_RANGE[0] <= self.robin <= ROBIN_RANGE[1],
                     "robin", f"robin = {self.robin!r} must lie in [{ROBIN_RANGE[0]:g}, "
                     f"{ROBIN_RANGE[1]:g}] (E/b): the Robin exchange slows down by about the "
                     "factor gamma/2 or 2/gamma away from its best value 2 (measured: 290 "
                     "iterations at 0.01; with two levels, 4 E over the element length) and "
                     "stops converging beyond that range")
            # the Robin-Robin exchange loses the penalised laws at gamma theta = 2 (docs/method.md)
            _require(self.robin * self.theta < 1.5, "robin",
                     f"robin = {self.robin!r} must be below 1.5/theta = {1.5 / self.theta:g}: "
                     "at gamma theta = 2 the Robin exchange no longer fixes the interface laws")
        elif self.two_levels:
            # the default's own range: the coarse level is given it as its robin
            gamma, rule = self.robin_choice()
            _require(ROBIN_RANGE[0] <= gamma <= ROBIN_RANGE[1], "robin_two_level_per_length",
                     f"robin_two_level_per_length = {self.robin_two_level_per_length!r} gives "
                     f"the default gamma = {rule} = {gamma:g} E/b, beyond robin's range "
                     f"[{ROBIN_RANGE[0]:g}, {ROBIN_RANGE[1]:g}]: give a smaller one, or robin")
        _require(_finite(self.rho) and 0 < self.rho <= 1, "rho",
                 f"rho = {self.rho!r} must lie in (0, 1]")
        _require(_finite(self.eps_u) and 0 < self.eps_u <= LOOSEST_EPS_U, "eps_u",
                 f"eps_u = {self.eps_u!r} must lie in (0, {LOOSEST_EPS_U:g}]: looser, the "
                 "contact set is decided on iterates too rough to place its edges and the "
                 "error estimate no longer bounds the error (measured: the bond shear 3.4 % "
                 "off at 1e-2)")
        _positive_int("max_iterations", self.max_iterations)
        _require(_finite(self.worker_timeout) and self.worker_timeout >= 1, "worker_timeout",
                 f"worker_timeout = {self.worker_timeout!r} must be at least 1 (seconds): a "
                 "worker's set-up alone takes a good part of a second")
        if self.memory_limit is not None:
            _positive("memory_limit", self.memory_limit)
        _require(_finite(self.model_tolerance) and 0 < self.model_tolerance <= 1,
                 "model_tolerance", f"model_tolerance = {self.model_tolerance!r} must lie in "
                 "(0, 1] (a relative error; 0.01 is 1 %)")
        _require(isinstance(self.body_fields, bool), "body_fields",
                 f"body_fields = {self.body_fields!r} must be true or false")

    def _check_knobs(self):
        """Every knob within KNOB_RANGES (an integer where its default is one); the
        stopping test's secant pairs within the history the loop keeps."""
        defaults = {f.name: f.default for f in fields(self)}
        for key, (low, high, unit, why) in KNOB_RANGES.items():
            value = getattr(self, key)
            if isinstance(defaults[key], int):
                number = isinstance(value, int) and not isinstance(value, bool)
                what = "an integer"
            else:
                number, what = _finite(value), "a number"
            _require(number and low <= value <= high, key,
                     f"{key} = {value!r} must be {what} in [{low:g}, {high:g}] ({unit}): {why}")
        name = "paper_amplification_window" if self.method == "paper" else "anderson_depth"
        history = getattr(self, name)
        # named by the one of the two that was moved from its default
        key = "min_secants" if self.min_secants != defaults["min_secants"] else name
        _require(self.min_secants <= history, key,
                 f"min_secants = {self.min_secants!r} must be at most {name} = {history!r}: "
                 "the loop keeps no more pairs of iterates")

    @property
    def element_length(self):
        """The finest interface element's length at mesh level 1 (b): element_size, or
        DEFAULT_ELEMENT_SIZE until sized_to sizes it to a scene's contact."""
        return DEFAULT_ELEMENT_SIZE if self.element_size is None else self.element_size

    def sized_to(self, a, reach=0.0):
        """These settings with the interface elements sized to a contact of a priori
        half-width ``a`` (b) where element_size is not given: contact_elements across a,
        never longer than DEFAULT_ELEMENT_SIZE, graded away from the contact to
        element_size_far, by default that or, where contact may happen up to ``reach``
        (b) from the contact's centre, reach / FAR_ELEMENTS if longer; a default theta
        follows the finest element. Given, element_size wins (uniform elements)."""
        if self.element_size is not None:
            return self
        if self.element_size_far is None:
            ceiling = DEFAULT_ELEMENT_SIZE
            far = max(ceiling, float(f"{reach / FAR_ELEMENTS:.12g}"))
        else:
            ceiling = far = self.element_size_far
        fine = min(ceiling, a / self.contact_elements) if a > 0 else ceiling
        # 12 digits: a scene in mm and its twin in b and E get the same mesh bit for bit
        fine = max(float(f"{fine:.12g}"), ELEMENT_SIZE_RANGE[0])
        return replace(self, element_size=fine,
                       element_size_far=far if far > fine * (1 + 1e-12) else None)

    def default_theta(self):
        """(theta where not given, b/E; the rule that gives it, in words): the paper's
        for its loop, else theta_per_length times the finest interface element's length."""
        if self.method == "paper":
            return PAPER_THETA, "the paper's (method = 'paper')"
        return (self.theta_per_length * self.element_length / self.mesh_level,
                f"theta_per_length {self.theta_per_length:g} x element_size "
                f"{self.element_length:g} b / mesh_level {self.mesh_level}")

    @property
    def two_levels(self):
        """Whether a run iterates with a coarse correction (orchestrate/ddm/coarse.py;
        unless its interfaces do not pair up with the coarse mesh's: the Strategy says):
        its coarse level starts with the run, and its workers probe no map
        (orchestrate/workers/subdomains.py)."""
        return self.method != "paper" and (
            self.inner_solve == "two-level"
            or (self.inner_solve == "auto" and self.mesh_level >= self.auto_two_level_mesh_level))

    @property
    def robin_parameter(self):
        """gamma, E/b: as given, else the default of robin_choice."""
        return self.robin_choice()[0]

    def robin_choice(self):
        """(gamma, E/b; the rule that gives it, in words): as given, else the paper's
        1/theta for its loop; for the active-set loop robin_one_level times the square
        root of the mesh level (docs/method.md), or robin_two_level_per_length over the
        element length where a coarse correction may take the smooth modes; never above
        1/theta, where the exchange stays away from its singularity gamma theta = 2."""
        if self.robin is not None:
            return self.robin, "given (robin)"
        if self.method == "paper":
            return 1.0 / self.theta, "1/theta (method = 'paper')"
        if self.two_levels:
            gamma = self.robin_two_level_per_length / self.element_length
            rule = (f"robin_two_level_per_length {self.robin_two_level_per_length:g} / "
                    f"element_size {self.element_length:g} b (two levels)")
        else:
            # an optimised Robin parameter grows as the inverse square root of the
            # interface element's length (the exchange's slow modes span the frequencies
            # from the contact's width to the element's)
            gamma = self.robin_one_level * math.sqrt(self.mesh_level)
            rule = ("robin_one_level" if self.mesh_level == 1 else
                    f"robin_one_level {self.robin_one_level:g} x sqrt(mesh_level "
                    f"{self.mesh_level})")
        if gamma > 1.0 / self.theta:
            return 1.0 / self.theta, f"1/theta, below {rule} = {gamma:g}"
        return gamma, rule


def check_compatible(scene, settings):
    """What a scene needs of the settings."""
    _require(not (scene.load.force is not None and settings.method == "paper"), "method",
             "method = 'paper' cannot carry load.force: the paper's loop leaves the indenter "
             "unsupported while no point is in contact; use method = 'active-set'")
    if scene.frictional:
        _require(settings.method != "paper", "method",
                 "method = 'paper' is frictionless (the paper's loop); friction needs "
                 "method = 'active-set'")
        _require(settings.inner_solve != "two-level", "inner_solve",
                 "inner_solve = 'two-level' with friction: the coarse level is "
                 "frictionless; 'auto', 'direct' or 'iterate'")
    if scene.partial_slip:
        _require(settings.inner_solve in ("auto", "iterate"), "inner_solve",
                 f"inner_solve = {settings.inner_solve!r} with load.tangential_force: the "
                 "workers' maps do not carry the stamp's shift; 'auto' or 'iterate'")


def to_dict(obj):
    """Plain data for JSON: dataclasses as dicts, an infinite radius as None."""
    data = asdict(obj)
    if isinstance(obj, Scene):
        data["coatings"] = [asdict(c) for c in obj.coatings]
        if math.isinf(obj.indenter.radius):
            data["indenter"]["radius"] = None
        data["contact_zone"] = list(obj.contact_zone) if obj.contact_zone else None
    return data


def scene_from_dict(data):
    """The inverse of ``to_dict`` for a scene (a summary.json's "scene")."""
    indenter = dict(data["indenter"])
    if indenter.get("radius") is None:
        indenter["radius"] = math.inf
    return Scene(indenter=Indenter(**indenter), base=Base(**data["base"]),
                 coatings=tuple(Coating(**c) for c in data["coatings"]),
                 load=Load(**data["load"]), symmetric=data["symmetric"],
                 contact_zone=data.get("contact_zone"),
                 axisymmetric=data.get("axisymmetric", False),
                 units=Units(**data.get("units", {})),     # older summaries: b and E
                 friction=data.get("friction", 0.0), sliding=data.get("sliding", False))

