"""Exceptions and warnings raised by robokin (all in one place)."""

__all__ = ["UnreachableError", "NoRouteError", "PrecisionWarning", "URDFWarning"]


class UnreachableError(ValueError):
    """A pose the robot cannot reach (a leg or the arm is too short, or a joint limit is in the way)."""


class NoRouteError(UnreachableError):
    """No motion between two 3-RRR poses that keeps clear of parallel singularities (``RRR3.connect``).

    ``reason`` is ``"start"`` or ``"goal"`` when that pose is unusable itself (a leg cannot reach
    it, or it is singular), ``"regions"`` when the two poses lie in different singularity-free
    regions of the working mode (det A has opposite signs there, or no path of one sign keeps the
    clearance).
    """

    reason: str = ""


class PrecisionWarning(UserWarning):
    """A numerical loop stopped before reaching its tolerance ("precision not reached", the RPR study)."""


class URDFWarning(UserWarning):
    """A URDF was loaded with something changed or ignored (e.g. a joint whose lower and upper
    limits are equal, taken as unlimited; urdfdom's own warnings)."""
