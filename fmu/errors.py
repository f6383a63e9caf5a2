"""The compiler's error: a Modelica source it cannot compile."""

from infra.errors import JudderError

__all__ = ["FrontEndError"]


class FrontEndError(JudderError):
    """The Modelica source could not be compiled; the message says where."""
