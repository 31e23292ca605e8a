"""Independent numpy references for the tests: DH matrices written from their textbook definitions."""

import numpy as np


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def trans(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def dh_standard(a, alpha, d, theta):
    """A = Rz(theta) Tz(d) Tx(a) Rx(alpha), written out entry by entry (Spong's form)."""
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1.0],
        ]
    )


def dh_modified(a, alpha, d, theta):
    """Craig's A = Rx(alpha) Tx(a) Rz(theta) Tz(d), as a product of elementary transforms."""
    return rot_x(alpha) @ trans(a, 0, 0) @ rot_z(theta) @ trans(0, 0, d)


def fk_dh(rows, q, modified=False):
    """Product of the rows' matrices; a revolute joint adds q to theta, a prismatic one to d."""
    T = np.eye(4)
    for (a, alpha, d, theta, kind), qi in zip(rows, q):
        if kind == "R":
            theta = theta + qi
        else:
            d = d + qi
        T = T @ (dh_modified if modified else dh_standard)(a, alpha, d, theta)
    return T


def numeric_jacobian(fk, q, h=1e-6):
    """Geometric Jacobian by central differences: linear velocity of the origin, angular velocity
    from dR R^T."""
    q = np.asarray(q, dtype=float)
    J = np.zeros((6, q.size))
    for i in range(q.size):
        dq = np.zeros_like(q)
        dq[i] = h
        Tp, Tm = fk(q + dq), fk(q - dq)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ fk(q)[:3, :3].T
        J[3:, i] = (W[2, 1], W[0, 2], W[1, 0])
    return J
