"""The interface quadrature shared by both sides of S12 and of S23.

Every coupling integral is evaluated at the same points by every worker and by the
monolithic solve alike, ``int_S f g dS = sum_q omega_q f(x_q) g(x_q)``, so that the
Robin loop and the monolithic problem are the same discrete problem.

The points are the P2 nodes of the interface (element ends and midpoints) with
Simpson's weights L/6, 4L/6, L/6: the penalty acts node to node. Gauss points (5 per
element, exact for the P2 x P4 products) were tried first: they constrain more points
per element than a P2 trace has nodes, and the contact pressure then oscillates near
the edge of the contact zone (measured, README); at the nodes it is smooth, and the
contact set settles in fewer updates (8 instead of 20 for the default scene).
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class InterfaceQuadrature:
    x: np.ndarray        # abscissae x_q of the points, increasing
    weight: np.ndarray   # omega_q
    gap: np.ndarray      # initial gap d(x_q); zero on the bonded interface

    @property
    def size(self):
        return len(self.x)

    def integrate(self, values):
        """sum_q omega_q f_q, the interface integral of a field given at the points."""
        return float(np.dot(self.weight, values))


def nodal_quadrature(nodes, gap=None):
    """Simpson's rule on the elements [nodes[e], nodes[e+1]]: the 2N+1 P2 nodes."""
    size = np.diff(nodes)
    x = np.empty(2 * len(size) + 1)
    x[0::2] = nodes
    x[1::2] = nodes[:-1] + 0.5 * size
    weight = np.zeros_like(x)
    weight[0:-1:2] += size / 6.0
    weight[1::2] += 4.0 * size / 6.0
    weight[2::2] += size / 6.0
    d = gap(x) if gap is not None else np.zeros_like(x)
    return InterfaceQuadrature(x, weight, d)


def write_quadrature(quadrature, path):
    """Write the points as FreeFEM's interface.idp reads them: three count-first arrays."""
    n = quadrature.size
    with open(Path(path), "w") as out:
        out.write(f"{n}\n")
        for array in (quadrature.x, quadrature.weight, quadrature.gap):
            out.write(f"{n}\n" + "\n".join(repr(float(v)) for v in array) + "\n")
