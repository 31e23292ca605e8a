"""Aspects and cuspidality of 3R positioning arms (the IK course: "a cuspidal robot can change
posture without meeting a singularity").

The aspects are the regions of joint space where det J (3 x 3, position) keeps its sign; det J does
not depend on q1, so they are drawn on the (q2, q3) torus. A 3R arm is cuspidal exactly when the
singular curves have a cusp point in the workspace, where three inverse solutions coincide (El Omri
and Wenger 1995 for the sufficiency; Salunkhe, Spartalis, Capco, Chablat and Wenger, "Necessary and
sufficient condition for a generic 3R serial manipulator to be cuspidal", Mechanism and Machine
Theory 171, 2022). The cusps are found in the C++ core; for a cuspidal arm the evidence also
includes a posture change that meets no singularity: two solutions of one point in the same aspect,
joined by a path of joint configurations whose det J keeps its sign.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from ._checks import chain as check_chain
from ._checks import whole
from ._core import Chain

__all__ = ["Cuspidality", "cuspidal"]

@dataclass
class Cuspidality:
    """Result of :func:`cuspidal`.

    Attributes:
        cuspidal: The arm can change posture without meeting a singularity.
        cusps: (k, 4) cusp points ``q2, q3, rho, z``: the joints on the singular curve and the
            workspace point (distance from axis 1, height along it, in the base frame).
        aspects: Number of aspects (connected regions of one sign of det J on the (q2, q3) torus).
        grid: (N,) the joint angles of the grid's rows (q2) and columns (q3).
        sign: (N, N) sign of det J on the grid; ``label``: (N, N) the aspect of each cell (-1 on a
            singularity).
        evidence: One sentence saying why.
        point: For a cuspidal arm, a tool point with two solutions in one aspect (else None).
        path: For a cuspidal arm, (m, 3) joint configurations from one of those solutions to the
            other, det J of one sign all along (checked at 8 points per step), else None.
    """

    cuspidal: bool
    cusps: np.ndarray
    aspects: int
    grid: np.ndarray
    sign: np.ndarray
    label: np.ndarray
    evidence: str
    point: Optional[np.ndarray]
    path: Optional[np.ndarray]


def _cell(q, grid):
    """The index of the grid angle nearest q (the grid is evenly spaced around the circle)."""
    n = len(grid)
    return int(round(np.remainder(q - grid[0], 2 * math.pi) / (2 * math.pi / n))) % n


def _grid_path(label, a, b):
    """Shortest 4-connected path of grid cells from a to b within a's aspect (torus), or None."""
    n = label.shape[0]
    comp = label[a]
    prev = {a: None}
    todo = deque([a])
    while todo:
        c = todo.popleft()
        if c == b:
            out = []
            while c is not None:
                out.append(c)
                c = prev[c]
            return out[::-1]
        i, j = c
        for nb in (((i + 1) % n, j), ((i - 1) % n, j), (i, (j + 1) % n), (i, (j - 1) % n)):
            if nb not in prev and label[nb] == comp:
                prev[nb] = c
                todo.append(nb)
    return None


def _posture_change(chain, grid, label, sign, cusps, size):
    """A point near a cusp with two solutions in one aspect, and a non-singular path between them."""
    from .closed import general_3r

    rng = np.random.default_rng(0)
    for q2c, q3c, _, _ in cusps:
        pc = chain.fk(np.array([0.0, q2c, q3c]))[:3, 3]
        for radius in (1e-3, 3e-3, 1e-2, 3e-2, 1e-1):
            for _ in range(12):
                d = rng.normal(size=3)
                p = pc + radius * size * d / np.linalg.norm(d)
                sols = general_3r(p, chain, limits=None)
                cells = [(_cell(q[1], grid), _cell(q[2], grid)) for q in sols.q]
                for x in range(len(cells)):
                    for y in range(x + 1, len(cells)):
                        a, b = cells[x], cells[y]
                        if label[a] < 0 or label[a] != label[b]:
                            continue
                        if np.sign(_core.det_3r(chain, *sols.q[x][1:])) != sign[a] or \
                                np.sign(_core.det_3r(chain, *sols.q[y][1:])) != sign[b]:
                            continue
                        cells_path = _grid_path(label, a, b)
                        if cells_path is None:
                            continue
                        qa, qb = sols.q[x], sols.q[y]
                        mids = [np.array([grid[i], grid[j]]) for i, j in cells_path]
                        pts = [qa[1:]] + mids + [qb[1:]]
                        # unwrap so that consecutive points are near (the torus)
                        for k in range(1, len(pts)):
                            pts[k] = pts[k - 1] + np.remainder(pts[k] - pts[k - 1] + math.pi, 2 * math.pi) - math.pi
                        t = np.linspace(0.0, 1.0, len(pts))
                        dq1 = np.remainder(qb[0] - qa[0] + math.pi, 2 * math.pi) - math.pi
                        path = np.column_stack([qa[0] + t * dq1, np.array(pts)])
                        s0 = np.sign(_core.det_3r(chain, *qa[1:]))
                        ok = all(np.sign(_core.det_3r(chain, *(u * path[k + 1, 1:] + (1 - u) * path[k, 1:]))) == s0
                                 for k in range(len(path) - 1) for u in np.linspace(0, 1, 9))
                        if ok:
                            return p, path
    return None, None


def cuspidal(chain: Chain, resolution: int = 256) -> Cuspidality:
    """Decides whether a 3R positioning arm is cuspidal, with the evidence.

    Args:
        chain: A 3-joint revolute chain (the tool point is the position the arm places).
        resolution: Grid size N on the (q2, q3) torus (16 to 4096): the singular curves are traced
            cell by cell and each cusp refined by bisection along the curve.

    Returns:
        Cuspidality: ``cuspidal``, the ``cusps``, the ``aspects`` (count, ``sign`` and ``label``
        grids), a sentence of ``evidence`` and, for a cuspidal arm, a ``point`` with two solutions in
        one aspect and a ``path`` of joint configurations between them that meets no singularity.
    """
    check_chain(chain)
    whole(resolution, "resolution", 16, 4096, "grid points per joint")
    r = _core.cuspidal_3r(chain, int(resolution))
    n = int(resolution)
    grid = np.asarray(r["grid"])
    cusps = np.asarray(r["cusps"])
    sign, label = np.asarray(r["sign"]), np.asarray(r["label"])
    point = path = None
    if r["cuspidal"]:
        size = float(np.max(np.linalg.norm(chain.frames(np.zeros(3))[:, :3, 3], axis=1))) or 1.0
        point, path = _posture_change(chain, grid, label, sign, cusps, size)
        q2, q3, rho, z = cusps[0]
        evidence = (f"{len(cusps)} cusp point(s) on the singular curves, e.g. q2 = {q2:.4f}, q3 = {q3:.4f} "
                    f"(rho = {rho:.4f}, z = {z:.4f}), where three inverse solutions coincide")
        if path is not None:
            evidence += (f"; a posture change without singularity: two solutions of {np.round(point, 4).tolist()} "
                         f"in one aspect, joined by {len(path)} configurations")
    else:
        evidence = (f"no cusp point on the singular curves ({n} x {n} grid of the (q2, q3) torus): "
                    f"every posture change meets a singularity; {r['aspects']} aspect(s)")
    return Cuspidality(bool(r["cuspidal"]), cusps, int(r["aspects"]), grid, sign, label, evidence, point, path)
