"""Anderson acceleration of a fixed-point map x = G(x), as preCICE's IQN-ILS.

From the last iterates x_i and their images g_i = G(x_i), with residuals r_i = g_i - x_i,
the next iterate is x_{k+1} = g_k - dG c, where c minimises || r_k - dR c || over the
differences dR, dG of successive residuals and images: a secant (quasi-Newton) model of
the interface Jacobian built from the history. Columns that make the least-squares
problem ill-conditioned are dropped (QR filter: a column whose R diagonal is below
``filter_tolerance`` times its norm adds no new direction). The caller restarts the
history when the map itself changes (a new contact set).

The QR of the differences, newest first, is kept from step to step and updated by
rotations (qr_update.py): a step costs O(n m) rather than a new factorisation's
O(n m^2) (with m up to ``memory`` columns it was a third of a Robin iteration's time).
"""

import math

import numpy as np

from orchestrate.ddm.qr_update import delete_column, prepend_column
from orchestrate.model.scene import Settings


class Anderson:
    """``memory``, ``filter_tolerance``, ``first_relaxation``: by default the settings'
    anderson_depth, anderson_filter and anderson_first_relaxation. ``measure``: the
    weights the parts' steps are measured in (amplification), by default ``scale``; an
    entry the residual leaves out (scale 0: a value the map derives, not iterates on)
    is measured by its image's step."""

    def __init__(self, scale, memory=Settings.anderson_depth,
                 filter_tolerance=Settings.anderson_filter,
                 first_relaxation=Settings.anderson_first_relaxation, parts=(), measure=None):
        self.scale = scale                  # weights making the residual norm meaningful
        self.measure = scale if measure is None else measure
        self.memory = memory
        self.filter_tolerance = filter_tolerance
        self.first_relaxation = first_relaxation
        self.parts = parts                  # index arrays: amplification's parts
        self.reset()

    def reset(self):
        self._residuals, self._images, self._ratios = [], [], []
        self._qr = None                     # QR of the residuals' differences, newest first
        self._norms = []                    # their norms, newest first

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

    def answer_errors(self):
        """One bound per part (``parts``; in the scaled norm) of the newest image's
        distance to the fixed point, or None before a secant. For an affine map with
        Jacobian J the differences are exact secants, dR = (J - I) dX, so the share of
        the residual r the history spans, r = dR c + rho with rho its least-squares
        remainder, has its error exactly: dG c, G the images. The rest, J (J - I)^-1 rho,
        is bounded by rho times the largest ||dG_part|| / ||dR|| over every combination of
        the history's pairs, ||dG_part R^-1||_2 (R from the QR of dR), at least each
        pair's own. Measured against the error itself over the gallery's final contact
        sets, this stayed above it where the pairs' amplification times the whole
        residual (amplification) dipped below it: a residual that dips while the
        error does not hides in a combination of pairs (the gallery's pads at mesh level
        2: a far pad's bond shear 2.7 times eps_u = 1e-3 off). It costs a dense solve
        and a Gram matrix per part, so the loop asks for it only to confirm a stop."""
        if self.secants < 1:
            return None
        order, q, upper = self._filtered(*self._qr, list(self._norms))
        if not order:
            return None
        r = self._residuals[-1]
        projection = q.T @ r
        coefficients = np.linalg.solve(upper, projection)
        remainder = math.sqrt(max(float(r @ r - projection @ projection), 0.0))
        d_g = self._image_differences()[:, order] * self.measure[:, None]
        explained = d_g @ coefficients
        m = np.linalg.solve(upper.T, d_g.T).T               # dG R^-1
        parts = self.parts or (slice(None),)
        spectral = np.array([math.sqrt(max(float(np.linalg.eigvalsh(m[part].T @ m[part])[-1]),
                                           0.0)) for part in parts])
        explained_parts = np.array([np.linalg.norm(explained[part]) for part in parts])
        return explained_parts + np.maximum(spectral, self.amplification()) * remainder

    def _pair_ratios(self):
        """||dx_part|| / ||dr|| of the newest pair of the history."""
        d_r = self._residuals[-1] - self._residuals[-2]
        d_x = (self._images[-1] - self._images[-2]) * self.measure - d_r   # scaled x = g - r
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
            column = r - self._residuals[-2]
            self._norms.insert(0, float(np.linalg.norm(column)))
            self._qr = (prepend_column(*self._qr, column) if self._updatable()
                        else prepend_column(None, None, column) if self._qr is None else None)
        if len(self._residuals) > self.memory + 1:
            self._residuals.pop(0)
            self._images.pop(0)
            self._ratios.pop(0)             # the pair of the entry dropped
            self._norms.pop()
            if self._updatable():           # the oldest column is the last: drop it
                q, upper = self._qr
                self._qr = (q[:, :-1], upper[:-1, :-1])
            else:
                self._qr = None
        if self._qr is None and len(self._residuals) > 1:
            # a column dependent on the history, or more columns than unknowns: anew
            self._qr = np.linalg.qr(self._residual_differences())
        return r

    def _updatable(self):
        """Whether the kept QR is an economic one (R square) that rotations update."""
        return self._qr is not None and self._qr[1].shape[0] == self._qr[1].shape[1]

    def _residual_differences(self):
        """The differences of the residuals, newest column first."""
        return np.diff(np.array(self._residuals), axis=0)[::-1].T

    def _image_differences(self):
        """The differences of the images, newest column first."""
        return np.diff(np.array(self._images), axis=0)[::-1].T

    def step(self, x, g):
        """Next iterate from the current iterate x and its image g = G(x)."""
        r = self.record(x, g)
        if len(self._residuals) == 1:
            return x + self.first_relaxation * (g - x)
        order, q, upper = self._filtered(*self._qr, list(self._norms))
        if not order:
            return g
        # the least-squares coefficients from the filter's own QR (no second factorisation)
        coefficients = np.linalg.solve(upper, q.T @ r)
        images = self._images
        step = np.zeros_like(g)
        for k, coefficient in zip(order, coefficients):     # column k: newest is 0
            step += coefficient * (images[-1 - k] - images[-2 - k])
        return g - step

    def _filtered(self, q, upper, norms):
        """(the kept columns' positions, newest (0) first; Q; R of their QR): the oldest
        dependent columns dropped, one at a time from the QR of the newest-first history,
        and every column beyond the unknowns' number (they cannot be independent)."""
        keep = min(len(norms), q.shape[0])
        order, q, upper, norms = list(range(keep)), q[:, :keep], upper[:keep, :keep], norms[:keep]
        while order:
            # newest first, so older near-duplicates are the ones dropped
            weak = np.flatnonzero(np.abs(np.diag(upper)) <= self.filter_tolerance
                                  * np.asarray(norms))
            if len(weak) == 0:
                return order, q, upper
            j = int(weak[0])
            q, upper = delete_column(q, upper, j)
            del order[j], norms[j]
        return order, None, None
