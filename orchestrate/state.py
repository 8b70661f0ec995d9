"""The interface state the Robin loop iterates on.

Every quantity lives at the shared interface points (orchestrate/interface.py), so one
flat vector holds them all and relaxation or acceleration acts on it as a whole. For
each side of each interface it holds the displacement trace and the traction that side
felt in its last solve:

    upper_n       Omega1 on S12: displacement along its outward normal (down), u1n
    coating_n     coating on S21: displacement along its outward normal (up), w
    coating_bond  coating on S23: displacement (u1, u2) of its bottom
    lower_bond    Omega3 on S32: displacement (u1, u2) of its top
and the same four as tractions (sigma.n: normal component on S12, vector on S23),
prefixed ``t_``. Non-penetration on S12 reads u1n + w <= d.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

# name: number of components
BLOCKS = {
    "upper_n": 1, "coating_n": 1, "coating_bond": 2, "lower_bond": 2,
    "t_upper_n": 1, "t_coating_n": 1, "t_coating_bond": 2, "t_lower_bond": 2,
}
DISPLACEMENTS = ("upper_n", "coating_n", "coating_bond", "lower_bond")


@dataclass(frozen=True)
class StateLayout:
    points: int   # interface points, the same on S12 and S23

    @cached_property
    def _blocks(self):
        """(slice of every block, total size), computed once."""
        slices, start = {}, 0
        for name, components in BLOCKS.items():
            slices[name] = slice(start, start + components * self.points)
            start += components * self.points
        return slices, start

    @property
    def size(self):
        return self._blocks[1]

    def zeros(self):
        return np.zeros(self.size)

    def get(self, x, name):
        """View of one block: shape (points,) or (2, points)."""
        block = x[self._blocks[0][name]]
        return block if BLOCKS[name] == 1 else block.reshape(BLOCKS[name], self.points)

    def pack(self, **blocks):
        """A state from every block by name."""
        x = self.zeros()
        slices = self._blocks[0]
        for name in BLOCKS:
            x[slices[name]] = np.ravel(blocks[name])
        return x

    def displacement_mask(self):
        """True on the displacement entries (the paper's stopping test looks at these)."""
        mask = np.zeros(self.size, dtype=bool)
        slices = self._blocks[0]
        for name in DISPLACEMENTS:
            mask[slices[name]] = True
        return mask

    def displacement_norm(self, x, weight):
        """Discrete L2 norm of the displacement traces over S12 and S23 (omega-weighted)."""
        mask = self.displacement_mask()
        weights = np.tile(weight, self.size // self.points)
        return float(np.sqrt(np.dot(weights[mask], np.square(x[mask]))))
