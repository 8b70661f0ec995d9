"""The penalised interface laws of (16) on every contact and bond interface:

    J = 1/(2 theta) int_contact [(d - u_A - u_B)^-]^2 + 1/(2 theta) int_bond |u_A - u_B|^2,

with (s)^- = min(s, 0), u_A, u_B the two sides' traces (a contact's: displacements along
each side's outward normal, the paper's u1n and w; a bond's: the coating's and the
base's displacements). Their derivatives are the interface stresses, compression
negative as in the paper.
"""

import numpy as np


def penetration(gap, u_a, u_b):
    """s = d - u_A - u_B: negative where the indenter penetrates its partner."""
    return gap - u_a - u_b


def contact_stress(gap, u_a, u_b, theta):
    """sigma_n = (1/theta) (d - u_A - u_B)^-: the contact's normal stress."""
    return np.minimum(penetration(gap, u_a, u_b), 0.0) / theta


def bond_traction(coating, base, theta):
    """Traction the coating exerts on the base, (coating - base)/theta, in the face's
    components (sigma_t, sigma_n)."""
    return (np.asarray(coating) - np.asarray(base)) / theta


def limits_on_axis(interface, stress):
    """An axisymmetric interface's stress with its value on the axis (a point of weight
    2 pi r ds = 0, which no equation holds: its penalty traction came out 5 % off a
    Hertz pressure that its neighbours met to 0.03 %) replaced by the field's limit
    there: a normal stress is even in r, A + B r^2 through the next two points (the
    first element's midpoint and end), a shear odd, 0."""
    if (interface.weight[0] != 0.0 or interface.position[0, 0] != 0.0
            or interface.kind == "friction"):      # no friction in a scene of revolution
        return stress
    stress = np.array(stress, dtype=float)
    normal = stress if interface.kind == "contact" else stress[1]
    r1, r2 = interface.position[1, 0], interface.position[2, 0]
    normal[..., 0] = (r2 ** 2 * normal[1] - r1 ** 2 * normal[2]) / (r2 ** 2 - r1 ** 2)
    if interface.kind == "bond":
        stress[0, 0] = 0.0
    return stress


def _edge(x, stress, last, step):
    """Where a contact zone ends beyond its last loaded point ``last`` (``step`` = +1:
    towards larger indices). Near the edge of a smooth contact the pressure goes like
    sqrt(a - x), so p^2 is linear there: the edge is where the line through the last two
    loaded points reaches zero, kept between the last loaded point and the next one."""
    after, before = last + step, last - step
    if not 0 <= after < len(x):
        return float(x[last])
    if not 0 <= before < len(x) or not stress[before] < 0:
        return float(0.5 * (x[last] + x[after]))
    p_last, p_prev = stress[last] ** 2, stress[before] ** 2
    if p_prev <= p_last:
        return float(0.5 * (x[last] + x[after]))
    a = x[last] + p_last * (x[last] - x[before]) / (p_prev - p_last)
    low, high = sorted((x[last], x[after]))
    return float(min(max(a, low), high))


def contact_zones(x, stress):
    """[(start, end)] of every stretch of consecutive loaded points (points ordered
    along the face); a zone that reaches the first or last point ends there."""
    loaded = stress < 0
    zones, i = [], 0
    while i < len(x):
        if not loaded[i]:
            i += 1
            continue
        j = i
        while j + 1 < len(x) and loaded[j + 1]:
            j += 1
        zones.append((_edge(x, stress, i, -1), _edge(x, stress, j, +1)))
        i = j + 1
    return zones


def contact_half_width(x, stress):
    """Half-width a of a contact zone that starts on the symmetry axis (the first
    point), zero without contact there."""
    zones = contact_zones(x, stress)
    if not zones or x[0] != zones[0][0] or not stress[0] < 0:
        return 0.0
    return zones[0][1]


def updated_active_set(psi, penetration, traction):
    """Semi-smooth Newton update of Psi12 from a solution computed with Psi, given its
    penetration d - u1n - w and contact traction.

    An active point stays active while its contact traction is compressive; an inactive
    one enters where the bodies interpenetrate. At a solution of the penalised problem
    this is Psi = [d - u1n - w < 0]; before it, the traction is the better judge on the
    active points, where the penetration is a difference of nearly equal traces."""
    return np.where(psi > 0, traction < 0, penetration < 0).astype(float)


def stick_zones(x, stick, margin):
    """[(start, end)] of every stretch of consecutive sticking points (ordered along the
    face), ``margin`` the friction's reserve mu p - |q| at every point. In Cattaneo's
    stick zone the reserve goes like sqrt(c - x) near its end c, so its square is
    linear there: an end is where the line through the last two sticking points'
    squared reserves reaches zero, kept between the last sticking point and the next."""
    zones, i, n = [], 0, len(x)
    squared = np.square(np.maximum(margin, 0.0))

    def end(last, step):
        after, before = last + step, last - step
        if not 0 <= after < n:
            return float(x[last])
        if not 0 <= before < n or not stick[before] or squared[before] <= squared[last]:
            return float(0.5 * (x[last] + x[after]))
        edge = x[last] + squared[last] * (x[last] - x[before]) / (squared[before] - squared[last])
        low, high = sorted((x[last], x[after]))
        return float(min(max(edge, low), high))
    while i < n:
        if not stick[i]:
            i += 1
            continue
        j = i
        while j + 1 < n and stick[j + 1]:
            j += 1
        zones.append((end(i, -1), end(j, +1)))
        i = j + 1
    return zones
