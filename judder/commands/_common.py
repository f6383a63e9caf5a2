"""What several API functions share: a caller's arguments checked and
the parameter set with its changes, the dithered driveline, timing, and
the checks of parameter names.
"""

import time

from drivelines import DEFAULT_MODEL
from sources import default_preset, get_preset
from infra.errors import JudderError
from stability.source import build_driveline

#: Amplitudes of the map drawn under tongue boundaries (0 to p_max).
BACKGROUND_AMPLITUDES = 150


def check_arguments(**arguments):
    """Refuse any of ``arguments`` (``freq_hz=...``, ``p_f_bar=...``) its
    rule does not allow: the rule of its name,
    :data:`judder.commands._values.RULES`, the option's own (None: not
    given).

    The API functions check a Python caller's values here, where they
    enter, as the command line's parser checks the options; the kernels
    below trust them.

    Raises
    ------
    JudderError
        Naming the argument, its value and what is allowed.
    """
    from ._values import RULES
    for name, value in arguments.items():
        if value is not None:
            RULES[name].check(value, name)


def checked_values(parameters, changes, **arguments):
    """The parameter set an API function works on (:func:`resolve`), once
    :func:`check_arguments` allowed ``arguments``."""
    check_arguments(**arguments)
    return resolve(parameters, changes)


def resolve(parameters, changes):
    """``parameters`` (default preset if None) with ``changes`` applied."""
    base = parameters if parameters is not None else \
        get_preset(default_preset(DEFAULT_MODEL))
    return base.replace(**(changes or {}))


def dithered(values, waveform):
    """The driveline of ``values``, dithered by ``waveform`` (None: the
    paper's cosine)."""
    driveline = build_driveline(values)
    if waveform is None:
        return driveline
    from stability.waveforms import Dithered
    return Dithered(driveline, waveform)


def timed(function, *args, **kwargs):
    started = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - started


def structural_names(values, preferred, extra=()):
    """``preferred`` if the model has them all, else its inertias,
    stiffnesses and coupling dampings (from the registry), plus ``extra``.

    A Modelica class or an FMU has no registry entry: those of
    ``preferred`` it has (its names follow the paper's where it is the
    paper's chain), and if it has none the names must be given."""
    if all(name in values.specs for name in preferred):
        return tuple(preferred)
    if not values.source_kind.is_chain:
        names = tuple(n for n in preferred if n in values.specs)
        if not names:
            raise JudderError(
                f"--params is required for {values.model}: it has none of "
                f"the default names {','.join(preferred)}; allowed: its "
                f"tunable parameters: {', '.join(values.specs)}")
        return names
    model = values.driveline
    return (tuple(b.inertia for b in model.bodies)
            + tuple(c.stiffness for c in model.couplings)
            + tuple(c.damping for c in model.couplings) + tuple(extra))


def check_names(values, names, option):
    unknown = [n for n in names if n not in values.specs]
    if unknown:
        raise JudderError(f"{option} {unknown[0]!r} is not a parameter of the "
                          f"{values.model} model; allowed: "
                          f"{', '.join(values.specs)}")
    zero = [n for n in names if values[n] == 0]
    if zero:
        raise JudderError(f"{option} {zero[0]!r} is 0 in this parameter set; "
                          "allowed: parameters with a non-zero value (changes "
                          "are relative)")
