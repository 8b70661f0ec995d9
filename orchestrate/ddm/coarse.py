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
  data from the state the groups before it left. Where the fine loop solves a base and
  its coatings as one worker (Strategy.bonds_inside), all its workers at once, B_c is
  that iteration: the contacts' data from the state before, the bonds' from the state
  after (their exchange converged: the worker's penalty); the coarse workers stay one
  per subdomain, their maps combined here. Either way, with A_c = S L split into the
  data computed from the state before and after, S L_a + S L_b, B_c =
  (I - S L_b)^-1 S L_a and (I - B_c)^-1 = (I - A_c)^-1 (I - S L_b), applied through an
  LU of the data's size (iteration_inverse).

The coarse level's workers start before the fine ones and probe while the fine run meshes
and starts (orchestrate/run/coarse_level.py); they stop once their maps are read.

Measured offline on the paper's scene (2D coating, b/8, 5E; GMRES on the final contact
set to 1e-7, as many fine solves as iterations): 77 -> 37 at mesh level 2, 85 -> 41 at
level 3.
"""

from dataclasses import replace
import math

import numpy as np
from scipy.linalg import lu_factor, lu_solve
from scipy.sparse import coo_matrix, csr_matrix

from orchestrate.ddm.first_contact import predicted_contact
from orchestrate.ddm.robin import first_contact_set, robin_laws, updated_contact_set
from orchestrate.ddm.robin_parameters import side_parameters
from orchestrate.mesh.discretization import discretize


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
    return replace(settings, mesh_level=1, theta=float(settings.theta),   # kept: given
                   robin=settings.robin_parameter, inner_solve="direct",
                   workers="persistent", element_size=coarse_element_size(settings),
                   element_size_far=(settings.element_size_far * _coarsening(settings)
                                     if settings.element_size_far else None))


def coarse_problem(scene, settings):
    """The coarse level's problem of a fine run's scene and settings. Its thin 2D
    coatings' cells are its face's elements, not narrowed at their ends and the
    contact's edges: the coarse level models the smooth modes, and the narrow cells were
    most of its interface unknowns, each a back-substitution to probe (docs/method.md,
    "Two levels", has the gallery's pads with and without them)."""
    return discretize(scene, coarse_settings(settings), cell_aspect=math.inf)


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
    (LoopKnobs.coarse_newton_steps); ``inside``: the interfaces of the bonds the fine
    loop solves inside a worker (Strategy.bonds_inside; the module's note)."""

    def __init__(self, layout, coarse, coarse_layout, system, newton_steps, inside=()):
        self.layout, self.coarse, self.coarse_layout, self.system = (layout, coarse,
                                                                     coarse_layout, system)
        self.newton_steps = newton_steps
        self.prolong = _interpolation(coarse_layout, layout)     # P: coarse -> fine
        self.restrict = _interpolation(layout, coarse_layout)    # R: fine -> coarse
        # the fine iteration's order: each data entry's step (a later step's data come
        # from the state the earlier steps left) and each state entry's; a base and its
        # coatings as one worker (inside) solve in one step, their bonds' data from the
        # state after it (their exchange converged in the worker's matrix), else the
        # sweep's groups one after the other
        if inside:
            self._state_step = np.zeros(coarse_layout.size, dtype=int)
            self._data_step = np.zeros(system.size, dtype=int)
            for i in inside:
                for side in (0, 1):
                    self._data_step[coarse_layout.slices["u", i, side]] = 1
        else:
            self._state_step = np.full(coarse_layout.size, -1)
            for step, group in enumerate(coarse.sweep):
                self._state_step[_rows_of(coarse, coarse_layout, group)] = step
            assert np.all(self._state_step >= 0), "a state entry no group solves"
            self._data_step = self._state_step[:system.size]   # data g ~ the traces u
        self._nearest = self._nearest_fine_points()
        self._psi = None        # the coarse contact set of the factors in _inverse

    def laws(self, psi):
        return coarse_laws(self.coarse, self.coarse_layout, psi)

    def first_state(self, half_width=None):
        """The fine state interpolated from the coarse contact problem's solution, its
        semi-smooth Newton steps from the points within the a priori ``half_width`` (b;
        Strategy.first_contact), if known (TiN at mesh level 2: one step, against ten
        grown from the first point touched)."""
        layout = self.coarse_layout
        psi = first_contact_set(self.coarse.scene, layout, layout.zeros(), True,
                                predicted_contact(self.coarse, layout, half_width))
        x = None
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
        coarse_psi = psi[self._nearest]
        if self._psi is None or not np.array_equal(coarse_psi, self._psi):
            self._set_contact(coarse_psi)    # factorised anew only where the coarse set moves
        coarse = self.restrict @ residual
        return self.prolong @ (self._inverse(coarse) - coarse)

    def _nearest_fine_points(self):
        """Each coarse contact point's fine contact point nearest along s (its entry in
        the fine contact set)."""
        nearest = np.empty(self.coarse_layout.gap.size, dtype=int)
        for (i, fine), (_, coarse) in zip(self.layout.contact_slices(),
                                          self.coarse_layout.contact_slices()):
            fine_s = self.layout.interfaces[i].s
            coarse_s = self.coarse_layout.interfaces[i].s
            nearest[coarse] = fine.start + np.abs(coarse_s[:, None]
                                                  - fine_s[None, :]).argmin(axis=1)
        return nearest

    def _set_contact(self, coarse_psi):
        L, _, alpha = self.system.laws_matrix(self.laws(coarse_psi))
        S, _ = self.system.state_matrix(alpha)
        self._inverse = iteration_inverse(S, L, self._data_step, self._state_step)
        self._psi = coarse_psi


def iteration_inverse(S, L, data_step, state_step):
    """r -> (I - B)^-1 r, B the linear part of one iteration of steps: the state x = S g +
    s0 of the data g = L x + h, each step solving its workers (S maps a step's data to its
    own state entries only) from data its laws compute from the state the earlier steps
    left (``data_step``, ``state_step``: each data and state entry's step).

    Split L = L_a + L_b by whether an entry's data come from the state before the
    iteration (L_a) or after an earlier step of it (L_b): x' = S L_b x' + S L_a x + c, so
    B = (I - S L_b)^-1 S L_a and (I - B)^-1 = (I - S L)^-1 (I - S L_b), with
    (I - S L)^-1 = I + S (I - L S)^-1 L: an LU of the data's size (half the state's), a
    solve per residual. (Forming B and factorising I - B took eight times the LU's work:
    TiN at mesh level 2, 0.2 s a contact set.)"""
    L = coo_matrix(L)               # a few entries per row
    after = data_step[L.row] > state_step[L.col]
    laws = L.tocsr()
    laws_after = csr_matrix((L.data[after], (L.row[after], L.col[after])), shape=L.shape)
    factors = lu_factor(np.eye(L.shape[0]) - np.asarray(laws @ S))

    def inverse(r):
        step = r - S @ (laws_after @ r)
        return step + S @ lu_solve(factors, laws @ step)
    return inverse


def _rows_of(problem, layout, names):
    """Whether each entry of the state belongs to a side of the subdomains ``names``."""
    rows = np.zeros(layout.size, dtype=bool)
    for name in names:
        for i, side in problem.sides_of(name):
            rows[layout.slices["u", i, side]] = rows[layout.slices["t", i, side]] = True
    return rows


def _interpolation(source, target):
    """The matrix taking a state of layout ``source`` to one of layout ``target``: every
    block (trace or traction of a side, per component) linearly along s (as np.interp:
    constant beyond the ends), two entries per row."""
    rows, columns, values = [], [], []
    for key, into in target.slices.items():
        _, i, _ = key
        start, to = source.slices[key].start, into.start
        s_from, s_to = source.interfaces[i].s, target.interfaces[i].s
        if len(s_from) == 1:
            left, weight = np.zeros(len(s_to), dtype=int), np.zeros(len(s_to))
        else:
            left = np.clip(np.searchsorted(s_from, s_to, side="right") - 1, 0, len(s_from) - 2)
            weight = np.clip((s_to - s_from[left]) / (s_from[left + 1] - s_from[left]), 0.0, 1.0)
        right = np.minimum(left + 1, len(s_from) - 1)
        for c in range(target.interfaces[i].components):
            row = to + c * len(s_to) + np.arange(len(s_to))
            first = start + c * len(s_from)
            rows += [row, row]
            columns += [first + left, first + right]
            values += [1.0 - weight, weight]
    return csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(columns))),
                      shape=(target.size, source.size))
