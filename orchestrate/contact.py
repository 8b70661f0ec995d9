"""The penalised interface laws of (16): contact on S12, bond on S23.

    J = 1/(2 theta) int_S12 [(d - u1n - w)^-]^2 + 1/(2 theta) int_S23 |u3 - f|^2,

with (s)^- = min(s, 0). Their derivatives are the interface stresses, compression
negative as in the paper.
"""

import numpy as np


def penetration(gap, upper_n, coating_n):
    """s = d - u1n - w: negative where Omega1 penetrates the coating."""
    return gap - upper_n - coating_n


def active_set(gap, upper_n, coating_n):
    """Psi12 of (20): 1 where the iterate penetrates, else 0."""
    return (penetration(gap, upper_n, coating_n) < 0).astype(float)


def contact_stress(gap, upper_n, coating_n, theta):
    """sigma_12n = (1/theta) (d - u1n - w)^-: the normal stress on S12."""
    return np.minimum(penetration(gap, upper_n, coating_n), 0.0) / theta


def bond_traction(coating_bond, lower_bond, theta):
    """Traction (sigma_21, sigma_22) the coating exerts on Omega3's top: (f - u3)/theta.

    Its second component is sigma_23n, the normal stress on S23."""
    return (np.asarray(coating_bond) - np.asarray(lower_bond)) / theta


def contact_half_width(x, stress):
    """Half-width a of the contact zone, zero without contact.

    Near the edge of a smooth contact the pressure goes like sqrt(a - x), so p^2 is
    linear there: a is where the line through the last two loaded points reaches zero,
    kept between the last loaded point and the next (unloaded) one."""
    loaded = np.flatnonzero(stress < 0)
    if len(loaded) == 0:
        return 0.0
    last = loaded[-1]
    if last + 1 >= len(x):
        return float(x[last])
    if len(loaded) < 2 or loaded[-2] != last - 1:
        return float(0.5 * (x[last] + x[last + 1]))
    p_last, p_prev = stress[last] ** 2, stress[last - 1] ** 2
    if p_prev <= p_last:
        return float(0.5 * (x[last] + x[last + 1]))
    a = x[last] + p_last * (x[last] - x[last - 1]) / (p_prev - p_last)
    return float(min(max(a, x[last]), x[last + 1]))


def updated_active_set(psi, gap, upper_n, coating_n, traction):
    """Semi-smooth Newton update of Psi12 from a solution computed with Psi.

    An active point stays active while its contact traction is compressive; an inactive
    one enters where the bodies interpenetrate. At a solution of the penalised problem
    this is Psi = [d - u1n - w < 0]; before it, the traction is the better judge on the
    active points, where the penetration is a difference of nearly equal traces."""
    penetrating = penetration(gap, upper_n, coating_n) < 0
    return np.where(psi > 0, traction < 0, penetrating).astype(float)
