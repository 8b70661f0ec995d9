"""The interface state the Robin loop iterates on.

Every quantity lives at the points of its interface (orchestrate/mesh/discretization.py),
so one flat vector holds them all and relaxation or acceleration acts on it as a
whole. For each side of each interface it holds the trace that side had in its last
solve and the traction it felt there:

    ("u", i, side)   trace of interface i's side 0 (A) or 1 (B): a contact's
                     displacement along the side's outward normal (towards the other
                     body), or a bond's tangential and normal displacement
    ("t", i, side)   the traction that side felt (normal component on a contact, both
                     components on a bond)

Traces come first, interface by interface (side A, side B), then tractions in the same
order. Non-penetration on a contact reads u_A + u_B <= d.
"""

from functools import cached_property

import numpy as np


class StateLayout:
    def __init__(self, interfaces):
        self.interfaces = tuple(interfaces)
        self.slices, start = {}, 0
        for kind in ("u", "t"):
            for i, interface in enumerate(self.interfaces):
                for side in (0, 1):
                    size = interface.components * interface.size
                    self.slices[kind, i, side] = slice(start, start + size)
                    start += size
        self.size = start
        self.contact_indices = [i for i, f in enumerate(self.interfaces) if f.kind == "contact"]
        self.friction_indices = [i for i, f in enumerate(self.interfaces) if f.kind == "friction"]
        self.contact_points = sum(self.interfaces[i].size for i in self.contact_indices)

    def zeros(self):
        return np.zeros(self.size)

    def get(self, x, kind, i, side):
        """View of one block: shape (points,) on a contact, (2, points) on a bond."""
        interface = self.interfaces[i]
        block = x[self.slices[kind, i, side]]
        return block if interface.components == 1 else block.reshape(2, interface.size)

    def pack(self, blocks):
        """A state from ``{(kind, i, side): values}``."""
        x = self.zeros()
        for key, where in self.slices.items():
            x[where] = np.ravel(blocks[key])
        return x

    # ---- the contact interfaces, concatenated ------------------------------------------
    def contact(self, x, kind, side):
        """One block of every contact interface, end to end (the contact set's points)."""
        if not self.contact_indices:
            return np.zeros(0)
        return np.concatenate([self.get(x, kind, i, side) for i in self.contact_indices])

    @cached_property
    def gap(self):
        return self._concatenate("gap")

    @cached_property
    def contact_weight(self):
        return self._concatenate("weight")

    @cached_property
    def contact_normal_x2(self):
        """The x2 component of the contact points' normals: a normal force's share of
        the vertical resultant."""
        if not self.contact_indices:
            return np.zeros(0)
        return np.concatenate([self.interfaces[i].normal[:, 1] for i in self.contact_indices])

    def _concatenate(self, name):
        if not self.contact_indices:
            return np.zeros(0)
        return np.concatenate([getattr(self.interfaces[i], name) for i in self.contact_indices])

    def friction_slices(self):
        """Where each friction interface's points sit in a contact state after its
        contact points (robin.py: Psi, then the friction states phi)."""
        return list(self._friction_slices.items())

    @cached_property
    def _friction_slices(self):
        slices, start = {}, self.contact_points
        for i in self.friction_indices:
            slices[i] = slice(start, start + self.interfaces[i].size)
            start += self.interfaces[i].size
        return slices

    def friction_state(self, psi, i):
        """Friction interface i's states phi in the contact state psi (0: sticks, +-1:
        slips, its traction +-mu p); a state of the contact points alone: +1, full
        sliding."""
        where = self._friction_slices[i]
        if len(psi) <= self.contact_points:
            return np.ones(where.stop - where.start)
        return psi[where]

    def contact_slices(self):
        """Where each contact interface's points sit in the concatenated contact arrays."""
        slices, start = [], 0
        for i in self.contact_indices:
            slices.append((i, slice(start, start + self.interfaces[i].size)))
            start += self.interfaces[i].size
        return slices

    # ---- norms -----------------------------------------------------------------------
    @cached_property
    def entry_weight(self):
        """The quadrature weight of every entry's point."""
        weight = self.zeros()
        for (kind, i, side), where in self.slices.items():
            interface = self.interfaces[i]
            weight[where] = np.tile(interface.weight, interface.components)
        return weight

    @cached_property
    def displacement_mask(self):
        """True on the displacement entries (the stopping tests look at these)."""
        mask = np.zeros(self.size, dtype=bool)
        for (kind, i, side), where in self.slices.items():
            if kind == "u":
                mask[where] = True
        return mask

    @cached_property
    def parts(self):
        """Index arrays of the quantities a user reads apart: all the displacements, then
        the tractions, one per interface, side and component (a contact's normal one; a
        bond's tangential and normal ones, e.g. its shear next to its peel stress)."""
        parts = [np.flatnonzero(self.displacement_mask)]
        for (kind, i, side), where in self.slices.items():
            if kind == "t":
                size = self.interfaces[i].size
                parts += [np.arange(where.start + c * size, where.start + (c + 1) * size)
                          for c in range(self.interfaces[i].components)]
        return parts

    def part_norms(self, x):
        """Discrete L2 norm of every part (parts): displacements first."""
        weight = self.entry_weight
        return np.array([np.sqrt(np.dot(weight[p], np.square(x[p]))) for p in self.parts])
