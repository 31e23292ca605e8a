"""Numerical inverse kinematics; the solvers run in the C++ core (GIL released for batches, and
for single solves that may be long: a timeout, or more than ~1700 iterations in all).

Methods:
    ``"lm"``: Levenberg-Marquardt, ``(J^T J + mu I) dq = J^T e`` with the damping ``mu`` adapted
    by the gain ratio (Nielsen's rule). The most robust; the default.
    ``"gn"``: Gauss-Newton, ``(J^T J) dq = J^T e`` with a backtracking line search.
    ``"nr"``: Newton-Raphson with the damped pseudoinverse ``dq = J^T (J J^T + lambda^2 I)^-1 e``.
    ``"halley"``: Halley's method (Lloyd, Irani, Ahmadi, IEEE T-RO 38(5), 2022): the Newton step
    ``a``, then ``(J + H a / 2) dq = e`` with the kinematic Hessian ``H`` built from the Jacobian's
    columns; cubic convergence near the solution.

Joint limits: a joint that would cross its limit stops on it and the other joints solve the rest
of the step (an active set renewed at every iteration, so no joint sticks at a limit); revolute
angles are wrapped by ``2 pi`` into limits wider than ``2 pi``. Success is decided on the returned
``q`` (wrapped, clamped) by forward kinematics: position error ``< tol_p`` and orientation error
``< tol_r``. Joints may have half-infinite or no limits; the returned ``q`` is always finite.

When no attempt succeeds, the returned ``q`` is the lowest-error point seen over every iteration
of every attempt (``nr`` and ``halley`` take every step, so their last iterate may be worse).

Default damping (the C++ core's ``default_damping``, the one source): ``lm`` 1e-1 (initial damping
relative to ``max diag(J^T J)``), ``nr`` 1e-6 and ``halley`` 1e-9 (lambda of the damped
pseudoinverse); ``gn`` uses none.

For many calls with the same options, ``IKSolver(chain, method=..., ...)`` binds the chain and the
options once; ``solver.solve(target, q0)`` then costs only the solve.

Defaults (``IK_DEFAULTS``, read from the C++ core's ``IkOptions``, the one place they are written):
``lm``, the chain's natural task (``task`` None: ``chain.natural_task``), tolerances 1e-9 m and
1e-9 rad, 100 iterations per attempt, and, with neither ``restarts`` nor ``timeout`` given,
restarts until a solution is found (for a pose target on a 6R arm with a closed form, first from
its closed-form solutions within the limits, nearest ``q0`` first; then from the chain's stored
configurations whose tools are nearest the target; then from random configurations within the
limits) or the time budget of
``IK_DEFAULTS["timeout"]`` = 5 ms (of the solving thread's CPU time, so
that a busy machine does not cut the search short) runs out. A reachable target is then
almost always solved (``benchmarks/bench_ik_defaults.py`` measures how often, on every catalogue
arm); an unreachable target costs the whole budget (5 ms per target, also per target of
``ik_batch``). An explicit ``restarts=k`` means at most k restarts and no time budget unless
``timeout`` is given; ``timeout=t`` alone restarts until success within t seconds.
"""

from __future__ import annotations

from typing import Optional

from . import _checks, _core
from ._core import IKBatchResult, IKOptions, IKResult, IKSolver
from ._options import with_options

__all__ = ["IK_DEFAULTS", "IKBatchResult", "IKOptions", "IKResult", "IKSolver", "ik", "ik_batch"]

#: The options of a solve given none, as a solve resolves them (read-only; from the core's IkOptions).
IK_DEFAULTS = _core.IK_DEFAULTS


@with_options(IKOptions)
def ik(chain: _core.Chain, target, q0, *, seed: Optional[int] = None, **options) -> IKResult:
    """Solves the inverse kinematics of one target numerically.

    Args:
        chain: The serial chain; its joint limits are respected.
        target: ``task="pose"``: a (4, 4) frame; ``"position"``: (x, y, z); ``"xy"``: (x, y);
            ``"xyphi"``: (x, y, phi). A target shaped for another task names it: ``target (3,) is
            a position (x, y, z): pass task="position" (task 'pose' takes a (4, 4) frame)``.
        q0: Start configuration, shape (dof,).
        seed: Seed of the restarts' generator (reproducible results), an int in ``[0, 2**64)``;
            None draws one. (With a time budget, how many restarts fit depends on the machine.)

    Returns:
        IKResult with ``q``, ``success``, ``iterations``, ``attempts``, ``error_p``, ``error_r``.
        When no attempt succeeds, ``q`` is the lowest-error point found (over every iteration
        of every attempt) and ``success`` is False. ``q`` is always finite.

    Raises:
        ValueError: For a bad value (the message names the argument).
        TypeError: For a chain that is not a robokin.Chain, an unknown option or one of the wrong
            kind (the message names it).
    """
    return _core.ik(_checks.chain(chain), target, q0, seed, **options)


@with_options(IKOptions)
def ik_batch(chain: _core.Chain, targets, q0, *, seed: Optional[int] = None, path: bool = False,
             **options) -> IKBatchResult:
    """Solves many targets in one call, the GIL released.

    Args:
        chain: The serial chain.
        targets: ``(N, 4, 4)`` frames for ``task="pose"``, ``(N, rows)`` otherwise (``task`` None:
            ``chain.natural_task``).
        q0: ``(dof,)`` start for every target, or ``(N, dof)`` one start per target.
        seed: Target ``k`` uses ``seed + k``: the results do not depend on the threads.
        path: The targets are a path: each starts from the previous solution (warm start, no
            branch jumps; sequential). With ``restarts`` None a path does not restart (a random
            restart could jump to another branch): a target the warm start misses is reported
            unsolved; ``restarts=k`` allows restarts. Otherwise the targets are solved in
            parallel on every core.
        The options are :func:`ik`'s (``timeout`` applies to each target).

    Returns:
        IKBatchResult with read-only arrays ``q`` (N, dof), ``success``, ``iterations``,
        ``attempts``, ``error_p``, ``error_r`` (N,). Every row is finite: a target not solved
        has ``success`` False and its row holds the best point found (no NaN rows).
    """
    return _core.ik_batch(_checks.chain(chain), targets, q0, seed=seed, path=path, **options)
