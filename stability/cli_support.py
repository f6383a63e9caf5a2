"""Helpers shared by the ``judder`` commands: grids, parameters, checks,
output, progress bars."""

import math
import sys
from pathlib import Path

import numpy as np

from .errors import JudderError

__all__ = ["PA_PER_BAR", "parse_grid", "resolve_parameters", "emit",
           "parse_list", "check_number", "bar_to_pa", "make_parents",
           "read_input", "Progress"]

PA_PER_BAR = 1e5


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


def read_input(path, option):
    """Text of a file the user named, or JudderError naming the option."""
    try:
        return Path(path).read_text()
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror})") from None


def resolve_parameters(args):
    """Parameters from --param-file/--preset/--model, then --set."""
    from . import parameters as par
    if args.param_file is not None:
        if args.preset is not None:
            raise JudderError("give either --param-file FILE or --preset "
                              "NAME, not both")
        params = par.load_toml(read_input(args.param_file, "--param-file"),
                               source=str(args.param_file))
    else:
        name = args.preset or par.default_preset(args.model or "4dof")
        params = par.get_preset(name)
    if args.model is not None and args.model != params.model:
        raise JudderError(f"--model {args.model} does not match the "
                          f"{params.model} parameter set given")
    return params.with_overrides(args.set)


def emit(args, data, text):
    """Print ``data`` as JSON with --json, else ``text``."""
    from .output import to_json
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


def bar_to_pa(value, option):
    return check_number(option, value, "bar") * PA_PER_BAR


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
        self._bar.update(done - self._bar.n)

    def __exit__(self, *exc):
        self._bar.close()
        return False
