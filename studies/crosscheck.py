"""Time-domain growth against Floquet exponents on a grid: the two views.

This study holds the two libraries against each other (``pysim`` runs the
FMU, ``stability`` gives the exponent), so it lives in the application
layer. For each (frequency, amplitude) point the driveline's FMU (Eq. 1,
``SlippingClutch``: linear) is run twice, the second time with the initial
speed ``w_in`` raised by :data:`SPEED_STEP`. The difference of the two
runs is the free response (the forced response cancels), and its growth
rate is fitted (:func:`pysim.bench.signals.free_response_growth`); the
Floquet exponent ``ln|lambda| / T`` of the same point comes from the
stability layer. The two verdicts and rates are compared, and every
disagreement gets a reason.
"""

from dataclasses import dataclass

import numpy as np

from fmu.store import parameter_default
from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.parallel import parallel_map
from infra.units import PA_PER_BAR
from pysim.bench.signals import free_response_growth
from pysim.simulation.runs import run_fmu
from sources.dither_modes import check_modes
from stability.monodromy import DEFAULT_METHOD, get_method
from stability.multipliers import floquet
from stability.source import build_driveline

from ._common import checked_values, timed
from ._records import rows_to_csv
from .timedomain import class_fmu, run_values

__all__ = ["CrosscheckPoint", "Crosscheck", "crosscheck_study"]

#: Samples per dither period in the runs.
SAMPLES_PER_PERIOD = 16
#: Change of the initial speed between the two runs of a point, rad/s.
SPEED_STEP = 1.0


@dataclass(frozen=True)
class CrosscheckPoint:
    """One grid point.

    ``floquet_rate`` and ``fitted_rate`` are in 1/s; ``reason`` is empty
    when the verdicts agree.
    """

    freq_hz: float
    p_f: float
    floquet_rate: float
    floquet_kind: str
    fitted_rate: float
    fitted_stderr: float
    floquet_unstable: bool
    time_unstable: bool
    agree: bool
    reason: str

    @property
    def rate_error(self):
        """Relative difference of the rates, where the exponent > 0."""
        if self.floquet_rate <= 0:
            return None
        return abs(self.fitted_rate - self.floquet_rate) / self.floquet_rate


@dataclass(frozen=True)
class Crosscheck:
    """All points of a cross-check.

    Attributes
    ----------
    points : list of CrosscheckPoint
    duration : float
        Length of each run, s.
    """

    points: list
    duration: float

    @property
    def agreement(self):
        """Share of points whose stable/unstable verdicts agree."""
        return float(np.mean([p.agree for p in self.points]))

    def max_rate_error(self, above=1.0):
        """Largest relative rate difference where the exponent > ``above``."""
        errors = [p.rate_error for p in self.points
                  if p.floquet_rate > above]
        return max(errors) if errors else None


def _verdict(fit):
    """Time-domain verdict: the free response grows."""
    return fit.rate > 0


def _reason(point_rate, fit, duration):
    if abs(point_rate) < 1.0 / duration:
        return (f"near the boundary: exponent {point_rate:+.3f} 1/s is below "
                f"what a {duration:g} s run resolves (1/duration)")
    if fit.stderr > 1e-3:
        return (f"the one-step fit leaves {fit.stderr:.1e} of the response "
                "unexplained: not linear, or too few periods")
    return "transient too short for the leading mode to dominate"


def _point(job):
    params, fmu_path, freq, p_f, duration, method, speeds, perturb = job
    period = 1.0 / freq
    run_params, base = run_values(params)
    perturbed = {perturb: (base[perturb] if perturb in base else
                           parameter_default(fmu_path, perturb))
                 + SPEED_STEP}
    runs = [run_fmu(fmu_path, freq, p_f, params=run_params,
                    duration=duration,
                    output_interval=period / SAMPLES_PER_PERIOD,
                    variables=speeds, extra={**base, **extra})
            for extra in ({}, perturbed)]
    fit = free_response_growth(
        runs[0].time, [runs[1][s] - runs[0][s] for s in speeds], period)
    result = floquet(build_driveline(params), freq, p_f, method=method)
    floquet_unstable = result.leading_abs > 1.0
    time_unstable = _verdict(fit)
    agree = floquet_unstable == time_unstable
    return CrosscheckPoint(
        freq_hz=float(freq), p_f=float(p_f), floquet_rate=result.growth_rate,
        floquet_kind=result.kind, fitted_rate=fit.rate,
        fitted_stderr=fit.stderr, floquet_unstable=bool(floquet_unstable),
        time_unstable=bool(time_unstable), agree=bool(agree),
        reason="" if agree else _reason(result.growth_rate, fit, duration))


def _fmu_and_speeds(params, perturb):
    """The FMU to run and the speeds whose difference is the free response.

    A registry driveline names the speeds; of a Modelica class
    (:class:`sources.modelica.ModelicaParameters`) every state in rad/s
    is recorded. An FMU of ``--fmu`` is refused (:func:`class_fmu`).
    """
    fmu_path = class_fmu(params, "crosscheck")
    if params.source_kind.is_chain:
        if perturb not in run_values(params)[1]:
            parameter_default(fmu_path, perturb)   # refuses an unknown name
        return fmu_path, params.driveline.free_response_speeds
    if perturb not in params.values:
        raise JudderError(
            f"perturb = {perturb!r} is not a tunable parameter of "
            f"{params.model}; allowed: a start speed among "
            f"{', '.join(params.values)}")
    return fmu_path, tuple(params.speed_states)


def crosscheck_study(params, freq_hz, p_f, duration=3.0,
                     method=DEFAULT_METHOD, workers=None, callback=None,
                     perturb="w_in"):
    """Run the FMU over a grid and compare with the Floquet exponents.

    Parameters
    ----------
    params : drivelines.Parameters or sources.modelica.ModelicaParameters
        The FMU of its driveline (registry) or of its Modelica class is
        run.
    freq_hz, p_f : array_like
        Grid: dither frequencies (Hz) and amplitudes (Pa).
    duration : float
        Length of each run, s.
    method : str
        Monodromy engine of the Floquet side, a key of
        :data:`stability.monodromy.METHODS`.
    workers : int, optional
        Processes (default all cores).
    callback : callable, optional
        ``callback(done, total)`` after each point.
    perturb : str
        The start-speed parameter raised by :data:`SPEED_STEP` in the
        second run of each point.

    Returns
    -------
    Crosscheck
    """
    get_method(method)
    fmu_path, speeds = _fmu_and_speeds(params, perturb)
    jobs = [(params, fmu_path, float(f), float(p), float(duration), method,
             speeds, perturb)
            for f in np.atleast_1d(freq_hz) for p in np.atleast_1d(p_f)]
    points = []
    for point in parallel_map(_point, jobs, workers):
        points.append(point)
        if callback is not None:
            callback(len(points), len(jobs))
    return Crosscheck(points=points, duration=float(duration))


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
    CrosscheckResult
    """
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_f_bar=p_f_bar)
    # the Floquet side is a linearisation in one mode: each setting of the
    # grid compared must hold it over a dither period
    grid = np.meshgrid(np.atleast_1d(freq_hz),
                       np.asarray(p_f_bar, dtype=float) * PA_PER_BAR,
                       indexing="ij")   # in the order the points run
    check_modes(values, grid[0].ravel(), grid[1].ravel())
    check, seconds = timed(
        crosscheck_study, values, freq_hz,
        np.asarray(p_f_bar, dtype=float) * PA_PER_BAR, duration=duration,
        method=method, workers=workers, callback=progress, perturb=perturb)
    return CrosscheckResult(params=values, check=check, seconds=seconds,
                            method=method)


@dataclass(frozen=True)
class CrosscheckResult:
    """``judder crosscheck``: a :class:`studies.crosscheck.Crosscheck`."""

    params: object
    check: object
    seconds: float
    method: str

    def rows(self):
        """One dict per grid point (Hz, bar, 1/s)."""
        return [{"freq_hz": p.freq_hz, "p_f_bar": p.p_f / PA_PER_BAR,
                 "floquet_kind": p.floquet_kind,
                 "floquet_rate_per_s": p.floquet_rate,
                 "fitted_rate_per_s": p.fitted_rate,
                 "floquet_unstable": p.floquet_unstable,
                 "time_unstable": p.time_unstable, "agree": p.agree,
                 "reason": p.reason} for p in self.check.points]

    def as_dict(self):
        rows = self.rows()
        return {"model": self.params.model, "method": self.method,
                "points": len(rows), "seconds": self.seconds,
                "duration_s": self.check.duration,
                "agreement": self.check.agreement,
                "max_rate_error_above_1_per_s":
                    self.check.max_rate_error(above=1.0),
                "disagreements": [r for r in rows if not r["agree"]]}

    @keeps_foreign_files
    def save(self, path):
        write_text(path, rows_to_csv(self.rows()))

    def figure(self, title=None):
        from .figures.crosscheck import crosscheck_figure
        return crosscheck_figure(self.check, title=title)
