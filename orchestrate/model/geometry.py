"""Where the faces of a scene are: the base's top face, faces offset from it (the
coatings' tops), the indenter's lower face, and the pairing of contact points.

The base's top face is parametrised by arc length s, with s = 0 at x1 = 0:
    block:  the line x2 = height, s = x1;
    roller: the circle of radius R about the origin, s = R phi with phi the angle from
            the top, clockwise (x1 = R sin phi).
A point at distance ``offset`` above the face along its outward normal n(s) (a coating
of that thickness) is face.point(s, offset); the face offset by ``offset`` has length
face.stretch(offset) per unit s (1 + offset/R on a roller), which is where the paper's
(1 +- k21 h2/2) factors of (8)-(10) come from.

Contact pairs points along the partner's normal (the paper's assumption that the
faces are close, n1 ~ -n2): the partner point P (a coating's top or the bare base) is
paired with the point P + d n of the indenter's face; d is the initial gap.
"""

import math

import numpy as np


class BlockTop:
    """The flat top x2 = height of a block."""

    curvature = 0.0

    def __init__(self, height):
        self.height = height

    def point(self, s, offset=0.0):
        s = np.asarray(s, dtype=float)
        return np.stack([s, np.full_like(s, self.height + offset)], axis=-1)

    def normal(self, s):
        s = np.asarray(s, dtype=float)
        return np.stack([np.zeros_like(s), np.ones_like(s)], axis=-1)

    def tangent(self, s):
        s = np.asarray(s, dtype=float)
        return np.stack([np.ones_like(s), np.zeros_like(s)], axis=-1)

    def s_of_x1(self, x1):
        return x1

    def stretch(self, offset):
        return 1.0


class RollerTop:
    """The circle of radius R about the origin."""

    def __init__(self, radius):
        self.radius = radius
        self.curvature = 1.0 / radius

    def point(self, s, offset=0.0):
        phi = np.asarray(s, dtype=float) / self.radius
        return (self.radius + offset) * np.stack([np.sin(phi), np.cos(phi)], axis=-1)

    def normal(self, s):
        phi = np.asarray(s, dtype=float) / self.radius
        return np.stack([np.sin(phi), np.cos(phi)], axis=-1)

    def tangent(self, s):
        phi = np.asarray(s, dtype=float) / self.radius
        return np.stack([np.cos(phi), -np.sin(phi)], axis=-1)

    def s_of_x1(self, x1):
        return self.radius * math.asin(max(-1.0, min(1.0, x1 / self.radius)))

    def stretch(self, offset):
        return (self.radius + offset) / self.radius


def base_face(base):
    return BlockTop(base.height) if base.shape == "block" else RollerTop(base.radius)


class IndenterFace:
    """The indenter's lower face x2 = lowest + sag(x1 - centre)."""

    def __init__(self, indenter, lowest):
        self.indenter = indenter
        self.lowest = lowest

    def height(self, x1):
        return self.lowest + self.indenter.sag(np.asarray(x1, dtype=float) - self.indenter.centre)

    def pair(self, points, normals):
        """Gap d >= 0 along each normal from the partner points to this face, and the
        face points P + d n. Along a vertical normal d is explicit (written so that a
        flat partner at the lowest point's height gets the sag exactly); along a tilted
        one (a roller) Newton's method solves the face equation from that guess."""
        points, normals = np.atleast_2d(points), np.atleast_2d(normals)
        centre = self.indenter.centre
        d = ((self.lowest - points[:, 1]) + self.indenter.sag(points[:, 0] - centre)) / normals[:, 1]
        tilted = normals[:, 0] != 0
        for _ in range(50):
            if not np.any(tilted):
                break
            x = points[tilted, 0] + d[tilted] * normals[tilted, 0]
            residual = points[tilted, 1] + d[tilted] * normals[tilted, 1] - self.height(x)
            slope = self.indenter.slope(x - centre)
            step = residual / (normals[tilted, 1] - slope * normals[tilted, 0])
            d[tilted] -= step
            if np.all(np.abs(step) <= 1e-15 * (1.0 + np.abs(d[tilted]))):
                break
        else:
            raise ValueError("the contact pairing did not converge: the faces are too steep "
                             "for pairing along the normal")
        return d, points + d[:, None] * normals

    def normal(self, x1):
        """Unit normal of the face pointing down (into the gap)."""
        slope = self.indenter.slope(np.asarray(x1, dtype=float) - self.indenter.centre)
        n = np.stack([slope, -np.ones_like(slope)], axis=-1)
        return n / np.linalg.norm(n, axis=-1, keepdims=True)


def lowest_point(indenter, partner_points):
    """Height of the indenter's lowest point when it first touches the partner faces,
    given dense samples of them: the face must pass above every point."""
    points = np.atleast_2d(partner_points)
    return float(np.max(points[:, 1] - indenter.sag(points[:, 0] - indenter.centre)))
