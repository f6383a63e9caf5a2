"""The Python API: one function per ``judder`` command.

Each function takes SI parameter sets and the units of the command line
(dither frequency in Hz, amplitude in bar), runs the kernels of
:mod:`stability` and :mod:`pysim`, and returns a result object of
:mod:`judder.results` (``as_dict()``, ``save()``, ``figure()``). The
command line calls these functions and only formats what they return.

Every function takes the parameter set as ``params`` (a
:class:`drivelines.Parameters`; default: the paper preset of the default
driveline, see :func:`judder.inputs.load_parameters` for files; or a
driveline of one's own, a Modelica class
:class:`drivelines.modelica.ModelicaParameters` or an FMU
:class:`drivelines.fmu_linear.FmuParameters`) and ``changes``, the values
the user set explicitly (``--set``), applied on top. What needs a
time-domain run (:func:`crosscheck`, :func:`simulate`) refuses an FMU,
what needs the bench (``fit(bench=...)``) or the paper's chains
(:func:`threshold`) refuses both, with a :class:`~infra.errors.JudderError`
that says why. Monodromy engines (``method``) are the keys of
:data:`stability.monodromy.METHODS`. ``progress`` is called as
``progress(done, total)`` on long work.

Examples
--------
>>> from judder import api
>>> result = api.floquet(102.9, 0.3)
>>> result.result.kind, round(result.result.leading_abs, 4)
('single-period', 1.0261)
"""

import dataclasses
import time
from pathlib import Path

import numpy as np

from drivelines import DEFAULT_MODEL, default_preset, get_preset
from drivelines.specs import MEAN_PRESSURE_DAMPING
from infra.errors import JudderError, check_number
from infra.units import PA_PER_BAR
from stability import floquet as floquet_kernel
from stability import modal
from stability.maps import stability_map as map_kernel
from stability.model import build_driveline
from stability.monodromy import DEFAULT_METHOD

from .results import (CampaignResult, ChartResult, CrosscheckResult,
                      EigResult, EnvelopeResult,
                      FitReport, FloquetPoint, MapResult, ParamsResult,
                      SensitivityResult, SimulationResult, ThresholdResult,
                      TonguesResult, CheckResult, AdviceResult)

__all__ = ["params", "eig", "floquet", "stability_map", "tongues", "check",
           "advise",
           "sensitivity", "threshold", "fit", "simulate", "crosscheck",
           "campaign", "chart", "report", "envelope",
           "BACKGROUND_AMPLITUDES"]

#: Amplitudes of the map drawn under tongue boundaries (0 to p_max).
BACKGROUND_AMPLITUDES = 150


def _resolve(parameters, changes):
    """``parameters`` (default preset if None) with ``changes`` applied."""
    base = parameters if parameters is not None else \
        get_preset(default_preset(DEFAULT_MODEL))
    return base.replace(**(changes or {}))


def _dithered(values, waveform):
    """The driveline of ``values``, dithered by ``waveform`` (None: the
    paper's cosine)."""
    driveline = build_driveline(values)
    if waveform is None:
        return driveline
    from stability.waveforms import Dithered
    return Dithered(driveline, waveform)


def _timed(function, *args, **kwargs):
    started = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - started


def params(parameters=None, changes=None):
    """``judder params``: a parameter set with units and meanings.

    Returns
    -------
    judder.results.ParamsResult
        ``save(path)`` writes it as TOML.
    """
    return ParamsResult(_resolve(parameters, changes))


def eig(parameters=None, changes=None):
    """``judder eig``: natural frequencies (Eq. 14-15) and the
    clutch-damper damping factor (Eq. 16), and the damped modes without
    dither.

    For a Modelica class or an FMU the natural frequencies are those of
    its Jacobian's stiffness part and the damped modes those of its
    system without dither, rigid-body angles removed; the closed forms
    (Eq. 15) and the clutch-damper factor (Eq. 16) belong to the paper's
    chains, so they are None there.

    Returns
    -------
    judder.results.EigResult

    Examples
    --------
    >>> eig().natural_frequencies_hz.round(3)
    array([ 18.939, 102.884])
    """
    values = _resolve(parameters, changes)
    driveline = build_driveline(values)
    damped_hz, ratio = modal.damped_modes(driveline)
    paper = values.driveline is not None
    return EigResult(
        params=values,
        natural_frequencies_hz=modal.natural_frequencies(driveline),
        closed_form_frequencies_hz=(modal.closed_form_frequencies(values)
                                    if paper else None),
        damping_factor_12=(float(modal.clutch_damper_damping_factor(values))
                           if paper else None),
        damped_frequencies_hz=damped_hz, damping_ratio=ratio)


def floquet(freq_hz, p_f_bar, parameters=None, changes=None,
            method=DEFAULT_METHOD, waveform=None):
    """``judder floquet``: Floquet multipliers at one dither setting
    (Eq. 10-13), rigid-body angles removed.

    Parameters
    ----------
    freq_hz : float
        Dither frequency, Hz.
    p_f_bar : float
        Dither amplitude, bar.

    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.

    Returns
    -------
    judder.results.FloquetPoint
    """
    values = _resolve(parameters, changes)
    result = floquet_kernel(_dithered(values, waveform), freq_hz,
                            p_f_bar * PA_PER_BAR, method=method)
    return FloquetPoint(params=values, method=method, result=result)


def stability_map(freq_hz, p_f_bar, parameters=None, changes=None,
                  method=DEFAULT_METHOD, progress=None, min_growth=None,
                  exact=False, waveform=None):
    """``judder map``: leading multiplier on a frequency x amplitude grid
    (Fig. 12, Fig. 14).

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_f_bar : array_like
        Dither amplitudes, bar.

    exact : bool
        Also compute the exact tongue boundaries and tips on the map's
        frequencies up to its largest amplitude
        (:func:`stability.tongues.tongue_boundaries`), which
        ``figure()`` draws over the grid with the tongue numbers.
    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.

    Returns
    -------
    judder.results.MapResult
        ``save(path)`` writes NPZ, ``figure()`` draws it.
    min_growth : float, optional
        1/s: the figure shades unstable points growing slower than this
        (not judder, :mod:`stability.relevance`) and the JSON counts the
        faster ones.
    """
    values = _resolve(parameters, changes)
    driveline = _dithered(values, waveform)
    result, seconds = _timed(
        map_kernel, driveline, freq_hz,
        np.asarray(p_f_bar, dtype=float) * PA_PER_BAR, method=method,
        callback=progress)
    boundaries = found = None
    p_top = float(np.max(p_f_bar)) * PA_PER_BAR
    if exact and len(result.freq_hz) > 1 and p_top > 0:
        from stability.tongues import find_tongues, tongue_boundaries
        boundaries = tongue_boundaries(driveline, result.freq_hz, p_top,
                                       method)
        found = find_tongues(driveline, boundaries)
    return MapResult(params=values, map=result, seconds=seconds,
                     boundaries=boundaries, tongues=found,
                     min_growth=min_growth)


def tongues(freq_hz, p_max_bar=1.5, parameters=None, changes=None,
            method=DEFAULT_METHOD, background=False, progress=None,
            min_growth=0.0, solver="hill", waveform=None):
    """``judder tongues``: exact tongue boundaries, tongue numbers (Fig.
    14) and tips.

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max_bar : float
        Largest amplitude searched, bar.
    background : bool
        Also compute the map drawn under the boundaries by ``figure()``
        (:data:`BACKGROUND_AMPLITUDES` amplitudes from 0 to ``p_max``).
    min_growth : float
        1/s: boundaries of judder growing at least this fast (0: the
        stability boundaries).
    solver : str
        Boundary solver, a key of :data:`stability.tongues.SOLVERS`.
    waveform : object, optional
        Dither shape (:mod:`stability.waveforms`); default the cosine.

    Returns
    -------
    judder.results.TonguesResult
    """
    from stability.tongues import find_tongues, tongue_boundaries
    values = _resolve(parameters, changes)
    driveline = _dithered(values, waveform)
    p_max = p_max_bar * PA_PER_BAR
    started = time.perf_counter()
    boundaries = tongue_boundaries(driveline, freq_hz, p_max, method,
                                   callback=progress, min_growth=min_growth,
                                   solver=solver)
    found = find_tongues(driveline, boundaries)
    seconds = time.perf_counter() - started
    under = (map_kernel(driveline, freq_hz,
                        np.linspace(0, p_max, BACKGROUND_AMPLITUDES),
                        method=method) if background else None)
    return TonguesResult(params=values, boundaries=boundaries,
                         tongues=found, seconds=seconds, background=under)


def sensitivity(names, freq_hz, p_max_bar=1.5, factors=(0.5, 2.0),
                values=None, parameters=None, changes=None,
                method=DEFAULT_METHOD, workers=None, progress=None):
    """``judder sensitivity``: tongue tips with parameters varied (Fig. 17,
    18), and the paper's conclusions of section 4.3 where the driveline is
    the paper's.

    Parameters
    ----------
    names : sequence of str
        Parameters to vary.
    factors : sequence of float
        Multipliers of the nominal values (used when ``values`` is None).
    values : sequence of float, optional
        Absolute values instead, SI.
    workers : int, optional
        Processes (default all cores).

    Returns
    -------
    judder.results.SensitivityResult
    """
    from stability.sensitivity import (paper_conclusions, sensitivity_study,
                                       tip_shifts)
    nominal = _resolve(parameters, changes)
    for name in names:
        if name not in nominal.specs:
            raise JudderError(f"--params: unknown parameter {name!r} for the "
                              f"{nominal.model} model; allowed names: "
                              f"{', '.join(nominal.specs)}")
    study, seconds = _timed(
        sensitivity_study, nominal, names, freq_hz, p_max_bar * PA_PER_BAR,
        factors=factors, values=values, method=method, workers=workers,
        callback=progress)
    conclusions = (paper_conclusions(study)
                   if nominal.driveline is not None
                   and nominal.driveline.paper_sensitivity else [])
    return SensitivityResult(params=nominal, study=study,
                             tip_shifts=tip_shifts(study),
                             conclusions=conclusions, seconds=seconds,
                             method=method)


def threshold(mu_g, c_ext, parameters=None, changes=None, progress=None):
    """``judder threshold``: the friction-gradient threshold without
    dither (Fig. 19).

    Fig. 19 needs the mean pressure in the slip damping, so
    ``mean_pressure_damping`` is 1 here unless ``changes`` sets it.

    Parameters
    ----------
    mu_g : array_like
        Friction gradients for Fig. 19a, s/rad.
    c_ext : array_like
        Values of every external damping c_i for Fig. 19b, N m s/rad.

    Returns
    -------
    judder.results.ThresholdResult

    Examples
    --------
    With every c_i = 0.1 N m s/rad the threshold is -1.25e-4 c_i:

    >>> r = threshold([0.0], [0.1])
    >>> round(float(r.study.threshold), 10)
    -1.25e-05
    """
    from stability.threshold import threshold_study
    changes = dict(changes or {})
    base = _resolve(parameters, {})
    if base.driveline is None:
        raise JudderError(f"threshold of {base.model} is not possible: "
                          "Fig. 19 varies mu_g and the external dampings "
                          "of the paper's chains by their roles; allowed: "
                          "a preset or a parameter file of one")
    changes.setdefault(MEAN_PRESSURE_DAMPING, 1.0)
    values = _resolve(parameters, changes)
    study = threshold_study(values, mu_g, c_ext, callback=progress)
    return ThresholdResult(params=values, study=study)


def fit(freq_hz, measured_p_f_bar, p_max_bar=1.5, names=None, bounds=None,
        parameters=None, changes=None, method=DEFAULT_METHOD, kinds=None,
        starts=3, uncertainty="auto", error_model="relative", seed=0,
        workers=None, progress=None, min_growth=None, bench=None,
        scatter=None, below_bar=None, threshold_spread=0.0):
    """``judder fit``: fit parameters to a measured boundary (section 4.2,
    Fig. 16a).

    Parameters
    ----------
    freq_hz : array_like
        Frequencies of the measured points, Hz.
    measured_p_f_bar : array_like
        Lowest amplitude with judder, bar; NaN where none was seen up to
        ``p_max_bar`` (see :func:`judder.inputs.read_boundary`).
    names : sequence of str, optional
        Parameters to fit (default
        :data:`stability.fitting.DEFAULT_FIT`).
    bounds : dict, optional
        ``{name: (low, high)}``, SI.
    kinds, starts, uncertainty, error_model, seed, workers, scatter
    threshold_spread
        As :func:`stability.fitting.fit_boundary` takes them (``scatter``
        in Pa with the absolute error model).
    min_growth : float, optional
        1/s: the model boundary compared is that of judder growing at
        this rate; default ``judder check``'s
        (:data:`stability.relevance.DEFAULT_MIN_GROWTH_PER_S`), so fit,
        check and chart call the same point judder.
    below_bar : array_like, optional
        The highest amplitude tried without judder below each onset, bar
        (NaN: none; :func:`judder.inputs.read_chart_below`): the fit
        compares with the middle of each interval (below, onset].
    bench : dict, optional
        Compare with the bench's linearisation, not the driveline alone:
        the damping its motor control adds
        (:attr:`drivelines.DrivelineModel.bench_damping`, ``c1 +
        d_control``), from these bench parameters (SI) or the bench
        model's defaults (``{}``). None: the driveline.

    Returns
    -------
    judder.results.FitReport
        ``fit.success`` is False when any of ``fit.problems`` holds (no
        convergence, a parameter on a bound or undetermined, another
        minimum as good).
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.fit import DEFAULT_FIT, fit_boundary
    start = _resolve(parameters, changes)
    if min_growth is None:
        min_growth = DEFAULT_MIN_GROWTH_PER_S
    result, seconds = _timed(
        fit_boundary, start, freq_hz,
        np.asarray(measured_p_f_bar, dtype=float) * PA_PER_BAR,
        p_max_bar * PA_PER_BAR, names=names or DEFAULT_FIT, bounds=bounds,
        method=method, kinds=kinds, starts=starts, uncertainty=uncertainty,
        error_model=error_model, seed=seed, workers=workers,
        callback=progress, min_growth=min_growth,
        added=None if bench is None else bench_damping(start, bench),
        scatter=scatter, below=None if below_bar is None else
        np.asarray(below_bar, dtype=float) * PA_PER_BAR,
        threshold_spread=threshold_spread)
    return FitReport(fit=result, seconds=seconds, method=method)


def _bench_fmu(values):
    """The driveline's bench engagement model and its FMU (built if
    needed)."""
    from pysim.fmus import ensure_fmu
    if values.driveline is None:
        raise JudderError(f"{values.model} (a Modelica class or an FMU) "
                          "has no bench engagement model: the bench belongs "
                          "to the registry's 4-DOF driveline; allowed: a "
                          "preset or its parameter file (or add the bench's "
                          "damping to the class with --set)")
    model_class = values.driveline.bench_class
    if model_class is None:
        raise JudderError(f"the {values.model} driveline has no bench "
                          "engagement model; give a parameter set of a "
                          "driveline that has one (4-DOF)")
    return model_class, ensure_fmu(model_class)


def bench_damping(values, bench=None):
    """What the bench's linearisation adds to the driveline's parameters.

    The bench's motor holds its speed by a proportional control, which
    acts on body 1 as a damping to ground about the set speed
    (:attr:`drivelines.DrivelineModel.bench_damping`): the Floquet model of
    the bench is the driveline with ``c1 + d_control``.

    Parameters
    ----------
    values : drivelines.Parameters
    bench : dict, optional
        Bench parameters (SI); the others are the bench model's defaults.

    Returns
    -------
    dict
        ``{driveline parameter: added value}``, SI.

    Raises
    ------
    JudderError
        Where the bench's slip (``w_motor - w_gearbox``) is not its
        friction curve's ``w_op``: there the linearisation also takes the
        curve's value and slope at that slip (:func:`simulate` does), which
        a sum cannot say.
    """
    fmu = _bench_fmu(values)[1]
    friction, _ = _operating_friction(values, fmu, dict(bench or {}))
    if not np.isclose(friction["mu_g"], values["mu_g"], rtol=1e-9):
        raise JudderError(
            "--bench: the bench's slip w_motor - w_gearbox is not its "
            "friction curve's w_op, where mu0 and mu_g are the curve's; "
            "its linearisation there has the slope "
            f"{friction['mu_g']:.3g} s/rad, not a fitted mu_g; allowed: "
            "a chart at the curve's operating slip (1000 rpm by default), "
            "or --bench w_op set to that chart's slip")
    return _added_damping(values, fmu, bench)


def _added_damping(values, fmu, bench):
    """:func:`bench_damping` with the bench's FMU ``fmu`` known."""
    from pysim.runs import parameter_default
    bench = dict(bench or {})
    for name in bench:
        parameter_default(fmu, name)    # the bench model must have it
    return {name: float(bench.get(added, parameter_default(fmu, added)))
            for name, added in values.driveline.bench_damping}


def _operating_friction(values, fmu, bench):
    """The bench's friction at its operating point.

    Returns ``({'mu0': ..., 'mu_g': ...}, linear range)``: the value and
    slope of its EVEN clutch's friction curve
    (:func:`stability.friction.curve_at`) at its steady slip, ``w_motor
    - w_gearbox`` (``values``' own when that slip is the curve's
    ``w_op``, as at the bench's default 1000 rpm), and the slip offset,
    rad/s, over which the curve keeps that slope
    (:func:`stability.friction.linear_range`).
    """
    from pysim.runs import parameter_default
    from stability.friction import curve_at, linear_range

    def bench_value(name):
        return float(bench.get(name, parameter_default(fmu, name)))
    if bench_value("w_gearbox") >= bench_value("w_motor"):
        raise JudderError(
            f"--bench w_gearbox {bench_value('w_gearbox'):g} rad/s is not "
            f"allowed with w_motor {bench_value('w_motor'):g} rad/s; "
            "allowed: below w_motor (the EVEN clutch slips forwards, "
            "at w_motor - w_gearbox)")
    delta_mu = bench_value("delta_mu")
    point = curve_at(bench_value("w_motor") - bench_value("w_gearbox"),
                     values["mu0"], values["mu_g"], delta_mu,
                     bench_value("w_op"))
    return ({"mu0": point.mu, "mu_g": point.slope},
            linear_range(point.slope, delta_mu))


def _linear_validity(driveline, run, linear_slip):
    """Whether the dither's forced slip swing stays within the friction
    curve's linear range (the run can then follow its linearisation):
    ``forced_slip_amplitude_rad_s``, ``friction_linear_range_rad_s`` and
    ``linearisation_holds`` (None for a model without the curve)."""
    from stability.friction import forced_slip_amplitude
    if linear_slip is None or run.p_f == 0:
        return {"forced_slip_amplitude_rad_s": None,
                "friction_linear_range_rad_s": linear_slip,
                "linearisation_holds": None}
    forced = forced_slip_amplitude(driveline, run.freq_hz, run.p_f)
    return {"forced_slip_amplitude_rad_s": forced,
            "friction_linear_range_rad_s": linear_slip,
            "linearisation_holds": bool(forced <= linear_slip)}


def simulate(freq_hz, p_f_bar, duration=None, compare=None, bench=None,
             parameters=None, changes=None, method=DEFAULT_METHOD):
    """``judder simulate``: an engagement on the driveline's bench model
    (Fig. 7, 8), run through its FMU, with the Floquet verdict of each
    dither setting for the bench's linearisation (the damping its motor
    control adds, :attr:`drivelines.DrivelineModel.bench_damping`).

    A Modelica class (:class:`drivelines.modelica.ModelicaParameters`)
    runs instead through its own FMU (the one ``crosscheck`` runs, see
    :mod:`judder.timedomain`) from its start values, a steady slip, with
    the dither; the Floquet verdict is that of its linearisation. An FMU
    of ``--fmu`` is refused: it has no time-domain model here.

    Parameters
    ----------
    freq_hz : float or sequence of float
        Dither frequency, Hz; several give one engagement each (Fig. 1,
        Fig. 8).
    p_f_bar : float
        Dither amplitude, bar.
    duration : float, optional
        Simulated time, s (default: the model's).
    compare : 'none' or float, optional
        Also run a correct engagement: ``'none'`` without dither, a number
        with dither at that frequency (Hz).
    bench : dict, optional
        Further parameters of the bench model (``w_motor``, ...), SI; not
        for a Modelica class (its parameters are ``changes``).

    Returns
    -------
    judder.results.SimulationResult
    """
    from drivelines.registry import SIGNALS
    from pysim.engagement import engagement_summary
    from pysim.runs import parameter_default, run_fmu
    from .timedomain import class_fmu, run_values
    values = _resolve(parameters, changes)
    bench = dict(bench or {})
    if values.driveline is not None:
        model_class, fmu = _bench_fmu(values)
        ramp_end = sum(bench.get(name, parameter_default(fmu, name))
                       for name in ("t_engage", "t_ramp"))
        run_params, extra = values, bench
        # the bench's linearisation: its motor control damps body 1, and
        # its friction curve has its own value and slope at the slip
        friction, linear_slip = _operating_friction(values, fmu, bench)
        driveline = build_driveline(values.replace(
            **{name: values[name] + value for name, value in
               _added_damping(values, fmu, bench).items()}, **friction))
    else:
        fmu = class_fmu(values, "simulate")
        if bench:
            raise JudderError(f"--bench {', '.join(bench)} is not allowed "
                              f"with the class {values.model}; allowed: "
                              "its parameters with --set (the bench "
                              "parameters belong to the bench model)")
        model_class, ramp_end = values.model, 0.0   # starts slipping
        run_params, extra = run_values(values)
        driveline, linear_slip = build_driveline(values), None
    if duration is not None and duration <= ramp_end:
        raise JudderError(f"duration {duration:g} s ends before the "
                          f"engagement (its pressure ramp ends at "
                          f"{ramp_end:g} s); allowed: > {ramp_end:g} s")
    freqs = [float(f) for f in np.atleast_1d(freq_hz)]
    settings = ([("with dither", freqs[0], p_f_bar * PA_PER_BAR)]
                if len(freqs) == 1 else
                [(f"dither at {f:g} Hz", f, p_f_bar * PA_PER_BAR)
                 for f in freqs])
    freq_hz = freqs[0]
    if compare is not None:
        settings.append(("without dither", freq_hz, 0.0)
                        if compare == "none" else
                        (f"dither at {float(compare):g} Hz", float(compare),
                         p_f_bar * PA_PER_BAR))
    interval = min(1e-3, 1.0 / (20 * max(f for _, f, _ in settings)))
    runs = [(label, run_fmu(fmu, freq, p_f, params=run_params, extra=extra,
                            duration=duration, output_interval=interval))
            for label, freq, p_f in settings]
    summaries = []
    for label, run in runs:
        linear = floquet_kernel(driveline, run.freq_hz, run.p_f,
                                method=method)
        summaries.append({"label": label,
                          **engagement_summary(run, ramp_end),
                          "floquet_kind": linear.kind,
                          "floquet_exponent_per_s": linear.growth_rate,
                          **_linear_validity(driveline, run, linear_slip)})
    return SimulationResult(runs=runs, summaries=summaries, fmu=fmu,
                            model_class=model_class, start=ramp_end,
                            signals=dict(SIGNALS))


def crosscheck(freq_hz, p_f_bar, duration=3.0, parameters=None,
               changes=None, method=DEFAULT_METHOD, workers=None,
               progress=None, perturb="w_in"):
    """``judder crosscheck``: growth rates of the driveline's FMU against
    the Floquet exponents on a grid (the two views of one model).

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_f_bar : array_like
        Dither amplitudes, bar.
    duration : float
        Length of each run, s.
    perturb : str
        Start-speed parameter raised in the second run of each point.

    Returns
    -------
    judder.results.CrosscheckResult
    """
    from .crosscheck import crosscheck as crosscheck_study
    values = _resolve(parameters, changes)
    check, seconds = _timed(
        crosscheck_study, values, freq_hz,
        np.asarray(p_f_bar, dtype=float) * PA_PER_BAR, duration=duration,
        method=method, workers=workers, callback=progress, perturb=perturb)
    return CrosscheckResult(params=values, check=check, seconds=seconds,
                            method=method)


def campaign(folder, freq_hz, p_f_bar, engine_rpm=(1000.0,),
             temperatures=("65-70",), duration=3.0, noise_rpm=0.5, seed=1,
             formats=("csv", "mf4"), parameters=None, changes=None,
             workers=None, progress=None):
    """``judder campaign``: emulate a bench campaign of engagements into
    ``folder`` (resumed when run again).

    Parameters
    ----------
    folder : path
    freq_hz, p_f_bar : sequence of float
        Dither grid, Hz and bar.
    engine_rpm : sequence of float
        Motor speeds, rpm.
    temperatures : sequence of str
        Keys of :data:`pysim.bench.TEMPERATURES`.

    Returns
    -------
    judder.results.CampaignResult
    """
    from pysim.bench import Campaign, run_campaign
    values = _resolve(parameters, changes)
    plan = Campaign(freq_hz=tuple(freq_hz), p_f_bar=tuple(p_f_bar),
                    engine_rpm=tuple(engine_rpm),
                    temperatures=tuple(temperatures), duration=duration,
                    noise_rpm=noise_rpm, formats=tuple(formats), seed=seed)
    rows, seconds = _timed(run_campaign, plan, values, folder,
                           workers=workers, callback=progress)
    return CampaignResult(rows=rows, index=str(Path(folder) / "index.csv"),
                          seconds=seconds)


def chart(sources, index=None, channels=None, group_by=None,
          min_growth=None, min_amplitude_rpm=None, model=False,
          parameters=None, changes=None, method=DEFAULT_METHOD,
          workers=None, progress=None):
    """``judder chart``: experimental stability charts from bench
    acquisitions (section 3.2, Fig. 10 and 11).

    Parameters
    ----------
    sources : sequence of path
        Campaign folders (``index.csv``) and acquisition files (MF4, CSV,
        TDMS, MAT).
    index : path, optional
        CSV with a ``file`` column and the runs' settings.
    channels : dict, optional
        Role (``upstream_speed``, ``pressure``, ``downstream_speed``) ->
        :class:`pysim.acquisitions.ChannelSpec`; default the names
        ``judder campaign`` writes.
    group_by : sequence of str, optional
        Columns making the panels (default: oil temperature and engine
        speed where they vary).
    min_growth : float, optional
        Growth rate (1/s) from which a run counts as judder (default
        :data:`pysim.run_analysis.MIN_GROWTH`).
    min_amplitude_rpm : float, optional
    model : bool
        Also compute the model's tongue boundaries (``parameters`` and
        ``changes``) over the chart's frequencies, drawn by ``figure()``.

    Returns
    -------
    judder.results.ChartResult
    """
    from pysim.charts import build_chart, gather_sources
    from pysim.run_analysis import MIN_AMPLITUDE_RPM, MIN_GROWTH
    started = time.perf_counter()
    result = build_chart(
        gather_sources(sources, index), channels=channels,
        group_by=group_by,
        min_growth=MIN_GROWTH if min_growth is None else min_growth,
        min_amplitude_rpm=(MIN_AMPLITUDE_RPM if min_amplitude_rpm is None
                           else min_amplitude_rpm),
        workers=workers, callback=progress)
    seconds = time.perf_counter() - started
    overlay = None
    if model and result.read:
        freqs = [r.analysis.freq_hz for r in result.read]
        top = max(r.analysis.p_f_bar for r in result.read)
        overlay = tongues(np.linspace(min(freqs), max(freqs), 200),
                          max(1.5 * top, 0.1), parameters, changes,
                          method=method)
    return ChartResult(chart=result, seconds=seconds, model=overlay)



#: Parameters whose effect on the margins ``check`` reports by default
#: (4-DOF model; other models: see :func:`_structural_names`).
DEFAULT_CHECK_PARAMETERS = ("J2", "J4", "k12", "k24", "c12", "mu_g")


def _structural_names(values, preferred, extra=()):
    """``preferred`` if the model has them all, else its inertias,
    stiffnesses and coupling dampings (from the registry), plus ``extra``.

    A Modelica class or an FMU has no registry entry: those of
    ``preferred`` it has (its names follow the paper's where it is the
    paper's chain), and if it has none the names must be given."""
    if all(name in values.specs for name in preferred):
        return tuple(preferred)
    model = values.driveline
    if model is None:
        names = tuple(n for n in preferred if n in values.specs)
        if not names:
            raise JudderError(
                f"--params is required for {values.model}: it has none of "
                f"the default names {','.join(preferred)}; allowed: its "
                f"tunable parameters: {', '.join(values.specs)}")
        return names
    return (tuple(b.inertia for b in model.bodies)
            + tuple(c.stiffness for c in model.couplings)
            + tuple(c.damping for c in model.couplings) + tuple(extra))


def _check_names(values, names, option):
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


def check(freq_hz, p_f_bar, parameters=None, changes=None, min_growth=None,
          p_max_bar=None, sensitivity=None, background=False,
          progress=None):
    """``judder check``: is each dither setting safe, and by how much.

    Parameters
    ----------
    freq_hz, p_f_bar : array_like, shape (n,)
        The settings, Hz and bar (pairs: a dither table).
    min_growth : float, optional
        Judder-relevant growth rate, 1/s (default
        :data:`stability.relevance.DEFAULT_MIN_GROWTH_PER_S`).
    p_max_bar : float, optional
        Largest boundary amplitude searched (default the larger of 1.5
        bar and twice the largest setting).
    sensitivity : sequence of str, optional
        Parameters whose effect on the margins is reported (empty: none;
        default :data:`DEFAULT_CHECK_PARAMETERS`, or the model's
        inertias, stiffnesses, coupling dampings and mu_g; for a Modelica
        class or an FMU those of :data:`DEFAULT_CHECK_PARAMETERS` it has,
        and JudderError if none).
    background : bool
        Also compute the map ``figure()`` marks the settings on.

    Returns
    -------
    judder.results.CheckResult
    """
    from infra.criteria import (DEFAULT_MIN_GROWTH_PER_S,
                                ENGAGEMENT_DURATION_S)
    from stability.decisions.margins import check_settings
    values = _resolve(parameters, changes)
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    p_f_bar = np.atleast_1d(np.asarray(p_f_bar, dtype=float))
    if freq_hz.shape != p_f_bar.shape or freq_hz.ndim != 1 or not len(freq_hz):
        raise JudderError(f"freq and p_f have {freq_hz.size} and "
                          f"{p_f_bar.size} values; allowed: as many of each")
    for f in freq_hz:
        check_number("freq", f, "Hz")
    for p in p_f_bar:
        check_number("p_f", p, "bar", strict=False)
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    check_number("min_growth", min_growth, "1/s", strict=False)
    if p_max_bar is None:
        p_max_bar = max(1.5, 2 * float(p_f_bar.max()))
    check_number("p_max", p_max_bar, "bar", low=float(p_f_bar.max()))
    if sensitivity is None:
        sensitivity = _structural_names(values, DEFAULT_CHECK_PARAMETERS,
                                        ("mu_g",))
    _check_names(values, sensitivity, "--params")
    started = time.perf_counter()
    checks = check_settings(values, freq_hz, p_f_bar * PA_PER_BAR, min_growth,
                            p_max_bar * PA_PER_BAR, tuple(sensitivity),
                            callback=progress)
    seconds = time.perf_counter() - started
    result = CheckResult(params=values, checks=checks, min_growth=min_growth,
                         engagement_s=ENGAGEMENT_DURATION_S,
                         p_max=p_max_bar * PA_PER_BAR, seconds=seconds)
    if background:
        low, high = freq_hz.min(), freq_hz.max()
        grid = np.linspace(max(low - 0.5 * (high - low) - 20, 1.0),
                           high + 0.5 * (high - low) + 20, 200)
        under = map_kernel(build_driveline(values), grid,
                           np.linspace(0, max(2 * p_f_bar.max(), 0.5), 100)
                           * PA_PER_BAR)
        result = dataclasses.replace(result, background=under)
    return result


def advise(parameters=None, changes=None, extra_sets=(), freq_range=(60.0, 200.0),
           p_max_bar=0.7, margin_bar=0.1, margin_hz=5.0, min_growth=None,
           names=None, weights=None, design=True, progress=None):
    """``judder advise``: safe dither windows, the ranking of the design
    parameters, and the smallest weighted change that clears the window.

    Parameters
    ----------
    extra_sets : sequence of drivelines.Parameters
        More parameter sets (an uncertainty envelope): the windows are
        those safe for every set, and the design must clear the window for
        every set (each gets the same relative change).
    freq_range : (float, float)
        Dither operating frequencies, Hz (default the paper's 60-200).
    p_max_bar : float
        Highest dither amplitude, bar (default 0.7).
    margin_bar, margin_hz : float
        Margins kept from every judder-relevant tongue, bar and Hz.
    min_growth : float, optional
        1/s, default :data:`stability.relevance.DEFAULT_MIN_GROWTH_PER_S`.
    names : sequence of str, optional
        Design parameters (default J2, J4, k12, k24, c12; for another
        model its inertias, stiffnesses and coupling dampings; for a
        Modelica class or an FMU those of the five it has, and
        JudderError if none).
    weights : sequence of float, optional
        Cost of a unit change of ln(value) of each (default 1).
    design : bool
        Also search the design change and recompute its map.

    Returns
    -------
    judder.results.AdviceResult
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.decisions import advice as kernel
    values = _resolve(parameters, changes)
    sets = [values, *extra_sets]
    models = {p.model for p in sets}
    if len(models) > 1:
        raise JudderError(f"parameter sets of models {sorted(models)}; "
                          "allowed: one model")
    low, high = (float(v) for v in freq_range)
    if not (np.isfinite(low) and np.isfinite(high) and 0 < low < high):
        raise JudderError(f"freq range = {low:g}:{high:g} Hz is not allowed; "
                          "allowed: 0 < LOW < HIGH")
    check_number("p_max", p_max_bar, "bar")
    check_number("margin_bar", margin_bar, "bar", strict=False)
    check_number("margin_hz", margin_hz, "Hz", strict=False)
    if margin_hz >= low:
        raise JudderError(f"margin_hz = {margin_hz:g} Hz is not allowed; "
                          f"allowed: below the lowest frequency {low:g} Hz")
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    check_number("min_growth", min_growth, "1/s", strict=False)
    names = tuple(_structural_names(values, kernel.DEFAULT_DESIGN_PARAMETERS)
                  if names is None else names)
    if not names:
        raise JudderError("--params is empty; allowed: design parameters "
                          "such as J2,J4,k24")
    for p in sets:
        _check_names(p, names, "--params")
    weights = np.ones(len(names)) if weights is None else \
        np.asarray(weights, dtype=float)
    if weights.shape != (len(names),):
        raise JudderError(f"{len(weights)} weights for {len(names)} "
                          "parameters; allowed: one weight per parameter")
    kernel.check_weights(names, weights)
    operating = kernel.OperatingRange(
        freq_hz=(low, high), p_max=p_max_bar * PA_PER_BAR,
        margin_p_f=margin_bar * PA_PER_BAR, margin_hz=margin_hz)
    p_search = max(1.5e5, 2 * operating.required_p_f)
    started = time.perf_counter()
    # 0.5 Hz steps, widened by the margin so that tongues just outside count
    grid = np.linspace(low - margin_hz, high + margin_hz,
                       int(round(2 * (high - low + 2 * margin_hz))) + 1)

    def windows_of(param_sets):
        boundary = kernel.window_boundary(param_sets, grid, min_growth,
                                          p_search)
        return kernel.safe_windows(grid, boundary, operating)
    safe, windows = windows_of(sets)
    order = kernel.ranking(values, names, operating, min_growth, p_search)
    found = advised_windows = verification = judder_points = None
    if design:
        found = kernel.advise_design(sets, names, weights, operating,
                                     min_growth, p_search, callback=progress)
        if found.success:
            factors = dict(zip(found.names, found.factors))
            advised = [p.replace(**{n: p[n] * factors[n] for n in names})
                       for p in sets]
            _, advised_windows = windows_of(advised)
            verification, judder_points = kernel.verify_design(
                advised[0], operating, min_growth)
    return AdviceResult(
        params=values, operating=operating, min_growth=min_growth,
        sets=len(sets), freq_hz=grid, safe_p_f=safe, windows=windows,
        ranking=order, advice=found, advised_windows=advised_windows or [],
        verification=verification, judder_points=judder_points,
        seconds=time.perf_counter() - started)


def report(parameters=None, changes=None, **options):
    """``judder report``: the paper's figure set and tables for one
    driveline in one self-contained HTML file; the options are those of
    :func:`judder.report.build_report` (dither setting, bench data,
    grids).

    Returns
    -------
    judder.report.ReportResult
        ``save(path)`` writes the HTML.
    """
    from .report import build_report
    return build_report(parameters, changes, **options)


def envelope(ranges, freq_hz, p_max_bar=1.5, samples=256, seed=0,
             sampler="sobol", vertices=True, min_growth=None, refine=20,
             parameters=None, changes=None, method=DEFAULT_METHOD,
             workers=None, checkpoint=None, progress=None):
    """``judder envelope``: the broadest unstable region over uncertain
    parameters and the probability of instability (section 4.2, Fig. 16).

    Parameters
    ----------
    ranges : path or stability.ranges.Ranges
        A ranges file (:func:`judder.envelope.read_ranges`) or the ranges.
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max_bar : float
        Largest amplitude searched, bar.
    samples, seed, sampler, vertices
        Space-filling samples after the vertices, as
        :func:`stability.ranges.design_points` takes them.
    min_growth : float, optional
        1/s: count only judder growing at least this fast (default
        :data:`stability.relevance.DEFAULT_MIN_GROWTH_PER_S`; 0: every
        instability).
    refine : int
        Boundary evaluations per uncertain parameter spent at each
        frequency searching the lowest boundary between the samples
        (:func:`stability.envelope.refine_at`); 0: the union of the
        samples only.
    workers : int, optional
        Local Dask worker processes (see :mod:`infra.parallel`).
    checkpoint : path, optional
        Resume from / save to this NPZ (see
        :func:`judder.envelope.run_envelope`).

    Returns
    -------
    judder.results.EnvelopeResult
        ``failures`` lists the samples that failed (left out).
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.uncertainty.ranges import Ranges
    from .envelope import read_ranges, run_envelope
    values = _resolve(parameters, changes)
    if not isinstance(ranges, Ranges):
        ranges = read_ranges(ranges, values)
    growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    if not np.isfinite(growth) or growth < 0:
        raise JudderError(f"--min-growth {growth!r} 1/s is not allowed; "
                          "allowed: a finite rate >= 0")
    started = time.perf_counter()
    result, failures, resumed = run_envelope(
        values, ranges, freq_hz, p_max_bar * PA_PER_BAR, samples=samples,
        seed=seed, sampler=sampler, vertices=vertices, method=method,
        min_growth=growth, amplitudes=BACKGROUND_AMPLITUDES, refine=refine,
        workers=workers, checkpoint=checkpoint, progress=progress)
    return EnvelopeResult(params=values, ranges=ranges, envelope=result,
                          failures=failures, resumed=resumed,
                          seconds=time.perf_counter() - started,
                          checkpoint=checkpoint)
