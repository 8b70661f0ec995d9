"""A coarse-mesh correction of the Robin loop on a fine mesh (two levels).

The loop's slow modes, those of its Robin map's eigenvalues near 1, are smooth along the
interfaces, and a coarse mesh sees them. The same scene at mesh level 1 (for a run on
level 1 itself: with interface elements twice as long), with the fine run's penalty and
Robin parameter, has an interface system small enough to probe and
solve directly (orchestrate/ddm/interface_system.py: x = A_c x + b_c for a frozen contact
set, A_c = S L). Interpolated along the interfaces (P: coarse state to fine, R: fine to
coarse), it serves twice:

- the first iterate: the coarse contact problem solved (semi-smooth Newton on the coarse
  system, no fine solve), interpolated;
- a preconditioner: each Robin residual r = F(x) - x of the fine loop becomes
  r + P ((I - B_c)^-1 - I) R r, and Anderson acceleration drives x to the fixed point
  of x + (that), the fine loop's own. B_c is the coarse model of the fine loop's whole
  iteration: its groups of subdomains (Problem.sweep) one after the other, each group's
  rows of the state taken from A_c, the others kept.

The coarse level's workers start before the fine ones and probe while the fine run meshes
and starts (orchestrate/run/coarse_level.py); they stop once their maps are read.

Measured offline on the paper's scene (2D coating, b/8, 5E; GMRES on the final contact
set to 1e-7, as many fine solves as iterations): 77 -> 37 at mesh level 2, 85 -> 41 at
level 3.
"""

from dataclasses import replace

import numpy as np
from scipy.linalg import lu_factor, lu_solve
from scipy.sparse import csr_matrix

from orchestrate.ddm.robin import first_contact_set, robin_laws, updated_contact_set
from orchestrate.ddm.robin_parameters import side_parameters


def _coarsening(settings):
    return settings.coarse_element_factor if settings.mesh_level == 1 else 1.0


def coarse_element_size(settings):
    """The coarse level's element length at mesh level 1: the fine one's at mesh level 1,
    coarse_element_factor times it when the fine run is at mesh level 1 itself."""
    return settings.element_length * _coarsening(settings)


def coarse_settings(settings):
    """The coarse level's settings: the scene at mesh level 1 (coarse_element_size) with
    the fine run's penalty and Robin parameter, probed and solved directly by persistent
    workers of its own, whatever the fine run's workers (a fresh process per solve keeps
    no factorisation to probe)."""
    return replace(settings, mesh_level=1, theta=settings.theta,
                   robin=settings.robin_parameter, inner_solve="direct",
                   workers="persistent", element_size=coarse_element_size(settings),
                   element_size_far=(settings.element_size_far * _coarsening(settings)
                                     if settings.element_size_far else None))


def coarse_laws(coarse, layout, psi):
    """The coarse problem's Robin laws for the contact set psi, every side's parameter by
    the fine run's rule, inactive points held (solved from its maps)."""
    settings = coarse.settings
    sides = side_parameters(coarse, coarse.robin, settings.robin_sides, settings.hold_contrast,
                            split_sides=False)      # as the fine loop's under two levels
    return robin_laws(coarse, layout, psi, coarse.penalty, sides, direct=True)


def paired(fine, coarse):
    """Whether the interfaces of two levels pair up along s (else no correction)."""
    return (len(fine) == len(coarse)
            and all(f.name == c.name and f.kind == c.kind for f, c in zip(fine, coarse))
            and all(np.all(np.diff(i.s) > 0) for i in (*fine, *coarse)))


class CoarseCorrection:
    """``newton_steps``: the coarse contact problem's semi-smooth Newton steps at most
    (LoopKnobs.coarse_newton_steps)."""

    def __init__(self, layout, coarse, coarse_layout, system, newton_steps):
        self.layout, self.coarse, self.coarse_layout, self.system = (layout, coarse,
                                                                     coarse_layout, system)
        self.newton_steps = newton_steps
        self.prolong = _interpolation(coarse_layout, layout)     # P: coarse -> fine
        self.restrict = _interpolation(layout, coarse_layout)    # R: fine -> coarse
        self._groups = [_rows_of(coarse, coarse_layout, group) for group in coarse.sweep]
        self._psi = None

    def laws(self, psi):
        return coarse_laws(self.coarse, self.coarse_layout, psi)

    def first_state(self):
        """The fine state interpolated from the coarse contact problem's solution."""
        layout = self.coarse_layout
        psi, x = first_contact_set(self.coarse.scene, layout, layout.zeros(), True), None
        for _ in range(self.newton_steps):
            x, _ = self.system.fixed_point(self.laws(psi))
            new_psi = updated_contact_set(layout, psi, x)
            if np.array_equal(new_psi, psi):
                break
            psi = new_psi
        return self.prolong @ x

    def correction(self, psi, residual):
        """P ((I - B_c)^-1 - I) R residual, with the coarse laws of the fine contact set
        psi (each coarse point takes the state of the fine point nearest along s)."""
        if self._psi is None or not np.array_equal(psi, self._psi):
            self._set_contact(psi)
        coarse = self.restrict @ residual
        # (I - B_c)^-1 - I applied by the LU factors of I - B_c: a solve per residual,
        # where forming (I - B_c)^-1 B_c took as many as its columns (TiN at mesh level 2:
        # 2.1 s of the loop's 8.9 s)
        return self.prolong @ (lu_solve(self._factors, coarse) - coarse)

    def _set_contact(self, psi):
        coarse_psi = np.empty(self.coarse_layout.gap.size)
        for (i, fine), (_, coarse) in zip(self.layout.contact_slices(),
                                          self.coarse_layout.contact_slices()):
            fine_s = self.layout.interfaces[i].s
            coarse_s = self.coarse_layout.interfaces[i].s
            nearest = np.abs(coarse_s[:, None] - fine_s[None, :]).argmin(axis=1)
            coarse_psi[coarse] = psi[fine][nearest]
        L, _, alpha = self.system.laws_matrix(self.laws(coarse_psi))
        S, _ = self.system.state_matrix(alpha)
        # L has a few entries per row: S L as dense times sparse (4 n^3 flops dense)
        one_iteration = _sweep_matrix(np.asarray(S @ csr_matrix(L)), self._groups)
        self._psi = psi.copy()
        self._factors = lu_factor(np.eye(len(one_iteration)) - one_iteration)


def _rows_of(problem, layout, names):
    """Whether each entry of the state belongs to a side of the subdomains ``names``."""
    rows = np.zeros(layout.size, dtype=bool)
    for name in names:
        for i, side in problem.sides_of(name):
            rows[layout.slices["u", i, side]] = rows[layout.slices["t", i, side]] = True
    return rows


def _sweep_matrix(A, groups):
    """The linear part of one iteration that solves the groups one after the other, each
    from the state the ones before left, where solving all at once is x -> A x + c: the
    product of the groups' steps, each A's rows of its group and the identity's others:
    a step replaces its group's rows of the product so far by A's rows times it (the
    rows no group has replaced yet are the identity's, so their product is A's columns)."""
    sweep = np.eye(len(A))
    replaced = np.zeros(len(A), dtype=bool)
    for rows in groups:
        sweep[rows] = (A[rows][:, replaced] @ sweep[replaced]
                       + np.where(replaced[None, :], 0.0, A[rows]))
        replaced |= rows
    return sweep


def _interpolation(source, target):
    """The matrix taking a state of layout ``source`` to one of layout ``target``: every
    block (trace or traction of a side, per component) linearly along s."""
    matrix = np.zeros((target.size, source.size))
    for key, into in target.slices.items():
        _, i, _ = key
        start, to = source.slices[key].start, into.start
        s_from, s_to = source.interfaces[i].s, target.interfaces[i].s
        weights = np.array([np.interp(s_to, s_from, unit) for unit in np.eye(len(s_from))]).T
        for c in range(target.interfaces[i].components):
            rows = slice(to + c * len(s_to), to + (c + 1) * len(s_to))
            columns = slice(start + c * len(s_from), start + (c + 1) * len(s_from))
            matrix[rows, columns] = weights
    return csr_matrix(matrix)         # two entries per row: applied once per iteration
