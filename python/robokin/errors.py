"""Exceptions and warnings raised by robokin (all in one place)."""


class UnreachableError(ValueError):
    """A pose the robot cannot reach (a leg or the arm is too short, or a joint limit is in the way)."""


class PrecisionWarning(UserWarning):
    """A numerical loop stopped before reaching its tolerance ("precision not reached", seed 000)."""


class URDFWarning(UserWarning):
    """A URDF was loaded with something changed or ignored (e.g. a joint whose lower and upper
    limits are equal, taken as unlimited; urdfdom's own warnings)."""
