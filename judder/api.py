"""The Python API: one function per ``judder`` command.

Each function takes SI parameter sets and the units of the command line
(dither frequency in Hz, amplitude in bar), runs the kernels of
:mod:`stability` and :mod:`pysim`, and returns a result object of
:mod:`judder.results` (``as_dict()``, ``save()``, ``figure()``). The
command line calls these functions and only formats what they return.

Every function takes the parameter set as ``params`` (a
:class:`drivelines.Parameters`; default: the paper preset of the default
driveline, see :func:`judder.inputs.load_parameters` for files) and
``changes``, the values the user set explicitly (``--set``), applied on
top. Monodromy engines (``method``) are the keys of
:data:`stability.monodromy.METHODS`. ``progress`` is called as
``progress(done, total)`` on long work.

Examples
--------
>>> from judder import api
>>> result = api.floquet(102.9, 0.3)
>>> result.result.kind, round(result.result.leading_abs, 4)
('single-period', 1.0261)
"""

import time
from pathlib import Path

import numpy as np

from drivelines import DEFAULT_MODEL, default_preset, get_preset
from drivelines.specs import MEAN_PRESSURE_DAMPING
from infra.errors import JudderError
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
                      TonguesResult)

__all__ = ["params", "eig", "floquet", "stability_map", "tongues",
           "sensitivity", "threshold", "fit", "simulate", "crosscheck",
           "campaign", "chart", "envelope", "BACKGROUND_AMPLITUDES"]

#: Amplitudes of the map drawn under tongue boundaries (0 to p_max).
BACKGROUND_AMPLITUDES = 150


def _resolve(parameters, changes):
    """``parameters`` (default preset if None) with ``changes`` applied."""
    base = parameters if parameters is not None else \
        get_preset(default_preset(DEFAULT_MODEL))
    return base.replace(**(changes or {}))


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
    return EigResult(
        params=values,
        natural_frequencies_hz=modal.natural_frequencies(driveline),
        closed_form_frequencies_hz=modal.closed_form_frequencies(values),
        damping_factor_12=float(modal.clutch_damper_damping_factor(values)),
        damped_frequencies_hz=damped_hz, damping_ratio=ratio)


def floquet(freq_hz, p_f_bar, parameters=None, changes=None,
            method=DEFAULT_METHOD):
    """``judder floquet``: Floquet multipliers at one dither setting
    (Eq. 10-13), rigid-body angles removed.

    Parameters
    ----------
    freq_hz : float
        Dither frequency, Hz.
    p_f_bar : float
        Dither amplitude, bar.

    Returns
    -------
    judder.results.FloquetPoint
    """
    values = _resolve(parameters, changes)
    result = floquet_kernel(build_driveline(values), freq_hz,
                            p_f_bar * PA_PER_BAR, method=method)
    return FloquetPoint(params=values, method=method, result=result)


def stability_map(freq_hz, p_f_bar, parameters=None, changes=None,
                  method=DEFAULT_METHOD, progress=None):
    """``judder map``: leading multiplier on a frequency x amplitude grid
    (Fig. 12, Fig. 14).

    Parameters
    ----------
    freq_hz : array_like
        Dither frequencies, Hz.
    p_f_bar : array_like
        Dither amplitudes, bar.

    Returns
    -------
    judder.results.MapResult
        ``save(path)`` writes NPZ, ``figure()`` draws it.
    """
    values = _resolve(parameters, changes)
    result, seconds = _timed(
        map_kernel, build_driveline(values), freq_hz,
        np.asarray(p_f_bar, dtype=float) * PA_PER_BAR, method=method,
        callback=progress)
    return MapResult(params=values, map=result, seconds=seconds)


def tongues(freq_hz, p_max_bar=1.5, parameters=None, changes=None,
            method=DEFAULT_METHOD, background=False, progress=None,
            min_growth=0.0):
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

    Returns
    -------
    judder.results.TonguesResult
    """
    from stability.tongues import find_tongues, tongue_boundaries
    values = _resolve(parameters, changes)
    driveline = build_driveline(values)
    p_max = p_max_bar * PA_PER_BAR
    started = time.perf_counter()
    boundaries = tongue_boundaries(driveline, freq_hz, p_max, method,
                                   callback=progress, min_growth=min_growth)
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
                   if nominal.driveline.paper_sensitivity else [])
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
    changes.setdefault(MEAN_PRESSURE_DAMPING, 1.0)
    values = _resolve(parameters, changes)
    study = threshold_study(values, mu_g, c_ext, callback=progress)
    return ThresholdResult(params=values, study=study)


def fit(freq_hz, measured_p_f_bar, p_max_bar=1.5, names=None, bounds=None,
        parameters=None, changes=None, method=DEFAULT_METHOD, kinds=None,
        starts=3, uncertainty="auto", error_model="absolute", seed=0,
        workers=None, progress=None):
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
    kinds, starts, uncertainty, error_model, seed, workers
        As :func:`stability.fitting.fit_boundary` takes them.

    Returns
    -------
    judder.results.FitReport
        ``fit.success`` is False when any of ``fit.problems`` holds (no
        convergence, a parameter on a bound or undetermined, another
        minimum as good).
    """
    from stability.fitting import DEFAULT_FIT, fit_boundary
    start = _resolve(parameters, changes)
    result, seconds = _timed(
        fit_boundary, start, freq_hz,
        np.asarray(measured_p_f_bar, dtype=float) * PA_PER_BAR,
        p_max_bar * PA_PER_BAR, names=names or DEFAULT_FIT, bounds=bounds,
        method=method, kinds=kinds, starts=starts, uncertainty=uncertainty,
        error_model=error_model, seed=seed, workers=workers,
        callback=progress)
    return FitReport(fit=result, seconds=seconds, method=method)


def simulate(freq_hz, p_f_bar, duration=None, compare=None, bench=None,
             parameters=None, changes=None, method=DEFAULT_METHOD):
    """``judder simulate``: an engagement on the driveline's bench model
    (Fig. 7, 8), run through its FMU, with the Floquet verdict of each
    dither setting for the bench's linearisation (the damping its motor
    control adds, :attr:`drivelines.DrivelineModel.bench_damping`).

    Parameters
    ----------
    freq_hz, p_f_bar : float
        Dither setting, Hz and bar.
    duration : float, optional
        Simulated time, s (default: the model's).
    compare : 'none' or float, optional
        Also run a correct engagement: ``'none'`` without dither, a number
        with dither at that frequency (Hz).
    bench : dict, optional
        Further parameters of the bench model (``w_motor``, ...), SI.

    Returns
    -------
    judder.results.SimulationResult
    """
    from pysim.engagement import engagement_summary
    from pysim.fmus import ensure_fmu
    from pysim.runs import parameter_default, run_fmu
    values = _resolve(parameters, changes)
    model_class = values.driveline.bench_class
    if model_class is None:
        raise JudderError(f"the {values.model} driveline has no bench "
                          "engagement model; give a parameter set of a "
                          "driveline that has one (4-DOF)")
    bench = dict(bench or {})
    fmu = ensure_fmu(model_class)
    interval = min(1e-3, 1.0 / (20 * freq_hz))
    settings = [("with dither", freq_hz, p_f_bar * PA_PER_BAR)]
    if compare is not None:
        settings.append(("without dither", freq_hz, 0.0)
                        if compare == "none" else
                        (f"dither at {float(compare):g} Hz", float(compare),
                         p_f_bar * PA_PER_BAR))
    runs = [(label, run_fmu(fmu, freq, p_f, params=values, extra=bench,
                            duration=duration, output_interval=interval))
            for label, freq, p_f in settings]
    def bench_value(name):
        return bench.get(name, parameter_default(fmu, name))
    start = bench_value("t_engage") + bench_value("t_ramp")
    # the bench's linearisation: its motor control damps body 1
    driveline = build_driveline(values.replace(**{
        name: values[name] + bench_value(added)
        for name, added in values.driveline.bench_damping}))
    summaries = []
    for label, run in runs:
        linear = floquet_kernel(driveline, run.freq_hz, run.p_f,
                                method=method)
        summaries.append({"label": label,
                          **engagement_summary(run, start),
                          "floquet_kind": linear.kind,
                          "floquet_exponent_per_s": linear.growth_rate})
    return SimulationResult(runs=runs, summaries=summaries, fmu=fmu,
                            model_class=model_class, start=start,
                            signals=dict(values.driveline.signals))


def crosscheck(freq_hz, p_f_bar, duration=3.0, parameters=None,
               changes=None, method=DEFAULT_METHOD, workers=None,
               progress=None):
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

    Returns
    -------
    judder.results.CrosscheckResult
    """
    from .crosscheck import crosscheck as crosscheck_study
    values = _resolve(parameters, changes)
    check, seconds = _timed(
        crosscheck_study, values, freq_hz,
        np.asarray(p_f_bar, dtype=float) * PA_PER_BAR, duration=duration,
        method=method, workers=workers, callback=progress)
    return CrosscheckResult(params=values, check=check, seconds=seconds,
                            method=method)


def campaign(folder, freq_hz, p_f_bar, engine_rpm=(1000.0,),
             temperatures=("65-70",), duration=1.5, noise_rpm=0.5, seed=1,
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
    from stability.ranges import Ranges
    from stability.relevance import DEFAULT_MIN_GROWTH_PER_S
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
