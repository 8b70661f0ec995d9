"""Closed forms of a plane-strain line contact with friction: the references the
frictional scenes are checked against (not a tool of the solver).

A cylinder on a half-plane of the same material (Dundurs' beta = 0: friction leaves the
pressure Hertzian), contact half-width a, peak pressure p0, x along the surface, z into
the body (z >= 0), compression negative:

    p(x) = p0 sqrt(1 - x^2 / a^2)                         Hertz, |x| <= a
    q(x) = mu p(x)                                        full sliding (McEwen, 1949)
    q(x) = mu p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)),  |x| < c
           mu p(x),                                       c <= |x| <= a
    c / a = sqrt(1 - Q / (mu P))                          partial slip (Cattaneo, 1938;
                                                          Mindlin, 1949), P = pi a p0 / 2
    q(x) = q*(x) - 2 q'(x)                                Q* then back to Q < Q*
                                                          (Mindlin & Deresiewicz, 1953)

where q* is Cattaneo's traction under the peak Q* and q' his traction under (Q* - Q) / 2
with 2 mu p in place of mu p: a zone of reversed slip c' <= |x| <= a, c' / a =
sqrt(1 - (Q* - Q) / (2 mu P)), where q = -mu p (the superposition of Johnson, 1985, §7.3).

q is the traction the indenter's face applies to the half-plane's surface, along +x (a
slider moving towards +x drags the surface with it).

The subsurface stresses under p and q in closed form (Johnson, Contact Mechanics, 1985,
eqs. 7.19-7.20 after McEwen), with

    m^2 = ((R + A) / 2),  n^2 = ((R - A) / 2),  A = a^2 - x^2 + z^2,
    R = sqrt(A^2 + 4 x^2 z^2),  m of z's sign, n of x's sign:

    under p:  sx = -(p0/a) (m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2 z)
              sz = -(p0/a) m (1 - (z^2 + n^2)/(m^2 + n^2))
              txz = -(p0/a) n (m^2 - z^2)/(m^2 + n^2)
    under q:  sx = (q0/a) (n (2 - (z^2 - m^2)/(m^2 + n^2)) - 2 x)
              sz = -(q0/a) n (m^2 - z^2)/(m^2 + n^2)
              txz = -(q0/a) (m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2 z)

with txz the shear on a face of normal x along z, so that a point load pressing at the
origin gives txz = -(2P/pi) x z^2/r^4 (Flamant: the radial stress -(2P/pi) cos(theta)/r),
and q along +x. flamant_stresses, the same field by quadrature of the point-load
solutions, is the independent check (tests/studies/test_line_contact_stresses.py); it
fixed the sign of txz under p, which Johnson writes for the opposite shear convention.
In plane strain sy = nu (sx + sz).
"""

import math

import numpy as np
from scipy import integrate, optimize


def hertz_line(force, radius, contact_modulus):
    """(a, p0) of a cylinder pressed with ``force`` per unit width: a = sqrt(4 F R /
    (pi E*)), p0 = 2 F / (pi a)."""
    a = math.sqrt(4.0 * force * radius / (math.pi * contact_modulus))
    return a, 2.0 * force / (math.pi * a)


def _mn(x, z, a):
    A = a * a - x * x + z * z
    R = np.sqrt(A * A + 4.0 * x * x * z * z)
    m = np.sqrt(np.maximum(0.5 * (R + A), 0.0)) * np.where(z < 0, -1.0, 1.0)
    n = np.sqrt(np.maximum(0.5 * (R - A), 0.0)) * np.where(x < 0, -1.0, 1.0)
    return m, n


def sliding_stresses(x, z, a, p0, mu, nu):
    """(sx, sz, txz, sy) at (x, z) under Hertz pressure p0 and the traction mu p along +x
    (McEwen's closed form, the module's docstring); arrays broadcast."""
    x, z = np.asarray(x, float), np.asarray(z, float)
    m, n = _mn(x, z, a)
    with np.errstate(invalid="ignore", divide="ignore"):  # at the contact's edges: nan
        mm_nn = m * m + n * n
        outside = (z * z + n * n) / mm_nn
        inside = (m * m - z * z) / mm_nn
        q0 = mu * p0
        sx = -(p0 / a) * (m * (1 + outside) - 2 * z) \
            + (q0 / a) * (n * (2 - (z * z - m * m) / mm_nn) - 2 * x)
        sz = -(p0 / a) * m * (1 - outside) - (q0 / a) * n * inside
        txz = -(p0 / a) * n * inside - (q0 / a) * (m * (1 + outside) - 2 * z)
    return sx, sz, txz, nu * (sx + sz)


def flamant_stresses(x, z, a, pressure, traction):
    """(sx, sz, txz) at one point (x, z > 0) by quadrature of Flamant's point-load
    solutions (Johnson eqs. 2.15, 2.19) over the surface loads ``pressure(s)`` and
    ``traction(s)`` on [-a, a]: an independent evaluation of the closed forms."""
    def kernel(s, which):
        dx = x - s
        r4 = (dx * dx + z * z) ** 2
        normal = -2.0 * pressure(s) / math.pi / r4
        tangential = -2.0 * traction(s) / math.pi / r4
        return (normal * (dx * dx * z, z ** 3, dx * z * z)[which]
                + tangential * (dx ** 3, dx * z * z, dx * dx * z)[which])
    options = dict(limit=400, epsabs=0.0, epsrel=1e-11, points=[x] if -a < x < a else None)
    return tuple(integrate.quad(kernel, -a, a, args=(k,), **options)[0] for k in range(3))


def von_mises(sx, sz, txz, sy):
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * txz ** 2)


def principal_shear(sx, sz, txz):
    """tau1: half the difference of the in-plane principal stresses."""
    return np.sqrt(0.25 * (sx - sz) ** 2 + txz ** 2)


def largest(field, mu, nu, a=1.0, p0=1.0):
    """(value, x, z) of the largest ``field`` (a function of sx, sz, txz, sy) under full
    sliding, over z >= 0: the best point of a grid over |x| <= 2a, z <= 2a, refined by
    Nelder-Mead."""
    def value(point):
        x, z = point
        return -float(field(*sliding_stresses(x, max(z, 0.0), a, p0, mu, nu)))
    xs, zs = np.linspace(-2 * a, 2 * a, 401), np.linspace(0.0, 2 * a, 201)
    X, Z = np.meshgrid(xs, zs)
    grid = field(*sliding_stresses(X, Z, a, p0, mu, nu))
    j, i = np.unravel_index(np.nanargmax(grid), grid.shape)
    best = optimize.minimize(value, [xs[i], zs[j]], method="Nelder-Mead",
                             options=dict(xatol=1e-10 * a, fatol=1e-14 * p0, maxiter=4000))
    x, z = best.x
    return -best.fun, x, max(z, 0.0)


def stick_half_width(a, tangential_over_limiting):
    """Cattaneo's stick zone half-width c = a sqrt(1 - Q / (mu P))."""
    return a * math.sqrt(1.0 - tangential_over_limiting)


def cattaneo_traction(x, a, p0, mu, tangential_over_limiting):
    """The partial-slip traction q(x) under Q = tangential_over_limiting * mu P (the
    module's docstring)."""
    x = np.asarray(x, float)
    c = stick_half_width(a, tangential_over_limiting)
    slip = mu * p0 * np.sqrt(np.maximum(1.0 - (x / a) ** 2, 0.0))
    stick = mu * p0 * (c / a) * np.sqrt(np.maximum(1.0 - (x / c) ** 2, 0.0)) if c > 0 else 0.0
    return np.where(np.abs(x) < c, slip - stick, slip)


def unloading_traction(x, a, p0, mu, peak_over_limiting, tangential_over_limiting):
    """The traction after Q rose from 0 to Q* = peak_over_limiting * mu P and went back
    to Q = tangential_over_limiting * mu P (Q* > Q > -Q*; the module's docstring): the
    reversed slip's zone c' <= |x| <= a where the friction turned, c inside it."""
    turn = 0.5 * (peak_over_limiting - tangential_over_limiting)
    return (cattaneo_traction(x, a, p0, mu, peak_over_limiting)
            - 2.0 * cattaneo_traction(x, a, p0, mu, turn))
