"""The stamp's force carried by its partner at every iteration (a one-dimensional coarse
correction of the Robin loop under a force).

Under a force the stamp's body finds its descent in its own solve (freefem/robin.idp),
but its partner, the worker holding every contact's side B (the base, or the coated
base), only takes what its Robin data give it. Early in a cold start these carry a
fraction of the force, or many times it: the descent is the slowest mode of the
exchange (a body-sized wave, where the Robin coefficients match the contact's), and
the gallery's scenes spent their first 5-13 iterations finding it, the tractions
swinging through ten times the force. So the partner's data on its contact sides are
shifted along the normal by the one offset Delta that makes its contact tractions carry
the stamp's force too:

    F(g + Delta b) = P,  F(g) = -sum over side B's points of omega b alpha (g - u),

b the x2 component of the contact's normal (F the force along x2), P the stamp's force
on the modelled part (Scene.half_force). At a fixed point both sides' tractions carry P,
so that with the contact's laws (robin_laws) sum omega (t_A - t_B) = Delta kappa sum omega
b = 0, kappa = 1 / (theta - 1/gamma_A - 1/gamma_B) per point, never 0 where the loop
converges (robin_laws: gamma theta < 1): Delta = 0 and the fixed point is the
unbalanced loop's, the monolithic solve's answer.

The offset is found without a solve of its own. The partner's traces are affine in its
data, u = M g + m with M = T A^-1 T' diag(omega alpha) (A its symmetric Robin matrix), so
F is affine in g, and by A's symmetry its gradient needs only M b:

    F(g') - F(g) = -sum over the partner's entries of omega alpha (g' - g) (b - M b).

M b is probed once per matrix (a solve at g + b beside the one at g, at the first
iteration of a set that changed the partner's alpha); from then on each request carries
the offset predicted from the last solve, and the partner's fields are its answer's.
"""

import numpy as np


class ForceBalance:
    """The offset of ``worker``'s contact data that makes it carry the stamp's force.
    ``sides``: the worker's (interface index, side) in order; ``problem``: the discrete
    problem (its interfaces, its scene's force)."""

    def __init__(self, problem, worker, sides):
        self.worker = worker
        self.sides = tuple(sides)
        self.force = problem.scene.half_force
        interfaces = problem.interfaces
        self.weight = {key: np.asarray(interfaces[key[0]].weight, dtype=float)
                       for key in self.sides}
        # b: the x2 component of the normal on every contact's side B, 0 elsewhere
        self.direction = {
            (i, side): (np.asarray(interfaces[i].normal[:, 1], dtype=float)[None, :]
                        if interfaces[i].kind == "contact" and side == 1
                        else np.zeros((interfaces[i].components, interfaces[i].size)))
            for i, side in self.sides}
        self._alpha = None          # the partner's alpha its response was probed at
        self._response = None       # M b, by side
        self._per_offset = None     # F(g + b) - F(g) at that alpha
        self._reference = None      # (the data g of the last solve, its force F(g))

    def applies(self, group):
        return self.worker in group

    def force_of(self, data, traces):
        """F: the force along x2 the partner's contact sides carry in a solve of
        ``data`` that answered ``traces``."""
        return -sum(float(np.sum(self.weight[key] * alpha * self.direction[key]
                                 * (g - np.atleast_2d(traces[key]))))
                    for key in self.sides for alpha, g in (data[key],))

    def _gradient_dot(self, data, step):
        """F(g + step) - F(g) for the partner's data ``data``: -sum omega alpha step
        (b - M b) (the module's docstring)."""
        return -sum(float(np.sum(self.weight[key] * data[key][0] * step[key]
                                 * (self.direction[key] - self._response[key])))
                    for key in self.sides)

    def _probed_at(self, data):
        return self._alpha is not None and all(
            np.array_equal(data[key][0], self._alpha[key]) for key in self.sides)

    def _shifted(self, data, offset):
        shifted = dict(data)
        for key in self.sides:
            alpha, g = data[key]
            shifted[key] = (alpha, np.atleast_2d(g) + offset * self.direction[key])
        return shifted

    def balanced(self, data):
        """``data`` with the partner's shifted by the offset that carries the force,
        predicted from its last solve where its matrix has not changed since; else
        ``data`` as they are (``settled`` then probes the response)."""
        if not self._probed_at(data):       # settled probes it (and sets the reference)
            return data
        reference, force = self._reference
        step = {key: np.atleast_2d(data[key][1]) - reference[key] for key in self.sides}
        return self._shifted(data, self._offset(force + self._gradient_dot(data, step)))

    def _offset(self, force):
        """The offset that takes a solve's force from ``force`` to the stamp's; 0 where
        the shift carries none (no point of side B in contact)."""
        if self._per_offset == 0.0:
            return 0.0
        return (self.force - force) / self._per_offset

    def settled(self, data, traces, solve):
        """The data and traces of the partner's solve as balanced: where its matrix is
        new, its response M b is probed (``solve(data, names)``, one more solve of the
        partner) and the solve of ``data`` is shifted to carry the force by linearity;
        the partner's fields are then the probe's until its next solve, which comes: the
        loop stops only after min_secants pairs of iterates of its final set, and a
        fallback to the direct solve solves again. Returns (data, traces) of every
        side."""
        if not self._probed_at(data):
            probe = self._shifted(data, 1.0)
            probed, _, _ = solve(probe, [self.worker])
            self._alpha = {key: np.array(data[key][0]) for key in self.sides}
            self._response = {key: np.atleast_2d(probed[key]) - np.atleast_2d(traces[key])
                              for key in self.sides}
            self._per_offset = self._gradient_dot(data, self.direction)
            offset = self._offset(self.force_of(data, traces))
            data = self._shifted(data, offset)
            traces = dict(traces)
            for key in self.sides:
                shape = np.shape(traces[key])
                traces[key] = np.reshape(np.atleast_2d(traces[key])
                                         + offset * self._response[key], shape)
        self._reference = ({key: np.atleast_2d(data[key][1]).copy() for key in self.sides},
                           self.force_of(data, traces))
        return data, traces
