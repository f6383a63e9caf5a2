"""MATLAB MAT acquisitions: scipy up to v7, h5py for v7.3 (HDF5)."""

import numpy as np

from infra.errors import JudderError

from ._common import TIME_NAMES, listing, plain

__all__ = ["read"]


def read(path, wanted):
    """MATLAB MAT up to v7: variables or struct fields with time vectors."""
    import scipy.io
    try:
        data = scipy.io.loadmat(str(path), simplify_cells=True)
    except NotImplementedError:      # v7.3: an HDF5 file
        data = _load_mat73(path)
    top = {k: v for k, v in data.items() if not k.startswith("__")}
    signals = _mat_signals(top)
    raws = {}
    for name in wanted:
        scope = _mat_scope(path, signals, name)
        if scope is not None:
            raws[name] = _mat_signal(path, top, scope)
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
    """(struct path, key) of ``name``: dotted, or a unique plain name."""
    if name in signals:
        return signals[name]
    matches = [dotted for dotted, (_, key) in signals.items() if key == name]
    if len(matches) > 1:
        raise JudderError(f"{path}: variable {name!r} is in several structs; "
                          f"name one of {listing(sorted(matches))}")
    return signals[matches[0]] if matches else None


def _mat_signal(path, top, scope):
    """(time, values, unit) of one signal, looking for its time vector and
    unit in its struct, then in the structs around it."""
    prefix, key = scope
    nodes = [_mat_node(top, prefix[:i]) for i in range(len(prefix), -1, -1)]
    time = _first(nodes, [f"{key}_time", f"t_{key}"] + list(TIME_NAMES))
    if time is None:
        name = ".".join(prefix + (key,))
        raise JudderError(f"{path}: variable {name!r} has no time vector; "
                          f"give one as {key}_time, t_{key}, time or t")
    units = [node["units"] for node in nodes
             if isinstance(node.get("units"), dict)]
    unit = _first(units, [key])
    if unit is not None:
        unit = str(unit).strip() or None
    return time, _mat_node(top, prefix)[key], unit


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
