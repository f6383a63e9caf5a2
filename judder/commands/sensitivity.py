"""``judder sensitivity``: tongue shifts per parameter (Fig. 17, 18)."""

from dataclasses import dataclass

from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from stability.monodromy import DEFAULT_METHOD

from ._arguments import (driveline_option, force_option, method_option, model_options,
                         pf_max_option, workers_option)
from ._common import (check_modes_of_changes, check_modes_up_to,
                      checked_values, timed)
from ._model import model_title, parameters_of
from ._output import Progress, emit, make_parents, write_outputs, written
from ._preflight import check_sensitivity, check_work
from ._records import rows_to_csv
from ._values import Grid, Listed, Quantity
from .tongues import tongue_record

#: The command's --help text.
DESCRIPTION = (
    "Vary each parameter (by --factors, or to --values), recompute the "
    "boundaries and report how each tongue tip moves in frequency (Hz) "
    "and amplitude (bar); checks the paper's conclusions of section "
    "4.3. The tips are where each tongue becomes unstable (|lambda| = 1, "
    "Fig. 17, 18), not where it becomes judder (growth >= 1 1/s, see "
    "judder tongues). Clutch-damper study: --params c12 --values 0.5,10.")
OUTPUTS = (("out", "--out", ("csv",)), ("plot", "--plot", None))
AMPLITUDE = "pf_max"


#: Multipliers of the nominal value in sensitivity without --factors.
DEFAULT_FACTORS = (0.5, 2.0)


def add_arguments(p):
    """The options of ``judder sensitivity``."""
    p.add_argument("--params", type=Listed("--params", str),
                   required=True, metavar="NAMES",
                   help="comma-separated parameters, e.g. "
                        "k12,k24,J1,J2,J3,J4,mu_g,c12")
    p.add_argument("--factors", metavar="F1,F2",
                   type=Listed("--factors", Quantity("--factors", "1", 0.0,
                                                     low_open=True)),
                   help="multipliers of the nominal value (default 0.5,2)")
    p.add_argument("--values", metavar="V1,V2", type=Listed("--values"),
                   help="absolute values (SI) instead of --factors")
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="10:220:200", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:200)")
    pf_max_option(p, "largest amplitude searched")
    workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="tip-shift table as CSV")
    p.add_argument("--plot", metavar="FILE.png",
                   help="one panel per parameter: nominal and varied "
                        "boundaries")
    method_option(p)
    model_options(p)
    driveline_option(p)
    force_option(p)


def run(args):
    """Tongue tips and boundaries with parameters varied (Fig. 17, 18)."""
    names = args.params
    freqs = args.freq
    p_max_bar = args.pf_max
    params, changes = parameters_of(args)
    if args.values is not None and args.factors is not None:
        raise JudderError("--values and --factors given; allowed: one of "
                          "them")
    factors = args.factors or DEFAULT_FACTORS
    values = args.values
    if values is None:
        values_now = params.replace(**changes)
        zero = [n for n in names if n in values_now.specs and
                values_now[n] == 0]
        if zero:
            raise JudderError(
                f"--params {zero[0]} is 0 in this parameter set, so "
                "--factors cannot vary it; allowed: --values for it, or a "
                "parameter with a non-zero value")
    make_parents(args.out, args.plot)
    cases = 1 + len(names) * len(values or factors)
    check_work("--params x --values/--factors", cases, "cases")
    check_sensitivity(params.replace(**changes), freqs, cases,
                      args.workers)
    with Progress(cases, "sensitivity cases") as progress:
        result = sensitivity(names, freqs, p_max_bar, factors=factors,
                             values=values, parameters=params,
                             changes=changes, method=args.method,
                             workers=args.workers, progress=progress,
                             driveline=args.driveline)
    files = write_outputs(args, result, figure={
        "title": "sensitivity of the unstable boundary "
                 r"($|\lambda| = 1$; "
                 "Fig. 17, 18), " + model_title(args, params)})
    rows = ["tips where each tongue becomes unstable (|lambda| = 1, "
            "growth 0), not where it becomes judder (growth >= 1 1/s; "
            "judder tongues gives both)",
            f"{'param':>8} {'factor':>7} {'value':>10} {'#':>2} "
            f"{'tip f [Hz]':>11} {'df [Hz]':>8} {'tip p_f':>8} {'dp_f':>8}"]
    for r in result.tip_shifts:
        if r["present"]:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2} "
                        f"{r['tip_freq_hz']:11.3f} {r['d_freq_hz']:+8.2f} "
                        f"{r['tip_p_f_bar']:8.4f} {r['d_p_f_bar']:+8.4f}")
        else:
            rows.append(f"{r['parameter']:>8} {r['factor']:7.3g} "
                        f"{r['value']:10.4g} {r['tongue']:>2}   above "
                        f"{p_max_bar:g} bar (gone)")
    if result.conclusions:
        rows.append("the paper's conclusions of section 4.3, checked on "
                    "this driveline ([does NOT hold]: this driveline "
                    "behaves otherwise, not an error of the tool):")
    rows += [f"[{'holds' if c['holds'] else 'does NOT hold'}] "
             f"{c['statement']}: {c['evidence']}" for c in result.conclusions]
    rows.append(f"{result.cases} cases in {result.seconds:.1f} s")
    emit(args, {**result.as_dict(), **files},
         "\n".join(rows) + written(args.out, args.plot))


def sensitivity(names, freq_hz, p_max_bar=1.5, factors=(0.5, 2.0),
                values=None, parameters=None, changes=None,
                method=DEFAULT_METHOD, workers=None, progress=None,
                driveline=None):
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
    driveline : {'chain', 'bench'}, optional
        The driveline whose tongues move (:func:`judder.bench.
        driveline_view`; default the bench where the preset has one).

    Returns
    -------
    SensitivityResult
    """
    from stability.sensitivity import (paper_conclusions, sensitivity_study,
                                       tip_shifts)
    from ..bench import driveline_view
    nominal, driveline = driveline_view(
        checked_values(parameters, changes, freq_hz=freq_hz,
                       p_max_bar=p_max_bar), driveline)
    check_modes_up_to(nominal, freq_hz, p_max_bar)
    for name in names:
        if name not in nominal.specs:
            raise JudderError(f"--params: unknown parameter {name!r} for the "
                              f"{nominal.model} model; allowed names: "
                              f"{', '.join(nominal.specs)}")
    # each changed set in the nominal mode, held up to p_max_bar, as the
    # nominal one (the study's own values: the factors of the nominal
    # values, or the values given)
    check_modes_of_changes(nominal, [
        {name: float(value)} for name in names for value in (
            values if values is not None else
            [nominal[name] * factor for factor in factors])],
        freq_hz, p_max_bar)
    study, seconds = timed(
        sensitivity_study, nominal, names, freq_hz, p_max_bar * PA_PER_BAR,
        factors=factors, values=values, method=method, workers=workers,
        callback=progress)
    conclusions = (paper_conclusions(study)
                   if nominal.source_kind.is_chain
                   and nominal.driveline.paper_sensitivity else [])
    return SensitivityResult(params=nominal, study=study,
                             tip_shifts=tip_shifts(study),
                             conclusions=conclusions, seconds=seconds,
                             method=method, driveline=driveline)


@dataclass(frozen=True)
class SensitivityResult:
    """``judder sensitivity``: tip shifts per varied parameter.

    ``study`` is the :class:`stability.sensitivity.SensitivityStudy`;
    ``tip_shifts`` and ``conclusions`` as
    :func:`stability.sensitivity.tip_shifts` and
    :func:`stability.sensitivity.paper_conclusions` give them.
    """

    params: object
    study: object
    tip_shifts: list
    conclusions: list
    seconds: float
    method: str
    driveline: str = "chain"

    @property
    def cases(self):
        return 1 + len(self.study.cases)

    def as_dict(self):
        from ..bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                "method": self.method,
                "seconds": self.seconds, "cases": self.cases,
                "min_growth_per_s": 0.0,
                "nominal_tongues": [tongue_record(t)
                                    for t in self.study.nominal.tongues],
                "tip_shifts": self.tip_shifts,
                "paper_conclusions": self.conclusions}

    @keeps_foreign_files
    def save(self, path):
        write_text(path, rows_to_csv(self.tip_shifts))

    def figure(self, title=None):
        return self.study.plot(
            title=title or f"{self.params.model}: sensitivity of the "
                           "unstable boundary (|lambda| = 1)",
            params=self.params)
