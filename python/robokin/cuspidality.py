"""Aspects and cuspidality of 3R positioning arms (the IK course: "a cuspidal robot can change
posture without meeting a singularity").

The aspects are the regions of joint space where det J (3 x 3, position) keeps its sign; det J does
not depend on q1, so they are drawn on the (q2, q3) torus. A 3R arm is cuspidal exactly when the
singular curves have a cusp point in the workspace, where three inverse solutions coincide (El Omri
and Wenger 1995 for the sufficiency; Salunkhe, Spartalis, Capco, Chablat and Wenger, "Necessary and
sufficient condition for a generic 3R serial manipulator to be cuspidal", Mechanism and Machine
Theory 171, 2022). For a cuspidal arm the evidence also includes a posture change that meets no
singularity: two solutions of one point in the same aspect, joined by a path of joint
configurations whose det J keeps its sign. All of it is computed in the C++ core.
"""

from __future__ import annotations

from . import _core
from ._checks import chain as check_chain
from ._core import Chain, Cuspidality, CuspidalOptions
from ._options import with_options

__all__ = ["CuspidalOptions", "Cuspidality", "cuspidal"]


@with_options(CuspidalOptions)
def cuspidal(chain: Chain, **options) -> Cuspidality:
    """Decides whether a 3R positioning arm is cuspidal, with the evidence.

    Args:
        chain: A 3-joint revolute chain (the tool point is the position the arm places).

    Returns:
        Cuspidality: ``cuspidal``, the ``cusps``, the ``aspects`` (count, ``sign`` and ``label``
        grids), a sentence of ``evidence`` and, for a cuspidal arm, a ``point`` with two solutions in
        one aspect and a ``path`` of joint configurations between them that meets no singularity.
        The search for that posture change tries tool points around each cusp; ``point`` and
        ``path`` are None when none of them gave one.
    """
    check_chain(chain)
    return _core.cuspidal(chain, **options)
