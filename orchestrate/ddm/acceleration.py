"""Anderson acceleration of a fixed-point map x = G(x), as preCICE's IQN-ILS.

From the last iterates x_i and their images g_i = G(x_i), with residuals r_i = g_i - x_i,
the next iterate is x_{k+1} = g_k - dG c, where c minimises || r_k - dR c || over the
differences dR, dG of successive residuals and images: a secant (quasi-Newton) model of
the interface Jacobian built from the history. Columns that make the least-squares
problem ill-conditioned are dropped (QR filter: a column whose R diagonal is below
``filter_tolerance`` times its norm adds no new direction). The caller restarts the
history when the map itself changes (a new contact set).
"""

import math

import numpy as np

from orchestrate.model.scene import Settings


class Anderson:
    """``memory``, ``filter_tolerance``, ``first_relaxation``: by default the settings'
    anderson_depth, anderson_filter and anderson_first_relaxation."""

    def __init__(self, scale, memory=Settings.anderson_depth,
                 filter_tolerance=Settings.anderson_filter,
                 first_relaxation=Settings.anderson_first_relaxation, parts=()):
        self.scale = scale                  # weights making the residual norm meaningful
        self.memory = memory
        self.filter_tolerance = filter_tolerance
        self.first_relaxation = first_relaxation
        self.parts = parts                  # index arrays: amplification's parts
        self.reset()

    def reset(self):
        self._residuals, self._images, self._ratios = [], [], []

    def amplification(self):
        """One factor per part (``parts``; the whole state if none): the max over the
        history of ||dx_part|| / ||dr||, the step between two iterates over the change of
        their residuals. For an affine map with Jacobian J, dr = (J - I) dx, so for the
        whole state this bounds ||(I - J)^-1|| from below, the factor by which a residual
        underestimates the distance to the fixed point (1/(1 - q) for a contraction by
        q); for a part, the share of that distance a residual hides, which for a small
        part (a bond's shear beside its peel stress) can be far above its share of the
        whole. Each pair's ratios are computed once, when it enters the history."""
        if not self._ratios:
            return np.full(max(len(self.parts), 1), math.inf)
        return np.max(self._ratios, axis=0)

    def _pair_ratios(self):
        """||dx_part|| / ||dr|| of the newest pair of the history."""
        d_r = self._residuals[-1] - self._residuals[-2]
        d_x = (self._images[-1] - self._images[-2]) * self.scale - d_r   # scaled x = g - r
        d_r_norm = max(float(np.linalg.norm(d_r)), 1e-300)
        parts = self.parts or (slice(None),)
        return np.array([np.linalg.norm(d_x[part]) for part in parts]) / d_r_norm

    @property
    def secants(self):
        """Differences of residuals in the history: what the secant model is made of."""
        return max(0, len(self._residuals) - 1)

    def record(self, x, g):
        """Keep the iterate x and its image g = G(x) in the history (the newest
        ``memory`` + 1); return the scaled residual."""
        r = (g - x) * self.scale
        self._residuals.append(r)
        self._images.append(g)
        if len(self._residuals) > 1:
            self._ratios.append(self._pair_ratios())
        if len(self._residuals) > self.memory + 1:
            self._residuals.pop(0)
            self._images.pop(0)
            self._ratios.pop(0)             # the pair of the entry dropped
        return r

    def step(self, x, g):
        """Next iterate from the current iterate x and its image g = G(x)."""
        r = self.record(x, g)
        if len(self._residuals) == 1:
            return x + self.first_relaxation * (g - x)
        d_residuals = np.diff(np.array(self._residuals), axis=0).T   # newest column last
        d_images = np.diff(np.array(self._images), axis=0).T
        order, q, upper = self._filtered_qr(d_residuals)
        if not order:
            return g
        # the least-squares coefficients from the filter's own QR (no second factorisation)
        coefficients = np.linalg.solve(upper, q.T @ r)
        return g - d_images[:, order] @ coefficients

    def _filtered_qr(self, columns):
        """(the kept columns' indices, newest first, dropping the oldest dependent ones;
        Q; R of their QR in that order)."""
        # more columns than unknowns cannot be independent: keep the newest ones
        newest, oldest = columns.shape[1] - 1, max(0, columns.shape[1] - columns.shape[0])
        order = list(range(newest, oldest - 1, -1))
        while order:
            # QR with the newest column first, so older near-duplicates are the ones dropped
            q, upper = np.linalg.qr(columns[:, order])
            norms = np.linalg.norm(columns[:, order], axis=0)
            weak = np.flatnonzero(np.abs(np.diag(upper)) <= self.filter_tolerance * norms)
            if len(weak) == 0:
                return order, q, upper
            del order[weak[0]]
        return order, None, None
