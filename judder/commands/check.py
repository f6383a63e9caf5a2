"""``judder check``: is a dither setting safe, and by how much."""

import dataclasses
from dataclasses import dataclass
import math
import time

import numpy as np

from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from stability.kinds import KINDS
from stability.maps import stability_map as map_kernel
from stability.source import build_driveline

from ._arguments import (decimal_option, driveline_option, force_option,
                         limit_option, min_growth_option,
                         model_options, refuse_decimal)
from ._common import (check_modes, check_modes_up_to, check_names,
                      checked_values, frequency_dependent, linearised_mode,
                      mode_words, structural_names)
from ._words import growth_words, margin_words, response_words
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._preflight import check_settings_time, check_work
from ._records import finite_or_none, rows_to_csv
from ._values import (FREQ, FREQ_RANGE_HZ, PF, PF_MAX, NameList, Settings,
                      check_amplitudes)

#: The command's --help text.
DESCRIPTION = (
    "Verdict of each dither setting, of a preset's driveline on its test "
    "bench unless --driveline chain (judder if its settled oscillation "
    "exceeds --limit, from the bench's periodic orbit or the chain's "
    "linear forced response, or if it grows faster than --min-growth; "
    "with the mechanism), its growth rate and e-folding time against the "
    "engagement, the margin to the nearest judder-relevant tongue "
    "boundary in bar (at the same frequency) and in Hz (at the same "
    "amplitude), exact from the boundary curves, which tongue that is, "
    "and how much each parameter moves those margins. Settings: --freq "
    "x --pf (every pair), or --table.")
OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))


#: Parameters whose effect on the margins ``check`` reports by default
#: (4-DOF model; other models: see :func:`structural_names`).
DEFAULT_CHECK_PARAMETERS = ("J2", "J4", "k12", "k24", "c12", "mu_g")


def add_arguments(p):
    """The options of ``judder check``."""
    p.add_argument("--freq", type=Settings("--freq", "Hz"),
                   metavar="HZ[,HZ...]",
                   help="dither frequencies, Hz: a list or START:STOP:N")
    p.add_argument("--pf", type=Settings("--pf", "bar"),
                   metavar="BAR[,BAR...]",
                   help="dither amplitudes, bar: a list or START:STOP:N")
    p.add_argument("--table", metavar="FILE.csv",
                   help="a dither table instead: columns freq_hz,p_f_bar, "
                        "one setting a row (e.g. a controller's table)")
    decimal_option(p, "the --table file")
    min_growth_option(p)
    limit_option(p)
    driveline_option(p)
    p.add_argument("--pf-max", type=PF_MAX, default=None, metavar="BAR",
                   help="largest boundary amplitude searched, bar (default "
                        "the larger of 1.5 and twice the largest setting)")
    p.add_argument("--params", type=NameList("--params"), default=None,
                   metavar="NAMES",
                   help="parameters whose effect on the margins is reported "
                        "(d margin / d ln value; default J2,J4,k12,k24,c12,"
                        "mu_g, for the 3-DOF model its inertias, stiffnesses, "
                        "dampings and mu_g; for --modelica/--fmu those of "
                        "J2,J4,k12,k24,c12,mu_g it has, and NAMES is "
                        "required if it has none; 'none' for none)")
    p.add_argument("--out", metavar="FILE.csv",
                   help="one row per setting (the scalar JSON fields)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the settings marked on the map")
    model_options(p)
    force_option(p)


def run(args):
    """Verdict, growth and margins of dither settings."""
    names = args.params
    freqs, amplitudes = _settings(args, len(
        DEFAULT_CHECK_PARAMETERS if names is None else names))
    if args.pf_max is not None and not args.pf_max > max(amplitudes):
        raise JudderError(f"--pf-max {args.pf_max:g} bar is not allowed; "
                          "allowed: above the largest setting, "
                          f"{max(amplitudes):g} bar")
    params, changes = parameters_of(args)
    make_parents(args.out, args.plot)
    with Progress(len(freqs), "check") as progress:
        result = check(freqs, amplitudes, params, changes,
                       min_growth=args.min_growth, p_max_bar=args.pf_max,
                       sensitivity=names, background=bool(args.plot),
                       progress=progress, driveline=args.driveline,
                       judder_limit_rpm=args.limit)
    data = {**result.as_dict(), **write_outputs(
        args, result, figure={"title": model_title(args, params)})}
    emit(args, data, result.summary() + written(args.out, args.plot))


def _settings(args, parameters):
    """Frequencies (Hz) and amplitudes (bar) of ``judder check``; the
    time of ``parameters`` sensitivity parameters per setting is estimated
    before the settings are made (a grid x grid of 1e10 would fill the
    memory first)."""
    from ..inputs import empty_cell, read_boundary_table, read_input
    if args.table:
        if args.freq or args.pf:
            raise JudderError("--table and --freq/--pf: allowed: one of them")
        # every message of the table names it as the option gave it
        source = f"--table {args.table}"
        table = read_boundary_table(read_input(args.table, "--table"),
                                    source, args.decimal)
        freqs, p_f, lines = table["freq_hz"], table["p_f"], table["lines"]
        empty = [line for line, p in zip(lines, p_f) if not math.isfinite(p)]
        if empty:
            raise empty_cell(source, empty[0], "p_f_bar", "a dither "
                             "amplitude >= 0 bar (every row is a setting "
                             "to check)")
        amplitudes = [p / PA_PER_BAR for p in p_f]
        check_amplitudes(amplitudes, f"{source}: p_f_bar")
        check_settings_time(len(freqs), parameters)
        check_work(source, len(freqs), "settings")
        low, high = FREQ_RANGE_HZ
        for line, f in zip(lines, freqs):
            if not low <= f <= high:
                raise JudderError(
                    f"{source}, line {line}: column 'freq_hz' = {f:g} Hz is "
                    f"not allowed; allowed: {low:g} to {high:g} Hz")
        return list(freqs), amplitudes
    refuse_decimal(args.decimal, "a --table file", "with --freq and --pf")
    if not (args.freq and args.pf):
        raise JudderError("--freq and --pf are required (or --table)")
    freqs, amplitudes = args.freq, args.pf
    # the time first (it says what to change); then, with the time limit
    # raised, the count (the pairs of 1e10 settings would not fit)
    check_settings_time(len(freqs) * len(amplitudes), parameters)
    check_work("--freq x --pf", len(freqs) * len(amplitudes), "settings")
    pairs = [(f, p) for f in freqs for p in amplitudes]
    return [f for f, _ in pairs], [p for _, p in pairs]


def check(freq_hz, p_f_bar, parameters=None, changes=None, min_growth=None,
          p_max_bar=None, sensitivity=None, background=False,
          progress=None, driveline=None, judder_limit_rpm=None):
    """``judder check``: is each dither setting safe, and by how much.

    Parameters
    ----------
    freq_hz, p_f_bar : array_like, shape (n,)
        The settings, Hz and bar (pairs: a dither table).
    min_growth : float, optional
        Judder-relevant growth rate, 1/s (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`).
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
    driveline : {'chain', 'bench'}, optional
        The driveline judged (:data:`judder.bench.DRIVELINES`): the
        preset's chain, or the same on its test bench (what ``simulate``
        runs); default the bench where the preset has one
        (:func:`judder.bench.default_driveline`).
    judder_limit_rpm : float, optional
        NVH limit of the upstream speed's oscillation, rpm (default
        :data:`infra.criteria.DEFAULT_JUDDER_LIMIT_RPM`): a settled
        oscillation above it is judder, forced or parametric.

    Returns
    -------
    CheckResult
        Each setting's verdict is the bench engineer's: JUDDER where the
        settled oscillation at the dither-related frequencies reaches the
        limit (the bench's periodic orbit; for the chain its linear
        harmonic response) or the response grows at ``min_growth`` or
        faster, with its mechanism.
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S, ENGAGEMENT_DURATION_S
    from stability.decisions.margins import check_settings
    freq_hz = np.atleast_1d(np.asarray(freq_hz, dtype=float))
    p_f_bar = np.atleast_1d(np.asarray(p_f_bar, dtype=float))
    if freq_hz.shape != p_f_bar.shape or freq_hz.ndim != 1 or not len(freq_hz):
        raise JudderError(f"freq and p_f have {freq_hz.size} and "
                          f"{p_f_bar.size} values; allowed: as many of each")
    from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM
    from ..bench import driveline_view
    judder_limit_rpm = (DEFAULT_JUDDER_LIMIT_RPM if judder_limit_rpm is None
                        else judder_limit_rpm)
    given = checked_values(parameters, changes, freq_hz=freq_hz,
                           p_f_bar=p_f_bar, min_growth=min_growth,
                           p_max_bar=p_max_bar,
                           judder_limit_rpm=judder_limit_rpm)
    values, driveline = driveline_view(given, driveline)
    min_growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    if p_max_bar is None:
        p_max_bar = max(1.5, 2 * float(p_f_bar.max()))
    elif not p_max_bar > p_f_bar.max():
        raise JudderError(f"p_max_bar = {p_max_bar:g} bar is not allowed; "
                          "allowed: above the largest p_f_bar, "
                          f"{p_f_bar.max():g} bar")
    if sensitivity is None:
        sensitivity = structural_names(values, DEFAULT_CHECK_PARAMETERS,
                                        ("mu_g",))
    check_names(values, sensitivity, "--params")
    check_modes(values, freq_hz, p_f_bar * PA_PER_BAR)
    if getattr(values, "check_mode", None) is not None:
        # a Modelica class: the margins are searched up to p_max_bar, on
        # the linearisation in its mode (presets need not import casadi)
        from sources.modelica import ModelicaError
        try:
            check_modes_up_to(values, freq_hz, p_max_bar)
        except ModelicaError as error:
            left = str(error).split("; allowed:")[0]
            raise JudderError(
                f"{left}: the margins are searched up to `p_max_bar` = "
                f"{p_max_bar:g} bar on the linearisation in one mode; "
                "allowed: a smaller `p_max_bar`, below the amplitude where "
                "the mode is left") from None
    if frequency_dependent(values):
        from infra.contract import warn
        warn(f"{values.model} is linearised at {freq_hz[0]:g} Hz (its "
             f"Jacobian depends on {values.frequency}): the Hz margin is "
             "searched on that linearisation, not on one at each "
             "neighbouring frequency")
    started = time.perf_counter()
    checks = check_settings(values, freq_hz, p_f_bar * PA_PER_BAR, min_growth,
                            p_max_bar * PA_PER_BAR, tuple(sensitivity),
                            callback=progress)
    responses = settled_responses(given, values, driveline, freq_hz,
                                  p_f_bar * PA_PER_BAR, judder_limit_rpm,
                                  min_growth,
                                  [c.floquet.growth_rate for c in checks])
    seconds = time.perf_counter() - started
    result = CheckResult(params=values, checks=checks, min_growth=min_growth,
                         engagement_s=ENGAGEMENT_DURATION_S,
                         p_max=p_max_bar * PA_PER_BAR, seconds=seconds,
                         responses=responses, driveline=driveline,
                         judder_limit_rpm=judder_limit_rpm)
    if background:
        low, high = freq_hz.min(), freq_hz.max()
        grid = np.linspace(max(low - 0.5 * (high - low) - 20, 1.0),
                           high + 0.5 * (high - low) + 20, 200)
        under = map_kernel(build_driveline(values), grid,
                           np.linspace(0, max(2 * p_f_bar.max(), 0.5), 100)
                           * PA_PER_BAR)
        result = dataclasses.replace(result, background=under)
    return result


#: Where a setting's settled amplitude comes from, by driveline.
AMPLITUDE_SOURCES = {
    "bench": "the bench's periodic orbit (harmonic balance of its "
             "friction curve and motor torque limit; the 2T orbit past "
             "period doubling; in a combination tongue the motion "
             "integrated until settled, stability.settle)",
    "chain": "the chain's linear harmonic response at the dither "
             "frequency (Eq. 6 driven by the column D of Eq. 9)"}


def settled_responses(given, values, driveline, freq_hz, p_f, limit_rpm,
                      min_growth, growth_rates):
    """The settled oscillation at each setting (Hz, Pa) and the verdict it
    gives (:func:`stability.orbit_chart.orbit_verdict`): for the bench,
    its periodic orbit; for a chain, its linear forced response with the
    linearisation's growth (``growth_rates``, 1/s). Returns one dict per
    setting; None for a Modelica class or an FMU (its verdict is the
    growth's)."""
    from infra.criteria import MECHANISMS, mechanism_code
    from infra.units import RAD_S_PER_RPM, RPM_PER_RAD_S
    from stability.friction import forced_upstream_amplitude
    from stability.orbit import periodic_orbit
    from stability.orbit_chart import held_slip_motion, orbit_verdict
    limit = limit_rpm * RAD_S_PER_RPM
    rows = []
    if not given.source_kind.is_chain:
        return None     # a class's or an FMU's forced response: not here
    if driveline == "bench":
        from stability.settle import settle_orbits
        from ..bench import engagement_model
        model = engagement_model(given)[0]
        orbits = [periodic_orbit(model, f, p) for f, p in zip(freq_hz, p_f)]
        motions = settle_orbits(model, orbits)
    else:
        system = build_driveline(values)
    for k, (f, p, rate) in enumerate(zip(freq_hz, p_f, growth_rates)):
        if driveline == "bench":
            orbit, doubled = held_slip_motion(model, orbits[k])
            motion = motions[k]
            verdict = orbit_verdict(
                orbit, doubled, limit, min_growth,
                0.0 if motion is None else motion["combination"])
            forced, settled, growth = (verdict.forced, verdict.settled,
                                       verdict.growth_rate)
            judder, mechanism = verdict.judder, verdict.mechanism
            converged, quasi = orbit.success, verdict.quasi_periodic
            settled_s = None if motion is None else motion["duration"]
        else:
            forced = settled = forced_upstream_amplitude(system, f, p)
            growth = rate
            parametric, is_forced = growth >= min_growth, forced > limit
            judder = parametric or is_forced
            mechanism = mechanism_code(is_forced, parametric)
            converged, quasi, settled_s = True, False, None
        rows.append({
            "forced_amplitude_rpm": forced * RPM_PER_RAD_S,
            "settled_amplitude_rpm": settled * RPM_PER_RAD_S,
            "amplitude_from": AMPLITUDE_SOURCES[driveline],
            "response_growth_per_s": growth,
            "quasi_periodic": bool(quasi), "converged": bool(converged),
            "integrated_s": settled_s,
            "judder": bool(judder) and bool(converged),
            "mechanism": MECHANISMS[int(mechanism)] if judder else None,
            "judder_limit_rpm": limit_rpm})
    return rows


def setting_record(check, min_growth, engagement_s, p_max, search_hz=None,
                   response=None):
    """One :class:`stability.decisions.margins.SettingCheck` as JSON fields.

    ``verdict`` is one of :data:`stability.decisions.relevance.VERDICTS`;
    ``search_hz`` the (low, high) frequencies the Hz margin was searched
    over (``frequency_search_hz``).
    """
    from infra.criteria import JUDDER
    from stability.decisions.relevance import verdict
    m, point = check.margin, check.floquet
    rate = point.growth_rate
    unstable = point.kind != KINDS[0]
    word = verdict(unstable, rate, min_growth)
    if response is not None:
        # the settled oscillation decides with the growth (the bench's
        # orbit is the motion, so its growth replaces the steady slip's)
        word = JUDDER if response["judder"] else verdict(
            response["response_growth_per_s"] > 0,
            response["response_growth_per_s"], min_growth)

    def tongue(t):
        # the tongue of judder (growth min_growth): its tip is where it
        # judders, named as `judder tongues` names it (``tip_*`` there is
        # where a tongue becomes unstable)
        return None if t is None else {
            "number": t.number, "kind": t.kind, "resonance": t.resonance,
            "judder_tip_freq_hz": t.tip_freq_hz,
            "judder_tip_p_f_bar": t.tip_p_f / PA_PER_BAR}
    sensitivity = sorted(
        ({"parameter": name,
          "margin_bar_per_unit_log": finite_or_none(bar / PA_PER_BAR),
          "margin_hz_per_unit_log": finite_or_none(hz)}
         for name, (bar, hz) in check.sensitivity.items()
         if np.isfinite(bar) or np.isfinite(hz)),
        key=lambda r: -abs(r["margin_hz_per_unit_log"] or 0.0)
        - abs(r["margin_bar_per_unit_log"] or 0.0) * 1e-6)
    return {"freq_hz": m.freq_hz, "p_f_bar": m.p_f / PA_PER_BAR,
            "verdict": word,
            **(response or {}),
            "kind": point.kind,
            "inside_stability_tongue": bool(unstable),
            "judder_relevant": bool(check.judder),
            "tongue": tongue(check.tongue),
            "growth_rate_per_s": rate,
            "e_folding_time_s": 1.0 / rate if rate > 0 else None,
            "efolds_per_engagement": rate * engagement_s,
            "min_growth_per_s": min_growth,
            "boundary_p_f_bar": finite_or_none(m.boundary_p_f / PA_PER_BAR),
            "unstable_boundary_p_f_bar": finite_or_none(
                check.unstable_p_f / PA_PER_BAR),
            "margin_bar": finite_or_none(m.margin_p_f / PA_PER_BAR),
            "margin_bar_at_least": (None if np.isfinite(m.margin_p_f)
                                    else (p_max - m.p_f) / PA_PER_BAR),
            "margin_bar_tongue": (tongue(check.bar_tongue)
                                  if np.isfinite(m.margin_p_f) else None),
            "crossing_hz": m.crossing_hz,
            "crossing_tolerance_hz": m.crossing_tolerance_hz,
            "margin_hz": finite_or_none(m.margin_hz),
            "margin_hz_tongue": tongue(check.hz_tongue),
            "frequency_search_hz": (None if search_hz is None else
                                    [float(f) for f in search_hz]),
            "sensitivity": sensitivity}


def sensitivity_words(record, count=3):
    """The ``count`` parameters that move the margin most, per +10 %
    (Hz where the frequency margin exists, else bar); "" if none."""
    parts = []
    for entry in record["sensitivity"][:count]:
        hz, bar = (entry["margin_hz_per_unit_log"],
                   entry["margin_bar_per_unit_log"])
        if hz is not None:
            parts.append(f"{entry['parameter']} {0.1 * hz:+.2f} Hz")
        elif bar is not None:
            parts.append(f"{entry['parameter']} {0.1 * bar:+.3f} bar")
    return "" if not parts else \
        "margin per +10 %: " + ", ".join(parts)


def setting_summary(record, engagement_s=1.0):
    """One line: verdict, growth against an engagement, both margins, the
    parameters that move the margin most."""
    head = f"{record['freq_hz']:g} Hz, {record['p_f_bar']:g} bar: " \
        f"{record['verdict']}"
    if record["inside_stability_tongue"]:
        tongue = record["tongue"]
        head += (f" ({record['kind']})" if tongue is None else
                 f" in tongue {tongue['number'] or '?'} ({record['kind']})")
    parts = [head]
    if "settled_amplitude_rpm" in record:
        parts.append(response_words(record))
    parts += [growth_words(record, engagement_s), *margin_words(record)]
    sensitive = sensitivity_words(record)
    if sensitive:
        parts.append(sensitive)
    return "; ".join(parts)


@dataclass(frozen=True)
class CheckResult:
    """``judder check``: verdict and margins of each dither setting.

    ``checks`` are :class:`stability.decisions.margins.SettingCheck` objects;
    ``min_growth`` the judder-relevant rate (1/s), ``engagement_s`` the
    engagement duration the e-folds are counted over.
    """

    params: object
    checks: list
    min_growth: float
    engagement_s: float
    p_max: float
    seconds: float
    background: object = None
    responses: list = None
    driveline: str = "chain"
    judder_limit_rpm: float = None

    def records(self):
        from stability.decisions.margins import search_grid
        grid = search_grid([c.margin.freq_hz for c in self.checks]) \
            if self.checks else None
        search = None if grid is None else (grid[0], grid[-1])
        responses = self.responses or [None] * len(self.checks)
        return [setting_record(c, self.min_growth, self.engagement_s,
                               self.p_max, search, response)
                for c, response in zip(self.checks, responses)]

    def as_dict(self):
        mode = linearised_mode(self.params)
        from ..bench import driveline_words
        return {"model": self.params.model,
                "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                **({"mode": mode} if mode else {}),
                "min_growth_per_s": self.min_growth,
                "engagement_s": self.engagement_s,
                "p_max_bar": self.p_max / PA_PER_BAR,
                "seconds": self.seconds, "settings": self.records()}

    def summary(self):
        from ..bench import driveline_words
        words = mode_words(linearised_mode(self.params))
        return "\n".join([f"driveline: {driveline_words(self.params, self.driveline)}"]
                         + ([words] if words else [])
                         + [setting_summary(r, self.engagement_s)
                            for r in self.records()])

    @keeps_foreign_files
    def save(self, path):
        """CSV: one row per setting (the scalar fields; tongues by
        number)."""
        rows = []
        for r in self.records():
            row = {k: v for k, v in r.items()
                   if not isinstance(v, (dict, list)) and k not in
                   ("tongue", "margin_bar_tongue", "margin_hz_tongue")}
            for key in ("tongue", "margin_bar_tongue", "margin_hz_tongue"):
                row[key] = None if r[key] is None else r[key]["number"]
            rows.append(row)
        write_text(path, rows_to_csv(rows))

    def figure(self, title=None):
        from ..figures.check import check_figure
        return check_figure(self.records(), self.background,
                            min_growth=self.min_growth, title=title)
