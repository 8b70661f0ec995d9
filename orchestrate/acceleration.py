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


class Anderson:
    def __init__(self, scale, memory=100, filter_tolerance=1e-10, first_relaxation=1.0):
        self.scale = scale                  # weights making the residual norm meaningful
        self.memory = memory
        self.filter_tolerance = filter_tolerance
        self.first_relaxation = first_relaxation
        self.reset()

    def reset(self):
        self._residuals, self._images = [], []

    def amplification(self, parts=None):
        """max over the history of ||dx|| / ||dr||, the step between two iterates over
        the change of their residuals: for an affine map with Jacobian J, dr = (J - I) dx,
        so this bounds ||(I - J)^-1|| from below, the factor by which a residual
        underestimates the distance to the fixed point (1/(1 - q) for a contraction by q).
        With ``parts`` (index arrays), one factor per part: max ||dx_part|| / ||dr||, the
        part of the distance a residual hides, which for a small part (a bond's shear
        beside its peel stress) can be far above its share of the whole."""
        if len(self._residuals) < 2:
            return math.inf if parts is None else np.full(len(parts), math.inf)
        residuals, images = np.array(self._residuals), np.array(self._images)
        iterates = images * self.scale - residuals            # scaled x = g - r
        d_r, d_x = np.diff(residuals, axis=0), np.diff(iterates, axis=0)
        d_r_norm = np.maximum(np.linalg.norm(d_r, axis=1), 1e-300)
        if parts is None:
            return float(np.max(np.linalg.norm(d_x, axis=1) / d_r_norm))
        return np.array([np.max(np.linalg.norm(d_x[:, part], axis=1) / d_r_norm)
                         for part in parts])

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
        if len(self._residuals) > self.memory + 1:
            self._residuals.pop(0)
            self._images.pop(0)
        return r

    def step(self, x, g):
        """Next iterate from the current iterate x and its image g = G(x)."""
        r = self.record(x, g)
        if len(self._residuals) == 1:
            return x + self.first_relaxation * (g - x)
        d_residuals = np.diff(np.array(self._residuals), axis=0).T   # newest column last
        d_images = np.diff(np.array(self._images), axis=0).T
        keep = self._filter(d_residuals)
        coefficients, *_ = np.linalg.lstsq(d_residuals[:, keep], r, rcond=None)
        return g - d_images[:, keep] @ coefficients

    def _filter(self, columns):
        """Indices of the columns kept, dropping the oldest dependent ones first."""
        # more columns than unknowns cannot be independent: keep the newest ones
        keep = list(range(max(0, columns.shape[1] - columns.shape[0]), columns.shape[1]))
        while keep:
            # QR with the newest column first, so older near-duplicates are the ones dropped
            order = keep[::-1]
            _, r = np.linalg.qr(columns[:, order])
            norms = np.linalg.norm(columns[:, order], axis=0)
            weak = np.flatnonzero(np.abs(np.diag(r)) < self.filter_tolerance * norms)
            if len(weak) == 0:
                return keep
            keep.remove(order[weak[0]])
        return keep
