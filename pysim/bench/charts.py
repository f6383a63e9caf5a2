"""Experimental stability charts from bench acquisitions (section 3.2).

A chart is a set of engagement runs, each at a dither frequency and
amplitude and in a group (an oil temperature, an engine speed, ...), read
by :func:`pysim.bench.verdict.analyse_run`. Contoured over (frequency,
amplitude) per group it is Fig. 10 and Fig. 11 of the paper; per
frequency the lowest amplitude with judder is the experimental stability
boundary that section 4.2 fits the model to.

Where runs come from:

* a campaign folder of ``judder campaign`` (its ``index.csv``);
* an index CSV with a ``file`` column (paths relative to the index) and
  optional ``freq_hz``, ``p_f_bar``, ``oil_temperature``, ``engine_rpm``
  and any further columns to group by;
* acquisition files alone; their own metadata, or the pressure channel,
  give the dither setting.
"""

from dataclasses import dataclass
import csv
import os
from pathlib import Path, PureWindowsPath

import numpy as np

from infra.criteria import DEFAULT_JUDDER_LIMIT_RPM, DEFAULT_MIN_GROWTH_PER_S
from infra.errors import JudderError
from infra.parallel import parallel_map
from infra.units import PA_PER_BAR

from .verdict import MIN_AMPLITUDE_RPM, SETTING, analyse_run
from .acquisition import ChannelSpec
from ._csv import _csv_lines
from .readers import read_acquisition
from .tables import numbers, split_rows

__all__ = ["RunSource", "ChartRun", "Chart", "DEFAULT_CHANNELS",
           "GROUP_COLUMNS", "sources_from_campaign", "sources_from_index",
           "sources_from_files", "gather_sources", "build_chart",
           "DITHER_ARRAYS"]

#: Channel names of the files ``judder campaign`` writes.
DEFAULT_CHANNELS = {"upstream_speed": ChannelSpec("n_upstream"),
                    "downstream_speed": ChannelSpec("n_downstream"),
                    "pressure": ChannelSpec("p_even")}
#: Columns a chart is grouped by when they take several values.
GROUP_COLUMNS = ("oil_temperature", "engine_rpm")
#: Metadata keys of acquisition files that give a run's settings.
_METADATA_KEYS = {"dither_frequency_hz": "freq_hz",
                  "dither_amplitude_bar": "p_f_bar",
                  "oil_temperature_degC": "oil_temperature",
                  "engine_speed_rpm": "engine_rpm"}
_NUMBER_COLUMNS = ("freq_hz", "p_f_bar", "engine_rpm")


@dataclass(frozen=True)
class RunSource:
    """An acquisition file and what is known of its run.

    ``settings`` may hold ``freq_hz`` (Hz), ``p_f_bar`` (bar) and group
    columns; what it lacks comes from the file's metadata or is estimated.
    ``origin`` says where the run was listed, for messages (an index's
    line, a source given).
    """

    path: Path
    settings: dict
    origin: str = ""


@dataclass(frozen=True)
class ChartRun:
    """One run of a chart: where it came from, its settings, its reading.

    ``analysis`` is a :class:`pysim.bench.verdict.RunAnalysis`, or None
    when the run could not be read (``error`` says why); ``speed_kind``
    what the upstream speed's samples were
    (:data:`pysim.bench.speed_channels.SPEED_KINDS`); ``warnings``
    what the run was read with but cannot support, in words naming the
    file and the channel (a dither estimated from a pressure sampled too
    sparsely, or a dither amplitude given that the pressure contradicts).
    """

    path: Path
    settings: dict
    analysis: object
    error: str = ""
    speed_kind: str = ""
    warnings: tuple = ()

    @property
    def reason(self):
        """Why the run could not be read, with its file named once."""
        named = self.error.startswith(str(self.path))
        return self.error if named else f"{self.path}: {self.error}"

    def group(self, columns):
        """Values of the group columns, as a tuple of text."""
        return tuple(str(self.settings.get(c, "")) for c in columns)


def _read_csv(path, option, decimal=None):
    """The rows of an index CSV as ``(line, {column: value})``: the columns of
    :data:`_NUMBER_COLUMNS` as numbers read as the file writes them (NaN
    where empty; :mod:`pysim.bench.tables`, ``decimal`` the file's
    decimal separator where given), the others as text. Fields are
    separated by ``,``, or by ``;`` or tab where the header has one."""
    try:
        lines = [(number, line) for number, line in
                 enumerate(_csv_lines(path), 1) if line.strip()]
        rows = split_rows(lines, f"{option} {path}")
    except (OSError, csv.Error) as exc:
        raise JudderError(f"{option} {path}: cannot read it as CSV "
                          f"({exc})") from None
    if not rows:
        return []
    header, body = rows[0][1], rows[1:]
    # short rows read as empty cells, extra cells are not read
    cells = [(number, row + [""] * (len(header) - len(row)))
             for number, row in body]
    read = numbers(f"{option} {path}", {
        name: [(number, row[header.index(name)]) for number, row in cells]
        for name in _NUMBER_COLUMNS if name in header}, decimal)
    return [(number, {**dict(zip(header, row)),
                      **{name: float(values[index])
                         for name, values in read.items()}})
            for index, (number, row) in enumerate(cells)]


def _settings(row):
    """A row's settings: its cells but ``file``, without the empty ones."""
    return {key: value for key, value in row.items()
            if key != "file" and value != ""
            and not (isinstance(value, float) and np.isnan(value))}


def sources_from_campaign(folder):
    """The runs of a ``judder campaign`` folder that succeeded.

    Each run's MF4 file is preferred (every channel on its own time base),
    else its CSV.
    """
    folder = Path(folder)
    if not (folder / "index.csv").is_file():
        raise JudderError(_no_campaign(folder))
    rows = _read_csv(folder / "index.csv", "campaign")
    sources = []
    for number, row in rows:
        if row.get("status") != "ok":
            continue
        files = row.get("files", "").split()
        chosen = next((f for f in files if f.endswith(".mf4")),
                      files[0] if files else None)
        if chosen is None:
            continue
        settings = _settings({k: row[k] for k in
                              ("freq_hz", "p_f_bar", "engine_rpm",
                               "oil_temperature") if k in row})
        sources.append(RunSource(folder / chosen, settings,
                                 f"campaign {folder / 'index.csv'}, line "
                                 f"{number}"))
    if not sources:
        raise JudderError(f"campaign {folder}: index.csv lists no run that "
                          "succeeded")
    return sources


def _no_campaign(folder):
    """Words for a folder given as a source that is no campaign (no
    ``index.csv``): what to give instead, naming the index CSVs it holds
    (a ``file`` column in their first line) and the channels a bench's
    own files need."""
    indexes = []
    for path in sorted(folder.glob("*.csv"))[:_INDEX_LOOKS]:
        try:
            with open(path, encoding="utf-8-sig", errors="replace") as f:
                first = f.readline()
        except OSError:
            continue
        if "file" in [cell.strip().strip('"').lower() for cell in
                      first.replace(";", ",").replace("\t", ",").split(",")]:
            indexes.append(path)
    return (f"`paths` {folder}: a folder without a campaign's index.csv "
            "(as judder campaign writes it); allowed: an index CSV of its "
            "runs as `index` FILE.csv (a 'file' column and optionally "
            "freq_hz, p_f_bar, oil_temperature, engine_rpm)"
            + (f", such as `index` {indexes[0]}" if indexes else "")
            + ", or its acquisition files as `paths`, with their channels "
            "as `channels` upstream_speed=NAME (and pressure=NAME, "
            "downstream_speed=NAME) where they are not the names judder "
            "campaign writes")


#: CSV files of a folder looked into for an index's ``file`` column.
_INDEX_LOOKS = 50


def sources_from_index(index, decimal=None):
    """Runs listed in an index CSV with a ``file`` column (its numbers
    read as written, or with the decimal separator ``decimal``, as
    :func:`_read_csv` reads them)."""
    index = Path(index)
    rows = _read_csv(index, "`index`", decimal)
    if not rows or "file" not in rows[0][1]:
        raise JudderError(f"`index` {index}: needs a 'file' column (and "
                          "optionally freq_hz, p_f_bar, oil_temperature, "
                          "engine_rpm)")
    for number, row in rows:
        _check_index_row(row, f"`index` {index}, line {number}")
    return [RunSource(index.parent / _listed_path(row["file"]),
                      _settings(row), f"`index` {index}, line {number}")
            for number, row in rows]


def _listed_path(name):
    """A file as an index lists it, as a path here: a relative Windows
    path (``..\\data\\run.csv``, as an index written on Windows has it)
    read with its backslashes as separators where they are none
    (elsewhere a backslash is a letter of a file name, and no bench
    names a file with one)."""
    windows = PureWindowsPath(name)
    if "\\" in name and os.sep != "\\" and not windows.anchor:
        return Path(*windows.parts)
    return Path(name)


#: Index columns of a dither setting -> (lowest allowed, its words).
_SETTING_RANGES = {"freq_hz": (0.0, "a dither frequency > 0 Hz"),
                   "p_f_bar": (None, "a dither amplitude >= 0 bar")}


def _check_index_row(row, where):
    """Refuse an index row without a file, or with a dither setting no
    bench runs (a negative frequency stopped the chart's filters)."""
    if not row["file"].strip():
        raise JudderError(f"{where}: column 'file' is empty; allowed: the "
                          "acquisition's file, relative to the index")
    windows = PureWindowsPath(row["file"])
    if os.sep != "\\" and windows.drive and not Path(row["file"]).exists():
        # C:\data\run.csv names a drive this machine does not have
        raise JudderError(
            f"{where}: column 'file' = '{row['file']}' is a Windows path "
            f"on drive {windows.drive}, which is not here; allowed: the "
            "acquisition's file relative to the index (such as "
            f"{PureWindowsPath(*windows.parts[-2:])}, backslashes read as "
            "separators) or a path on this machine")
    for name, (above, allowed) in _SETTING_RANGES.items():
        value = row.get(name, float("nan"))
        if np.isnan(value):
            continue
        if not np.isfinite(value) or value < 0 or \
                (above is not None and value <= above):
            raise JudderError(f"{where}: column {name!r} = {value:g} is "
                              f"not allowed; allowed: {allowed}")


def sources_from_files(paths):
    """Runs from acquisition files alone."""
    return [RunSource(Path(p), {}, f"`paths` {p}") for p in paths]


def gather_sources(paths, index=None, decimal=None):
    """Runs of campaign folders, acquisition files and an index CSV (read
    with ``decimal``, :func:`sources_from_index`)."""
    sources = []
    files = []
    for path in map(Path, paths):
        if path.is_dir():
            sources += sources_from_campaign(path)
        elif path.exists():
            files.append(path)
        else:
            raise JudderError(f"`paths` {path}: no such file or folder")
    sources += sources_from_files(files)
    if index is not None:
        sources += sources_from_index(index, decimal)
    if not sources:
        raise JudderError("give at least one SOURCE (campaign folder or "
                          "acquisition file) or `index`")
    _refuse_repeated(sources)
    return sources


def _refuse_repeated(sources):
    """Refuse an acquisition listed twice (two lines of an index, or an
    index and a source given), naming both places: it would count as two
    runs, two votes at its set point and two points of its contour, and
    which of its two settings is meant is no guess to make."""
    seen = {}
    for source in sources:
        key = os.path.normcase(os.path.realpath(source.path))
        if key in seen:
            raise JudderError(
                f"{seen[key].origin} and {source.origin} both list "
                f"{source.path}; allowed: each acquisition once (one run "
                "per file)")
        seen[key] = source


def _analyse(job):
    source, channels, min_growth, min_amplitude, limit, decimal = job
    try:
        acquisition = read_acquisition(source.path, channels, decimal)
        settings = {**{_METADATA_KEYS[k]: v
                       for k, v in acquisition.metadata.items()
                       if k in _METADATA_KEYS}, **source.settings}
        ch = acquisition.channels
        speed = ch["upstream_speed"]
        if len(speed.time) < 2:
            # one sample, or every time stamp the same instant
            raise JudderError(
                f"{source.path}: upstream_speed channel {speed.name!r} has "
                f"{len(speed.time)} distinct time stamp(s); allowed: a "
                "recording of the engagement (many samples in time)")

        def pair(role):
            # an optional channel with too few samples is as good as none
            return (ch[role].interval_means()
                    if role in ch and len(ch[role].time) >= 2 else None)
        analysis = analyse_run(pair("upstream_speed"), pair("pressure"),
                               pair("downstream_speed"),
                               freq_hz=settings.get("freq_hz"),
                               p_f_bar=settings.get("p_f_bar"),
                               min_growth=min_growth,
                               min_amplitude_rpm=min_amplitude,
                               judder_limit_rpm=limit)
        warnings = () if analysis.dither is None else tuple(
            f"{source.path}: pressure channel {ch['pressure'].name!r}: "
            f"dither estimated from it: {text}"
            for text in analysis.dither.warnings)
        return ChartRun(source.path, settings, analysis,
                        speed_kind=ch["upstream_speed"].kind,
                        warnings=warnings)
    except JudderError as exc:
        return ChartRun(source.path, source.settings, None, str(exc))


def _window(analysis):
    """Length of a run's engagement window, s."""
    start, stop = analysis.window_s
    return max(stop - start, 1e-9)


@dataclass(frozen=True)
class Chart:
    """Runs read into an experimental stability chart.

    Attributes
    ----------
    runs : list of ChartRun
    group_by : tuple of str
        Columns whose values make the groups (panels).
    min_growth : float
        1/s, the verdict's growth threshold.
    judder_limit_rpm : float
        rpm, the verdict's NVH limit of the dither-related oscillation.
    """

    runs: list
    group_by: tuple
    min_growth: float
    judder_limit_rpm: float = DEFAULT_JUDDER_LIMIT_RPM

    @property
    def read(self):
        """Runs that were read."""
        return [r for r in self.runs if r.analysis is not None]

    @property
    def failed(self):
        """Runs that could not be read."""
        return [r for r in self.runs if r.analysis is None]

    def groups(self):
        """``{group: [ChartRun, ...]}`` of the runs read, in order."""
        out = {}
        for run in self.read:
            out.setdefault(run.group(self.group_by), []).append(run)
        return out

    def set_points(self, group):
        """The dither frequencies of one group's runs, as set points.

        A frequency the index or the file gives is a set point of its own.
        Frequencies estimated from the pressure (a bench that records no
        dither setting) scatter about the set point by far less than the
        spectral resolution of the run, ``1/T`` over its engagement window
        ``T``: estimates closer than half of it to each other, or to a
        given frequency, are one set point, at the given frequency or
        their median. A run whose frequency was estimated where the
        sampling cannot tell it from its aliases
        (:attr:`pysim.bench.verdict.RunAnalysis.frequency_aliased`) is
        at no set point, so on no boundary: which frequency it was run at
        is not known (:meth:`aliased` lists them).

        Returns
        -------
        list of (float, float, list of ChartRun)
            Per set point (Hz, ascending): its frequency, the spread of
            its runs' frequencies (Hz), and its runs.
        """
        runs = sorted((r for r in self.groups().get(group, [])
                       if not r.analysis.frequency_aliased),
                      key=lambda r: r.analysis.freq_hz)
        clusters = []
        for run in runs:
            a = run.analysis
            if clusters:
                last = clusters[-1][-1].analysis
                close = (a.estimated or last.estimated) and \
                    a.freq_hz - last.freq_hz <= 0.5 / max(
                        _window(a), _window(last))
                if close or round(a.freq_hz, 6) == round(last.freq_hz, 6):
                    clusters[-1].append(run)
                    continue
            clusters.append([run])
        out = []
        for cluster in clusters:
            freqs = np.array([r.analysis.freq_hz for r in cluster])
            given = [r.analysis.freq_hz for r in cluster
                     if not r.analysis.estimated]
            centre = given[0] if given else float(np.median(freqs))
            out.append((float(centre), float(np.ptp(freqs)), cluster))
        return out

    def aliased(self, group):
        """The runs of one group left out of its set points and its
        boundary: their frequency, estimated from the pressure, may be an
        alias of the one run (:meth:`set_points`)."""
        return [r for r in self.groups().get(group, [])
                if r.analysis.frequency_aliased]

    def boundary(self, group):
        """Experimental stability boundary of one group.

        Returns
        -------
        list of (float, float or None, float)
            Per set point (:meth:`set_points`, Hz, ascending): the lowest
            amplitude with judder (bar), or None where no run had judder
            (a censored point: no judder up to the largest amplitude run
            there), and that largest amplitude (bar).
        """
        rows = []
        for freq, _, runs in self.set_points(group):
            judder = [r.analysis.p_f_bar for r in runs if r.analysis.judder]
            rows.append((freq, min(judder) if judder else None,
                         max(r.analysis.p_f_bar for r in runs)))
        return rows

    def quiet_below(self, group):
        """Per set point of :meth:`boundary`: the highest amplitude run
        without judder below the onset (bar), or None (no onset, or no
        quiet run below it). The boundary lies between the two: the
        onset was found on the grid of amplitudes tried."""
        rows = []
        for (_, onset, _), (_, _, runs) in zip(self.boundary(group),
                                               self.set_points(group)):
            quiet = [r.analysis.p_f_bar for r in runs
                     if not r.analysis.judder and onset is not None
                     and r.analysis.p_f_bar < onset]
            rows.append(max(quiet) if quiet else None)
        return rows

    def boundary_csv(self, group):
        """The boundary as ``judder fit --boundary`` reads it, the header
        first (as a spreadsheet expects), then in comments at the end the
        growth rate the verdict called judder from (``judder fit``
        compares with the model's boundary of that growth) and, per set
        point, the range tested: the highest amplitude run without judder
        (below the onset) and the largest amplitude run (so a point
        without judder is censored where it was, not at an assumed
        amplitude)."""
        def cell(value):
            return "" if value is None else f"{value:.9g}"
        lines = ["freq_hz,p_f_bar,no_judder_bar,tried_bar"] + [
            # without an onset every run was without judder, up to top
            ",".join([f"{f:.9g}", cell(p), cell(top if p is None else q),
                      cell(top)])
            for (f, p, top), q in zip(self.boundary(group),
                                      self.quiet_below(group))] + [
            f"# min_growth_per_s: {self.min_growth:g}",
            f"# judder_limit_rpm: {self.judder_limit_rpm:g}"]
        return "\n".join(lines) + "\n"

    def told(self, group):
        """The runs of one group whose reading is a verdict (not
        :attr:`pysim.bench.verdict.RunAnalysis.cannot_tell`)."""
        return [r for r in self.groups().get(group, [])
                if r.analysis.cannot_tell is None]

    def arrays(self):
        """Per-run arrays (NaN where unknown), for NPZ files and plots;
        ``verdict`` the run's word, and a run that cannot be told is
        neither ``judder`` nor of a ``kind`` or ``mechanism``."""
        runs = self.read

        def told(run):
            return run.analysis.cannot_tell is None
        return {
            "source_file": np.array([str(r.path) for r in runs]),
            "group": np.array(["/".join(r.group(self.group_by))
                               for r in runs]),
            "freq_hz": np.array([r.analysis.freq_hz for r in runs]),
            "p_f_bar": np.array([r.analysis.p_f_bar for r in runs]),
            "amplitude_rpm": np.array([r.analysis.amplitude_rpm
                                       for r in runs]),
            "growth_per_s": np.array([np.nan if r.analysis.growth_per_s
                                      is None else r.analysis.growth_per_s
                                      for r in runs]),
            # a run that cannot be told is no verdict: not judder, of
            # no kind (``verdict`` says CANNOT TELL)
            "growth_std_per_s": np.array([
                np.nan if r.analysis.growth_std_per_s is None
                else r.analysis.growth_std_per_s for r in runs],
                dtype=float),
            "judder": np.array([r.analysis.judder and told(r)
                                for r in runs], dtype=bool),
            "verdict": np.array([r.analysis.verdict for r in runs]),
            "kind": np.array([r.analysis.kind if told(r) else ""
                              for r in runs]),
            "mechanism": np.array([(r.analysis.mechanism or "") if told(r)
                                   else "" for r in runs]),
            "oscillation_rpm": np.array([r.analysis.oscillation_rpm
                                         for r in runs]),
            "forced_rpm": np.array([r.analysis.forced_rpm for r in runs]),
            "dither_estimated": np.array([r.analysis.estimated
                                          for r in runs]),
            # which values of the setting were given (the others were
            # estimated from the pressure)
            "freq_given": np.array([SETTING[0] in r.analysis.given
                                    for r in runs], dtype=bool),
            # a frequency estimated that may be an alias: on no boundary
            "dither_aliased": np.array([r.analysis.frequency_aliased
                                        for r in runs], dtype=bool),
            "p_f_given": np.array([SETTING[1] in r.analysis.given
                                   for r in runs], dtype=bool),
            **_dither_arrays([r.analysis.dither for r in runs])}


#: NPZ arrays of the pressure's estimate of the dither (NaN where the
#: setting was given, and the frequency's uncertainty where the frequency
#: was given): array name -> (attribute of the fit, its value in the
#: array's unit). ``dither_p_f_bar`` is the pressure's amplitude, which
#: is the run's ``p_f_bar`` unless that was given.
DITHER_ARRAYS = {"dither_freq_std_hz": ("freq_std_hz", 1.0),
                 "dither_p_f_bar": ("amplitude", PA_PER_BAR),
                 "dither_p_f_std_bar": ("amplitude_std", PA_PER_BAR),
                 "dither_phase_rad": ("phase_rad", 1.0),
                 "dither_phase_std_rad": ("phase_std_rad", 1.0),
                 "dither_phase_time_s": ("reference_s", 1.0)}


def _dither_arrays(fits):
    """The standard uncertainties (and the phase) of the runs' dither
    estimates (:class:`pysim.bench.dither.SinusoidFit`, None where the
    setting was given), as :data:`DITHER_ARRAYS`, and ``dither_warnings``:
    what the sampling cannot support, in words joined by ``'; '`` (empty
    where nothing, or the setting was given)."""
    return {**{name: np.array([np.nan if fit is None else
                               getattr(fit, attribute) / unit
                               for fit in fits], dtype=float)
               for name, (attribute, unit) in DITHER_ARRAYS.items()},
            "dither_warnings": np.array(
                ["" if fit is None else "; ".join(fit.warnings)
                 for fit in fits], dtype=str)}


def build_chart(sources, channels=None, group_by=None,
                min_growth=DEFAULT_MIN_GROWTH_PER_S, min_amplitude_rpm=MIN_AMPLITUDE_RPM,
                judder_limit_rpm=DEFAULT_JUDDER_LIMIT_RPM, workers=None,
                callback=None, run_bytes=0, decimal=None):
    """Read every run and make the chart.

    Parameters
    ----------
    sources : sequence of RunSource
    channels : dict, optional
        Role -> :class:`pysim.bench.acquisition.ChannelSpec`; default
        :data:`DEFAULT_CHANNELS` (the names ``judder campaign`` writes).
    group_by : sequence of str, optional
        Group columns; default those of :data:`GROUP_COLUMNS` that take
        more than one value.
    min_growth, min_amplitude_rpm, judder_limit_rpm : float
        The verdict's thresholds (:mod:`pysim.bench.verdict`).
    workers : int, optional
    callback : callable, optional
        ``callback(done, total)`` after each run.
    run_bytes : int
        Memory one run takes to read (bounds the worker processes,
        :func:`infra.parallel.worker_count`).
    decimal : {'.', ','}, optional
        Decimal separator of the text (CSV) acquisitions
        (:func:`pysim.bench.readers.read_acquisition`); default
        decided per file from its cells.

    Returns
    -------
    Chart
        Runs that cannot be read are kept with their error.
    """
    channels = dict(channels or DEFAULT_CHANNELS)
    if "upstream_speed" not in channels:
        raise JudderError("`channels` upstream_speed=NAME is required (the "
                          "speed upstream of the clutch)")
    jobs = [(s, channels, min_growth, min_amplitude_rpm, judder_limit_rpm,
             decimal) for s in sources]
    runs = []
    # a failure names the file, not the job's Python repr
    for run in parallel_map(_analyse, jobs, workers,
                            describe=lambda job: str(job[0].path),
                            job_bytes=run_bytes):
        runs.append(run)
        if callback is not None:
            callback(len(runs), len(jobs))
    if group_by is None:
        group_by = tuple(c for c in GROUP_COLUMNS if len(
            {r.settings.get(c) for r in runs if r.analysis}) > 1)
    known = {c for r in runs for c in r.settings}
    unknown = [c for c in group_by if c not in known]
    if unknown:
        raise JudderError(f"`group_by` {unknown[0]}: no run has that column; "
                          f"allowed: {', '.join(sorted(known)) or 'none'}")
    return Chart(runs=runs, group_by=tuple(group_by), min_growth=min_growth,
                 judder_limit_rpm=judder_limit_rpm)
