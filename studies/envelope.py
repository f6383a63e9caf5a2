"""``judder envelope``: the ranges file, the fit it may name, and a run
that survives interruption (a checkpoint of the per-sample boundaries).

Ranges file (TOML, SI units; see ``examples/ranges.toml``)::

    coverage = 0.95                  # central share kept of a normal
    [parameters]
    c12 = [5.0, 15.0]                # an interval
    k24 = { relative = [0.94, 1.06] }  # an interval around the nominal
    mu_g = { distribution = "uniform", low = 0.018, high = 0.026 }
    J2 = { distribution = "normal", mean = 0.05, std = 0.002 }
    [fit]                            # `judder fit --json > fit.json`
    file = "fit.json"                # normal with the fit's covariance
    names = ["c12", "k24"]           # optional: a subset of its names

The kernels are in :mod:`stability.uncertainty.envelope`; this module only reads
files and keeps the checkpoint.
"""

from dataclasses import dataclass
import hashlib
import io
import json
import math
from pathlib import Path
import time
import tomllib
import zipfile

import numpy as np

from infra.errors import JudderError
from infra.files import atomic_write, keeps_foreign_files, save_npz, write_text
from infra.parallel import cluster
from infra.units import PA_PER_BAR
from sources.dither_modes import linearised_mode, mode_words
from stability.kinds import KINDS
from stability.monodromy import DEFAULT_METHOD
from stability.tongues import lowest_of_kinds
from stability.uncertainty.envelope import (REFINE_EVALUATIONS, build_envelope,
                                            compute_samples, refine_union,
                                            refinement_starts)
from stability.uncertainty.ranges import (DEFAULT_COVERAGE, Correlated, Normal,
                                          Ranges, Uniform, check_values,
                                          design_points)

#X checkpoint_path
from ._common import BACKGROUND_AMPLITUDES, checked_values
from ._records import finite_or_none, rows_to_csv
from .inputs import read_input

__all__ = ["read_ranges", "run_envelope", "checkpoint_path"]

#: Seconds between two checkpoint writes.
CHECKPOINT_SECONDS = 2.0
#: Keys a ranges file may have.
_TOP_KEYS = {"coverage", "parameters", "fit"}


def _number(path, where, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value):
        raise JudderError(f"{path}: {where} = {value!r} is not allowed; "
                          "allowed: a finite number")
    return float(value)


def _pair(path, where, value):
    if not isinstance(value, list) or len(value) != 2:
        raise JudderError(f"{path}: {where} = {value!r} is not allowed; "
                          "allowed: [low, high]")
    return [_number(path, where, v) for v in value]


def _parameter(path, name, spec, nominal):
    where = f"parameters.{name}"
    if isinstance(spec, list):
        return Uniform(name, *_pair(path, where, spec))
    if not isinstance(spec, dict):
        raise JudderError(f"{path}: {where} = {spec!r} is not allowed; "
                          "allowed: [low, high] or a table")
    if "relative" in spec:
        low, high = _pair(path, f"{where}.relative", spec["relative"])
        return Uniform(name, low * nominal, high * nominal)
    kind = spec.get("distribution", "uniform")
    keys = {"uniform": ("low", "high"), "normal": ("mean", "std")}
    if kind not in keys:
        raise JudderError(f"{path}: {where}.distribution = {kind!r} is "
                          "unknown; allowed: uniform, normal (or "
                          "relative = [low, high])")
    unknown = sorted(set(spec) - {"distribution", *keys[kind]})
    missing = [k for k in keys[kind] if k not in spec]
    if unknown or missing:
        raise JudderError(f"{path}: {where} ({kind}) needs "
                          f"{' and '.join(keys[kind])}"
                          + (f"; unknown key {unknown[0]!r}" if unknown
                             else f"; {missing[0]} is missing"))
    a, b = (_number(path, f"{where}.{k}", spec[k]) for k in keys[kind])
    return Uniform(name, a, b, "uniform") if kind == "uniform" \
        else Normal(name, a, b)


def _fit(path, spec):
    """A :class:`Correlated` from the JSON of ``judder fit --json``."""
    if not isinstance(spec, dict) or "file" not in spec:
        raise JudderError(f"{path}: [fit] needs file = \"FIT.json\" (the "
                          "JSON judder fit prints)")
    unknown = sorted(set(spec) - {"file", "names"})
    if unknown:
        raise JudderError(f"{path}: [fit] has unknown key {unknown[0]!r}; "
                          "allowed: file, names")
    source = (path.parent / spec["file"]).resolve()
    try:
        data = json.loads(source.read_text())
        fitted = data["fitted"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise JudderError(f"{path}: [fit] file {source}: not the JSON of "
                          f"judder fit ({exc})") from None
    if not isinstance(fitted, dict) or not all(
            isinstance(entry, dict) for entry in fitted.values()):
        raise JudderError(f"{path}: [fit] file {source}: 'fitted' is not "
                          "a table of parameters; allowed: the JSON of "
                          "judder fit")
    names = spec.get("names", list(fitted))
    if not isinstance(names, list) or not names or not all(
            isinstance(n, str) for n in names):
        raise JudderError(f"{path}: [fit] names = {names!r} is not allowed; "
                          "allowed: a list of fitted parameter names")
    unknown = [n for n in names if n not in fitted]
    if unknown:
        raise JudderError(f"{path}: [fit] names: {unknown[0]!r} was not "
                          f"fitted in {source}; allowed: {', '.join(fitted)}")
    where = f"[fit] file {source}: fitted"
    for n in names:
        if "value" not in fitted[n] or "std" not in fitted[n]:
            missing = "value" if "value" not in fitted[n] else "std"
            raise JudderError(f"{path}: {where}.{n} has no {missing}; "
                              "allowed: the JSON judder fit prints")
    mean = np.array([_number(path, f"{where}.{n}.value",
                             fitted[n]["value"]) for n in names])
    std = [None if fitted[n]["std"] is None else
           _number(path, f"{where}.{n}.std", fitted[n]["std"])
           for n in names]
    bad = [n for n, s in zip(names, std) if s is None or s <= 0]
    if bad:
        raise JudderError(f"{path}: [fit] {bad[0]} is undetermined by the "
                          f"fit in {source} (no finite uncertainty); give it"
                          " a range under [parameters] instead")
    covariance = data.get("covariance")
    if covariance is None:
        matrix = np.diag(np.square(std))
    else:
        matrix = _covariance(path, source, covariance, names)
    return Correlated(tuple(names), mean, matrix,
                      source=f"judder fit {source.name}")


def _covariance(path, source, covariance, names):
    """The block of ``names`` of a fit's covariance, checked: names that
    the fit has, a square matrix of their number, numbers (null: an
    undetermined entry, infinite)."""
    where = f"{path}: [fit] file {source}: covariance"
    allowed = "allowed: the JSON judder fit prints"
    if not isinstance(covariance, dict) or not isinstance(
            covariance.get("names"), list) or not isinstance(
            covariance.get("matrix"), list):
        raise JudderError(f"{where} is not {{names, matrix}}; {allowed}")
    known = covariance["names"]
    missing = [n for n in names if n not in known]
    if missing:
        raise JudderError(f"{where} has no row for {missing[0]!r}; "
                          f"{allowed}")
    rows = covariance["matrix"]
    if len(rows) != len(known) or not all(
            isinstance(row, list) and len(row) == len(known)
            for row in rows):
        raise JudderError(f"{where}: the matrix is not {len(known)} x "
                          f"{len(known)} (one row and column per name); "
                          f"{allowed}")
    cells = [v for row in rows for v in row if v is not None]
    if any(isinstance(v, bool) or not isinstance(v, (int, float))
           for v in cells):
        raise JudderError(f"{where} holds something that is not a number; "
                          f"{allowed}")
    order = [known.index(n) for n in names]
    full = np.array([[np.inf if v is None else v for v in row]
                     for row in rows], dtype=float)
    return full[np.ix_(order, order)]


def read_ranges(path, params):
    """The uncertain parameters of a ranges file (see the module
    docstring).

    Parameters
    ----------
    path : str or Path
    params : drivelines.Parameters
        The nominal set (``relative`` ranges multiply its values).

    Returns
    -------
    stability.uncertainty.ranges.Ranges

    Raises
    ------
    JudderError
        A missing or malformed file, an unknown key or parameter, a range
        the model does not allow (the message names the key and value).
    """
    path = Path(path)
    try:
        data = tomllib.loads(read_input(path, "`ranges`"))
    except tomllib.TOMLDecodeError as exc:
        raise JudderError(f"`ranges` {path}: not TOML ({exc})") from None
    unknown = sorted(set(data) - _TOP_KEYS)
    if unknown:
        raise JudderError(f"{path}: unknown key {unknown[0]!r}; allowed: "
                          f"{', '.join(sorted(_TOP_KEYS))}")
    items = []
    table = data.get("parameters", {})
    if not isinstance(table, dict):
        raise JudderError(f"{path}: parameters = {table!r} is not allowed; "
                          "allowed: a [parameters] table, one line a "
                          "parameter (NAME = [low, high] or a table)")
    for name, spec in table.items():
        if name not in params.specs:
            raise JudderError(f"{path}: unknown parameter {name!r} for the "
                              f"{params.model} model; allowed names: "
                              f"{', '.join(params.specs)}")
        items.append(_parameter(path, name, spec, params[name]))
    if "fit" in data:
        items.append(_fit(path, data["fit"]))
    coverage = _number(path, "coverage",
                       data.get("coverage", DEFAULT_COVERAGE))
    return Ranges(tuple(items), coverage)


def checkpoint_path(*outputs):
    """Checkpoint file beside the first output given (None if none)."""
    for output in outputs:
        if output:
            output = Path(output)
            return output.with_name(output.name + ".checkpoint.npz")
    return None


def _key(params, names, values, freq_hz, p_max, method, min_growth, refine):
    digest = hashlib.sha256(json.dumps(
        {"model": params.model, "params": sorted(params.values.items()),
         "names": list(names), "p_max": p_max, "method": method,
         "min_growth": min_growth, "refine": refine}).encode())
    digest.update(np.ascontiguousarray(values, dtype=float).tobytes())
    digest.update(np.ascontiguousarray(freq_hz, dtype=float).tobytes())
    return digest.hexdigest()


def _load(path, key, shape):
    """Samples and refined frequencies of a checkpoint, ``({}, {})`` if
    there is none."""
    if path is None or not Path(path).exists():
        return {}, {}
    try:
        with np.load(path) as data:
            stored = str(data["key"])
            arrays = {name: data[name] for name in (
                "index", "amplitude", "refined_index", "refined_value",
                "refined_unit")}
    except (OSError, ValueError, KeyError, EOFError,
            zipfile.BadZipFile) as exc:
        # numpy's own words (pickles, allow_pickle) are not the user's
        raise JudderError(f"checkpoint {path}: not a checkpoint of judder "
                          f"envelope ({type(exc).__name__} reading it); "
                          "allowed: a checkpoint of this envelope, or a new "
                          "path (delete the file to start again)") from None
    if stored != key or arrays["amplitude"].shape[1:] != shape:
        raise JudderError(f"checkpoint {path} belongs to another envelope "
                          "(other ranges, samples, grid or parameters); "
                          "delete it or write elsewhere")
    return (dict(zip(arrays["index"].tolist(), arrays["amplitude"])),
            {j: (v, u) for j, v, u in zip(arrays["refined_index"].tolist(),
                                          arrays["refined_value"],
                                          arrays["refined_unit"])})


def _save(path, key, done, refined, shape, dimension):
    index = np.array(sorted(done), dtype=int)
    amplitude = np.array([done[i] for i in index]).reshape(-1, *shape)
    where = np.array(sorted(refined), dtype=int)
    buffer = io.BytesIO()
    np.savez(buffer, key=key, index=index, amplitude=amplitude,
             refined_index=where,
             refined_value=np.array([refined[j][0] for j in where]),
             refined_unit=np.array([refined[j][1] for j in where]
                                   ).reshape(-1, dimension))
    atomic_write(path, lambda stream: stream.write(buffer.getvalue()))


class _Checkpoint:
    """Writes the state at most every :data:`CHECKPOINT_SECONDS`."""

    def __init__(self, path, key, shape, dimension):
        self.path, self.key = path, key
        self.shape, self.dimension = shape, dimension
        self.done, self.refined = _load(path, key, shape)
        self._last = time.monotonic()
        self._dirty = False

    def changed(self):
        self._dirty = True
        if self.path is not None and \
                time.monotonic() - self._last > CHECKPOINT_SECONDS:
            self.write()

    def write(self):
        if self.path is not None and self._dirty:
            _save(self.path, self.key, self.done, self.refined, self.shape,
                  self.dimension)
            self._last = time.monotonic()
            self._dirty = False


def run_envelope(params, ranges, freq_hz, p_max, samples=256, seed=0,
                 sampler="sobol", vertices=True, method="dyson",
                 min_growth=0.0, amplitudes=150, refine=REFINE_EVALUATIONS,
                 workers=None,
                 checkpoint=None, progress=None):
    """Compute (or resume) an envelope.

    Parameters
    ----------
    params : drivelines.Parameters
        The nominal set.
    ranges : stability.uncertainty.ranges.Ranges
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max : float
        Largest amplitude searched, Pa.
    samples, seed, sampler, vertices
        As :func:`stability.uncertainty.ranges.design_points` takes them.
    method, min_growth
        As :func:`stability.tongues.tongue_boundaries` takes them.
    amplitudes : int
        Points of the amplitude grid of the probability.
    refine : int
        Boundary evaluations per uncertain parameter at each frequency to
        refine the union between the samples
        (:func:`stability.uncertainty.envelope.refine_union`); 0: no refinement.
    checkpoint : path, optional
        NPZ of the boundaries computed so far, rewritten (atomically) at
        most every :data:`CHECKPOINT_SECONDS` and when interrupted; a run
        with the same inputs resumes from it.

    Returns
    -------
    envelope : stability.uncertainty.envelope.Envelope
    failures : list of infra.parallel.TaskFailure
        Samples (and refinements) that failed: left out of the envelope,
        not checkpointed.
    resumed : int
        Samples taken from the checkpoint.
    """
    freq_hz = np.asarray(freq_hz, dtype=float)
    unit, is_vertex = design_points(ranges, samples, seed, sampler, vertices)
    values = ranges.values(unit)
    names = ranges.names
    check_values(params, names, values)
    nominal_row = np.array([[params[n] for n in names]])
    rows = np.vstack([nominal_row, values])        # row 0: the nominal set
    key = _key(params, names, rows, freq_hz, p_max, method, min_growth,
               int(refine))
    shape = (len(freq_hz), 3)
    with cluster(workers):     # one for the samples and the refinement
        return _run(params, ranges, names, values, is_vertex, unit, rows,
                    freq_hz, p_max, method, min_growth, amplitudes, refine,
                    workers, _Checkpoint(checkpoint, key, shape, len(names)),
                    progress)


def _run(params, ranges, names, values, is_vertex, unit, rows, freq_hz,
         p_max, method, min_growth, amplitudes, refine, workers, state,
         progress):
    shape = state.shape
    resumed = len(state.done)
    failures = []
    try:
        total = len(rows)
        if progress is not None:
            progress(len(state.done), total)
        for index, outcome in compute_samples(
                params, names, rows, freq_hz, p_max, method, min_growth,
                skip=state.done, workers=workers):
            if isinstance(outcome, np.ndarray):
                state.done[index] = outcome
                state.changed()
            else:
                failures.append(outcome)
            if progress is not None:
                progress(len(state.done) + len(failures), total)
        ok = np.array([i in state.done for i in range(len(rows))])
        amplitude = np.array([state.done.get(i, np.full(shape, np.nan))
                              for i in range(len(rows))])
        lowest = np.where(ok[1:, None], lowest_of_kinds(amplitude[1:]),
                          np.inf)
        if refine and len(values):
            total += int(np.sum(refinement_starts(lowest) >= 0))
            for index, outcome in refine_union(
                    params, ranges, unit, lowest, freq_hz, p_max, method,
                    min_growth, skip=state.refined, evaluations=refine,
                    workers=workers):
                if isinstance(outcome, tuple):
                    state.refined[index] = outcome
                    state.changed()
                else:
                    failures.append(outcome)
                if progress is not None:
                    progress(len(state.done) + len(state.refined)
                             + len(failures), total)
    finally:
        state.write()
    refined = np.full(len(freq_hz), np.inf)
    refined_values = np.full((len(freq_hz), len(names)), np.nan)
    for j, (value, point) in state.refined.items():
        refined[j] = value
        refined_values[j] = ranges.values(point[None])[0]
    envelope = build_envelope(
        freq_hz, p_max, names, values, is_vertex, amplitude[1:], ok[1:],
        amplitude[0], amplitudes=amplitudes, min_growth=min_growth,
        method=method, coverage=ranges.coverage, refined=refined,
        refined_values=refined_values)
    return envelope, failures, resumed


def envelope(ranges, freq_hz, p_max_bar=1.5, samples=256, seed=0,
             sampler="sobol", vertices=True, min_growth=None, refine=20,
             parameters=None, changes=None, method=DEFAULT_METHOD,
             workers=None, checkpoint=None, progress=None, driveline=None):
    """``judder envelope``: the broadest unstable region over uncertain
    parameters and the probability of instability (section 4.2, Fig. 16).

    Parameters
    ----------
    ranges : path or stability.uncertainty.ranges.Ranges
        A ranges file (:func:`studies.envelope.read_ranges`) or the ranges.
    freq_hz : array_like
        Dither frequencies, Hz.
    p_max_bar : float
        Largest amplitude searched, bar.
    samples, seed, sampler, vertices
        Space-filling samples after the vertices, as
        :func:`stability.uncertainty.ranges.design_points` takes them.
    min_growth : float, optional
        1/s: count only judder growing at least this fast (default
        :data:`infra.criteria.DEFAULT_MIN_GROWTH_PER_S`; 0: every
        instability).
    refine : int
        Boundary evaluations per uncertain parameter spent at each
        frequency searching the lowest boundary between the samples
        (:func:`stability.uncertainty.envelope.refine_at`); 0: the union of the
        samples only.
    workers : int, optional
        Local Dask worker processes (see :mod:`infra.parallel`).
    checkpoint : path, optional
        Resume from / save to this NPZ (see
        :func:`studies.envelope.run_envelope`).

    Returns
    -------
    EnvelopeResult
        ``failures`` lists the samples that failed (left out).
    """
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    from stability.uncertainty.ranges import Ranges

    from stability.bench import driveline_view
    values, driveline = driveline_view(
        checked_values(parameters, changes, freq_hz=freq_hz,
                       p_max_bar=p_max_bar, min_growth=min_growth),
        driveline)
    _refuse_modes(values)
    if not isinstance(ranges, Ranges):
        ranges = read_ranges(ranges, values)
    growth = DEFAULT_MIN_GROWTH_PER_S if min_growth is None else min_growth
    started = time.perf_counter()
    result, failures, resumed = run_envelope(
        values, ranges, freq_hz, p_max_bar * PA_PER_BAR, samples=samples,
        seed=seed, sampler=sampler, vertices=vertices, method=method,
        min_growth=growth, amplitudes=BACKGROUND_AMPLITUDES, refine=refine,
        workers=workers, checkpoint=checkpoint, progress=progress)
    return EnvelopeResult(params=values, ranges=ranges, envelope=result,
                          failures=failures, resumed=resumed,
                          seconds=time.perf_counter() - started,
                          checkpoint=checkpoint, driveline=driveline)


def _refuse_modes(values):
    """Refuse a hybrid Modelica class (:func:`linearised_mode`): its
    linearisation holds in one mode, which would have to be checked at
    each of the envelope's parameter sets (its samples, the corners of
    the ranges, the refinement's) and each frequency (about 6 ms a
    setting checked in batches: 256 samples over 100 frequencies take
    2.5 minutes), and was
    checked at the nominal set only."""
    mode = linearised_mode(values)
    if mode:
        raise JudderError(
            f"{values.model} is {mode_words(mode)}, checked at the "
            "nominal parameters only: each of the envelope's parameter "
            "sets (its samples, the corners of the ranges and those the "
            "refinement searches) would need it checked at every "
            "frequency, about 6 ms a setting, so the envelope is not run "
            "on a class with modes; allowed: judder sensitivity, which "
            "checks the mode at each parameter set it uses, or a class "
            "without Integer and Boolean modes")


def _bar_or_none(values):
    return [finite_or_none(v / PA_PER_BAR) for v in values]


@dataclass(frozen=True)
class EnvelopeResult:
    """``judder envelope``: a
    :class:`stability.uncertainty.envelope.Envelope`, the
    ranges it was sampled from, the failed samples (each an
    :class:`infra.parallel.TaskFailure`) and how many samples came from the
    checkpoint."""

    params: object
    ranges: object
    envelope: object
    failures: list
    resumed: int
    seconds: float
    checkpoint: object = None
    driveline: str = "chain"

    #: Probabilities whose boundaries the CSV lists.
    LEVELS = (0.1, 0.5, 0.9)

    def as_dict(self):
        e = self.envelope
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                "method": e.method,
                "min_growth_per_s": e.min_growth, "seconds": self.seconds,
                "ranges": self.ranges.describe(),
                "samples": int(len(e.ok)), "vertices": int(e.is_vertex.sum()),
                "computed": int(e.ok.sum()), "resumed": self.resumed,
                "failures": [{"index": f.index, "inputs": f.inputs,
                              "message": f.message} for f in self.failures],
                "convergence": e.convergence,
                "freq_hz": e.freq_hz, "p_max_bar": e.p_max / PA_PER_BAR,
                "nominal_p_f_bar": _bar_or_none(e.nominal_boundary),
                "broadest_p_f_bar": _bar_or_none(e.broadest),
                "unstable_share_at_p_max":
                    [finite_or_none(v) for v in e.probability[:, -1]]}

    def csv_text(self):
        """Per frequency: nominal and broadest boundary, and the amplitude
        from which 10, 50, 90 % of the samples are unstable (bar; empty:
        none up to p_max)."""
        e = self.envelope
        columns = [e.nominal_boundary, e.broadest] + [
            e.quantile_boundary(q) for q in self.LEVELS]
        rows = [{"freq_hz": f"{f:.9g}", **{
            name: (None if not math.isfinite(c[i]) else
                   f"{c[i] / PA_PER_BAR:.9g}")
            for name, c in zip(["nominal_p_f_bar", "broadest_p_f_bar"] + [
                f"p_f_bar_{round(100 * q)}pct_unstable" for q in self.LEVELS],
                columns)}} for i, f in enumerate(e.freq_hz)]
        return rows_to_csv(rows)

    @keeps_foreign_files
    def save_csv(self, path):
        write_text(path, self.csv_text())

    @keeps_foreign_files
    def save(self, path):
        """NPZ: every sample's values and boundaries, the nominal, the
        broadest edge, the probability grid (bar where named so).

        ``amplitude_bar`` is (samples, frequencies, kinds) and
        ``nominal_bar`` (frequencies, kinds): the lowest boundary of each
        kind, the kinds named by ``amplitude_bar_axes`` and
        ``kind_columns`` (NaN: none up to ``p_max_bar``); ``probability``
        is (frequencies, amplitudes)."""
        e = self.envelope
        arrays = {"freq_hz": e.freq_hz, "p_f_bar": e.p_f / PA_PER_BAR,
                  "p_max_bar": e.p_max / PA_PER_BAR,
                  "names": np.array(e.names), "values": e.values,
                  "is_vertex": e.is_vertex, "ok": e.ok,
                  "amplitude_bar": e.amplitude / PA_PER_BAR,
                  "amplitude_bar_axes": np.array(["sample", "freq_hz",
                                                  "kind"]),
                  "kind_columns": np.array(KINDS[1:]),
                  "nominal_bar": e.nominal / PA_PER_BAR,
                  "broadest_bar": e.broadest / PA_PER_BAR,
                  "probability": e.probability,
                  "area_history_bar_hz": e.area_history / PA_PER_BAR,
                  "min_growth_per_s": e.min_growth,
                  "meta": json.dumps({
                      "model": self.params.model,
                      "ranges": self.ranges.describe(),
                      "convergence": e.convergence, "method": e.method,
                      "failures": [str(f) for f in self.failures]})}
        save_npz(path, arrays)

    def discard_checkpoint(self):
        """Delete the checkpoint once the outputs are written (kept while
        samples failed, so a new run retries only those)."""
        if self.checkpoint is not None and not self.failures:
            Path(self.checkpoint).unlink(missing_ok=True)

    def figure(self, title=None):
        from stability.plots import envelope_figure
        return envelope_figure(self.envelope, title=title)
