"""The fixed point of a frozen contact set, solved at once from the subdomains' maps.

With every subdomain's Robin-to-trace map known (orchestrate/workers/robin_map.py), one Robin
iteration for a frozen contact set Psi is an affine map of the Robin data g of all
sides: the state of the interfaces (robin.py: every side's trace u and traction t) is
x = S g + s0, the traces u = M g + m (M has a block per subdomain) and the tractions
t = alpha (g - u); the next data are g = L x + h by the sides' Robin laws
(robin.robin_laws, written as coefficients: own trace, the other side's trace and
traction, and on a friction side its contact's normal stress, the mean of the contact's
two tractions at the same point). Its fixed point, the penalised problem's solution for
that Psi, solves

    (I - L S) g = L s0 + h,

a dense system of the size of the interface traces. Solved directly, each contact set
costs one solve of it instead of the tens of accelerated Robin iterations that approach
its fixed point (whose convergence the Robin parameter cannot speed up much: the map has
eigenvalues near 1 wherever a coating is bonded). The contact-set updates around it are
then semi-smooth Newton steps with an exact Jacobian.
"""

import numpy as np
from scipy.linalg import lu_factor, lu_solve


class InterfaceSystem:
    """The frozen-set system of a run's subdomain maps.

    ``layout``: the run's StateLayout; ``sides``: {worker: [(interface, side), ...]}
    in request order; ``maps``: {worker: RobinMap} at the laws' coefficients alpha;
    ``finish``: what makes a state of S g + s0 whole (the tractions of the bonds inside a
    worker, robin.with_bond_tractions), or None."""

    def __init__(self, layout, sides, maps, finish=None):
        self.layout = layout
        self.finish = finish or (lambda state: state)
        self.size = size = int(np.count_nonzero(layout.displacement_mask))
        self.matrix, self.constant = np.zeros((size, size)), np.zeros(size)
        for name, robin_map in maps.items():
            rows = np.concatenate([_entries(layout.slices["u", i, side])
                                   for i, side in sides[name]])
            self.matrix[np.ix_(rows, rows)] = robin_map.matrix
            self.constant[rows] = robin_map.constant
        self.other = np.empty(size, dtype=int)   # the same point of the interface's other side
        for (kind, i, side), where in layout.slices.items():
            if kind == "u":
                self.other[_entries(where)] = _entries(layout.slices["u", i, 1 - side])
        # a friction side's entries: its contact's side A entries at the same points
        # (side B's are their ``other``); elsewhere the entry itself, with no weight
        self.contact = np.arange(size)
        for i, interface in enumerate(layout.interfaces):
            if interface.kind == "friction":
                for side in (0, 1):
                    self.contact[_entries(layout.slices["u", i, side])] = _entries(
                        layout.slices["u", interface.contact, 0])

    def laws_matrix(self, laws):
        """(L, h, alpha): the data g = L x + h of the state x under ``laws``, and the
        Robin coefficient of every trace entry."""
        n = self.size
        coefficients, h = self._coefficients(laws)
        rows = np.arange(n)
        L = np.zeros((n, 2 * n))
        L[rows, rows] = coefficients["own"]
        L[rows, self.other] += coefficients["other_u"]
        L[rows, n + self.other] = coefficients["other_t"]
        half = 0.5 * coefficients["by_pressure"]
        L[rows, n + self.contact] += half
        L[rows, n + self.other[self.contact]] += half
        return L, h, coefficients["alpha"]

    def _coefficients(self, laws):
        """Every trace entry's coefficients of its law (alpha, own, other_u, other_t:
        robin.robin_laws), and the laws' constants h."""
        n = self.size
        coefficients = {name: np.zeros(n) for name in ("alpha", "own", "other_u", "other_t",
                                                       "by_pressure")}
        h = np.empty(n)
        for (i, side), law in laws.items():
            where = self.layout.slices["u", i, side]
            components = law.constant.shape[0]
            for name, values in coefficients.items():
                value = getattr(law, name)
                if value is not None:
                    values[where] = np.tile(value, components)
            h[where] = np.ravel(law.constant)
        return coefficients, h

    def _times_laws(self, coefficients, x):
        """L x, for a state x (a vector or the columns of a matrix): every entry's law
        takes its own trace and the other side's trace and traction, and a friction
        entry its contact's two tractions (L is that sparse; a dense product would cost
        most of a solve)."""
        n, other, contact = self.size, self.other, self.contact
        shape = (-1,) + (1,) * (x.ndim - 1)
        return (coefficients["own"].reshape(shape) * x[:n]
                + coefficients["other_u"].reshape(shape) * x[other]
                + coefficients["other_t"].reshape(shape) * x[n + other]
                + (0.5 * coefficients["by_pressure"]).reshape(shape)
                * (x[n + contact] + x[n + other[contact]]))

    def state_matrix(self, alpha):
        """(S, s0): the state x = S g + s0 the subdomains answer to the data g."""
        M, m = self.matrix, self.constant
        S = np.vstack([M, alpha[:, None] * (np.eye(self.size) - M)])
        return S, np.concatenate([m, -alpha * m])

    def fixed_point(self, laws):
        """(state, refined): the state at the fixed point for ``laws``, and the state after
        one step of iterative refinement; their difference estimates the first's
        rounding error."""
        coefficients, h = self._coefficients(laws)
        S, s0 = self.state_matrix(coefficients["alpha"])
        system = np.eye(self.size) - self._times_laws(coefficients, S)
        right = self._times_laws(coefficients, s0) + h
        factors = lu_factor(system)                 # factorised once, solved twice
        g = lu_solve(factors, right)
        correction = lu_solve(factors, right - system @ g)
        return self.finish(S @ g + s0), self.finish(S @ (g + correction) + s0)


def _entries(where):
    return np.arange(where.start, where.stop)
