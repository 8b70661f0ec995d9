"""Updates of an economic QR factorisation A = Q R (Q: n x m with orthonormal columns,
R: m x m upper triangular) by Givens rotations, O(n m) each instead of the O(n m^2) of
a new factorisation: a column put first, a column taken out (Golub & Van Loan,
"Matrix Computations", 6.5). Anderson acceleration (acceleration.py) keeps the QR of its
history this way, newest column first.
"""

import numpy as np

# A new column whose part outside Q's span is below this share of its norm adds no
# direction that rotations could keep orthonormal: the caller factorises anew.
INDEPENDENT = 1e-12


def _rotation(a, b):
    """(c, s) with [[c, s], [-s, c]] @ [a, b] = [hypot(a, b), 0]."""
    h = np.hypot(a, b)
    return (1.0, 0.0) if h == 0 else (a / h, b / h)


def _rotate(q, r, i, c, s):
    """Rotate rows i, i + 1 of r and columns i, i + 1 of q by [[c, s], [-s, c]]."""
    upper, lower = r[i].copy(), r[i + 1].copy()
    r[i], r[i + 1] = c * upper + s * lower, -s * upper + c * lower
    left, right = q[:, i].copy(), q[:, i + 1].copy()
    q[:, i], q[:, i + 1] = c * left + s * right, -s * left + c * right


def prepend_column(q, r, u):
    """The QR of [u, A] from that of A (q, r; None for no column); None where u lies
    (numerically) in A's column space."""
    norm = float(np.linalg.norm(u))
    if q is None:
        if norm == 0:
            return None
        return (u / norm)[:, None], np.array([[norm]])
    w = q.T @ u
    residual = u - q @ w
    again = q.T @ residual                  # once more: Gram-Schmidt loses orthogonality
    residual -= q @ again
    w += again
    rho = float(np.linalg.norm(residual))
    if rho <= INDEPENDENT * norm:
        return None
    m = r.shape[0]
    h = np.zeros((m + 1, m + 1))
    h[:m, 0], h[m, 0], h[:m, 1:] = w, rho, r
    q_new = np.column_stack([q, residual / rho])
    for i in range(m - 1, -1, -1):          # zero the first column from the bottom up
        c, s = _rotation(h[i, 0], h[i + 1, 0])
        _rotate(q_new, h, i, c, s)
        h[i + 1, 0] = 0.0
    return q_new, h


def delete_column(q, r, j):
    """The QR of A without its column j, from that of A."""
    m = r.shape[0]
    h = np.delete(r, j, axis=1)             # upper Hessenberg from column j on
    q_new = q.copy()
    for i in range(j, m - 1):
        c, s = _rotation(h[i, i], h[i + 1, i])
        _rotate(q_new, h, i, c, s)
        h[i + 1, i] = 0.0
    return q_new[:, :m - 1], h[:m - 1]
