"""Exceptions raised on bad input, caught by the command line."""

__all__ = ["JudderError", "ParameterError"]


class JudderError(ValueError):
    """Bad input to the tool; the message says what is wrong and what is allowed."""


class ParameterError(JudderError):
    """A model parameter or option is unknown, missing or out of range."""
