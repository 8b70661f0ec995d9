"""The fixed point of a frozen contact set, solved at once from the subdomains' maps.

With every subdomain's Robin-to-trace map known (orchestrate/robin_map.py), one Robin
iteration for a frozen contact set Psi is an affine map of the Robin data g of all
sides: the traces are u = M g + m (M has a block per subdomain), each side's traction
is t = alpha (g - u), and the next data are g' = own u + other_u Pu + other_t Pt +
constant by the sides' Robin laws (robin.robin_laws; P takes every entry to the same
point and component of the interface's other side). Its fixed point, the penalised
problem's solution for that Psi, solves

    (I - B) g = c,   B = own M + other_u P M + other_t P alpha (I - M),

a dense system of the size of the interface traces. Solved directly, each contact set
costs one solve of it instead of the tens of accelerated Robin iterations that approach
its fixed point (whose linear convergence the Robin parameter cannot speed up much:
METHOD.md's map has eigenvalues near 1 wherever a coating is bonded). The contact-set
updates around it are then semi-smooth Newton steps with an exact Jacobian.
"""

import numpy as np


class InterfaceSystem:
    """The frozen-set system of a run's subdomain maps.

    ``layout``: the run's StateLayout; ``sides``: {subdomain: [(interface, side), ...]}
    in request order; ``maps``: {subdomain: RobinMap} at the laws' coefficients alpha."""

    def __init__(self, layout, sides, maps):
        self.layout = layout
        self.size = size = int(np.count_nonzero(layout.displacement_mask))
        self.matrix, self.constant = np.zeros((size, size)), np.zeros(size)
        for name, robin_map in maps.items():
            rows = np.concatenate([_entries(layout.slices["u", i, side])
                                   for i, side in sides[name]])
            self.matrix[np.ix_(rows, rows)] = robin_map.matrix
            self.constant[rows] = robin_map.constant
        self.other = np.empty(size, dtype=int)   # P as an index: (P v)[k] = v[other[k]]
        for (kind, i, side), where in layout.slices.items():
            if kind == "u":
                self.other[_entries(where)] = _entries(layout.slices["u", i, 1 - side])

    def _per_entry(self, laws):
        """The laws' coefficients at every trace entry, and their constants."""
        names = ("alpha", "own", "other_u", "other_t")
        coefficients = {name: np.empty(self.size) for name in names}
        constant = np.empty(self.size)
        for (i, side), law in laws.items():
            where = self.layout.slices["u", i, side]
            components = law.constant.shape[0]
            for name in names:
                coefficients[name][where] = np.tile(getattr(law, name), components)
            constant[where] = np.ravel(law.constant)
        return coefficients, constant

    def fixed_point(self, laws):
        """(state, refined): the state at the fixed point for ``laws``, and the state after
        one step of iterative refinement; their difference estimates the first's
        rounding error."""
        k, constant = self._per_entry(laws)
        M, m, other = self.matrix, self.constant, self.other
        weight = k["other_t"] * k["alpha"][other]
        shifted = M[other]
        system = -(k["own"][:, None] * M + k["other_u"][:, None] * shifted
                   - weight[:, None] * shifted)
        system[np.arange(self.size), other] -= weight
        system[np.diag_indices(self.size)] += 1.0
        right = k["own"] * m + (k["other_u"] - weight) * m[other] + constant
        g = np.linalg.solve(system, right)
        correction = np.linalg.solve(system, right - system @ g)
        return self._state(g, k["alpha"]), self._state(g + correction, k["alpha"])

    def _state(self, g, alpha):
        u = self.matrix @ g + self.constant
        return np.concatenate([u, alpha * (g - u)])


def _entries(where):
    return np.arange(where.start, where.stop)
