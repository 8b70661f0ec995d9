"""The contact half-width of a cylinder pressed into a coated half-space (plane strain):
where the loop's first contact set is drawn (Strategy.first_contact).

Hertz's half-width of the base, and a stiff coating's own (estimate.predicted_half_width),
bound the answer: a coating of 4 E, 0.5 b thick, under a rigid cylinder took the base's
1.52 b where the answer is 1.18-1.22 b, and the loop's contact set shrank from there a
point or two an update (15 updates, most of one iteration, at mesh level 2). This
solves that contact itself, the bodies taken infinite and the coating a layer of its
thickness everywhere:

1. The surface compliance. At the wavenumber xi, a pressure p cos(xi x) on the layer
   (E2, nu2, thickness h) bonded to the half-space (E3, nu3) deflects its surface by
   (2 (1 - nu2^2) / E2) F(xi h) p / xi: F is 1 as xi h -> inf (the layer's own
   half-space) and E2 (1 - nu3^2) / (E3 (1 - nu2^2)) as xi h -> 0 (the base's). Each
   body's fields are u_x = U(z) sin(xi x), u_z = W(z) cos(xi x), sigma_zz = S(z) cos,
   sigma_xz = T(z) sin, z into the body; with t = xi z and kappa = 3 - 4 nu the field that
   decays downwards is
       U = (A + B t) e^-t,   W = (A + (kappa + t) B) e^-t,
       S = -2 mu (A + (2 (1 - nu) + t) B) e^-t,   T = -2 mu (A + (1 - 2 nu + t) B) e^-t
   (xi = 1), and its mirror image (z -> h - z: W and T change sign) decays upwards. The
   layer takes both, the half-space the first: six amplitudes, fixed by T = 0 and
   S = -p on top and U, W, S, T continuous at the bond.
2. The contact. The pressure is constant on cells of a uniform grid; the deflections
   come from the compliance (the indenter's, 2 (1 - nu1^2) / E1 / xi, added) by a
   zero-padded FFT, as a symmetric Toeplitz matrix. The contact is one zone about the
   centre (a convex profile): held on its points (deflection + x^2 / 2R = the approach,
   the pressures summing to the force), its edge pressure is negative where the zone is
   too wide and positive where it is too narrow; the half-width is where it changes
   sign, bisected over the points and interpolated between two.

Checked against Hertz (a coating like the base, and one thicker than the contact is
wide) and against the loop's answers of the gallery's coated scenes
(tests/model/test_layered_contact.py).
"""

import functools
import math

import numpy as np

CELLS_PER_HALF_WIDTH = 64   # grid cells over the widest plausible half-width
DOMAIN = 4                  # the grid spans DOMAIN times that half-width either side
WIDEST = 1.25               # the widest plausible half-width over the wider Hertz bound


def layer_factor(t, E2, nu2, E3, nu3):
    """F(xi h) (the module's docstring, 1.) at the values ``t`` of xi h."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    mu2, mu3 = E2 / (2 * (1 + nu2)), E3 / (2 * (1 + nu3))
    k2, k3 = 3 - 4 * nu2, 3 - 4 * nu3
    e = np.exp(-t)
    zero, one = np.zeros_like(t), np.ones_like(t)
    # unknowns: the layer's down (A, B) and up (C, D) amplitudes, the base's (E, G)
    rows = [
        # top, z = 0 (down field at t = 0, up field at s = xi h): T = 0, S = -p (p = 1)
        [-one, -(1 - 2 * nu2) * one, e, (1 - 2 * nu2 + t) * e, zero, zero],
        [-one, -2 * (1 - nu2) * one, -e, -(2 * (1 - nu2) + t) * e, zero, zero],
        # bond, z = h (down field at t = xi h, up field at s = 0, the base's at 0):
        # U, W, S / 2 and T / 2 continuous
        [e, t * e, one, zero, -one, zero],
        [e, (k2 + t) * e, -one, -k2 * one, -one, -k3 * one],
        [-mu2 * e, -mu2 * (2 * (1 - nu2) + t) * e, -mu2 * one, -2 * mu2 * (1 - nu2) * one,
         mu3 * one, 2 * mu3 * (1 - nu3) * one],
        [-mu2 * e, -mu2 * (1 - 2 * nu2 + t) * e, mu2 * one, mu2 * (1 - 2 * nu2) * one,
         mu3 * one, mu3 * (1 - 2 * nu3) * one],
    ]
    matrix = np.moveaxis(np.array(rows), -1, 0)            # (n, 6, 6)
    rhs = np.zeros((len(t), 6))
    rhs[:, 1] = -1.0 / (2 * mu2)                           # S = -2 mu (...) = -p
    a, b, c, d, _, _ = np.linalg.solve(matrix, rhs[..., None])[..., 0].T
    deflection = (a + k2 * b) - (c + (k2 + t) * d) * e    # W at z = 0
    return deflection / (2 * (1 - nu2 ** 2) / E2)


def layered_half_width(force, radius, layer, base, indenter=None):
    """The contact half-width (the module's docstring) of a cylinder of relative radius
    ``radius`` pressed with ``force`` per unit width into the layer (E2, nu2, h) on the
    half-space ``base`` (E3, nu3); ``indenter``: (E1, nu1), or None (rigid)."""
    E2, nu2, h = layer
    E3, nu3 = base
    own = 0.0 if indenter is None else 2 * (1 - indenter[1] ** 2) / indenter[0]
    layer_compliance = 2 * (1 - nu2 ** 2) / E2

    def half_width(widest):
        dx = widest / CELLS_PER_HALF_WIDTH
        n = 2 * DOMAIN * CELLS_PER_HALF_WIDTH             # cells over [-DOMAIN, DOMAIN) widest
        xi = 2 * math.pi * np.fft.rfftfreq(2 * n, dx)    # zero-padded to twice the span
        kernel = np.zeros_like(xi)
        kernel[1:] = ((own + layer_compliance * layer_factor(xi[1:] * h, E2, nu2, E3, nu3))
                      / xi[1:] * np.sinc(xi[1:] * dx / (2 * math.pi)))   # a cell's mean
        influence = np.fft.irfft(kernel, 2 * n) / dx      # deflection of a unit pressure's cell
        return _one_zone(influence, dx, force, radius)

    # between Hertz's half-widths of the base's and the layer's half-spaces; then again on
    # a grid sized to the answer (a soft layer's can lie far inside both)
    bound = max(math.sqrt(2 * force * radius * (own + c) / math.pi)   # a^2 = 4 F R / (pi E*)
                for c in (layer_compliance, 2 * (1 - nu3 ** 2) / E3))
    return half_width(WIDEST * half_width(WIDEST * bound))


def _one_zone(influence, dx, force, radius):
    """The half-width of the one contact zone about x = 0 (the module's docstring, 2.)."""
    widest = CELLS_PER_HALF_WIDTH

    @functools.cache
    def edge_pressure(m):
        """The pressure at the zone's edge when held on the points |i| <= m."""
        i = np.arange(-m, m + 1)
        x = i * dx
        matrix = np.zeros((2 * m + 2, 2 * m + 2))
        matrix[:-1, :-1] = influence[np.abs(i[:, None] - i[None, :])] * dx
        matrix[:-1, -1] = -1.0                             # the approach
        matrix[-1, :-1] = dx                               # the pressures sum to the force
        rhs = np.append(-x ** 2 / (2 * radius), force)
        return np.linalg.solve(matrix, rhs)[0]

    low, high = 0, widest                # edge pressure positive at low, negative at high
    if edge_pressure(high) >= 0:
        return (high + 0.5) * dx
    while high - low > 1:
        middle = (low + high) // 2
        if edge_pressure(middle) >= 0:
            low = middle
        else:
            high = middle
    p_low, p_high = edge_pressure(low), edge_pressure(high)
    return (low + p_low / (p_low - p_high)) * dx
