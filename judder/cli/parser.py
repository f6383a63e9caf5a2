"""The argparse parser of ``judder``: options, units and help texts.

Choices of models, presets and monodromy engines come from their
registries (:mod:`drivelines.registry`, :data:`stability.monodromy.METHODS`).
"""

import argparse

from drivelines import DEFAULT_MODEL, MODELS, PRESETS
from infra.criteria import DEFAULT_MIN_GROWTH_PER_S, ENGAGEMENT_DURATION_S
from stability.monodromy import DEFAULT_METHOD, METHODS

from . import commands

__all__ = ["build_parser"]

DEFAULT_MAP_FREQ = "5:250:300"
DEFAULT_MAP_PF = "0:1.5:150"
#: The report's map grid: 1 Hz x 0.0125 bar, two thirds of the points of
#: ``judder map``'s (the exact boundaries are drawn over it; the report
#: stays under 20 s, docs/figures.md).
REPORT_MAP_FREQ = "5:250:246"
REPORT_MAP_PF = "0:1.5:121"


def _model_options(parser, modelica=True):
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
    parser.add_argument("--json", action="store_true",
                        help="print the result as JSON")
    if modelica:
        _own_driveline_options(parser)


def _own_driveline_options(parser):
    group = parser.add_argument_group(
        "your own driveline", "Analyse a Modelica class or an FMU instead "
        "of a preset: it is linearised about its start values (a steady "
        "slip) and its rigid-body angles removed; --set NAME=VALUE then "
        "sets its parameters by their names (SI), --param-file reads a "
        "file of `judder params --modelica CLASS --save` (or --fmu). "
        "Replaces --model and --preset.")
    group.add_argument("--modelica", metavar="CLASS",
                       help="full class name, e.g. "
                            "Judder.Examples.Driveline5DOFGeared, compiled "
                            "by the project's compiler")
    group.add_argument("--library", metavar="DIR",
                       help="folder holding your own top-level package "
                            "(the Judder library is always available)")
    group.add_argument(
        "--fmu", metavar="FILE.fmu",
        help="an FMI 2.0 Model Exchange FMU that provides directional "
             "derivatives: its state Jacobian is read over one dither "
             "period at its start values; replaces --modelica "
             "(docs/fmu-path.md)")
    group.add_argument("--dither-amplitude", default="p_f", metavar="NAME",
                       help="parameter of the class or FMU that is the "
                            "dither amplitude, Pa (default p_f)")
    group.add_argument("--dither-frequency", default="f_dither",
                       metavar="NAME",
                       help="parameter of the class or FMU that is the "
                            "dither frequency, Hz (default f_dither)")


def _waveform_option(parser):
    parser.add_argument(
        "--dither-wave", default="cosine", metavar="SPEC",
        help="shape of the dither, per unit --pf: cosine (Eq. 4, default); "
             "square[:TAU_MS], a square wave of amplitude 1 through the "
             "valve's first-order lag TAU_MS (ms); fourier:A1,A2,...[/B1,"
             "B2,...], cosine and sine coefficients of the harmonics; "
             "period:FILE.csv, one measured period of pressure (last column, "
             "equally spaced; --pf then scales its fundamental)")


def _pf_max_option(parser, meaning):
    parser.add_argument("--pf-max", type=str, default=1.5, metavar="BAR",
                        help=f"{meaning}, bar (default 1.5)")


def _workers_option(parser, default="all cores"):
    parser.add_argument("--workers", type=int, default=None,
                        help="local worker processes of a Dask cluster "
                             f"started for the command (default: {default}; "
                             "1 runs everything in this process)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run the jobs on an existing Dask cluster, "
                             "e.g. tcp://127.0.0.1:8786 (see docs/envelope.md)")


MIN_GROWTH_HELP = (
    "judder-relevant growth rate, 1/s: an instability growing slower "
    "than this stays below one e-fold over a {:g} s engagement (the "
    "slipping phase), so it is not judder (default %(default)g = one "
    "e-fold per engagement; 0: every instability)"
    .format(ENGAGEMENT_DURATION_S))


def _min_growth_option(parser, extra=""):
    parser.add_argument("--min-growth", type=str,
                        default=DEFAULT_MIN_GROWTH_PER_S, metavar="1/S",
                        help=MIN_GROWTH_HELP + extra)
def _force_option(parser):
    parser.add_argument("--force", action="store_true",
                        help="allow replacing output files judder did not "
                             "write (a file it wrote is replaced anyway)")


def _method_option(parser):
    parser.add_argument("--method", default=DEFAULT_METHOD,
                        choices=tuple(METHODS),
                        help="monodromy engine: dyson (fast, default) or "
                             "solve_ivp (per-point reference)")


def _version():
    """The installed package's version (``pyproject.toml``)."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("judder")
    except PackageNotFoundError:
        return "(not installed: run make setup)"


def build_parser():
    """The argparse parser of ``judder``."""
    parser = argparse.ArgumentParser(
        prog="judder",
        description="Clutch judder from parametric excitation by hydraulic "
                    "dither: Floquet stability of the 3-DOF and 4-DOF "
                    "driveline. Frequencies in Hz, dither amplitude in bar, "
                    "parameters in SI units.",
        epilog="Long work (map, floquet, tongues, sensitivity, crosscheck, "
               "campaign, envelope) is estimated before it starts: above "
               "10 s the estimate is printed on a terminal, above 24 h the "
               "request is refused; the environment variable "
               "JUDDER_MAX_HOURS=HOURS sets another limit.")
    parser.add_argument("--version", action="version",
                        version=f"judder {_version()}",
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", required=True,
                                metavar="COMMAND")

    p = sub.add_parser("params", help="show, or save as TOML, a parameter set",
                       description="Show a parameter set with units, or save "
                                   "it (--save FILE.toml) to edit and load "
                                   "with --param-file.")
    _model_options(p)
    p.add_argument("--save", metavar="FILE.toml",
                   help="write the set as TOML (never overwrites unless "
                        "--force)")
    p.add_argument("--force", action="store_true",
                   help="allow --save to replace an existing file")
    p.set_defaults(handler=commands.cmd_params)

    p = sub.add_parser("eig", help="natural frequencies and damping factor",
                       description="Undamped natural frequencies (Eq. 14-15, "
                                   "Hz), clutch-damper damping factor "
                                   "(Eq. 16) and the damped modes without "
                                   "dither, rigid-body angles removed. For "
                                   "--modelica or --fmu: the frequencies of "
                                   "its Jacobian's stiffness part and its "
                                   "damped modes; Eq. 15-16 are the paper's "
                                   "chains' formulas (null in --json).")
    _model_options(p)
    p.set_defaults(handler=commands.cmd_eig)

    p = sub.add_parser("floquet", help="Floquet multipliers at one point",
                       description="Monodromy matrix over one dither period "
                                   "and its Floquet multipliers (Eq. 10-13), "
                                   "rigid-body angles removed; the leading "
                                   "multiplier is classified as in Fig. 15.")
    p.add_argument("--freq", type=str, required=True, metavar="HZ",
                   help="dither frequency, Hz")
    p.add_argument("--pf", type=str, required=True, metavar="BAR",
                   help="dither amplitude p_f, bar (1 bar = 1e5 Pa)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the multipliers on the complex plane with the "
                        "unit circle, and near the leading one (Fig. 15)")
    _method_option(p)
    _model_options(p)
    _waveform_option(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_floquet)

    p = sub.add_parser("map", help="stability map over frequency x amplitude",
                       description="Leading Floquet multiplier on a grid of "
                                   "dither frequency (Hz) x amplitude (bar), "
                                   "classified single-period, double-period "
                                   "or combination (Fig. 14). Ctrl-C stops it "
                                   "without writing a partial file.")
    p.add_argument("--freq", default=DEFAULT_MAP_FREQ, metavar="START:STOP:N",
                   help=f"dither frequencies, Hz (default {DEFAULT_MAP_FREQ})")
    p.add_argument("--pf", default=DEFAULT_MAP_PF, metavar="START:STOP:N",
                   help=f"dither amplitudes, bar (default {DEFAULT_MAP_PF})")
    p.add_argument("--out", metavar="FILE.npz",
                   help="save the map arrays (NPZ, see README)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="save a plot of the map (PNG, SVG or PDF), with the "
                        "exact tongue boundaries and numbers")
    _min_growth_option(p, "; the plot shades slower ones grey")
    _method_option(p)
    _model_options(p)
    _waveform_option(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_map)

    p = sub.add_parser(
        "check", help="is a dither setting safe, and by how much",
        description="Verdict of each dither setting (judder if it grows "
                    "faster than --min-growth), its growth rate and e-folding "
                    "time against the engagement, the margin to the nearest "
                    "judder-relevant tongue boundary in bar (at the same "
                    "frequency) and in Hz (at the same amplitude), exact "
                    "from the boundary curves, which tongue that is, and "
                    "how much each parameter moves those margins. Settings: "
                    "--freq x --pf (every pair), or --table.")
    p.add_argument("--freq", metavar="HZ[,HZ...]",
                   help="dither frequencies, Hz: a list or START:STOP:N")
    p.add_argument("--pf", metavar="BAR[,BAR...]",
                   help="dither amplitudes, bar: a list or START:STOP:N")
    p.add_argument("--table", metavar="FILE.csv",
                   help="a dither table instead: columns freq_hz,p_f_bar, "
                        "one setting a row (e.g. a controller's table)")
    _min_growth_option(p)
    p.add_argument("--pf-max", type=float, default=None, metavar="BAR",
                   help="largest boundary amplitude searched, bar (default "
                        "the larger of 1.5 and twice the largest setting)")
    p.add_argument("--params", default=None, metavar="NAMES",
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
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_check)

    p = sub.add_parser(
        "advise", help="safe dither windows and the design change that "
                       "clears the dither range",
        description="(a) The safe (frequency, amplitude) windows inside the "
                    "valve's operating range, keeping --margin-bar and "
                    "--margin-hz from every judder-relevant tongue (over "
                    "every --also parameter set: the broadest region); "
                    "(b) the ranking of the design parameters by the share "
                    "of the way out of the window per relative change, and "
                    "the smallest weighted relative change of them that "
                    "clears the window of judder, checked by recomputing "
                    "the Floquet map of the advised design (section 4.3, 5).")
    p.add_argument("--freq-range", default="60:200", metavar="LOW:HIGH",
                   help="dither operating frequencies, Hz (default "
                        "%(default)s, the paper's valve)")
    p.add_argument("--pf-max", type=float, default=0.7, metavar="BAR",
                   help="highest operating dither amplitude, bar (default "
                        "%(default)g)")
    p.add_argument("--margin-bar", type=float, default=0.1, metavar="BAR",
                   help="amplitude margin below every tongue, bar (default "
                        "%(default)g)")
    p.add_argument("--margin-hz", type=float, default=5.0, metavar="HZ",
                   help="frequency margin from every tongue edge, Hz "
                        "(default %(default)g)")
    _min_growth_option(p)
    p.add_argument("--params", default=None, metavar="NAMES",
                   help="design parameters that may change (default "
                        "J2,J4,k12,k24,c12; for the 3-DOF model its "
                        "inertias, stiffnesses and dampings; for --modelica"
                        "/--fmu those of J2,J4,k12,k24,c12 it has, and "
                        "NAMES is required if it has none: its tunable "
                        "parameters by their names, e.g. k24,J4,k35)")
    p.add_argument("--weights", default=None, metavar="W[,W...]",
                   help="cost of a unit change of ln(value) of each design "
                        "parameter, in the order of --params (default 1 "
                        "each)")
    p.add_argument("--also", action="append", default=[],
                   metavar="FILE.toml",
                   help="another parameter set the advice must hold for "
                        "(an uncertainty envelope), a file of `judder params "
                        "--save` for the same model (with --modelica or "
                        "--fmu: of `judder params --modelica CLASS --save`)"
                        "; repeatable")
    p.add_argument("--no-design", action="store_true",
                   help="only the windows and the ranking")
    p.add_argument("--out", metavar="FILE.csv",
                   help="safe amplitude per frequency: freq_hz,safe_p_f_bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="safe amplitude per frequency and the map of the "
                        "advised design")
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_advise)

    p = sub.add_parser("tongues", help="tongue boundaries, labels and tips",
                       description="Exact tongue boundaries by Hill's "
                                   "method (--solver hill: every kind, all "
                                   "frequencies at once; scan: combination "
                                   "by Brent's method on the monodromy); "
                                   "each point checked against the "
                                   "monodromy. Tongues numbered as in "
                                   "Fig. 14, with their tips (lowest p_f).")
    p.add_argument("--freq", default="10:220:500", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:500)")
    _pf_max_option(p, "largest amplitude searched")
    p.add_argument("--min-growth", type=str, default=0.0, metavar="1/S",
                   help="boundaries of judder growing at least this fast, "
                        "1/s (default 0: the stability boundaries of Fig. "
                        "14; map, check and advise use 1, one e-fold per "
                        "1 s engagement, the judder-relevant rate)")
    p.add_argument("--solver", default="hill", choices=("hill", "scan"),
                   help="boundary solver: hill (default, fast) or scan "
                        "(per frequency, Brent on the monodromy)")
    p.add_argument("--out", metavar="FILE.csv",
                   help="boundaries as CSV: freq_hz, p_f_bar (lowest, empty "
                        "if none), then per kind, bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="boundaries drawn over the map (Fig. 16)")
    _method_option(p)
    _model_options(p)
    _waveform_option(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_tongues)

    p = sub.add_parser("sensitivity", help="tongue shifts per parameter "
                                           "(Fig. 17, 18)",
                       description="Vary each parameter (by --factors, or to "
                                   "--values), recompute the boundaries and "
                                   "report how each tongue tip moves in "
                                   "frequency (Hz) and amplitude (bar); "
                                   "checks the paper's conclusions of "
                                   "section 4.3. Clutch-damper study: "
                                   "--params c12 --values 0.5,10.")
    p.add_argument("--params", required=True, metavar="NAMES",
                   help="comma-separated parameters, e.g. "
                        "k12,k24,J1,J2,J3,J4,mu_g,c12")
    p.add_argument("--factors", metavar="F1,F2",
                   help="multipliers of the nominal value (default 0.5,2)")
    p.add_argument("--values", metavar="V1,V2",
                   help="absolute values (SI) instead of --factors")
    p.add_argument("--freq", default="10:220:200", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:200)")
    _pf_max_option(p, "largest amplitude searched")
    _workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="tip-shift table as CSV")
    p.add_argument("--plot", metavar="FILE.png",
                   help="one panel per parameter: nominal and varied "
                        "boundaries")
    _method_option(p)
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_sensitivity)

    p = sub.add_parser("threshold", help="friction-gradient threshold "
                                         "without dither (Fig. 19)",
                       description="Largest real part of the eigenvalues "
                                   "without dither against mu_g (Fig. 19a), "
                                   "and the threshold mu_g* against the "
                                   "external damping c_i (Fig. 19b; every c_i "
                                   "set to the value). Uses the mean "
                                   "pressure in the damping "
                                   "(mean_pressure_damping = 1) unless "
                                   "--set gives it.")
    p.add_argument("--mu-g", default="-0.001:0.001:81",
                   metavar="START:STOP:N",
                   help="friction gradients for Fig. 19a, s/rad")
    p.add_argument("--c-ext", default="0:2:41", metavar="START:STOP:N",
                   help="external damping values for Fig. 19b, N m s/rad")
    p.add_argument("--out", metavar="FILE.csv",
                   help="threshold against c_i as CSV")
    p.add_argument("--plot", metavar="FILE.png", help="Fig. 19a and 19b")
    _model_options(p, modelica=False)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_threshold)

    p = sub.add_parser("fit", help="fit parameters to a measured boundary "
                                   "(section 4.2)",
                       description="Adjust hard-to-know parameters so the "
                                   "model's boundary of judder growing at "
                                   "--min-growth matches a measured one "
                                   "(CSV: freq_hz,p_f_bar; empty p_f_bar = "
                                   "no judder up to --pf-max), or the "
                                   "boundary of a chart (judder chart "
                                   "--out). Reports each value with its "
                                   "standard uncertainty, 95 % interval "
                                   "and unit, their correlations and the "
                                   "scatter of the onsets; refuses what the "
                                   "data cannot determine (k parameters "
                                   "need k + 2 onsets, k with --scatter) "
                                   "and names a parameter that does not "
                                   "move the measured boundary.")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--boundary", metavar="FILE.csv",
                        help="measured boundary, Hz and bar")
    source.add_argument("--chart", metavar="FILE.npz",
                        help="an experimental chart (judder chart --out); "
                             "--pf-max defaults to its largest amplitude")
    p.add_argument("--group", metavar="VALUE",
                   help="group of the chart to fit, when it has several "
                        "(e.g. 65-70)")
    p.add_argument("--fit", default="c12,mu_g,k24", metavar="NAMES",
                   help="parameters to fit (default c12,mu_g,k24)")
    p.add_argument("--bounds", action="append", default=[],
                   metavar="NAME=LOW:HIGH",
                   help="search range of a fitted parameter, SI; repeatable "
                        "(default a factor 100 either way of the start)")
    p.add_argument("--pf-max", type=str, default=None, metavar="BAR",
                   help="largest amplitude tried on the bench (and searched "
                        "in the model), bar (default 1.5, or the chart's)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="measured and fitted boundaries (Fig. 16a)")
    p.add_argument("--starts", type=int, default=3, metavar="N",
                   help="starts: the given one plus N-1 sampled within a "
                        "factor 3 of it (default 3)")
    p.add_argument("--uncertainty", default="auto",
                   choices=("auto", "jacobian", "profile", "bootstrap"),
                   help="how the 95 %% intervals are found (default auto: "
                        "the Jacobian, profiled where it is not trusted)")
    p.add_argument("--error-model", default="relative",
                   choices=("relative", "absolute"),
                   help="scatter of the measured onsets: a share of the "
                        "amplitude (default, as a pressure sensor's and a "
                        "valve's errors are) or the same in bar everywhere")
    p.add_argument("--scatter", metavar="SHARE|BAR",
                   help="the bench's known scatter of the onsets (its "
                        "repeatability): a share of the amplitude such as "
                        "3%% (relative error model) or bar such as 20mbar "
                        "(absolute); default: estimated from the residuals, "
                        "which needs two onsets more than the parameters")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the sampled starts and the bootstrap")
    _workers_option(p, "one, as starting Dask costs more than the few "
                       "parallel starts gain; all cores for --uncertainty "
                       "bootstrap")
    p.add_argument("--save-params", metavar="FILE.toml",
                   help="write the fitted set (never overwrites unless "
                        "--force)")
    p.add_argument("--force", action="store_true",
                   help="allow --save-params to replace a file")
    p.add_argument("--min-growth", type=float, default=None, metavar="1/S",
                   help="compare with the model's boundary of judder "
                        "growing at this rate, 1/s (default: the chart's "
                        "--min-growth with --chart or its --boundary file, "
                        "else check's 1 1/s, so "
                        "fit, check and chart call the same point judder; "
                        "0: the stability boundary)")
    p.add_argument("--threshold-spread", type=float, default=None,
                   metavar="1/S",
                   help="how far the growth rate the onsets were called "
                        "judder at may lie from --min-growth, 1/s: the fit "
                        "is repeated at --min-growth minus and plus it and "
                        "the intervals cover the values found (default: "
                        "0.25 with --chart, as a 3 s run's growth is read "
                        "to about that, docs/fitting.md; 0 with "
                        "--boundary)")
    p.add_argument("--bench-linearisation", action="store_true",
                   help="compare with the bench's linearisation (c1 + "
                        "d_control: its motor speed control damps body 1), "
                        "as for a chart of `judder campaign` runs; the "
                        "fitted values stay the driveline's")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter for --bench-linearisation (SI), "
                        "e.g. d_control=2000; repeatable (default: the "
                        "bench model's)")
    _method_option(p)
    _model_options(p)
    p.set_defaults(handler=commands.cmd_fit)

    p = sub.add_parser("simulate", help="bench engagement with dither "
                                        "(Fig. 7, 8), run through the FMU",
                       description="Engagement of the EVEN clutch at 1000 rpm "
                                   "on the test-bench model "
                                   "(TestBenchEngagement FMU, built if "
                                   "needed), run with fmpy. Writes the time "
                                   "histories (SI units) and reports the "
                                   "spectrum peaks of the upstream speed and "
                                   "of the pressure, the judder verdict, kind "
                                   "and growth as judder chart reads them, "
                                   "and the Floquet verdict of the bench's "
                                   "linearisation (c1 + d_control, the "
                                   "friction curve's value and slope at the "
                                   "slip), and whether the dither's forced "
                                   "slip swing stays within the curve's "
                                   "linear range (else the run need not "
                                   "follow that verdict). With "
                                   "--modelica CLASS: the class's FMU (built "
                                   "by the project's compiler) from its "
                                   "start values, a steady slip, with the "
                                   "dither, and the Floquet verdict of its "
                                   "linearisation; --fmu is refused (its "
                                   "Jacobian is all the FMU path reads).")
    p.add_argument("--freq", type=str, required=True, metavar="HZ[,HZ...]",
                   help="dither frequency, Hz; several (e.g. 86,206) give "
                        "one engagement each, side by side, with their "
                        "spectra overlaid (Fig. 1, Fig. 8)")
    p.add_argument("--pf", type=str, required=True, metavar="BAR",
                   help="dither amplitude, bar")
    p.add_argument("--duration", type=str, metavar="S",
                   help="simulated time, s (default: the model's "
                        "StopTime, 4 s for the bench)")
    p.add_argument("--compare", nargs="?", const="none", metavar="HZ",
                   help="also run a correct engagement: without dither, or "
                        "with dither at HZ; plotted side by side (Fig. 7)")
    p.add_argument("--bench", action="append", default=[],
                   metavar="NAME=VALUE",
                   help="bench parameter of the model (SI, or with a "
                        "unit: w_motor=1500rpm): w_motor, w_gearbox (the "
                        "steady slip is w_motor - w_gearbox), w_op and "
                        "delta_mu (the EVEN friction curve: mu0 and mu_g "
                        "are its value and slope at the slip w_op, mu stays "
                        "within mu0 +- delta_mu), t_engage, t_ramp, "
                        "p_load, load_share (REV torque over the EVEN "
                        "mean torque: 1 keeps the slip steady), N_c_load, "
                        "d_control; repeatable (not with --modelica: set "
                        "the class's parameters with --set)")
    p.add_argument("--out", metavar="run.csv|run.mf4",
                   help="time histories as CSV or ASAM MDF4")
    p.add_argument("--plot", metavar="FILE.png",
                   help="time histories and spectra")
    _method_option(p)
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_simulate)

    p = sub.add_parser("crosscheck", help="FMU growth rates against Floquet "
                                          "exponents",
                       description="Run the paper's driveline FMU (Eq. 1) on "
                                   "a grid, twice per point with initial "
                                   "speeds 1 rad/s apart; the difference is "
                                   "the free response, whose Floquet "
                                   "multipliers are fitted (Prony/Hankel "
                                   "DMD on samples once per dither period) "
                                   "and compared with the stability layer's. "
                                   "With --modelica CLASS: the class's FMU "
                                   "and its linearisation; --fmu is refused "
                                   "(the FMU path reads only its Jacobian, "
                                   "it has no time-domain run here).")
    p.add_argument("--freq", default="75:130:23", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 75:130:23: tongues "
                        "5, 2 and 6)")
    p.add_argument("--pf", default="0.1:0.7:4", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.1:0.7:4)")
    p.add_argument("--duration", type=str, default=3.0, metavar="S",
                   help="length of each run, s (default 3)")
    _workers_option(p)
    p.add_argument("--out", metavar="FILE.csv", help="table of all points")
    p.add_argument("--plot", metavar="FILE.png",
                   help="fitted against Floquet rates, and the verdicts")
    _method_option(p)
    _model_options(p)
    p.add_argument("--perturb", default="w_in", metavar="NAME",
                   help="start-speed parameter raised by 1 rad/s in the "
                        "second run of each point (default w_in)")
    _force_option(p)
    p.set_defaults(handler=commands.cmd_crosscheck)

    p = sub.add_parser("campaign", help="bench emulator: engagement "
                                        "acquisitions over a dither grid",
                       description="Emulate a bench campaign (section 3): one "
                                   "engagement per dither frequency x "
                                   "amplitude x engine speed x oil "
                                   "temperature, speeds sampled by a "
                                   "41-tooth pick-up (684 samples/s at "
                                   "1000 rpm) with noise, pressure at 1 kHz; "
                                   "one CSV and/or MF4 per run and "
                                   "OUT/index.csv. Runs in parallel; an "
                                   "interrupted or failed campaign resumes "
                                   "when run again.")
    p.add_argument("--freq", default="70:130:31", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 70:130:31: "
                        "tongues 5, 2 and 6 of the paper's driveline)")
    p.add_argument("--pf", default="0.1:0.7:7", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.1:0.7:7)")
    p.add_argument("--rpm", default="1000", metavar="N1,N2",
                   help="engine (motor) speeds, rpm (default 1000; the "
                        "paper also used 1500)")
    p.add_argument("--temperatures", default="65-70", metavar="T1,T2|all",
                   help="oil temperature ranges (55-60, 65-70, 75-80, "
                        "85-90, or all): each run at the middle of its "
                        "range, the external damping scaled with the oil's "
                        "viscosity (pysim.bench.oil_viscosity)")
    p.add_argument("--duration", type=str, default=3.0, metavar="S",
                   help="length of each engagement, s (default 3: the "
                        "0.6 s pressure ramp, then the judder's growth)")
    p.add_argument("--noise-rpm", type=str, default=0.5,
                   help="speed measurement noise, rpm (default 0.5)")
    p.add_argument("--seed", type=int, default=1, help="noise seed")
    p.add_argument("--format", default="csv,mf4", metavar="csv,mf4",
                   help="file formats per run (default both)")
    _workers_option(p)
    p.add_argument("--out", required=True, metavar="DIR",
                   help="campaign folder (created; an existing campaign "
                        "there is resumed)")
    _model_options(p, modelica=False)
    p.set_defaults(handler=commands.cmd_campaign)
    p = sub.add_parser("chart", help="experimental stability chart from "
                                     "bench acquisitions (Fig. 10, 11)",
                       description="Read engagement acquisitions (a campaign "
                                   "folder, or MF4, CSV, TDMS and MAT files), "
                                   "find in each run the engagement window, "
                                   "the dither setting (given, from the "
                                   "file's metadata, or estimated from the "
                                   "pressure), the amplitude and growth of "
                                   "the upstream speed at f, f/2 and other "
                                   "peaks, and a judder verdict (the part "
                                   "not periodic with the dither grows at "
                                   ">= --min-growth; see README). Draws "
                                   "the amplitude contour per oil "
                                   "temperature or engine speed, and writes "
                                   "the experimental boundary for `judder "
                                   "fit --boundary`. Give --model, --preset, "
                                   "--param-file or --set to draw the "
                                   "model's tongue boundaries over it.")
    p.add_argument("sources", nargs="*", metavar="SOURCE",
                   help="campaign folder (with index.csv) or acquisition "
                        "file (.mf4, .csv, .tdms, .mat)")
    p.add_argument("--index", metavar="FILE.csv",
                   help="CSV with a 'file' column (relative to it) and "
                        "optional freq_hz, p_f_bar, oil_temperature, "
                        "engine_rpm and further columns")
    p.add_argument("--channel", action="append", default=[],
                   metavar="ROLE=NAME[:UNIT[:KIND]]",
                   help="channel of ROLE (upstream_speed, required; "
                        "pressure; downstream_speed) in the files, with its "
                        "unit if the file has none (rpm, rad/s, bar, Pa, "
                        "...; an angle unit, rad, deg, rev or counts/N "
                        "(N a revolution), for an encoder); for a speed, "
                        "KIND says what its samples "
                        "are: passage (a pick-up's tooth passages), "
                        "sampled (a DAQ's rate), angle (an encoder), "
                        "default told from the data; repeatable. Without "
                        "any, the names judder campaign writes")
    p.add_argument("--group-by", action="append", metavar="COLUMN",
                   help="panel per value of COLUMN; repeatable (default: "
                        "oil_temperature and engine_rpm where they vary)")
    p.add_argument("--min-growth", type=str, default=None, metavar="1/S",
                   help="growth rate of the non-periodic part from which "
                        "a run is judder, 1/s (default 1)")
    p.add_argument("--min-amplitude", type=str, default=None,
                   metavar="RPM", help="smallest judder amplitude, rpm "
                                       "(default 2)")
    p.add_argument("--out", metavar="FILE.npz",
                   help="per-run arrays and boundaries (NPZ)")
    p.add_argument("--boundary", metavar="FILE.csv",
                   help="experimental boundary (freq_hz,p_f_bar; empty = "
                        "no judder), one file per group if several")
    p.add_argument("--plot", metavar="FILE.png",
                   help="the chart, one panel per group")
    _workers_option(p)
    _method_option(p)
    _model_options(p, modelica=False)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_chart)

    p = sub.add_parser("report", help="one HTML file with the paper's "
                                      "figures and tables for a driveline",
                       description="Run the studies of the paper for one "
                                   "driveline and write one self-contained "
                                   "HTML file (figures embedded): the "
                                   "driveline, the verdict and margin of "
                                   "the configured dither (--freq, --pf) "
                                   "with its multipliers (Fig. 15), the map "
                                   "with the exact tongues (Fig. 14) and "
                                   "their tips, the sensitivity ranking "
                                   "(Fig. 17, 18), and the fit to bench "
                                   "data (--chart or --boundary, Fig. 16a). "
                                   "Open it in a browser; print it to PDF "
                                   "from there.")
    p.add_argument("--out", required=True, metavar="FILE.html",
                   help="the report")
    p.add_argument("--pdf", metavar="FILE.pdf",
                   help="also print it to PDF (needs Debian's chromium)")
    p.add_argument("--engagement", action="store_true",
                   help="with --freq and --pf: also run the bench "
                        "engagement through the FMU (Fig. 7, 8)")
    p.add_argument("--freq", metavar="HZ",
                   help="dither frequency of the configured setting, Hz")
    p.add_argument("--pf", metavar="BAR",
                   help="dither amplitude of the configured setting, bar")
    source = p.add_mutually_exclusive_group()
    source.add_argument("--chart", metavar="FILE.npz",
                        help="bench data: a chart (judder chart --out)")
    source.add_argument("--boundary", metavar="FILE.csv",
                        help="bench data: a measured boundary "
                             "(freq_hz,p_f_bar)")
    p.add_argument("--group", metavar="VALUE",
                   help="group of the chart, when it has several")
    p.add_argument("--fit", default="c12,mu_g,k24", metavar="NAMES",
                   help="parameters fitted to the bench data (default "
                        "c12,mu_g,k24)")
    p.add_argument("--sensitivity", metavar="NAMES",
                   help="parameters of the sensitivity study (default the "
                        "stiffnesses, inertias, mu_g and c12)")
    p.add_argument("--grid", default="10:220:300", metavar="START:STOP:N",
                   help="frequencies of the boundaries, Hz (default "
                        "10:220:300)")
    p.add_argument("--map-freq", default=REPORT_MAP_FREQ,
                   metavar="START:STOP:N",
                   help=f"map frequencies, Hz (default {REPORT_MAP_FREQ})")
    p.add_argument("--map-pf", default=REPORT_MAP_PF, metavar="START:STOP:N",
                   help=f"map amplitudes, bar (default {REPORT_MAP_PF})")
    _min_growth_option(p, "; the verdict and the map's shading use it")
    _workers_option(p)
    _method_option(p)
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_report)
    _envelope_parser(sub)
    return parser


def _envelope_parser(sub):
    # nothing imported here: every command's start would pay for it
    p = sub.add_parser("envelope", help="broadest unstable region over "
                                        "uncertain parameters (Fig. 16)",
                       description="Exact tongue boundaries for every "
                                   "vertex of the parameter ranges and a "
                                   "space-filling sample of them (section "
                                   "4.2): the broadest unstable region "
                                   "(their union, refined between the "
                                   "samples), the probability of "
                                   "instability over frequency x amplitude, "
                                   "and how converged the union is. Resumes "
                                   "from FILE.checkpoint.npz beside the "
                                   "first output when interrupted. See "
                                   "docs/envelope.md.")
    p.add_argument("--ranges", required=True, metavar="FILE.toml",
                   help="uncertain parameters: intervals, uniform or normal "
                        "distributions, a judder fit's covariance (see "
                        "examples/ranges.toml)")
    p.add_argument("--freq", default="10:220:106", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 10:220:106)")
    _pf_max_option(p, "largest amplitude searched")
    p.add_argument("--samples", type=int, default=256, metavar="N",
                   help="space-filling samples after the 2**d vertices "
                        "(default 256)")
    p.add_argument("--sampler", default="sobol", metavar="{sobol,lhs}",
                   help="scrambled Sobol (default) or Latin hypercube (lhs)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the sample (default 0)")
    p.add_argument("--no-vertices", action="store_true",
                   help="leave out the vertices of the ranges")
    p.add_argument("--refine", type=int, default=20, metavar="N",
                   help="boundary evaluations per uncertain parameter spent "
                        "at each frequency searching the lowest boundary "
                        "between the samples (default 20; 0: the union of "
                        "the samples only)")
    _min_growth_option(p)
    p.add_argument("--out", metavar="FILE.npz",
                   help="every sample's boundaries, the broadest edge and "
                        "the probability grid (NPZ, see docs/envelope.md)")
    p.add_argument("--csv", metavar="FILE.csv",
                   help="per frequency: nominal and broadest boundary and "
                        "where 10/50/90 %% of the samples are unstable, bar")
    p.add_argument("--plot", metavar="FILE.png",
                   help="Fig. 16 style plot: probability shading, broadest "
                        "and nominal boundary (PNG, SVG or PDF)")
    p.add_argument("--checkpoint", metavar="FILE.npz",
                   help="checkpoint file (default beside the first of --out, "
                        "--csv, --plot; none without outputs)")
    _method_option(p)
    _workers_option(p)
    _model_options(p)
    _force_option(p)
    p.set_defaults(handler=commands.cmd_envelope)
