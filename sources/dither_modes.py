"""Whether a driveline holds the mode it is linearised in under a
dither: the check each model source offers.

A registry chain and an FMU's Jacobian have one mode; a hybrid Modelica
class (a clutch with MSL's friction modes) is linearised in the mode of
its operating point, and :meth:`sources.modelica.ModelicaParameters.
check_mode` refuses the dither settings at which it would leave that mode
within a dither period. The functions here apply that check to the
settings of a study (pairs, or each frequency up to a largest
amplitude, or each changed parameter set) and say the mode in words;
for the other sources they do nothing.
"""

import numpy as np

from infra.units import PA_PER_BAR

__all__ = ["check_modes", "check_modes_up_to", "check_modes_of_changes",
           "linearised_mode", "mode_words"]


def check_modes(values, freq_hz, p_f):
    """Refuse the dither settings (Hz, Pa; pairs) at which a hybrid
    Modelica class (a clutch with MSL's friction modes) leaves the mode
    it is linearised in within a dither period
    (:meth:`sources.modelica.ModelicaParameters.check_mode`); nothing for
    other models."""
    check = getattr(values, "check_mode", None)
    if check is not None:
        check(np.atleast_1d(freq_hz), np.atleast_1d(p_f))


def check_modes_up_to(values, freq_hz, p_max_bar):
    """:func:`check_modes` at each frequency of ``freq_hz`` with the
    largest amplitude ``p_max_bar`` (bar) of a study over amplitudes (a
    map, tongue boundaries): what leaves a friction clutch's mode, a slip
    through zero or a normal force to zero, is the excursion from the
    operating point, which grows with the amplitude."""
    p_max = float(np.max(p_max_bar)) * PA_PER_BAR
    check_modes(values, freq_hz, np.full(np.size(freq_hz), p_max))


def check_modes_of_changes(values, changes, freq_hz, p_max_bar):
    """:func:`check_modes_up_to` at each parameter set a study uses
    beside ``values`` (``changes``: one ``{name: value}`` a set), each
    linearised in the mode ``values`` is: a study comparing its sets
    (sensitivity's tip shifts) compares them in one mode. Nothing for
    other models.

    Raises
    ------
    JudderError
        Naming the change: a set in another mode, or one whose mode the
        dither leaves (:class:`sources.modelica.ModelicaError`'s words).
    """
    if getattr(values, "check_mode", None) is None:
        return
    from sources.modelica import ModelicaError
    nominal = linearised_mode(values)
    for change in changes:
        words = ", ".join(f"{name} = {value:g}"
                          for name, value in change.items())
        changed = values.replace(**change)
        try:
            mode = linearised_mode(changed)
            if mode != nominal:
                raise ModelicaError(
                    f"{values.model} is linearised in another mode: "
                    + ", ".join(f"{name} = {value} (nominal "
                                f"{nominal.get(name)})"
                                for name, value in mode.items()
                                if nominal.get(name) != value)
                    + ", so its boundaries do not compare with the "
                    "nominal ones; allowed: changes that keep the mode")
            check_modes_up_to(changed, freq_hz, p_max_bar)
        except ModelicaError as error:
            raise ModelicaError(f"with {words}: {error}") from None


def linearised_mode(values):
    """``{name: value}`` of the Integer and Boolean variables of a hybrid
    Modelica class in the mode it is linearised in
    (:attr:`sources.modelica.LinearPeriodicModel.mode`); empty for other
    models."""
    if not getattr(values, "check_mode", None):
        return {}
    return dict(values.linear_model().mode)


def mode_words(mode, checked_at_bar=None):
    """``linearised in the mode clutch.mode = 1 (clutch.Forward), ...``
    (Integer variables first), or ``""`` without a mode; with
    ``checked_at_bar``, the amplitude (bar) at which each frequency of a
    study over amplitudes was checked (:func:`check_modes_up_to`)."""
    if not mode:
        return ""
    ordered = sorted(mode.items(), key=lambda item: item[1] in
                     ("true", "false"))
    return "linearised in the mode " + ", ".join(
        f"{name} = {value}" for name, value in ordered) + (
        "" if checked_at_bar is None else
        f"; held at each frequency's largest amplitude, {checked_at_bar:g} "
        "bar (what leaves it, a slip through zero or a normal force to "
        "zero, grows with the amplitude)")
