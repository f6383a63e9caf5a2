"""Reading what the user gives: parameter sets and measured boundaries.

Every reader names the file (or option) in its errors, so a command can
pass the message on as it is.
"""

from pathlib import Path

import numpy as np

from drivelines import (DEFAULT_MODEL, default_preset, get_preset,
                        load_toml)
from infra.errors import JudderError
from infra.units import PA_PER_BAR

__all__ = ["read_input", "load_parameters", "read_boundary_csv",
           "read_boundary", "read_chart_boundary", "read_chart_min_growth"]


def read_input(path, option):
    """Text of a file the user named, or JudderError naming ``option``."""
    try:
        return Path(path).read_text()
    except OSError as exc:
        raise JudderError(f"{option} {path}: cannot read it "
                          f"({exc.strerror})") from None


def load_parameters(preset=None, model=None, param_file=None):
    """The parameter set named by a preset, a model or a TOML file.

    Parameters
    ----------
    preset : str, optional
        A preset name (:data:`drivelines.PRESETS`).
    model : str, optional
        A driveline (:data:`drivelines.MODELS`); alone, its paper preset.
        With ``preset`` or ``param_file``, it must match their model.
    param_file : path, optional
        A TOML file as written by ``judder params --save``.

    Returns
    -------
    drivelines.Parameters
        With nothing given, the paper preset of the default driveline.
    """
    if param_file is not None:
        if preset is not None:
            raise JudderError("give either --param-file FILE or --preset "
                              "NAME, not both")
        params = load_toml(read_input(param_file, "--param-file"),
                           source=str(param_file))
    else:
        params = get_preset(preset or default_preset(model or DEFAULT_MODEL))
    if model is not None and model != params.model:
        raise JudderError(f"--model {model} does not match the "
                          f"{params.model} parameter set given")
    return params


def read_boundary_csv(text, source="boundary file"):
    """Parse a measured boundary: columns ``freq_hz,p_f_bar``.

    A header line is allowed, and further columns are ignored (so the CSV
    of ``judder tongues --out`` can be read back); an empty ``p_f_bar``
    means no judder up to the largest amplitude tried.

    Returns
    -------
    freq_hz, p_f : ndarray
        Hz and Pa (NaN for censored points).

    Examples
    --------
    >>> f, p = read_boundary_csv("freq_hz,p_f_bar\\n100,0.3\\n60,\\n")
    >>> f.tolist(), p.tolist()
    ([100.0, 60.0], [30000.0, nan])
    """
    freqs, amps = [], []
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.split("#")[0].strip()
        if not line:
            continue
        cells = [c.strip() for c in line.split(",")][:2]
        if number == 1 and not _is_number(cells[0]):
            continue
        if len(cells) != 2 or not _is_number(cells[0]) or not (
                cells[1] == "" or _is_number(cells[1])):
            raise JudderError(f"{source}, line {number}: {line!r} is not "
                              "'freq_hz,p_f_bar' (p_f_bar empty for no "
                              "judder)")
        freq = float(cells[0])
        amp = float(cells[1]) * PA_PER_BAR if cells[1] else np.nan
        if not np.isfinite(freq) or freq <= 0 or amp < 0:
            raise JudderError(f"{source}, line {number}: frequency must be "
                              "> 0 Hz and amplitude >= 0 bar")
        freqs.append(freq)
        amps.append(amp)
    if not freqs:
        raise JudderError(f"{source}: no data lines")
    return np.array(freqs), np.array(amps)


def read_boundary(path, option="--boundary"):
    """A measured boundary file (see :func:`read_boundary_csv`)."""
    return read_boundary_csv(read_input(path, option), source=str(path))


def read_chart_boundary(path, group=None, option="--chart"):
    """The experimental boundary of a chart written by ``judder chart
    --out``.

    Parameters
    ----------
    path : path
        The chart's NPZ file.
    group : str, optional
        Which group (``'65-70'``, ``'65-70/1000'``, ...); needed when the
        chart has several.

    Returns
    -------
    freq_hz, p_f : ndarray
        Hz and Pa (NaN where no run had judder).
    tried_bar : float
        The largest amplitude tried, bar.
    """
    try:
        with np.load(path, allow_pickle=False) as npz:
            groups = npz["boundary_group"]
            freq, p_bar = npz["boundary_freq_hz"], npz["boundary_p_f_bar"]
            tried = npz["boundary_tried_bar"]
    except (OSError, ValueError, KeyError) as exc:
        raise JudderError(f"{option} {path}: not a chart written by judder "
                          f"chart --out ({exc})") from None
    names = list(dict.fromkeys(groups.tolist()))
    if group is None and len(names) > 1:
        raise JudderError(f"{option} {path} has {len(names)} groups; give "
                          f"--group, one of {', '.join(names)}")
    chosen = names[0] if group is None else group
    if chosen not in names:
        raise JudderError(f"--group {group!r} is not in {path}; allowed: "
                          f"{', '.join(names)}")
    keep = groups == chosen
    return (freq[keep].astype(float), p_bar[keep] * PA_PER_BAR,
            float(tried[keep].max()))


def read_chart_min_growth(path, option="--chart"):
    """The growth rate (1/s) from which the chart's verdict called a run
    judder (``judder chart --min-growth``); 0 for a chart without it."""
    try:
        with np.load(path, allow_pickle=False) as npz:
            if "min_growth_per_s" not in npz.files:
                return 0.0
            value = float(npz["min_growth_per_s"])
    except (OSError, ValueError) as exc:
        raise JudderError(f"{option} {path}: not a chart written by judder "
                          f"chart --out ({exc})") from None
    if not (np.isfinite(value) and value >= 0):
        raise JudderError(f"{option} {path}: its min_growth_per_s = {value!r} "
                          "is not allowed; allowed: a finite number >= 0")
    return value


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True
