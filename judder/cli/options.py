"""Option parsing shared by the ``judder`` commands: grids, lists,
number checks, parameter options, output folders, JSON or text, progress
bars. Every error names the option, its value and what is allowed."""

import math
import sys
from pathlib import Path

import numpy as np

from infra.errors import JudderError, check_number
from infra.files import check_folder_writable, check_output, to_json

from ..inputs import load_parameters, read_input

__all__ = ["parse_grid", "parameters_of", "parameter_file",
           "own_driveline", "emit", "parse_list",
           "make_parents", "Progress",
           "model_title", "check_outputs", "OUTPUTS"]

#: The output files of each command: (option attribute, option, suffixes;
#: None for a figure, any format matplotlib writes).
OUTPUTS = {
    "params": (("save", "--save", ("toml",)),),
    "floquet": (("plot", "--plot", None),),
    "map": (("out", "--out", ("npz",)), ("plot", "--plot", None)),
    "tongues": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "sensitivity": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "threshold": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "fit": (("save_params", "--save-params", ("toml",)),
            ("plot", "--plot", None)),
    "simulate": (("out", "--out", ("csv", "mf4")), ("plot", "--plot", None)),
    "crosscheck": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "chart": (("out", "--out", ("npz",)), ("plot", "--plot", None),
              ("boundary", "--boundary", ("csv",))),
    "check": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "advise": (("out", "--out", ("csv",)), ("plot", "--plot", None)),
    "report": (("out", "--out", ("html",)), ("pdf", "--pdf", ("pdf",))),
    "envelope": (("out", "--out", ("npz",)), ("csv", "--csv", ("csv",)),
                 ("plot", "--plot", None)),
}


def _figure_formats():
    from matplotlib.backend_bases import FigureCanvasBase
    return set(FigureCanvasBase.get_supported_filetypes())


def check_outputs(args):
    """Refuse every output of the command before any work: a folder, a
    parent that is a file, an unwritable folder, an unknown format, or a
    file judder did not write (unless --force); see
    :func:`infra.files.check_output`."""
    force = getattr(args, "force", False)
    seen = {}
    for attribute, option, suffixes in OUTPUTS.get(args.command, ()):
        path = getattr(args, attribute, None)
        if path is None:
            continue
        check_output(path, option, suffixes or _figure_formats(), force)
        key = Path(path).resolve()
        if key in seen:
            raise JudderError(f"{option} {path} is also given as "
                              f"{seen[key]}; allowed: a different file for "
                              "each output")
        seen[key] = option
    if args.command == "envelope":
        _check_checkpoint(args, seen)
    if args.command == "campaign":
        check_campaign_folder(args.out)


def _check_checkpoint(args, seen):
    """The envelope's checkpoint (given, or beside the first output) on
    none of its outputs: it is written during the work and removed at the
    end, so the output would be lost (or refused only after the work)."""
    from ..envelope import checkpoint_path
    given = args.checkpoint
    path = given or checkpoint_path(args.out, args.csv, args.plot)
    if path is None:
        return
    other = seen.get(Path(path).resolve())
    if other is not None:
        what = f"--checkpoint {given}" if given else \
            f"the checkpoint {path} (beside the first output)"
        raise JudderError(f"{what} is also given as {other}; allowed: a "
                          "different file for the checkpoint and each "
                          "output")


def check_campaign_folder(text):
    """A campaign folder: a non-empty path that is not a file, in a
    writable place."""
    if not str(text).strip():
        raise JudderError(f"--out {text!r}: allowed: a folder name (the "
                          "campaign folder, created if needed)")
    check_folder_writable(text, "--out", text)


#: Most values of one grid axis (a typo like N = 100000000000 would
#: otherwise allocate hundreds of GiB).
MAX_GRID_VALUES = 100_000


def parse_grid(text, option, unit, allow_negative=False):
    """Parse ``START:STOP:N`` (or a single value) into a linspace.

    START and STOP are plain numbers in ``unit`` or carry a unit
    (``0:300mbar:10``); see :func:`judder.cli.values.option_value`.

    Raises
    ------
    JudderError
        Naming ``option`` and saying what is allowed.
    """
    from .values import FREQ_RANGE_HZ, option_value
    parts = text.split(":")
    lowest = "" if allow_negative else "0 <= "
    allowed = (f"allowed: START:STOP:N with {lowest}START <= STOP in {unit} "
               f"and N a whole number from 1 to {MAX_GRID_VALUES} (1 only "
               f"when START = STOP), or one value (e.g. {option} 10:220:300)")
    low, high = (-math.inf, math.inf) if allow_negative else (0.0, math.inf)
    if unit == "Hz":
        low, high = FREQ_RANGE_HZ
    try:
        if len(parts) == 1:
            start = stop = option_value(parts[0], option, unit, low, high)
            count = 1
        elif len(parts) == 3:
            start = option_value(parts[0], option, unit, low, high)
            stop = option_value(parts[1], option, unit, low, high)
            count = int(parts[2])
        else:
            raise ValueError
    except JudderError:
        raise
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a grid; {allowed}") \
            from None
    if start > stop or count < 1 or count > MAX_GRID_VALUES \
            or (count == 1 and start != stop):
        raise JudderError(f"{option} {text!r} is not allowed; {allowed}")
    return np.linspace(start, stop, count)


def parameters_of(args):
    """Base parameter set and explicit changes of a command's options.

    Returns
    -------
    params : drivelines.Parameters, ModelicaParameters or FmuParameters
        From --fmu, --modelica, --param-file, --preset or --model.
    changes : dict
        The --set values, validated (SI).
    """
    params = (own_driveline(args, args.param_file, "--param-file")
              or load_parameters(preset=args.preset, model=args.model,
                                 param_file=args.param_file))
    changed = params.with_overrides(args.set)
    names = [text.partition("=")[0].strip() for text in args.set]
    from .values import check_file_pressure, check_plain_pressure
    if args.param_file:
        check_file_pressure(params, args.param_file)
    for text in args.set:
        check_plain_pressure(text)
    return params, {name: changed[name] for name in names}


def parameter_file(args, path, option):
    """The parameter set of a file of ``judder params --save`` for the
    model the options select (``--also`` of ``advise``): a preset's
    file, or with --modelica/--fmu a file of ``judder params --modelica
    CLASS --save`` (``--fmu FILE.fmu --save``)."""
    from drivelines import load_toml
    return own_driveline(args, path, option) or load_toml(
        read_input(path, option), source=str(path))


def own_driveline(args, path=None, option="--param-file"):
    """The parameter set of ``--fmu FILE.fmu`` (docs/fmu-path.md) or
    ``--modelica CLASS [--library DIR]`` (docs/onemodel.md), with the
    values of the file ``path`` if given; None if neither is given."""
    fmu, modelica = getattr(args, "fmu", None), getattr(args, "modelica", None)
    for flag, given, allowed in (
            ("--fmu", fmu, "a .fmu file"),
            ("--modelica", modelica, "a full class name, e.g. "
                                     "Judder.Examples.Driveline5DOFGeared")):
        if given is not None and not given.strip():
            raise JudderError(f"{flag} {given!r} is empty; allowed: "
                              f"{allowed}")
    if fmu:
        from drivelines.fmu_linear import FmuParameters
        flag, given = "--fmu", fmu
        replaced = ("modelica", "library", "model", "preset")
    elif modelica:
        from drivelines.modelica import ModelicaParameters
        flag, given = "--modelica", modelica
        replaced = ("model", "preset")
    else:
        return None
    for name in replaced:
        if getattr(args, name, None) is not None:
            raise JudderError(f"{flag} {given} replaces "
                              f"--{name.replace('_', '-')}; give one")
    names = {"amplitude": args.dither_amplitude,
             "frequency": args.dither_frequency}
    base = (FmuParameters(fmu, **names) if fmu else
            ModelicaParameters(modelica, args.library, **names))
    if path is None:
        return base
    return base.replace(**_file_values(path, option, base.model,
                                       f"{flag} {given}"))


def _file_values(path, option, model, selected):
    """The ``[parameters]`` of a file of ``judder params --save`` whose
    ``model`` is ``model``."""
    import tomllib
    try:
        table = tomllib.loads(read_input(path, option))
    except tomllib.TOMLDecodeError as exc:
        raise JudderError(f"{option} {path}: not TOML ({exc})") from None
    if table.get("model") != model or \
            not isinstance(table.get("parameters"), dict):
        raise JudderError(
            f"{option} {path}: model = {table.get('model')!r} is not "
            f"{model!r} of {selected} (or the [parameters] table is "
            f"missing); allowed: a file of `judder params {selected} "
            "--save`")
    return _flat(table["parameters"])


#: Forms of --dither-wave, for its help and its error message.
WAVEFORMS = ("cosine", "square[:TAU_MS]", "fourier:A1,A2,...[/B1,B2,...]",
             "period:FILE.csv")


def parse_waveform(text):
    """The dither waveform of ``--dither-wave`` (None: the cosine).

    ``square:TAU_MS`` is a square wave through a first-order valve lag of
    time constant TAU_MS (ms, default 0); ``fourier:A/B`` the cosine and
    sine coefficients of the harmonics 1, 2, ...; ``period:FILE.csv`` one
    measured period of pressure, equally spaced, the last column of each
    numeric row (a header line is skipped).
    """
    from stability.waveforms import FilteredSquare, FourierSeries, \
        from_samples
    kind, _, rest = (text or "cosine").partition(":")
    option = f"--dither-wave {text!r}"
    if kind == "cosine" and not rest:
        return None
    if kind == "square":
        tau = parse_list(rest, "--dither-wave square:")[0] if rest else 0.0
        check_number("--dither-wave square: TAU_MS", tau, "ms", strict=False)
        return FilteredSquare(tau * 1e-3)
    if kind == "fourier" and rest:
        cos, _, sin = rest.partition("/")
        return FourierSeries(
            cos=tuple(parse_list(cos, option)) if cos.strip() else (),
            sin=tuple(parse_list(sin, option)) if sin.strip() else ())
    if kind == "period" and rest:
        rows = [line.split(",")[-1].strip()
                for line in read_input(rest, "--dither-wave period:")
                .splitlines() if line.strip()]
        if rows and not _is_float(rows[0]):
            rows = rows[1:]
        return from_samples(parse_list(",".join(rows), option))
    raise JudderError(f"{option} is not allowed; allowed: "
                      + ", ".join(WAVEFORMS))


def _is_float(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


def _flat(table, prefix=""):
    """TOML reads ``housing.phi0 = 0`` as a table; back to dotted names."""
    flat = {}
    for key, value in table.items():
        if isinstance(value, dict):
            flat.update(_flat(value, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = value
    return flat


def emit(args, data, text):
    """Print ``data`` as JSON with --json, else ``text``."""
    print(to_json(data) if args.json else text)


def parse_list(text, option, convert=float):
    """Comma-separated values of ``option``."""
    items = [item.strip() for item in text.split(",")]
    if len(items) > 1 and not all(items):
        raise JudderError(f"{option} {text!r} has an empty item; allowed: "
                          "values separated by single commas")
    items = [item for item in items if item]
    try:
        values = [convert(item) for item in items]
    except JudderError:          # a value out of range, or its unit
        raise
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a comma-separated list "
                          "of numbers") from None
    if not values:
        raise JudderError(f"{option} is empty")
    return values


def make_parents(*paths):
    for path in paths:
        if path is not None:
            Path(path).parent.mkdir(parents=True, exist_ok=True)


class Progress:
    """tqdm bar on stderr (shown on a terminal only) as a map callback."""

    def __init__(self, total, description):
        from tqdm import tqdm
        self._bar = tqdm(total=total, desc=description, unit="freq",
                         disable=None, file=sys.stderr)

    def __enter__(self):
        return self._update

    def _update(self, done, total):
        if self._bar.total != total:
            self._bar.total = total
        self._bar.update(done - self._bar.n)

    def __exit__(self, *exc):
        self._bar.close()
        return False


def model_title(args, params):
    """The model and every change the options made, for figure titles:
    ``'4dof, paper-4dof-fitted, c12=20'``."""
    source = (getattr(args, "param_file", None)
              or getattr(args, "preset", None)
              or ("start values of the FMU" if getattr(args, "fmu", None)
                  else "defaults of the class"
                  if getattr(args, "modelica", None) else "paper preset"))
    changes = [text.replace(" ", "") for text in getattr(args, "set", [])]
    return ", ".join([f"{params.model} driveline", str(source)] + changes)
