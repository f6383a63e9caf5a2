"""Sensitivity of the tongues to the model parameters (Fig. 17, Fig. 18).

Each parameter is scaled by a set of factors (the paper doubles and halves
them) or set to given values (the clutch-damper study of Fig. 16b and
18b); the boundaries and tongue tips of every case are compared with the
nominal ones. :func:`paper_conclusions` checks the paper's statements of
section 4.3 on the result.
"""

from dataclasses import dataclass

import numpy as np

from infra.errors import JudderError
from infra.parallel import parallel_map
from infra.units import PA_PER_BAR

from .modal import clutch_damper_damping_factor
from .source import build_driveline
from .monodromy import DEFAULT_METHOD, get_method
from .tongues import find_tongues, tongue_boundaries

__all__ = ["SensitivityCase", "SensitivityStudy", "sensitivity_study",
           "tip_shifts", "paper_conclusions"]


@dataclass(frozen=True)
class SensitivityCase:
    """Boundaries and tongues of one parameter variation.

    Attributes
    ----------
    parameter : str or None
        Varied parameter (None for the nominal case).
    factor : float
        Value divided by the nominal value.
    value : float
        Value used, SI units.
    boundaries : stability.tongues.Boundaries
    tongues : list of stability.tongues.Tongue
    damper_zeta : float or None
        Damping factor of the clutch damper with this case's values, Eq.
        (16), as a fraction; None for a model without that role (a
        Modelica class or an FMU).
    """

    parameter: object
    factor: float
    value: float
    boundaries: object
    tongues: list
    damper_zeta: float = None

    def tongue(self, number):
        """The tongue with this number, or None if it is not there."""
        return next((t for t in self.tongues if t.number == number), None)


@dataclass(frozen=True)
class SensitivityStudy:
    """Nominal case and its variations.

    Attributes
    ----------
    nominal : SensitivityCase
    cases : list of SensitivityCase
        In the order of the parameters, then of the factors or values.
    """

    nominal: SensitivityCase
    cases: list

    def plot(self, **kwargs):
        """Figure of boundaries per parameter; see
        :func:`stability.plots.sensitivity_figure`."""
        from .plots import sensitivity_figure
        return sensitivity_figure(self, **kwargs)


def _run_case(args):
    params, parameter, value, freq_hz, p_max, method = args
    case_params = params if parameter is None else \
        params.replace(**{parameter: value})
    driveline = build_driveline(case_params)
    boundaries = tongue_boundaries(driveline, freq_hz, p_max, method)
    nominal = value if parameter is None else params[parameter]
    return SensitivityCase(
        parameter=parameter,
        factor=1.0 if parameter is None or nominal == 0 else value / nominal,
        value=value, boundaries=boundaries,
        tongues=find_tongues(driveline, boundaries),
        damper_zeta=_damper_zeta(case_params))


def _damper_zeta(params):
    """Eq. (16) of a registry driveline's clutch damper, else None."""
    if not params.source_kind.is_chain or \
            params.driveline.clutch_damper is None:
        return None
    return float(clutch_damper_damping_factor(params))


def sensitivity_study(params, names, freq_hz, p_max, factors=(0.5, 2.0),
                      values=None, method=DEFAULT_METHOD, workers=None,
                      callback=None):
    """Tongue boundaries with each parameter varied.

    Parameters
    ----------
    params : drivelines.Parameters
        Nominal set.
    names : sequence of str
        Parameters to vary.
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max : float
        Largest amplitude searched, Pa.
    factors : sequence of float
        Multipliers of the nominal value (used when ``values`` is None).
    values : sequence of float, optional
        Absolute values to set instead (SI units), e.g. c12 = 0.5 ... 10.
    method : str
        Monodromy engine, a key of :data:`stability.monodromy.METHODS`.
    workers : int, optional
        Processes to use (default: all cores).
    callback : callable, optional
        ``callback(done, total)`` after each case.

    Returns
    -------
    SensitivityStudy

    Raises
    ------
    ParameterError
        If a name is unknown or a varied value is not allowed.
    """
    names = list(names)
    if not names:
        raise JudderError("give at least one parameter to vary")
    get_method(method)
    jobs = [(params, None, 0.0, freq_hz, p_max, method)]
    for name in names:
        varied = (np.asarray(values, dtype=float) if values is not None
                  else params[name] * np.asarray(factors, dtype=float))
        for value in varied:
            params.replace(**{name: float(value)})  # validate early
            jobs.append((params, name, float(value), freq_hz, p_max,
                         method))
    results = []
    for case in parallel_map(_run_case, jobs, workers):
        results.append(case)
        if callback is not None:
            callback(len(results), len(jobs))
    return SensitivityStudy(nominal=results[0], cases=results[1:])


def tip_shifts(study):
    """Table of tip movements: one row per case and nominal tongue.

    Returns
    -------
    list of dict
        Keys: ``parameter``, ``factor``, ``value``, ``tongue``, ``kind``,
        ``resonance``, ``tip_freq_hz``, ``tip_p_f_bar``, ``d_freq_hz``,
        ``d_p_f_bar`` (case minus nominal; None where the tongue is not
        found below p_max in the case), ``present``.
    """
    rows = []
    for case in study.cases:
        for base in study.nominal.tongues:
            if base.number is None:
                continue
            moved = case.tongue(base.number)
            rows.append({
                "parameter": case.parameter, "factor": case.factor,
                "value": case.value, "tongue": base.number,
                "kind": base.kind, "resonance": base.resonance,
                "tip_freq_hz": None if moved is None else moved.tip_freq_hz,
                "tip_p_f_bar": None if moved is None
                else moved.tip_p_f / PA_PER_BAR,
                "d_freq_hz": None if moved is None
                else moved.tip_freq_hz - base.tip_freq_hz,
                "d_p_f_bar": None if moved is None
                else (moved.tip_p_f - base.tip_p_f) / PA_PER_BAR,
                "present": moved is not None})
    return rows


def _relative_shift(study, parameter, factor, number):
    """|tip frequency change| / nominal tip frequency, or None."""
    base = study.nominal.tongue(number)
    case = next((c for c in study.cases if c.parameter == parameter
                 and np.isclose(c.factor, factor)), None)
    moved = None if case is None else case.tongue(number)
    if base is None or moved is None:
        return None
    return (moved.tip_freq_hz - base.tip_freq_hz) / base.tip_freq_hz


def paper_conclusions(study, factor=2.0):
    """Check the statements of section 4.3 on a 4-DOF study.

    Each statement is judged only if the study varied the parameters it
    needs by ``factor`` (and ``1/factor`` for mu_g).

    Returns
    -------
    list of dict
        ``statement``, ``holds`` (bool) and ``evidence`` (text).
    """
    numbers = [t.number for t in study.nominal.tongues if t.number]
    shift = {}
    for case in study.cases:
        if np.isclose(case.factor, factor):
            shift[case.parameter] = {
                n: _relative_shift(study, case.parameter, factor, n)
                for n in numbers}
    out = []

    def judge(statement, holds, evidence):
        out.append({"statement": statement, "holds": bool(holds),
                    "evidence": evidence})

    # a difference tongue (f2 - f1) moves against the lower frequency, so
    # the direction statements are judged on the other tongues and the
    # difference tongues are reported on their own
    difference = {t.number for t in study.nominal.tongues
                  if t.resonance and "-" in t.resonance}
    for names, sign, text in ((("k12", "k24"), 1, "stiffness up moves "
                               "the tongues up in frequency"),
                              (("J1", "J2", "J3", "J4"), -1, "inertia up "
                               "moves the tongues down in frequency")):
        present = [n for n in names if n in shift]
        if not present:
            continue
        moved = {n: {k: v for k, v in shift[n].items()
                     if v is not None and k not in difference}
                 for n in present}
        ok = all(sign * v >= -1e-6 for vs in moved.values()
                 for v in vs.values())
        judge(text + " (tongues at f_i, 2 f_i and f_i + f_j)", ok,
              "; ".join(f"{n} x{factor:g}: " + ", ".join(
                  f"tongue {k} {100 * v:+.2f} %" for k, v in vs.items())
                  for n, vs in moved.items()))
        for number in sorted(difference):
            against = {n: shift[n][number] for n in present
                       if shift[n].get(number) is not None}
            if against:
                judge(f"tongue {number} (difference f_j - f_i) moves "
                      f"{'up' if sign > 0 else 'down'} too", all(
                          sign * v >= -1e-6 for v in against.values()),
                      ", ".join(f"{n} x{factor:g}: {100 * v:+.2f} %"
                                for n, v in against.items()))
    if "k12" in shift and {1, 2} <= set(shift["k12"]):
        low, high = abs(shift["k12"][1] or 0), abs(shift["k12"][2] or 0)
        judge("k12 acts mainly on the low-frequency tongues", low > high,
              f"k12 x{factor:g}: tongue 1 {100 * low:.2f} %, tongue 2 "
              f"{100 * high:.2f} %")
    if "k24" in shift and {1, 2} <= set(shift["k24"]):
        low, high = abs(shift["k24"][1] or 0), abs(shift["k24"][2] or 0)
        judge("k24 acts mainly on the high-frequency single-period tongue",
              high > low, f"k24 x{factor:g}: tongue 2 {100 * high:.2f} %, "
              f"tongue 1 {100 * low:.2f} %")
    inertias = [n for n in ("J1", "J2", "J3", "J4") if n in shift]
    if len(inertias) == 4 and all(shift[n].get(2) is not None
                                  for n in inertias):
        effect = {n: abs(shift[n][2]) for n in inertias}
        ok = (min(effect["J2"], effect["J4"]) > effect["J1"] > effect["J3"]
              and effect["J3"] < 1e-3)
        judge("J2 and J4 move the tongue near 105 Hz most, J1 little, J3 not "
              "at all", ok, ", ".join(f"{n} {100 * e:.3f} %"
                                      for n, e in effect.items()))
    lower = next((c for c in study.cases if c.parameter == "mu_g"
                  and np.isclose(c.factor, 1 / factor)), None)
    if lower is not None:
        rises = []
        for base in study.nominal.tongues:
            if base.number is None:
                continue
            moved = lower.tongue(base.number)
            rises.append(moved is None or moved.tip_p_f > base.tip_p_f)
        judge("lower mu_g shrinks the tongues (tips rise or vanish)",
              all(rises), f"mu_g x{1 / factor:g}: {sum(rises)} of "
              f"{len(rises)} tips higher or gone")
    return out
