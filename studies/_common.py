"""What several API functions share: a caller's arguments checked and
the parameter set with its changes, the dithered driveline, timing, and
the checks of parameter names.
"""

import time

import numpy as np

from drivelines import DEFAULT_MODEL
from infra.errors import JudderError
from sources import default_preset, get_preset
from stability.source import build_driveline

#: Amplitudes of the map drawn under tongue boundaries (0 to p_max).
BACKGROUND_AMPLITUDES = 150


def check_arguments(**arguments):
    """Refuse any of ``arguments`` (``freq_hz=...``, ``p_f_bar=...``) its
    rule does not allow: the rule of its name,
    :data:`studies.rules.RULES`, the option's own (None: not
    given).

    The API functions check a Python caller's values here, where they
    enter, as the command line's parser checks the options; the kernels
    below trust them.

    Raises
    ------
    JudderError
        Naming the argument, its value and what is allowed.
    """
    from .rules import RULES
    for name, value in arguments.items():
        if value is not None:
            RULES[name].check(value, name)


def checked_values(parameters, changes, followed=False, **arguments):
    """The parameter set an API function works on (:func:`resolve`), once
    :func:`check_arguments` allowed ``arguments``; with ``freq_hz``, held
    where the study reads it (:func:`at_dither_frequency`; ``followed``:
    the study linearises it at each frequency itself)."""
    check_arguments(**arguments)
    values = resolve(parameters, changes)
    if arguments.get("freq_hz") is not None:
        values = at_dither_frequency(values, arguments["freq_hz"], followed)
    return values


def frequency_dependent(values):
    """Whether the Jacobian of ``values``' model depends on its dither
    frequency parameter beyond the cosine (a valve's roll-off written
    with ``f_dither``: :attr:`sources.modelica.LinearPeriodicModel.
    frequency_dependent`); False for the registry's chains."""
    if not getattr(values, "frequency", None):
        return False
    try:
        return values.linear_model().frequency_dependent
    except JudderError:
        # a model that cannot be linearised is refused by the study, in
        # its order (the names it needs first)
        return False


def at_dither_frequency(values, freq_hz, followed=False, argument="freq_hz"):
    """``values`` linearised at the dither frequencies ``freq_hz`` (Hz) a
    study reads them at.

    A frequency-dependent model (:func:`frequency_dependent`) holds at its
    frequency parameter's value only: at one frequency the parameter is
    set to it; over several, a study that linearises the model at each
    (``followed``, :func:`per_frequency`) gets ``values`` as they are,
    any other is refused (naming ``argument``, the caller's name of the
    frequencies). Any other model is returned as it is.

    Raises
    ------
    JudderError
        Over several frequencies of a frequency-dependent model that the
        study does not follow, naming the parameter.
    """
    if not frequency_dependent(values):
        return values
    freqs = np.unique(np.atleast_1d(np.asarray(freq_hz, dtype=float)))
    if len(freqs) == 1:
        return values.replace(**{values.frequency: float(freqs[0])})
    if followed:
        return values
    raise JudderError(
        f"`{argument}` {freqs[0]:g} to {freqs[-1]:g} Hz: the Jacobian of "
        f"{values.model} depends on its dither frequency {values.frequency} "
        "beyond the dither's cosine, so one linearisation holds at one "
        "frequency only; allowed: one frequency at a time (the model is "
        "linearised there), a map (linearised at each frequency), or a "
        f"model whose {values.frequency} enters as the cosine's frequency "
        "alone")


def per_frequency(values, waveform, freq_hz, study, progress=None):
    """``study(driveline, [f])`` at each frequency ``f`` of ``freq_hz``,
    the model linearised there (its frequency parameter set to ``f``):
    what a loop of ``--set f_dither=f`` gives, in one call."""
    freqs = [float(f) for f in np.atleast_1d(freq_hz)]
    parts = []
    for done, f in enumerate(freqs, start=1):
        driveline = dithered(values.replace(**{values.frequency: f}),
                             waveform)
        parts.append(study(driveline, [f]))
        if progress is not None:
            progress(done, len(freqs))
    return parts


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


def structural_names(values, preferred, extra=(), argument="names"):
    """``preferred`` if the model has them all, else its inertias,
    stiffnesses and coupling dampings (from the registry), plus ``extra``;
    without those whose value is 0 (a relative change of them is none:
    ``mu_g`` of a flat friction characteristic).

    A Modelica class or an FMU has no registry entry: those of
    ``preferred`` it has (its names follow the paper's where it is the
    paper's chain), and if it has none the names must be given."""
    return tuple(name for name in _structural_names(values, preferred, extra,
                                                    argument)
                 if values[name] != 0)


def _structural_names(values, preferred, extra, argument):
    """:func:`structural_names` with the zero values kept."""
    if all(name in values.specs for name in preferred):
        return tuple(preferred)
    if not values.source_kind.is_chain:
        names = tuple(n for n in preferred if n in values.specs)
        if not names:
            raise JudderError(
                f"`{argument}` is required for {values.model}: it has none of "
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
