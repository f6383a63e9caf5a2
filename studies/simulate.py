"""``judder simulate``: a held-slip bench run or a full engagement with
dither (Fig. 7, 8), run through the FMU.
"""

from dataclasses import dataclass, field
import math

import numpy as np

from infra.criteria import (DEFAULT_JUDDER_LIMIT_RPM, DEFAULT_MIN_GROWTH_PER_S,
                            JUDDER)
from infra.errors import JudderError
from infra.files import keeps_foreign_files
from infra.units import PA_PER_BAR
from sources.dither_modes import check_modes
from stability import floquet as floquet_kernel
from stability.bench import (added_damping, bench_parameters, check_bench,
                             engagement_model, linear_validity,
                             linearisation_at, operating_friction)
from stability.monodromy import DEFAULT_METHOD
from stability.source import build_driveline

from ._common import checked_values
from .bench import bench_fmu, refuse_bench_of_class

#: The bench's friction laws, as each output names them.
CURVE_LAW = "curve (mu0, mu_g at w_op, delta_mu)"


LINEAR_LAW = "straight line, Eq. 5"


#: Runs of the bench, by ``--engagement``: the class of the library each
#: runs (None: the driveline's own held-slip bench,
#: :attr:`drivelines.DrivelineModel.bench_class`), the kind of run
#: (``held_slip``: held at a steady slip, never engaging; ``engagement``:
#: the gearbox side brought up to lock-up) and its EVEN clutch's friction
#: law. ``full`` runs the held-slip bench's law (its mu0, mu_g, delta_mu,
#: w_op); ``full-linear-law`` the straight line over the whole slip.
ENGAGEMENTS = {"steady": None,
               "full": "Judder.Examples.TestBenchCurveLockUp",
               "full-linear-law": "Judder.Examples.TestBenchLockUp"}


RUN_KINDS = {"steady": "held_slip", "full": "engagement",
             "full-linear-law": "engagement"}


FRICTION_LAWS = {"steady": CURVE_LAW, "full": CURVE_LAW,
                 "full-linear-law": LINEAR_LAW}


def simulate(freq_hz, p_f_bar, duration=None, compare=None, bench=None,
             parameters=None, changes=None, method=DEFAULT_METHOD,
             min_growth=DEFAULT_MIN_GROWTH_PER_S,
             judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM, engagement="steady"):
    """``judder simulate``: a held-slip bench run (the default) or a full
    engagement on the driveline's bench model (Fig. 7, 8), run through
    its FMU, with the Floquet verdict of each dither setting for the
    bench's linearisation (the damping its motor control adds,
    :attr:`drivelines.DrivelineModel.bench_damping`).

    A Modelica class (:class:`sources.modelica.ModelicaParameters`)
    runs instead through its own FMU (the one ``crosscheck`` runs, see
    :mod:`studies.timedomain`) from its start values, a steady slip, with
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
        Also run the same kind of run: ``'none'`` without dither, a number
        with dither at that frequency (Hz).
    bench : dict, optional
        Further parameters of the bench model (``w_motor``, ...), SI; not
        for a Modelica class (its parameters are ``changes``).
    min_growth : float
        Growth rate from which an instability is judder, 1/s.
    judder_limit_rpm : float
        NVH limit of the dither-related oscillation of the upstream
        speed, rpm: larger is judder, forced or parametric.
    engagement : {'steady', 'full', 'full-linear-law'}
        ``'steady'``: the held-slip bench run (the EVEN clutch held at a
        steady slip with the bench's friction curve; it never engages).
        ``'full'``: the engagement that ends in lock-up
        (``TestBenchCurveLockUp``: the gearbox side from rest, the EVEN
        clutch with the held-slip bench's friction curve, locking by
        events); ``'full-linear-law'``: the same engagement with the
        straight line of Eq. 5 over the whole slip (``TestBenchLockUp``),
        another friction law. The linearisation of either takes the
        driveline's own ``mu0`` and ``mu_g`` (the curve's value and slope
        at w_op, which the engagement passes; the straight line's at
        every slip); each summary adds ``lock_up_time_s`` (None: it slips
        at the end), ``lockups``, ``slip_at_ramp_end_rad_s`` and
        ``duration_s``, and its verdict and spectra are those of the run
        before the lock-up.

    Returns
    -------
    SimulationResult
    """
    from drivelines.registry import SIGNALS
    from fmu.store import parameter_default
    from pysim.bench.engagement import (LOCK_VARIABLES,
                                             engagement_summary, lock_up,
                                             until)
    from pysim.simulation.runs import run_fmu

    from .timedomain import class_fmu, run_values
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_f_bar=p_f_bar, min_growth=min_growth,
                            judder_limit_rpm=judder_limit_rpm)
    if engagement not in ENGAGEMENTS:
        raise JudderError(f"`engagement` {engagement!r} is not allowed; "
                          f"allowed: {', '.join(ENGAGEMENTS)}")
    bench = dict(bench or {})
    full = RUN_KINDS[engagement] == "engagement"
    if full and not values.source_kind.is_chain:
        bench_fmu(values)       # refuses a class or FMU, naming the bench
    if full and values.friction is not None:
        raise JudderError(f"`engagement` {engagement} is not allowed with "
                          f"the {values.friction.words()}; allowed: steady "
                          "(the held-slip bench reads the table; the "
                          "engagements to lock-up run the bench's curve or "
                          "the straight line)")
    if values.source_kind.is_chain:
        bench = check_bench(values, bench)
        model_class, fmu = bench_fmu(values)
        if full:
            from fmu.store import ensure_fmu
            model_class = ENGAGEMENTS[engagement]
            fmu = ensure_fmu(model_class)
        ramp_end = sum(bench.get(name, parameter_default(fmu, name))
                       for name in ("t_engage", "t_ramp"))
        run_params, extra = values, dict(bench)
        if values.friction is not None:
            extra.update(values.friction.start_values())
        # the bench's linearisation: its motor control damps body 1, and
        # its friction curve has its own value and slope at the slip
        # (a full engagement sweeps the slip: it is linearised where its
        # law has the driveline's own mu0 and mu_g, the curve at w_op, the
        # straight line of Eq. 5 at every slip)
        friction, linear_slip = ((({}, None)) if full else
                                 operating_friction(values, bench))
        driveline = build_driveline(values.replace(
            **{name: values[name] + value for name, value in
               added_damping(values, bench).items()}, **friction))
        orbit_model = None if full else engagement_model(
            values, bench, duration)[0]
    else:
        fmu = class_fmu(values, "simulate")
        if bench:
            refuse_bench_of_class(values, bench)
        model_class, ramp_end = values.model, 0.0   # starts slipping
        run_params, extra = run_values(values)
        driveline, linear_slip = build_driveline(values), None
        orbit_model = None
    if duration is not None and duration <= ramp_end:
        raise JudderError(f"duration {duration:g} s ends before the "
                          f"engagement (its pressure ramp ends at "
                          f"{ramp_end:g} s); allowed: > {ramp_end:g} s")
    if duration is None and ramp_end >= _stop_time(fmu):
        raise JudderError(
            f"`bench` t_engage + t_ramp = {ramp_end:g} s ends after the "
            f"run ({_stop_time(fmu):g} s, the model's StopTime); allowed: "
            f"t_engage + t_ramp < {_stop_time(fmu):g} s, or a `duration` "
            f"> {ramp_end:g} s")
    freqs = [float(f) for f in np.atleast_1d(freq_hz)]
    settings = ([("with dither" if p_f_bar > 0 else "without dither",
                  freqs[0], p_f_bar * PA_PER_BAR)]
                if len(freqs) == 1 else
                [(f"dither at {f:g} Hz", f, p_f_bar * PA_PER_BAR)
                 for f in freqs])
    freq_hz = freqs[0]
    if compare is not None:
        settings.append(("without dither", freq_hz, 0.0)
                        if compare == "none" else
                        (f"dither at {float(compare):g} Hz", float(compare),
                         p_f_bar * PA_PER_BAR))
    # each run's Floquet verdict is the linearisation's, in one mode
    check_modes(values, [f for _, f, _ in settings],
                [p for _, _, p in settings])
    interval = min(1e-3, 1.0 / (20 * max(f for _, f, _ in settings)))
    runs = [(label, run_fmu(fmu, freq, p_f, params=run_params, extra=extra,
                            duration=duration, output_interval=interval,
                            variables=LOCK_VARIABLES if full else ()))
            for label, freq, p_f in settings]
    summaries, slipping, paths = [], [], []
    # the bench's load clutch takes less than the EVEN clutch's torque:
    # the slip falls, and the run is an engagement judged by its envelope
    falling = (values.source_kind.is_chain and not full and bench.get(
        "load_share", bench_parameters(values)["load_share"].default) < 1)
    linearised = (None if not values.source_kind.is_chain else
                  (lambda slip: driveline)
                  if FRICTION_LAWS[engagement] == LINEAR_LAW else
                  linearisation_at(values, bench))
    for label, run in runs:
        lock = lock_up(run) if full else None
        slipping.append(until(run, lock))
        paths.append(_path(linearised, slipping[-1], ramp_end))
        linear = floquet_kernel(driveline, run.freq_hz, run.p_f,
                                method=method)
        summaries.append({"label": label,
                          **engagement_summary(slipping[-1], ramp_end,
                                               min_growth, judder_limit_rpm),
                          **(_lock_fields(run, lock, ramp_end) if full
                             else {}),
                          "floquet_kind": linear.kind,
                          "floquet_exponent_per_s": linear.growth_rate,
                          **linear_validity(driveline, run, linear_slip),
                          **_orbit_fields(orbit_model, run, min_growth,
                                          judder_limit_rpm),
                          **_path_fields(paths[-1], min_growth)})
        _judge_burst(summaries[-1], slipping[-1], ramp_end,
                     paths[-1] if falling else None, judder_limit_rpm)
    run_kind, friction_law = ((RUN_KINDS[engagement] if not falling
                               else "falling_slip",
                               FRICTION_LAWS[engagement]
                               if values.friction is None else
                               values.friction.words())
                              if values.source_kind.is_chain else
                              ("class", "the class's own"))
    return SimulationResult(runs=runs, summaries=summaries, fmu=fmu,
                            model_class=model_class, start=ramp_end,
                            asked=len(freqs),
                            run_kind=run_kind, friction_law=friction_law,
                            paths=paths, min_growth=min_growth,
                            # (the lock counters are counts: unit 1)
                            signals={**SIGNALS, **dict.fromkeys(
                                LOCK_VARIABLES if full else (), "1")},
                            slipping=slipping if full else None)


def _stop_time(fmu):
    """The run's length when no ``duration`` is given: the model's
    StopTime, s (inf where it declares none)."""
    from fmu.store import model_description
    experiment = model_description(fmu).defaultExperiment
    stop = None if experiment is None else experiment.stopTime
    return math.inf if stop is None else float(stop)


def _lock_fields(run, lock, ramp_end):
    """How a full engagement ends: its lock-up time (s, None: none), the
    lock-ups that broke away, the slip at the ramp's end (rad/s), the
    run's length and its last slip."""
    at_ramp_end = int(np.searchsorted(run.time, ramp_end))
    return {"lock_up_time_s": lock,
            "lockups": int(round(run["clutch.lockups"][-1]))
            - (lock is not None),
            "slip_at_ramp_end_rad_s": float(run["slip"][at_ramp_end]),
            "duration_s": float(run.time[-1]),
            "final_slip_rad_s": float(run["slip"][-1])}


def _orbit_fields(model, run, min_growth, judder_limit_rpm):
    """The periodic orbit of the bench at the run's setting
    (:mod:`stability.orbit`; in a combination tongue the motion
    integrated until settled, :mod:`stability.settle`), what the
    engagement settles into: its
    settled amplitude (rpm), kind, growth (1/s) and judder mechanism, as
    ``orbit_*`` fields (None for a model without the bench, or without
    dither)."""
    names = ("orbit_settled_rpm", "orbit_kind", "orbit_growth_per_s",
             "orbit_mechanism")
    if model is None or run.p_f == 0:
        return dict.fromkeys(names)
    from stability.orbit import periodic_orbit
    from stability.orbit_chart import held_slip_motion

    from .orbit import orbit_row, settled_motions
    found = periodic_orbit(model, run.freq_hz, run.p_f)
    quasi = settled_motions(model, [found])[0]
    found, doubled = held_slip_motion(model, found)
    row = orbit_row(found, doubled, judder_limit_rpm, min_growth, quasi)
    return dict(zip(names, (row["settled_rpm"], row["kind"],
                            row["growth_per_s"], row["mechanism"])))


#: Window over which the run's slip is averaged for its path through the
#: map, s: longer than the slowest mode's period (16.5 Hz on the bench),
#: short against an engagement.
PATH_WINDOW_S = 0.1


def _path(linearised, run, start):
    """The run's path through the map after ``start`` (the end of the
    pressure ramp): the quasi-static Floquet exponent along its mean slip
    (:func:`stability.engagement_path.engagement_path`), sampled every 2
    ms; None without dither, without a bench linearisation, or without
    a slipping part after ``start``."""
    from stability.engagement_path import engagement_path, mean_slip
    after = run.time >= start
    if linearised is None or run.p_f == 0 or after.sum() < 2:
        return None
    time = run.time[after]
    slip = mean_slip(run.time, run["slip"], 1.0 / PATH_WINDOW_S)[after]
    samples = np.arange(time[0], time[-1], 2e-3)
    return engagement_path(linearised, run.freq_hz, run.p_f, samples,
                           np.interp(samples, time, slip))


def _path_fields(path, min_growth):
    """The path's summary as ``path_*`` fields: the mean slip at its
    start and end (rad/s), its largest exponent (1/s), the e-folds it
    accumulates and the predicted amplitude gain over the whole run, and
    each span in which it grows faster than ``min_growth`` (start and
    stop s, slips, kind, e-folds)."""
    names = ("path_slip_start_rad_s", "path_slip_end_rad_s",
             "path_max_growth_per_s", "path_efolds", "path_gain",
             "path_spans")
    if path is None:
        return dict.fromkeys(names)
    spans = [dict(zip(("start_s", "stop_s", "slip_start_rad_s",
                       "slip_stop_rad_s", "kind", "efolds"), span))
             for span in path.spans(min_growth)]
    return dict(zip(names, (float(path.slip[0]), float(path.slip[-1]),
                            float(path.growth_per_s.max()),
                            float(path.accumulated[-1]), path.gain(),
                            spans)))


#: Window (s) and step of the envelope a run whose slip moves is judged
#: by: 12 periods of the bench's 103 Hz mode, short against a burst.
ENVELOPE_WINDOW_S, ENVELOPE_STEP_S = 0.12, 0.02
def _judge_burst(summary, run, start, path, limit_rpm):
    """Judge a run whose slip falls by the envelope of its upstream
    speed, in place: the largest amplitude at the dither-related
    frequencies (f, f/2 and the spectrum's peak) in windows sliding over
    the run (:func:`infra.spectrum.sliding_amplitude`), where and when it
    is above the limit. A burst the whole run's spectrum averages below
    the limit (a tongue crossed for a few tenths of a second) is judder
    of the engagement: ``judder`` True, ``oscillation_rpm`` the burst's
    peak (the spectrum's in ``spectrum_oscillation_rpm``), its mechanism
    from the burst's frequency (f/2: double-period, another than f:
    combination, parametric; f: forced). Adds ``envelope_peak_rpm``,
    ``envelope_peak_s``, ``envelope_peak_hz``, ``envelope_peak_slip_rad_s``
    and ``judder_from_s``/``judder_to_s`` (None for a held slip: ``path``
    None)."""
    names = ("envelope_peak_rpm", "envelope_peak_s", "envelope_peak_hz",
             "envelope_peak_slip_rad_s", "judder_from_s", "judder_to_s")
    summary.update(dict.fromkeys(names))
    if path is None:
        return
    from infra.spectrum import sliding_amplitude
    from infra.units import RPM_PER_RAD_S
    after = run.time >= start
    if run.time[after][-1] - run.time[after][0] < 2 * ENVELOPE_WINDOW_S:
        return
    freqs = sorted({run.freq_hz, run.freq_hz / 2,
                    summary["speed_peak_freq_hz"]})
    centres, amplitudes = sliding_amplitude(
        run.time[after], run["w_upstream"][after] * RPM_PER_RAD_S, freqs,
        ENVELOPE_WINDOW_S, ENVELOPE_STEP_S)
    envelope = amplitudes.max(axis=1)
    peak = int(np.argmax(envelope))
    at = float(centres[peak])
    frequency = freqs[int(np.argmax(amplitudes[peak]))]
    above = centres[envelope > limit_rpm]
    summary.update(dict(zip(names, (
        float(envelope[peak]), at, frequency,
        float(np.interp(at, path.time, path.slip)),
        float(above[0]) if len(above) else None,
        float(above[-1]) if len(above) else None))))
    if len(above) and not summary["judder"]:
        kind = ("double-period" if frequency == run.freq_hz / 2 else
                "single-period" if frequency == run.freq_hz else
                "combination")
        # the oscillation compared with the limit is the burst's; the
        # whole run's spectrum is kept beside it
        summary.update(judder=True, verdict=JUDDER,
                       spectrum_oscillation_rpm=summary["oscillation_rpm"],
                       oscillation_rpm=float(envelope[peak]),
                       mechanism="forced" if kind == "single-period" and
                       float(np.interp(at, path.time, path.growth_per_s))
                       <= 0 else "parametric",
                       judder_kind=kind, judder_in_burst=True)


@dataclass(frozen=True)
class SimulationResult:
    """``judder simulate``: held-slip bench runs or full engagements
    through the FMU.

    Attributes
    ----------
    runs : list of (str, pysim.simulation.runs.Run)
        Labelled runs: the setting asked for first, then the comparison.
    summaries : list of dict
        Per run, :func:`pysim.bench.engagement.engagement_summary` plus its
        ``label`` and the Floquet verdict of its dither setting
        (``floquet_kind``, ``floquet_exponent_per_s``).
    fmu : path
    model_class : str
    start : float
        End of the pressure ramp, s.
    run_kind : {'held_slip', 'falling_slip', 'engagement', 'class'}
        What ran: the bench held at a steady slip (never engaging), the
        bench whose slip falls (``load_share`` below 1), an engagement
        brought up to lock-up, or a Modelica class from its start
        values.
    friction_law : str
        The EVEN clutch's friction law (:data:`CURVE_LAW`,
        :data:`LINEAR_LAW`, or the class's own).
    slipping : list of Run, optional
        Of a full engagement, each run before its lock-up (what its
        verdict and spectra read).
    paths : list of stability.engagement_path.EngagementPath or None
        Per run, its path through the map (None without dither or bench).
    min_growth : float
        1/s, the growth the paths' spans are judged by.
    asked : int
        How many of ``runs`` are the dither settings asked for (the
        first ones; the comparison follows).
    """

    runs: list
    summaries: list
    fmu: object
    model_class: str
    start: float
    run_kind: str = "held_slip"
    friction_law: str = CURVE_LAW
    signals: dict = field(default_factory=dict)
    slipping: list = None
    asked: int = 1
    paths: list = None
    min_growth: float = None

    def as_dict(self):
        return {"model": self.model_class.rsplit(".", 1)[-1],
                "run_kind": self.run_kind,
                "friction_law": self.friction_law,
                "fmu": str(self.fmu), "runs": self.summaries}

    @keeps_foreign_files
    def save(self, path, run=None):
        """Time histories of one run as CSV or MF4 (by suffix): ``run``
        (an index of ``runs``), or the only setting asked for (the
        comparison is not written); several settings without ``run``
        are refused rather than one written for all."""
        from pysim.simulation.export import write_run
        if run is None:
            if self.asked > 1:
                raise JudderError(
                    f"{path} holds the time histories of one run; "
                    f"`freq_hz` gave {self.asked} runs ("
                    + ", ".join(f"{r.freq_hz:g}" for _, r in
                                self.runs[:self.asked])
                    + " Hz); allowed: one `freq_hz`, or `run` naming "
                      "which to write")
            run = 0
        if not 0 <= run < len(self.runs):
            raise JudderError(f"`run` {run!r} is not a run; allowed: 0 to "
                              f"{len(self.runs) - 1}")
        run = self.runs[run][1]
        write_run(path, run.time, run.signals, self.signals,
                  {"model": self.model_class, "run_kind": self.run_kind,
                   "friction_law": self.friction_law,
                   "freq_hz": run.freq_hz,
                   "p_f_bar": run.p_f / PA_PER_BAR,
                   "start_values": run.start_values})

    def spectra(self):
        """The ``(speed, pressure)`` amplitude spectra of each run after
        ``start`` (:func:`pysim.bench.engagement.display_spectra`), as
        ``--plot`` draws them."""
        from pysim.bench.engagement import display_spectra
        runs = self.slipping or [run for _, run in self.runs]
        return [display_spectra(run, self.start) for run in runs]

    def figure(self, title=None, only=None):
        """The runs' time histories and spectra, one column each; with
        ``only`` (an index of ``runs``) that run's column alone (6.5 in
        wide: a page's width, as in the report)."""
        from pysim.bench.engagement import verdict_line
        from pysim.bench.run_plots import run_figure
        shown = range(len(self.runs)) if only is None else [only]
        spectra = self.spectra()
        return run_figure([self.runs[i] for i in shown],
                          [spectra[i] for i in shown], title=title,
                          verdicts=[verdict_line(self.summaries[i])
                                    for i in shown],
                          lock_ups=[self.summaries[i].get("lock_up_time_s")
                                    for i in shown],
                          # a held slip's path is one point of the map:
                          # the row is drawn where the slip falls
                          paths=None if self.run_kind != "falling_slip"
                          else [_path_curves(self.paths[i]) for i in shown],
                          min_growth=self.min_growth)


def _path_curves(path):
    """``(time s, exponent 1/s, mean slip rad/s)`` of a path, for the
    run figure (None without one)."""
    return None if path is None else (path.time, path.growth_per_s,
                                      path.slip)
