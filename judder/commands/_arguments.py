"""Option groups the commands share (model selection, waveform, workers,
method, ``--force``, ``--min-growth``, ``--limit``, the safe windows'
operating range and margins), with their help texts.

Choices of models, presets and monodromy engines come from their
registries (:mod:`drivelines.registry`, :data:`stability.monodromy.METHODS`).
"""

import argparse

from drivelines import DEFAULT_MODEL, MODELS, PRESETS
from infra.contract import warn
from infra.criteria import (DEFAULT_JUDDER_LIMIT_RPM, DEFAULT_MIN_GROWTH_PER_S,
                            ENGAGEMENT_DURATION_S)
from stability.monodromy import DEFAULT_METHOD, METHODS

from ._values import (FREQ_RANGE_HZ, LIMIT, MARGIN_BAR, MARGIN_HZ, MIN_GROWTH,
                      PF_MAX, VALVE_MAX, WORKERS, Interval)

MIN_GROWTH_HELP = (
    "judder-relevant growth rate, 1/s: an instability growing slower "
    "than this stays below one e-fold over a {:g} s engagement (the "
    "slipping phase), so it is not judder (default %(default)g = one "
    "e-fold per engagement; 0: every instability)"
    .format(ENGAGEMENT_DURATION_S))


def model_options(parser, modelica=True, fmu=True):
    """The model selection every analysis command shares: --model,
    --preset, --param-file, --set, --json and, with ``modelica``, a
    driveline of your own: --modelica CLASS [--library DIR] or --fmu
    FILE.fmu, with --dither-amplitude/--dither-frequency NAME
    (docs/onemodel.md, docs/fmu-path.md)."""
    group = parser.add_argument_group(
        "model", "Parameter set: a preset or a TOML file, then --set "
        "overrides. Values in SI units (see `judder params`).")
    group.add_argument("--model", choices=tuple(MODELS),
                       help="driveline; picks the paper's preset for it "
                            f"(default {DEFAULT_MODEL}): " + "; ".join(
                                f"{m.name}: {m.title}"
                                for m in MODELS.values()))
    group.add_argument("--preset", choices=tuple(PRESETS),
                       metavar="NAME",
                       help="a preset: " + "; ".join(
                           f"{name}: {text}" for name, text in
                           PRESETS.items()).replace("%", "%%"))
    group.add_argument("--param-file", metavar="FILE.toml",
                       help="parameter file (see `judder params --save`)")
    group.add_argument("--set", action="append", default=[],
                       metavar="NAME=VALUE",
                       help="override one parameter, SI units; repeatable "
                            "(e.g. --set c12=10 --set "
                            "mean_pressure_damping=1)")
    group.add_argument("--friction", metavar="bounded|straight|FILE.csv",
                       help="the EVEN clutch's friction characteristic "
                            "mu(slip): bounded (default: the bench's "
                            "bounded rising curve, mu0 and mu_g at its "
                            "slip), straight (the straight line of Eq. 5 "
                            "there), or a friction rig's table: a CSV with "
                            "slip_rpm or slip_rad_s, then mu or mu_<T>C "
                            "per oil temperature (up to 64 rows). mu0 and "
                            "mu_g become its value and slope at the bench's "
                            "slip (1000 rpm); the bench, the orbit and "
                            "simulate read the whole table. The share of "
                            "the clamping load that feels it stays "
                            "mean_pressure_damping (0 by default)")
    group.add_argument("--oil-temp", type=float, metavar="C",
                       help="oil temperature, C, at which a --friction "
                            "table with a column per temperature is read "
                            "(linear between its columns; default 67.5 C, "
                            "the paper's 65-70 C)")
    parser.add_argument("--json", action="store_true",
                        help="print the result as JSON")
    if modelica:
        own_driveline_options(parser, fmu=fmu)


def own_driveline_options(parser, fmu=True):
    own = "a Modelica class or an FMU" if fmu else "a Modelica class"
    holder = "class or FMU" if fmu else "class"
    group = parser.add_argument_group(
        "your own driveline", f"Analyse {own} instead of a preset: it is "
        "linearised about its start values (a steady slip) and its "
        "rigid-body angles removed; --set NAME=VALUE then sets its "
        "parameters by their names (SI), --param-file reads a file of "
        "`judder params --modelica CLASS --save`"
        + (" (or --fmu)" if fmu else "") + ". Replaces --model and --preset.")
    group.add_argument("--modelica", metavar="CLASS",
                       help="full class name, e.g. "
                            "Judder.Examples.Driveline5DOFGeared, compiled "
                            "by the project's compiler")
    group.add_argument("--library", metavar="DIR", action="append",
                       help="folder holding your own top-level package, "
                            "or one .mo file holding a whole package; "
                            "repeatable, searched in the order given, "
                            "before MODELICAPATH (the Judder library is "
                            "always available)")
    # a command that cannot take an FMU still reads --fmu, to refuse it
    # with its reason before reading the file (`refused_fmu`, with the
    # command's name), but does not offer it in its --help
    if not fmu:
        parser.set_defaults(fmu_refused_by=parser.prog.rsplit(" ", 1)[-1])
    group.add_argument(
        "--fmu", metavar="FILE.fmu", dest="fmu" if fmu else "refused_fmu",
        help="an FMI 2.0 or 3.0 Model Exchange FMU: its state Jacobian "
             "(directional derivatives, else central differences) is "
             "read over one dither "
             "period at its start values; replaces --modelica "
             "(docs/fmu-path.md)" if fmu else argparse.SUPPRESS)
    group.add_argument("--dither-amplitude", default="p_f", metavar="NAME",
                       help=f"parameter of the {holder} that is "
                            "the dither amplitude, Pa (default p_f)")
    group.add_argument("--dither-frequency", default="f_dither",
                       metavar="NAME",
                       help=f"parameter of the {holder} that is "
                            "the dither frequency, Hz (default f_dither)")


def waveform_option(parser):
    parser.add_argument(
        "--dither-wave", default="cosine", metavar="SPEC",
        help="shape of the dither, per unit --pf: cosine (Eq. 4, default); "
             "square[:TAU_MS], a square wave of amplitude 1 through the "
             "valve's first-order lag TAU_MS (ms); fourier:A1,A2,...[/B1,"
             "B2,...], cosine and sine coefficients of the harmonics; "
             "period:FILE.csv, one measured period of pressure (last column, "
             "equally spaced; --pf then scales its fundamental)")
    decimal_option(parser, "the --dither-wave period: file")


def pf_max_option(parser, meaning):
    parser.add_argument("--pf-max", type=PF_MAX, default=1.5, metavar="BAR",
                        help=f"{meaning}, bar (default 1.5)")


#: The argparse ``type=`` of the valve's highest amplitude, by option.



def window_options(parser, subject="", freq_note="", valve_note="",
                   margin_words=("below every tongue",
                                 "from every tongue edge")):
    """The operating range and margins of the safe dither windows
    (``judder advise``, ``judder compare``): --freq-range, --valve-max
    (the valve's highest amplitude), --margin-bar and --margin-hz.

    Parameters
    ----------
    subject : str
        Words after "dither operating frequencies" (e.g. " of the safe
        windows").
    freq_note, valve_note : str
        Words after the default of --freq-range and of --valve-max.
    margin_words : (str, str)
        What the amplitude and the frequency margin are of.
    """
    parser.add_argument("--freq-range", type=Interval("--freq-range", "Hz",
                                                      *FREQ_RANGE_HZ),
                        default="60:200", metavar="LOW:HIGH",
                        help=f"dither operating frequencies{subject}, Hz "
                             f"(default %(default)s{freq_note})")
    parser.add_argument("--valve-max", type=VALVE_MAX, default=0.7,
                        metavar="BAR",
                        help="the valve's highest dither amplitude, the top "
                             "of the operating range, bar (default "
                             f"%(default)g{valve_note})")
    parser.add_argument("--margin-bar", type=MARGIN_BAR, default=0.1,
                        metavar="BAR",
                        help=f"amplitude margin {margin_words[0]}, bar "
                             "(default %(default)g)")
    parser.add_argument("--margin-hz", type=MARGIN_HZ, default=5.0,
                        metavar="HZ",
                        help=f"frequency margin {margin_words[1]}, Hz "
                             "(default %(default)g)")


def workers_option(parser, default="all cores"):
    parser.add_argument("--workers", type=WORKERS, default=None,
                        help="local worker processes of a Dask cluster "
                             f"started for the command (default: {default}; "
                             "1 runs everything in this process)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run the jobs on an existing Dask cluster, "
                             "e.g. tcp://127.0.0.1:8786 (see docs/envelope.md)")


def min_growth_option(parser, extra=""):
    parser.add_argument("--min-growth", type=MIN_GROWTH,
                        default=DEFAULT_MIN_GROWTH_PER_S, metavar="1/S",
                        help=MIN_GROWTH_HELP + extra)


def driveline_option(parser, default=None, default_words=None):
    """``--driveline``: the driveline a Floquet view is of
    (:data:`stability.bench.DRIVELINES`); ``default`` and the words saying
    it where a command's default is not the preset's bench."""
    parser.add_argument("--driveline", choices=("chain", "bench"),
                        default=default,
                        help="bench: the preset's driveline on its test "
                             "bench, as simulate, orbit and chart run it "
                             "(the motor's speed control damps body 1, the "
                             "friction curve's value and slope at the "
                             "bench's slip; its first resonance is 16.5 "
                             "Hz, not 18.9); chain: the driveline alone "
                             "(Eq. 6, free, as the paper's Fig. 12 and 14); "
                             + (default_words or "default: bench where the "
                                "preset has one, else chain (a model "
                                "without a bench, a Modelica class or an "
                                "FMU)"))


def limit_option(parser):
    parser.add_argument("--limit", type=LIMIT,
                        default=DEFAULT_JUDDER_LIMIT_RPM, metavar="RPM",
                        help="NVH limit, rpm: an oscillation of the "
                             "upstream speed at the dither frequency, its "
                             "half or a combination frequency larger than "
                             "this in the engagement window is judder, "
                             "forced or parametric (default "
                             f"{DEFAULT_JUDDER_LIMIT_RPM:g})")


def decimal_option(parser, files):
    """``--decimal``: the decimal separator of the CSV ``files`` (in
    words), for those whose cells cannot tell it."""
    parser.add_argument("--decimal", choices=(".", ","), default=None,
                        metavar=".|,",
                        help=f"decimal separator of {files}, '.' or ',' "
                             "(the thousands separator follows: ',' or "
                             "'.', or a space or apostrophe), for files "
                             "whose cells cannot tell it (integers with "
                             "1,000); a cell written otherwise is refused "
                             "(default: decided per file from its cells)")


def force_option(parser):
    parser.add_argument("--force", action="store_true",
                        help="allow replacing output files judder did not "
                             "write (a file it wrote is replaced anyway)")


def method_option(parser):
    parser.add_argument("--method", default=DEFAULT_METHOD,
                        choices=tuple(METHODS),
                        help="monodromy engine: dyson (fast, default) or "
                             "solve_ivp (per-point reference)")


class Renamed(argparse.Action):
    """An option's old spelling, kept for one release: it sets the new
    option's value (``const`` for a flag, else its value parsed by
    ``type``) and says once, on stderr, what it is called now."""

    def __init__(self, option_strings, dest, new, **kwargs):
        super().__init__(option_strings, dest, **kwargs)
        self.new = new

    def __call__(self, parser, namespace, values, option_string=None):
        warn(f"{option_string} is {self.new} now (the old spelling works "
             "for this release)")
        setattr(namespace, self.dest, self.const if self.nargs == 0
                else values)


def renamed_option(parser, old, new, dest, const=None, type=None,
                   metavar=None):
    """``old``, the former spelling of ``new`` (a flag setting ``dest`` to
    ``const``, or an option parsed by ``type``), for one release."""
    parser.add_argument(old, action=Renamed, new=new, dest=dest,
                        nargs=0 if type is None else None, const=const,
                        type=type, metavar=metavar,
                        help=f"former spelling of {new}, for this release")
