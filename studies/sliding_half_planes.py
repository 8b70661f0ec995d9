"""Full sliding between two elastic half-planes of different materials: an independent
reference for the frictional scenes (not a tool of the solver).

A cylinder of radius R on a half-plane, both elastic (or the cylinder rigid), pressed by
P per unit width and sliding towards +x, the friction traction mu p on both surfaces (the
lower body dragged towards +x). Each surface's normal displacement into its body is
Flamant's, with u_z > 0 into the body:

    u_z(x) = -K int p(s) ln|x - s| ds + (C/2) int q(s) sgn(x - s) ds,
    K = 2 (1 - nu^2) / (pi E),   C = (1 - 2 nu)(1 + nu) / E,

q the tangential traction on that surface along its own x. The sign of the second term
follows from the first's partner by Betti's reciprocity: a normal load P draws the
surface towards itself, u_x = -(C/2) P sgn(x) (Johnson, Contact Mechanics, eq. 2.19a),
so a tangential load Q at s moves a point x along the normal by (C/2) Q sgn(x - s): the
surface ahead of a drag sinks, behind it rises. (Written first from memory with the
opposite sign, this reference put the pressure forwards, the solver backwards by the
same amount; the reciprocity settles it.) The lower body takes q = mu p along +x; the
cylinder, seen in its own frame (x' = -x, z' = -z), also mu p along +x', so that its
term changes sign in the common x, and the gap

    g(x) = x^2 / (2R) - delta + u_z1 + u_z2
         = x^2 / (2R) - delta - (K1 + K2) int p ln|x - s| ds
           + ((C2 - C1) / 2) mu int p(s) sgn(x - s) ds

is zero where p > 0 and positive elsewhere, with int p = P. The coupling term vanishes
for bodies of one material (Dundurs' beta = 0: the pressure stays Hertz's); under a
stiffer cylinder (C2 > C1) the surface sinks ahead of the contact and rises behind, and
the pressure shifts backwards, against the sliding.

Solved by collocation: piecewise-constant pressures on N cells over [-L, L] (integrals
of both kernels over a cell in closed form), the contact set by an active-set iteration
(cells with negative pressure leave, cells with a negative gap enter). Checked against
Hertz without friction (tests/studies/test_sliding_half_planes.py).
"""

import math

import numpy as np


def _log_integral(x, left, right):
    """int_left^right ln|x - s| ds, for every x and cell [left, right]."""
    def primitive(t):       # int ln|t| dt = t ln|t| - t, with 0 ln 0 = 0
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(t == 0, 0.0, t * np.log(np.abs(t)) - t)
    return primitive(x - left) - primitive(x - right)


def _sign_integral(x, left, right):
    """int_left^right sgn(x - s) ds: the cell's length below x less its length above."""
    length = right - left
    return np.clip(x - left, 0, length) - np.clip(right - x, 0, length)


def compliance(E, nu):
    """(K, C) of a body (E = inf: rigid, 0 and 0)."""
    if math.isinf(E):
        return 0.0, 0.0
    return 2 * (1 - nu ** 2) / (math.pi * E), (1 - 2 * nu) * (1 + nu) / E


def sliding_contact(force, radius, mu, upper, lower, cells=1200, reach=None):
    """(x, p, delta) of the sliding contact: cell centres, their pressures, the approach.
    ``upper``, ``lower``: (E, nu) of the cylinder and the half-plane (E = inf: rigid);
    ``reach``: the half-length of the grid (default 1.6 Hertz half-widths)."""
    K1, C1 = compliance(*upper)
    K2, C2 = compliance(*lower)
    K = K1 + K2
    hertz_a = math.sqrt(2 * force * radius * K)   # a^2 = 4 P R / (pi E*), K = 2 / (pi E*)
    reach = 1.6 * hertz_a if reach is None else reach
    edges = np.linspace(-reach, reach, cells + 1)
    x = 0.5 * (edges[:-1] + edges[1:])
    width = np.diff(edges)
    left, right = edges[:-1][None, :], edges[1:][None, :]
    X = x[:, None]
    # gap = h - delta + G p
    G = -K * _log_integral(X, left, right) + 0.5 * (C2 - C1) * mu * _sign_integral(X, left, right)
    h = x ** 2 / (2 * radius)
    active = np.abs(x) < hertz_a
    for _ in range(10 * cells):
        n = int(active.sum())
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = G[np.ix_(active, active)]
        A[:n, n] = -1.0
        A[n, :n] = width[active]
        rhs = np.concatenate([-h[active], [force]])
        solution = np.linalg.solve(A, rhs)
        p = np.zeros(cells)
        p[active] = solution[:n]
        delta = solution[n]
        gap = h - delta + G @ p
        leave = active & (p < 0)
        enter = ~active & (gap < 0)
        if not leave.any() and not enter.any():
            return x, p, delta
        if leave.any():            # the most negative pressures leave first
            active &= ~(p < 0)
        else:
            active |= enter
    raise RuntimeError("the contact set did not settle")


def centre_and_edges(x, p):
    """(the centre of pressure, the contact's first and last loaded x)."""
    loaded = np.flatnonzero(p > 0)
    return (float(np.sum(p * x) / np.sum(p)), float(x[loaded[0]]), float(x[loaded[-1]]))
