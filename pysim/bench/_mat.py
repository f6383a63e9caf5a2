"""MATLAB MAT acquisitions: scipy up to v7, h5py for v7.3 (HDF5)."""

import numpy as np

from infra.errors import JudderError

from ._common import TIME_NAMES, column_factor, listing, plain, time_unit

__all__ = ["read"]


def read(path, wanted, time=None):
    """MATLAB MAT up to v7: variables or struct fields with time vectors,
    and dSPACE's struct arrays (:func:`_dspace_signals`)."""
    import scipy.io
    try:
        data = scipy.io.loadmat(str(path), simplify_cells=True)
    except NotImplementedError:      # v7.3: an HDF5 file
        data = _load_mat73(path)
    top = {k: v for k, v in data.items() if not k.startswith("__")}
    signals = _mat_signals(top)
    _dspace_signals(path, top, signals)
    raws = {}
    for name in wanted:
        scope = _mat_scope(path, signals, name)
        if scope is not None:
            raws[name] = scope[2] if len(scope) == 3 else \
                _mat_signal(path, top, scope, time)
    return sorted(signals), _mat_metadata(top), raws


def _load_mat73(path):
    """A MAT v7.3 file (HDF5, h5py) as ``loadmat(simplify_cells=True)``
    gives a v7 one: structs as dicts, char arrays as text, vectors 1-D,
    scalars as numbers."""
    import h5py
    with h5py.File(path, "r") as top:
        return {key: _mat73_value(top[key]) for key in top
                if not key.startswith("#")}


def _mat73_value(node):
    import h5py
    kind = node.attrs.get("MATLAB_class", b"")
    kind = kind.decode() if isinstance(kind, bytes) else str(kind)
    if isinstance(node, h5py.Group):
        return {key: _mat73_value(node[key]) for key in node
                if not key.startswith("#")}
    values = np.asarray(node[()]).T       # MATLAB stores column-major
    if kind == "char":
        return "".join(map(chr, values.ravel()))
    values = np.squeeze(values)
    return values.item() if values.ndim == 0 else values


def _mat_signals(top, prefix=(), scopes=None):
    """Dotted name -> (path of struct names, key) of every numeric array."""
    scopes = {} if scopes is None else scopes
    node = _mat_node(top, prefix)
    for key, value in node.items():
        if isinstance(value, dict) and key not in ("units", "metadata"):
            _mat_signals(top, prefix + (key,), scopes)
        elif isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
            scopes[".".join(prefix + (key,))] = (prefix, key)
    return scopes


def _mat_node(top, prefix):
    node = top
    for key in prefix:
        node = node[key]
    return node


def _mat_scope(path, signals, name):
    """The scope (struct path, key[, what was read]) of ``name``: dotted,
    or a unique plain name."""
    if name in signals:
        return signals[name]
    matches = [dotted for dotted, scope in signals.items()
               if scope[1] == name]
    if len(matches) > 1:
        raise JudderError(f"{path}: variable {name!r} is in several structs; "
                          f"name one of {listing(sorted(matches))}")
    return signals[matches[0]] if matches else None


def _mat_signal(path, top, scope, time):
    """(time, values, unit) of one signal, looking for its time vector and
    unit in its struct, then in the structs around it; ``time`` (the
    ``time`` role's ChannelSpec, or None) names a shared time vector of
    another name than ``time`` or ``t``, and its unit (default s)."""
    prefix, key = scope
    nodes = [_mat_node(top, prefix[:i]) for i in range(len(prefix), -1, -1)]
    shared = [time.name] if time is not None else list(TIME_NAMES)
    stamps = _first(nodes, [f"{key}_time", f"t_{key}"] + shared)
    if stamps is None:
        name = ".".join(prefix + (key,))
        raise JudderError(f"{path}: variable {name!r} has no time vector; "
                          f"give one as {key}_time, t_{key}, "
                          + (time.name if time is not None else
                             "time or t, or name it with `channels` "
                             "time=NAME[:UNIT]"))
    units = [node["units"] for node in nodes
             if isinstance(node.get("units"), dict)]
    unit = _first(units, [key])
    if unit is not None:
        unit = str(unit).strip() or None
    factor = column_factor(path, ("time", time_unit(time, None)), "time")
    return (np.asarray(stamps, dtype=float) * factor,
            _mat_node(top, prefix)[key], unit)


def _records(value):
    """A struct array as loadmat gives it (a dict for one element, a list
    of dicts for several), as a list of dicts; [] for anything else."""
    if isinstance(value, dict):
        return [value]
    if isinstance(value, (list, np.ndarray)) and len(value) and all(
            isinstance(v, dict) for v in value):
        return list(value)
    return []


def _dspace_signals(path, top, scopes):
    """dSPACE ControlDesk's MAT export, added to ``scopes``: a struct
    (``judder_run``) whose ``X`` holds the time bases (``X(k).Data``, s)
    and ``Y`` the signals (``Y(i).Name``, ``Y(i).Data``, ``Y(i).Unit``
    where given, ``Y(i).XIndex``: which time base, from 1). A signal is
    named ``STRUCT.NAME`` or ``NAME``; its scope holds (time, values,
    unit) as read."""
    for struct, node in top.items():
        if not isinstance(node, dict):
            continue
        bases, signals = _records(node.get("X")), _records(node.get("Y"))
        if not bases or not signals:
            continue
        for signal in signals:
            if "Name" not in signal or "Data" not in signal:
                continue
            name = str(signal["Name"]).strip()
            index = int(signal.get("XIndex", 1)) - 1
            if not 0 <= index < len(bases) or "Data" not in bases[index]:
                raise JudderError(
                    f"{path}: {struct}.Y signal {name!r} has XIndex "
                    f"{index + 1}; allowed: 1 to {len(bases)}, an X with "
                    "Data (its time base)")
            unit = str(signal.get("Unit", "")).strip() or None
            scopes[f"{struct}.{name}"] = ((struct,), name, (
                np.asarray(bases[index]["Data"], dtype=float),
                np.asarray(signal["Data"]), unit))


def _first(nodes, keys):
    """The first value of ``keys`` found in ``nodes`` (inner first)."""
    for node in nodes:
        for key in keys:
            if key in node and not isinstance(node[key], dict):
                return node[key]
    return None


def _mat_metadata(top):
    """The ``metadata`` struct and the scalar variables (numbers, text)."""
    metadata = {key: plain(value) for key, value in top.items()
                if isinstance(value, (str, int, float, bool, np.generic))}
    if isinstance(top.get("metadata"), dict):
        metadata.update(plain(top["metadata"]))
    return metadata
