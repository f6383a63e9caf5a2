"""Option parsing shared by the ``judder`` commands: grids, lists,
number checks, parameter options, output folders, JSON or text, progress
bars. Every error names the option, its value and what is allowed."""

import math
import sys
from pathlib import Path

import numpy as np

from infra.errors import JudderError
from infra.files import to_json

from ..inputs import load_parameters, read_input

__all__ = ["parse_grid", "parameters_of", "emit", "parse_list",
           "check_number", "make_parents", "check_plot_format", "Progress",
           "model_title"]


def parse_grid(text, option, unit, allow_negative=False):
    """Parse ``START:STOP:N`` (or a single value) into a linspace.

    Raises
    ------
    JudderError
        Naming ``option`` and saying what is allowed.
    """
    parts = text.split(":")
    lowest = "" if allow_negative else "0 <= "
    allowed = (f"allowed: START:STOP:N with {lowest}START <= STOP in {unit} "
               f"and N a whole number >= 1, or one value "
               f"(e.g. {option} 10:220:300)")
    try:
        if len(parts) == 1:
            start = stop = float(parts[0])
            count = 1
        elif len(parts) == 3:
            start, stop = float(parts[0]), float(parts[1])
            count = int(parts[2])
        else:
            raise ValueError
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a grid; {allowed}") \
            from None
    if not (np.isfinite(start) and np.isfinite(stop)) or start > stop \
            or (start < 0 and not allow_negative) or count < 1 \
            or (count == 1 and start != stop):
        raise JudderError(f"{option} {text!r} is not allowed; {allowed}")
    return np.linspace(start, stop, count)


def parameters_of(args):
    """Base parameter set and explicit changes of a command's options.

    Returns
    -------
    params : drivelines.Parameters
        From --param-file, --preset or --model.
    changes : dict
        The --set values, validated (SI).
    """
    if getattr(args, "modelica", None):
        params = modelica_parameters(args)
    else:
        params = load_parameters(preset=args.preset, model=args.model,
                                 param_file=args.param_file)
    changed = params.with_overrides(args.set)
    names = [text.partition("=")[0].strip() for text in args.set]
    return params, {name: changed[name] for name in names}


def modelica_parameters(args):
    """The parameter set of ``--modelica CLASS [--library DIR]``."""
    import tomllib
    from drivelines.modelica import ModelicaParameters
    for option in ("model", "preset"):
        if getattr(args, option, None) is not None:
            raise JudderError(f"--modelica {args.modelica} replaces "
                              f"--{option}; give one")
    values = {}
    if args.param_file is not None:
        # a file of `judder params --modelica CLASS --save`
        try:
            table = tomllib.loads(read_input(args.param_file,
                                             "--param-file"))
        except tomllib.TOMLDecodeError as exc:
            raise JudderError(f"--param-file {args.param_file}: not TOML "
                              f"({exc})") from None
        if table.get("model") != args.modelica or \
                not isinstance(table.get("parameters"), dict):
            raise JudderError(
                f"--param-file {args.param_file}: model = "
                f"{table.get('model')!r} is not --modelica {args.modelica} "
                "(or the [parameters] table is missing)")
        values = _flat(table["parameters"])
    return ModelicaParameters(args.modelica, args.library, values,
                              amplitude=args.dither_amplitude,
                              frequency=args.dither_frequency)


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
    items = [item.strip() for item in text.split(",") if item.strip()]
    try:
        values = [convert(item) for item in items]
    except ValueError:
        raise JudderError(f"{option} {text!r} is not a comma-separated list "
                          "of numbers") from None
    if not values:
        raise JudderError(f"{option} is empty")
    return values


def check_number(option, value, unit, strict=True):
    """Raise JudderError unless ``value`` is finite and > 0 (>= 0)."""
    if value is None:
        return value
    ok = math.isfinite(value) and (value > 0 if strict else value >= 0)
    if not ok:
        raise JudderError(f"{option} {value:g} {unit} is not allowed; "
                          f"allowed: a finite value {'>' if strict else '>='}"
                          f" 0 {unit}")
    return value


def check_plot_format(path):
    """Refuse a --plot file whose suffix matplotlib cannot write, before
    any work is done."""
    from matplotlib.backend_bases import FigureCanvasBase
    formats = FigureCanvasBase.get_supported_filetypes()
    suffix = Path(path).suffix.lstrip(".").lower()
    if suffix not in formats:
        raise JudderError(f"--plot {path}: unknown format {suffix!r}; "
                          f"allowed: {', '.join(sorted(formats))}")


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
              or "paper preset")
    changes = [text.replace(" ", "") for text in getattr(args, "set", [])]
    return ", ".join([f"{params.model} driveline", str(source)] + changes)
