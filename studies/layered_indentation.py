"""A rigid sphere on a coated half-space: a semi-analytical reference, independent of the
tool (numpy and scipy only), to check the finite element results against.

The body: an elastic layer (E2, nu2, thickness h) perfectly bonded to an elastic
half-space (E3, nu3); its top z = 0 carries an axisymmetric pressure p(r) and no shear.
The indenter: a rigid sphere of radius R, frictionless, whose profile is the paraboloid
r^2 / (2 R) (the sphere to second order, as in Hertz), pressed by the force P or the
approach delta: the sphere's rigid displacement from first touch, measured against the
far field of the half-space (the surface deflection at r = 0 under a central contact).

1. The surface compliance. With z pointing into the body, at the wavenumber xi the
   axisymmetric fields are u_r = U(z) J1(xi r), u_z = W(z) J0, sigma_zz = S(z) J0,
   sigma_rz = T(z) J1. Navier's equations reduce to ordinary ones in z, solved by
   (A + B t) e^{-t} with t = xi z; with kappa = 3 - 4 nu, the solution that decays
   downwards is
       U = (A + B t) e^{-t},                W = (A + (kappa + t) B) e^{-t},
       S = -2 mu xi (A + (2 (1 - nu) + t) B) e^{-t},
       T = -2 mu xi (A + (1 - 2 nu + t) B) e^{-t}
   (lambda has cancelled: nu = 1/2 is allowed). Mirroring z -> -z (u_z and sigma_rz
   change sign) gives the solution that decays upwards. The layer takes two of each,
   the first in t = xi z and the second in s = xi (h - z), so that every exponential is
   at most 1 and nothing overflows at large xi h; the half-space takes the downward pair
   in xi (z - h). Six conditions fix the six amplitudes: at z = 0, T = 0 and S = -p_hat;
   at z = h, U, W, S and T continuous. For one material W(0) = (2 (1 - nu^2) / E) p_hat
   / xi, whence the layer factor F(xi h) = W(0) / (2 (1 - nu2^2) / E2 p_hat / xi): 1 as
   xi h -> inf (the layer's own half-space), E2 (1 - nu3^2) / (E3 (1 - nu2^2)) as
   xi h -> 0 (the substrate's). With the Hankel pair
       p_hat(xi) = int_0^inf p(r) J0(xi r) r dr,     p(r) = int_0^inf p_hat J0(xi r) xi dxi,
   the surface deflection is
       u_z(r) = (2 (1 - nu2^2) / E2) int_0^inf F(xi h) p_hat(xi) J0(xi r) dxi.
2. Rings. The pressure is constant on each of N equal annuli of [0, r_max]; the
   influence matrix is the deflection at the rings' mid-radii of a unit pressure on each
   ring. Its homogeneous part (F = 1) is closed form: a uniform pressure q on the disc of
   radius c deflects the surface by (2 (1 - nu^2) / E) q (2 / pi) times
       c E(r / c)                                   for r <= c,
       r [E(c / r) - (1 - c^2 / r^2) K(c / r)]      for r > c,
   (complete elliptic integrals of modulus k, scipy's parameter m = k^2), and a ring is
   the difference of two discs. The rest, F - 1, decays like e^{-2 xi h} and is
   integrated numerically with the disc's transform q c J1(xi c) / xi: Gauss-Legendre
   panels on [0, tau_max / h], each shorter than the scale h of F and than one period
   of the Bessel product.
3. The contact. For an approach delta the gap at the mid-radii is
   g = r^2 / (2 R) - delta + u_z >= 0, with p >= 0 and p g = 0: an active-set loop (load
   the rings that would interpenetrate, solve for their pressures, drop those pulling,
   add those interpenetrating, until nothing changes). A force P is met by solving for
   delta (brentq); the ring grid is then redrawn over the contact found, so that it
   always covers the contact with the same resolution. The contact radius comes from the
   outermost two loaded rings, p^2 linear in r^2 (p ~ sqrt(a - r) at a smooth edge)
   extrapolated to zero; the peak pressure from the central two, p linear in r^2
   extrapolated to r = 0; the approach is the delta solved for.
4. Hertz, for a rigid sphere on one material: 1 / E* = (1 - nu^2) / E,
   a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2), delta = a^2 / R.
   The confined (Winkler) limit of a thin layer on a rigid substrate: p = M (delta -
   r^2 / (2 R)) / h with the oedometric modulus M = E2 (1 - nu2) / ((1 + nu2)(1 - 2 nu2)),
   so P = pi M a^4 / (4 R h); it needs nu2 well below 1/2. A layer much thicker than a:
   Hertz on the layer, the approach shifted by the far field, where p_hat ~ P / (2 pi):
   delta - a^2 / R -> (2 (1 - nu2^2) / E2) P / (2 pi h) int_0^inf (F(tau) - 1) dtau.
5. The contact stiffness. A flat rigid punch of radius a (uniform deflection on the
   rings) gives S = dP/ddelta = 2 a E_eq, the equivalent modulus of indentation papers;
   a smooth indenter's dP/ddelta at contact radius a is the same S, its pressure
   vanishing at the edge.

    python -m studies.layered_indentation           # the table against Hertz
    python -m studies.layered_indentation --rings 400
"""

import argparse
from dataclasses import dataclass
import math

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk, j0, j1, roots_legendre

RINGS = 200              # rings of the contact grid
GRID_MARGIN = 1.25       # the grid spans GRID_MARGIN times the contact radius
GRID_TOLERANCE = 0.02    # redraw the grid until the contact radius moves less than this
MAX_GRIDS = 6
MAX_ACTIVE_SET_STEPS = 200


@dataclass(frozen=True)
class CoatedHalfSpace:
    """A layer (E2, nu2, thickness h) bonded to a half-space (E3, nu3)."""
    layer_E: float
    layer_nu: float
    thickness: float
    substrate_E: float
    substrate_nu: float

    def __post_init__(self):
        for name in ("layer_E", "thickness", "substrate_E"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be > 0, got {getattr(self, name)}")
        for name in ("layer_nu", "substrate_nu"):
            if not -1.0 < getattr(self, name) <= 0.5:
                raise ValueError(f"{name} must be in (-1, 0.5], got {getattr(self, name)}")

    @property
    def layer_compliance(self):
        """2 (1 - nu2^2) / E2: the factor of the deflection integral (= 2 / E2*)."""
        return 2.0 * (1.0 - self.layer_nu ** 2) / self.layer_E

    @property
    def shear_ratio(self):
        """The substrate's shear modulus over the layer's."""
        return (self.substrate_E / (1.0 + self.substrate_nu)) / (
            self.layer_E / (1.0 + self.layer_nu))

    @property
    def thin_limit(self):
        """F as xi h -> 0: the substrate's compliance over the layer's."""
        return (self.layer_E * (1.0 - self.substrate_nu ** 2)
                / (self.substrate_E * (1.0 - self.layer_nu ** 2)))


@dataclass(frozen=True)
class Quadrature:
    """The xi integral of F - 1: Gauss-Legendre panels of ``order`` points on
    [0, tau_max / h], each at most panel_tau / h and panel_phase / (2 r_max) long."""
    tau_max: float = 25.0        # F - 1 ~ e^{-2 xi h}: negligible beyond
    order: int = 16
    panel_tau: float = 1.0       # F varies on the scale xi h ~ 1
    panel_phase: float = 2.0 * math.pi   # J0(xi r) J1(xi c) turns at most at r + c <= 2 r_max


@dataclass(frozen=True)
class Indentation:
    """A solved contact: the scalars and the ring pressures."""
    force: float
    approach: float
    contact_radius: float
    peak_pressure: float
    edges: np.ndarray            # the rings' edges, 0 to r_max
    pressure: np.ndarray         # the pressure on each ring

    @property
    def radii(self):
        return ring_midpoints(self.edges)


# ---- Hertz and Winkler -------------------------------------------------------------------

def reduced_modulus(E, nu):
    """E* of one elastic body against a rigid one."""
    return E / (1.0 - nu ** 2)


def hertz(force, sphere_radius, modulus):
    """(a, p0, delta) of a rigid sphere pressed by ``force`` on a half-space of reduced
    modulus ``modulus`` (E*)."""
    a = (3.0 * force * sphere_radius / (4.0 * modulus)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a ** 2), a ** 2 / sphere_radius


def hertz_force(contact_radius, sphere_radius, modulus):
    """The force that gives the Hertz contact radius ``contact_radius``."""
    return 4.0 * modulus * contact_radius ** 3 / (3.0 * sphere_radius)


def oedometric_modulus(E, nu):
    """M = E (1 - nu) / ((1 + nu)(1 - 2 nu)): the stiffness of a laterally confined layer."""
    return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def winkler_force(contact_radius, sphere_radius, body):
    """P = pi M a^4 / (4 R h): a thin layer on a rigid substrate as a bed of springs."""
    M = oedometric_modulus(body.layer_E, body.layer_nu)
    return math.pi * M * contact_radius ** 4 / (4.0 * sphere_radius * body.thickness)


def thick_layer_approach(force, sphere_radius, body):
    """Hertz's approach on the layer's material plus the far-field shift of a layer much
    thicker than the contact (module docstring, 4)."""
    _, _, delta = hertz(force, sphere_radius, reduced_modulus(body.layer_E, body.layer_nu))
    excess, _ = quad(lambda tau: layer_factor(tau, body)[0] - 1.0, 0.0,
                     Quadrature.tau_max, limit=200)
    return delta + body.layer_compliance * force * excess / (2.0 * math.pi * body.thickness)


# ---- the layer factor F(xi h) -------------------------------------------------------------

def decaying_mode(t, nu, shear_ratio=1.0):
    """The fields of the two solutions that decay in t >= 0, per unit amplitude A and B:
    shape (..., 4, 2), rows U, W (displacements) and S, T (stresses over 2 mu_layer xi),
    columns A, B. ``shear_ratio``: this material's shear modulus over the layer's."""
    decay = np.exp(-t)
    ones = np.ones_like(t)
    rows = [(ones, t),
            (ones, 3.0 - 4.0 * nu + t),
            (-shear_ratio * ones, -shear_ratio * (2.0 * (1.0 - nu) + t)),
            (-shear_ratio * ones, -shear_ratio * (1.0 - 2.0 * nu + t))]
    return np.stack([np.stack(row, axis=-1) for row in rows], axis=-2) * decay[..., None, None]


MIRROR = np.array([1.0, -1.0, 1.0, -1.0])[:, None]   # z -> -z flips u_z and sigma_rz


def layer_factor(tau, body):
    """F(xi h) at the values ``tau`` = xi h: the surface compliance of the coated
    half-space over that of the layer's material alone (module docstring, 1)."""
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    zero = np.zeros_like(tau)
    nu2, nu3 = body.layer_nu, body.substrate_nu
    top_down, top_up = decaying_mode(zero, nu2), MIRROR * decaying_mode(tau, nu2)
    bond_down, bond_up = decaying_mode(tau, nu2), MIRROR * decaying_mode(zero, nu2)
    substrate = decaying_mode(zero, nu3, body.shear_ratio)
    system = np.zeros(tau.shape + (6, 6))
    # z = 0: S = -p_hat (p_hat = 2 mu2 xi) and T = 0
    system[..., 0:2, 0:2] = top_down[..., 2:4, :]
    system[..., 0:2, 2:4] = top_up[..., 2:4, :]
    # z = h: U, W, S and T of the layer equal the substrate's
    system[..., 2:6, 0:2] = bond_down
    system[..., 2:6, 2:4] = bond_up
    system[..., 2:6, 4:6] = -substrate
    load = np.zeros(tau.shape + (6, 1))
    load[..., 0, 0] = -1.0
    amplitudes = np.linalg.solve(system, load)[..., 0]
    surface_W = (np.sum(top_down[..., 1, :] * amplitudes[..., 0:2], axis=-1)
                 + np.sum(top_up[..., 1, :] * amplitudes[..., 2:4], axis=-1))
    return surface_W / (2.0 * (1.0 - nu2))     # the layer's own half-space: W(0) = 2 (1 - nu2)


# ---- rings and their influence matrix -----------------------------------------------------

def ring_edges(r_max, rings=RINGS):
    return np.linspace(0.0, r_max, rings + 1)


def ring_midpoints(edges):
    return 0.5 * (edges[1:] + edges[:-1])


def ring_areas(edges):
    return math.pi * np.diff(edges ** 2)


def disc_deflection(r, c):
    """The surface deflection at r of a unit pressure on the disc of radius c of a
    homogeneous half-space, over 2 (1 - nu^2) / E (module docstring, 2)."""
    r, c = np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(c, dtype=float))
    deflection = np.zeros(r.shape)
    inside = (r <= c) & (c > 0)
    deflection[inside] = c[inside] * ellipe((r[inside] / c[inside]) ** 2)
    outside = r > c
    m = (c[outside] / r[outside]) ** 2
    deflection[outside] = r[outside] * (ellipe(m) - (1.0 - m) * ellipk(m))
    return 2.0 / math.pi * deflection


def half_space_influence(edges):
    """The homogeneous part: deflections at the mid-radii of unit ring pressures, over
    2 (1 - nu^2) / E; column j is ring j."""
    discs = disc_deflection(ring_midpoints(edges)[:, None], edges[None, :])
    return discs[:, 1:] - discs[:, :-1]


def hankel_nodes(thickness, r_max, quadrature):
    """Nodes and weights of the xi integral (module docstring, 2)."""
    xi_max = quadrature.tau_max / thickness
    longest = min(quadrature.panel_tau / thickness, quadrature.panel_phase / (2.0 * r_max))
    panels = max(1, math.ceil(xi_max / longest))
    points, weights = roots_legendre(quadrature.order)
    half = 0.5 * xi_max / panels
    starts = np.arange(panels) * 2.0 * half
    nodes = (starts[:, None] + half * (points[None, :] + 1.0)).ravel()
    return nodes, np.tile(half * weights, panels)


def layer_correction_influence(edges, body, quadrature, chunk=4096):
    """The part of F - 1: deflections at the mid-radii of unit ring pressures, over
    2 (1 - nu2^2) / E2, integrated over xi in chunks of nodes (memory)."""
    radii = ring_midpoints(edges)
    nodes, weights = hankel_nodes(body.thickness, edges[-1], quadrature)
    influence = np.zeros((len(radii), len(radii)))
    for start in range(0, len(nodes), chunk):
        xi, w = nodes[start:start + chunk], weights[start:start + chunk]
        weight = (layer_factor(xi * body.thickness, body) - 1.0) * w
        disc_transform = edges[:, None] * j1(np.outer(edges, xi)) / xi
        ring_transform = disc_transform[1:] - disc_transform[:-1]
        influence += (j0(np.outer(radii, xi)) * weight) @ ring_transform.T
    return influence


def influence_matrix(edges, body, quadrature=Quadrature()):
    """Deflection at ring i's mid-radius of a unit pressure on ring j."""
    return body.layer_compliance * (half_space_influence(edges)
                                    + layer_correction_influence(edges, body, quadrature))


# ---- the contact on one grid ----------------------------------------------------------------

def pressure_at_approach(approach, matrix, edges, sphere_radius):
    """The ring pressures (>= 0, gap >= 0, one of them zero on each ring) for the sphere's
    approach, by an active-set loop from the rings that the rigid sphere would enter."""
    interference = approach - ring_midpoints(edges) ** 2 / (2.0 * sphere_radius)
    active = interference > 0
    for _ in range(MAX_ACTIVE_SET_STEPS):
        pressure = np.zeros_like(interference)
        if active.any():
            pressure[active] = np.linalg.solve(matrix[np.ix_(active, active)],
                                               interference[active])
        gap = matrix @ pressure - interference
        updated = (active & (pressure > 0)) | (~active & (gap < 0))
        if np.array_equal(updated, active):
            return pressure
        active = updated
    raise RuntimeError(f"the active set did not settle in {MAX_ACTIVE_SET_STEPS} steps "
                       f"(approach {approach:g})")


def approach_for_force(force, matrix, edges, sphere_radius):
    """The approach at which the rings carry ``force`` (brentq; the bracket doubles)."""
    areas = ring_areas(edges)

    def excess(approach):
        return areas @ pressure_at_approach(approach, matrix, edges, sphere_radius) - force

    high = edges[-1] ** 2 / (2.0 * sphere_radius)     # the grid's edge touches
    while excess(high) < 0:
        high *= 2.0
    return brentq(excess, 0.0, high, xtol=1e-15 * high, rtol=1e-13)


def edge_radius(edges, pressure):
    """The contact radius: p^2 linear in r^2 through the outermost two loaded rings,
    extrapolated to zero (the outer edge of the only ring if one is loaded)."""
    radii, loaded = ring_midpoints(edges), np.flatnonzero(pressure > 0)
    if len(loaded) < 2:
        return float(edges[loaded[-1] + 1]) if len(loaded) else 0.0
    outer, inner = loaded[-1], loaded[-2]
    p2_out, p2_in = pressure[outer] ** 2, pressure[inner] ** 2
    r2_out, r2_in = radii[outer] ** 2, radii[inner] ** 2
    if p2_in <= p2_out:       # not falling towards the edge: the loaded rings' edge
        return float(edges[outer + 1])
    return math.sqrt(r2_out + p2_out * (r2_out - r2_in) / (p2_in - p2_out))


def centre_pressure(edges, pressure):
    """The pressure at r = 0: p linear in r^2 through the central two rings."""
    r2 = ring_midpoints(edges)[:2] ** 2
    return float(pressure[0] + (pressure[0] - pressure[1]) * r2[0] / (r2[1] - r2[0]))


def contact_on_grid(approach, matrix, edges, sphere_radius):
    pressure = pressure_at_approach(approach, matrix, edges, sphere_radius)
    return Indentation(force=float(ring_areas(edges) @ pressure), approach=float(approach),
                       contact_radius=edge_radius(edges, pressure),
                       peak_pressure=centre_pressure(edges, pressure),
                       edges=edges, pressure=pressure)


def punch_stiffness(body, contact_radius, rings=RINGS, quadrature=Quadrature()):
    """S = dP/ddelta of a flat rigid punch of radius ``contact_radius``: the force of a
    unit deflection of every ring."""
    edges = ring_edges(contact_radius, rings)
    pressure = np.linalg.solve(influence_matrix(edges, body, quadrature), np.ones(rings))
    return float(ring_areas(edges) @ pressure)


# ---- the contact, its grid drawn over it ---------------------------------------------------

def contact_radius_bound(body, sphere_radius, force=None, approach=None):
    """A first grid's radius, which the contact should not exceed (indent() widens the grid
    if it does): Hertz on the softer material for a force (F lies between its limits);
    sqrt(2 R delta) for an approach (where the sphere leaves the undeformed surface)."""
    if force is not None:
        softer = min(reduced_modulus(body.layer_E, body.layer_nu),
                     reduced_modulus(body.substrate_E, body.substrate_nu))
        return hertz(force, sphere_radius, softer)[0]
    return math.sqrt(2.0 * sphere_radius * approach)


def indent(body, sphere_radius, force=None, approach=None, rings=RINGS,
           quadrature=Quadrature()):
    """The rigid sphere pressed on the coated half-space by ``force`` or to ``approach``
    (one of them): rings over GRID_MARGIN times the contact, redrawn until the contact
    radius settles."""
    if (force is None) == (approach is None):
        raise ValueError("give one of force and approach")
    r_max = GRID_MARGIN * contact_radius_bound(body, sphere_radius, force, approach)
    for _ in range(MAX_GRIDS):
        edges = ring_edges(r_max, rings)
        matrix = influence_matrix(edges, body, quadrature)
        delta = approach if force is None else approach_for_force(force, matrix, edges,
                                                                 sphere_radius)
        result = contact_on_grid(delta, matrix, edges, sphere_radius)
        fits = result.pressure[-1] == 0       # the contact stays inside the grid
        settled = abs(GRID_MARGIN * result.contact_radius / r_max - 1.0) < GRID_TOLERANCE
        if fits and settled:
            return result
        r_max = GRID_MARGIN * result.contact_radius if fits else 2.0 * r_max
    raise RuntimeError(f"the ring grid did not settle in {MAX_GRIDS} grids")


def indent_to_radius(body, sphere_radius, contact_radius, rings=RINGS,
                     quadrature=Quadrature()):
    """The contact of radius ``contact_radius`` (within the estimate's resolution): the
    approach solved for on one grid of GRID_MARGIN times that radius."""
    edges = ring_edges(GRID_MARGIN * contact_radius, rings)
    matrix = influence_matrix(edges, body, quadrature)

    def excess(approach):
        return contact_on_grid(approach, matrix, edges, sphere_radius).contact_radius \
            - contact_radius

    high = contact_radius ** 2 / sphere_radius
    while excess(high) < 0:
        high *= 1.5
    delta = brentq(excess, 0.0, high, xtol=1e-12 * high)
    return contact_on_grid(delta, matrix, edges, sphere_radius)


# ---- the table -----------------------------------------------------------------------------

MODULUS_RATIOS = (0.1, 1.0, 10.0)     # E2 / E3
THICKNESSES = (0.1, 1.0, 2.0)         # h / a
NU = 0.3
SPHERE_RADIUS = 100.0                 # in units of the contact radius a


def table_rows(rings=RINGS, quadrature=Quadrature()):
    """One row per (E2/E3, h/a): a = 1, E3 = 1, nu2 = nu3 = NU, R = SPHERE_RADIUS; the
    force, the contact radius, the peak pressure and the approach found, and the last
    three over Hertz's for that force on the layer's material alone (H2) and on the
    substrate's (H3)."""
    rows = []
    for ratio in MODULUS_RATIOS:
        for thickness in THICKNESSES:
            body = CoatedHalfSpace(ratio, NU, thickness, 1.0, NU)
            result = indent_to_radius(body, SPHERE_RADIUS, 1.0, rings, quadrature)
            row = {"E2/E3": ratio, "h/a": thickness / result.contact_radius,
                   "P": result.force, "a": result.contact_radius,
                   "p0": result.peak_pressure, "delta": result.approach}
            for name, E in (("H2", ratio), ("H3", 1.0)):
                a, p0, delta = hertz(result.force, SPHERE_RADIUS, reduced_modulus(E, NU))
                row[f"a/{name}"] = result.contact_radius / a
                row[f"p0/{name}"] = result.peak_pressure / p0
                row[f"delta/{name}"] = result.approach / delta
            rows.append(row)
    return rows


def format_table(rows):
    columns = list(rows[0])
    width = max(len(c) for c in columns) + 1
    lines = [" ".join(f"{c:>{width}}" for c in columns)]
    lines += [" ".join(f"{row[c]:>{width}.4g}" for c in columns) for row in rows]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rings", type=int, default=RINGS,
                        help="rings over the grid (1.25 times the contact radius)")
    args = parser.parse_args(argv)
    print(f"A rigid sphere (paraboloid, R = {SPHERE_RADIUS:g} a) on a layer (E2, h) bonded "
          f"to a half-space (E3 = 1), nu = {NU:g} in both, pressed until a = 1; "
          f"{args.rings} rings. X/H2, X/H3: X over Hertz's for the same force on the "
          "layer's material alone, on the substrate's.")
    print(format_table(table_rows(args.rings)))


if __name__ == "__main__":
    main()
