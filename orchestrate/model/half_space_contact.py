"""The frictionless contact of two elastic half-planes (plane strain) across a given gap
profile: the first contact set of a contact that spans several faces of different
heights, such as a cylinder across thin pads and the bare base between them.

Each point of the face carries a uniform pressure on its strip (from the midpoints to
its neighbours). A line load P on a half-plane lowers its surface at distance r by
-(2 P / (pi E*)) ln r plus a constant (Johnson, Contact Mechanics, 2.19, E* = E / (1 -
nu^2)); both bodies add, so the strips' pressures p close the gap d by C p, C_ij =
-(2 / (pi E*_c)) times the integral of ln|x_i - s| over strip j, 1/E*_c = 1/E1* + 1/E3*.
The bodies approach by delta (2D: a half-plane's approach is defined only up to that
constant, so a force, not a descent, fixes the contact). The contact is the
complementarity problem g = d - delta + C p >= 0, p >= 0, g p = 0, with the force the
strips' p w summed; solved by active sets: the points in contact solve g = 0 with
the force, a point leaves where its pressure is negative, enters where it penetrates.
A half model (``mirrored``) counts every strip's mirror image about x = 0 too.

The elastic bodies' size and the coatings' stiffness are left out: what it gives is the
set's shape across the gap's steps, the loop's starting point (robin.first_contact_set),
not an answer.
"""

import numpy as np

# Active-set steps before the solve gives up (it then has no estimate): each step moves
# at least one point, and a contact of a few hundred points settles in a handful.
MAX_STEPS = 50


def face_strips(x):
    """(lower, upper) edges of the strips of one face's points at ``x`` (increasing,
    its ends included): from the midpoints between neighbours, the end points' strips
    half as wide, ending at the face's ends."""
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[x[0]], mid]), np.concatenate([mid, [x[-1]]])


def _log_integral(t):
    """The integral of ln|t| dt: t ln|t| - t (0 at t = 0)."""
    t = np.asarray(t, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t == 0.0, 0.0, t * np.log(np.abs(t)) - t)


def influence(at, lower, upper, compliance, mirrored=False):
    """C (points x strips): the gap closed at ``at`` per unit pressure on each strip,
    ``compliance`` 1/E*_c; with ``mirrored``, each strip's mirror about x = 0 pressed
    alike."""
    xi = at[:, None]
    # the integral over [lower, upper] of ln|x_i - s| ds
    integral = _log_integral(xi - lower[None, :]) - _log_integral(xi - upper[None, :])
    if mirrored:
        integral += _log_integral(xi + upper[None, :]) - _log_integral(xi + lower[None, :])
    return -2.0 * compliance / np.pi * integral


def contact_pressure(lower, upper, gap, compliance, force, mirrored=False):
    """(pressure on each strip, approach) of the contact across ``gap`` (one value per
    strip [lower, upper]) under a ``force`` per unit length (the whole contact's, mirror
    included), the gap closed at the strips' centres; None where the active sets do not
    settle or a set's system is singular (strips of no width). The strips may come from
    several faces (face_strips), in any order."""
    lower, upper = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    gap = np.asarray(gap, dtype=float)
    widths = (upper - lower) * (2.0 if mirrored else 1.0)
    c = influence(0.5 * (lower + upper), lower, upper, compliance, mirrored)
    active = gap <= gap.min() + 1e-12 * max(gap.max(), 1e-300)
    seen = set()
    for _ in range(MAX_STEPS):
        try:
            p, delta = _solve_active(c, gap, widths, active, force)
        except np.linalg.LinAlgError:
            return None
        g = gap - delta + c @ p
        leaving = active & (p < 0.0)
        entering = ~active & (g < 0.0)
        if not leaving.any() and not entering.any():
            return p, delta
        key = active.tobytes()
        if key in seen:
            return None
        seen.add(key)
        # leave first: a set with tension overstates the reach of the rest
        active = (active & ~leaving) if leaving.any() else (active | entering)
        if not active.any():
            return None
    return None


def _solve_active(c, gap, widths, active, force):
    """Pressures (zero off ``active``) and approach with g = 0 on ``active`` and the
    force balanced."""
    idx = np.flatnonzero(active)
    n = len(idx)
    system = np.zeros((n + 1, n + 1))
    system[:n, :n] = c[np.ix_(idx, idx)]
    system[:n, n] = -1.0
    system[n, :n] = widths[idx]
    solution = np.linalg.solve(system, np.concatenate([-gap[idx], [force]]))
    p = np.zeros(len(gap))
    p[idx] = solution[:n]
    return p, solution[n]
