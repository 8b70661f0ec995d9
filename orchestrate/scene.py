"""The scene (geometry, materials, loading) and the solver settings, as validated data.

Lengths are in units of b and moduli in units of E (b = E = 1 internally), as in
../METHOD.md. Both objects are checked once, on creation, and written next to every
result so that any result can be reproduced.
"""

from dataclasses import asdict, dataclass
import math
from typing import Optional

MODELS = ("shell", "elastic")
METHODS = ("active-set", "paper")
WORKERS = ("persistent", "fresh")
DEFAULT_ROBIN = 2.0    # E/b


class ParameterError(ValueError):
    """A scene or settings value outside its allowed range; the message names it."""


def _require(condition, message):
    if not condition:
        raise ParameterError(message)


def _positive(name, value):
    _require(_finite(value) and value > 0, f"{name} = {value!r} must be a positive number")


def _finite(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _poisson(name, value):
    _require(_finite(value) and -1.0 < value < 0.5,
             f"{name} = {value!r} must lie in (-1, 0.5): outside it the body has no "
             "positive elastic energy")


def _positive_int(name, value):
    _require(isinstance(value, int) and not isinstance(value, bool) and value >= 1,
             f"{name} = {value!r} must be a positive integer")


@dataclass(frozen=True)
class Scene:
    """Two bodies and a partial coating in frictionless contact (METHOD.md)."""

    length: float = 4.0            # l: length of Omega1 and Omega3
    height: float = 8.0            # h: height of Omega1 and Omega3
    coating_length: float = 2.0    # l2: the coating covers x1 in [0, l2]
    h2: float = 0.125              # coating thickness
    E1: float = 1.0                # Young's moduli of Omega1, the coating, Omega3
    E2: float = 1.0
    E3: float = 1.0
    nu1: float = 0.3               # Poisson ratios
    nu2: float = 0.3
    nu3: float = 0.3
    shear_factor: float = 5.0 / 6.0  # k' of the Timoshenko shell
    chi: float = 1.0e-3            # initial gap d(x1) = chi x1^2
    stamp: float = 2.778999e-3     # Delta: the stamp pushes Omega1's top down by Delta

    def __post_init__(self):
        for name in ("length", "height", "coating_length", "h2", "E1", "E2", "E3",
                     "shear_factor", "chi"):
            _positive(name, getattr(self, name))
        for name in ("nu1", "nu2", "nu3"):
            _poisson(name, getattr(self, name))
        _require(_finite(self.stamp) and self.stamp >= 0,
                 f"stamp = {self.stamp!r} must be a non-negative displacement")
        _require(self.h2 < self.height,
                 f"h2 = {self.h2!r} must be smaller than the body height h = {self.height!r}")
        _require(self.coating_length <= self.length,
                 f"coating_length = {self.coating_length!r} must not exceed the body "
                 f"length l = {self.length!r}")

    def gap(self, x1):
        """Initial normal gap between Omega1 and the coating, d(x1) = chi x1^2 / b^2."""
        return self.chi * x1 ** 2

    @property
    def hertz_radius(self):
        """Radius R of the parabola d = x1^2 / (2R) equivalent to the gap."""
        return 1.0 / (2.0 * self.chi)


@dataclass(frozen=True)
class Settings:
    """How the scene is solved: coating model, penalty, Robin loop, mesh."""

    model: str = "shell"           # coating model: "shell" (Timoshenko) or "elastic" (2D)
    theta: float = 1.0e-3          # penalty parameter of (16), in b/E
    method: str = "active-set"     # Robin loop: "active-set" (accelerated) or "paper"
    robin: Optional[float] = None  # Robin parameter gamma, E/b; None: 1/theta (paper), 2
    rho: float = 0.5               # relaxation (24), in (0, 1]
    eps_u: float = 1.0e-6          # stop when the relative change of displacements < eps_u
    max_iterations: int = 3000
    mesh_level: int = 1            # 1: the paper's mesh; L: every mesh size divided by L
    shell_elements: int = 32       # interface elements at mesh level 1
    workers: str = "persistent"    # FreeFEM workers: persistent, or a fresh process per solve

    def __post_init__(self):
        _require(self.model in MODELS, f"model = {self.model!r} must be one of {MODELS}")
        _require(self.workers in WORKERS, f"workers = {self.workers!r} must be one of {WORKERS}")
        _require(self.method in METHODS, f"method = {self.method!r} must be one of {METHODS}")
        _positive("theta", self.theta)
        if self.robin is not None:
            _positive("robin", self.robin)
            # the Robin-Robin exchange loses the penalised laws at gamma theta = 2 (README)
            _require(self.robin * self.theta < 1.5,
                     f"robin = {self.robin!r} must be below 1.5/theta = {1.5 / self.theta:g}: "
                     "at gamma theta = 2 the Robin exchange no longer fixes the interface laws")
        _require(_finite(self.rho) and 0 < self.rho <= 1,
                 f"rho = {self.rho!r} must lie in (0, 1]")
        _positive("eps_u", self.eps_u)
        _positive_int("max_iterations", self.max_iterations)
        _positive_int("mesh_level", self.mesh_level)
        _positive_int("shell_elements", self.shell_elements)

    @property
    def robin_parameter(self):
        """gamma: as given, else the paper's 1/theta for its loop and 2 E/b otherwise
        (measured best for the active-set loop on the figure scenes, README), but never
        above 1/theta, where the exchange stays away from its singularity gamma theta = 2."""
        if self.robin is not None:
            return self.robin
        return 1.0 / self.theta if self.method == "paper" else min(DEFAULT_ROBIN, 1.0 / self.theta)


def to_dict(obj):
    return asdict(obj)
