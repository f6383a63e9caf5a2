"""Option parsing shared by the ``judder`` commands: grids, lists,
number checks, parameter options, output folders, JSON or text, progress
bars. Every error names the option, its value and what is allowed."""

import math
import sys
from pathlib import Path

import numpy as np

from infra.errors import JudderError
from infra.files import to_json

from ..inputs import load_parameters

__all__ = ["parse_grid", "parameters_of", "emit", "parse_list",
           "check_number", "make_parents", "check_plot_format", "Progress"]


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
    from drivelines.modelica import ModelicaParameters
    for option in ("model", "preset", "param_file"):
        if getattr(args, option, None) is not None:
            raise JudderError(f"--modelica {args.modelica} replaces "
                              f"--{option.replace('_', '-')}; give one")
    return ModelicaParameters(args.modelica, args.library,
                              amplitude=args.dither_amplitude,
                              frequency=args.dither_frequency)


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
