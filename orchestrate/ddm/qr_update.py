"""Updates of an economic QR factorisation A = Q R (Q: n x m with orthonormal columns,
R: m x m upper triangular), O(n m) each instead of the O(n m^2) of a new factorisation:
a column put first, a column taken out (Golub & Van Loan, "Matrix Computations", 6.5).
Anderson acceleration (acceleration.py) keeps the QR of its history this way, newest
column first. The Givens rotations are scipy's (scipy.linalg.qr_insert, qr_delete,
compiled, with their own reorthogonalisation): written in Python, each rotation a few
numpy calls on short rows, they had cost more per Robin iteration than the rest of
the Anderson step.
"""

import numpy as np
import scipy.linalg

# A new column whose part outside Q's span is below this share of its norm adds no
# direction that rotations could keep orthonormal: the caller factorises anew.
INDEPENDENT = 1e-12


def prepend_column(q, r, u):
    """The QR of [u, A] from that of A (q, r; None for no column); None where u lies
    (numerically) in A's column space (a Q as wide as it is long spans everything)."""
    norm = float(np.linalg.norm(u))
    if q is None:
        if norm == 0:
            return None
        return (u / norm)[:, None], np.array([[norm]])
    if q.shape[1] >= q.shape[0] or norm == 0:
        return None
    try:
        return scipy.linalg.qr_insert(q, r, u, 0, which="col", rcond=INDEPENDENT,
                                      check_finite=False)
    except scipy.linalg.LinAlgError:        # its reorthogonalisation failed: dependent
        return None


def delete_column(q, r, j):
    """The QR of A without its column j, from that of A (economic: a square Q is taken
    for a full QR, whose R keeps a last row of zeros, dropped here with Q's column)."""
    q, r = scipy.linalg.qr_delete(q, r, j, which="col", check_finite=False)
    columns = r.shape[1]
    return q[:, :columns], r[:columns]
