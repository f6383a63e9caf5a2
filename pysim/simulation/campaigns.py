"""Bench emulator: campaigns of engagement runs written like acquisitions.

Each run of the driveline's bench FMU (its registry entry names it:
``TestBenchEngagement`` for the 4-DOF driveline) is turned into what
the bench of section 2.2 records:

* the speeds upstream and downstream of the EVEN clutch, as a magnetic
  pick-up on a toothed wheel measures them: one sample per tooth passage
  (41 teeth: 684 samples/s at 1000 rpm), speed = tooth pitch / time
  between passages, plus Gaussian measurement noise;
* the EVEN actuation pressure at 1 kHz with noise;
* metadata: dither frequency and amplitude, oil temperature, engine speed,
  run id and noise seed.

A campaign runs a grid (frequency x amplitude x engine speed x oil
temperature) in parallel, writes one CSV and/or MF4 file per run and a
campaign index (``index.csv``) updated atomically, under a lock of the
folder, after each run: several campaigns may run into one folder at
once, and the index keeps every run of each. A run id ends with a digest
of every setting that changes the run's data (:meth:`Campaign.runs`), so
a campaign with other settings adds runs instead of reusing old ones. A
failed run is recorded with its message and does not stop the campaign;
running the same campaign again skips the runs already done.
"""

from dataclasses import dataclass, field
import csv
import hashlib
import io
import json
from pathlib import Path
import time

import numpy as np

from drivelines.registry import MODELS
from fmu.store import ensure_fmu
from infra.errors import JudderError
from infra.files import atomic_write
from infra.lifecycle import FolderLock, die_with_parent
from infra.parallel import parallel_map
from infra.units import PA_PER_BAR, RAD_S_PER_RPM

from .export import write_csv, write_mdf
from .runs import run_fmu

__all__ = ["Campaign", "pickup_samples", "run_campaign", "at_temperature",
           "oil_viscosity", "TEMPERATURES", "REFERENCE_TEMPERATURE_C",
           "OIL_VISCOSITY_MM2_S", "INDEX_COLUMNS"]

#: Hex digits of the settings digest that ends a run id.
RUN_DIGEST_LENGTH = 10
#: Age (s) from which a ``.part`` file in a campaign folder is a leftover.
STALE_PART_S = 600.0

#: Oil temperature ranges of Fig. 11 and the temperature (degC) a run of
#: each is made at: the middle of the range.
TEMPERATURES = {"55-60": 57.5, "65-70": 67.5, "75-80": 77.5, "85-90": 87.5}
#: Temperature (degC) the parameter sets describe: the range of the
#: paper's chart of Fig. 10 and of its fit (Fig. 16a), 65-70 degC.
REFERENCE_TEMPERATURE_C = 67.5
#: Kinematic viscosity (mm^2/s) of the transmission oil at 40 and 100
#: degC: a universal tractor transmission oil (UTTO) of the kind the
#: gearbox runs on, ISO VG 46-68 (the paper does not name it).
OIL_VISCOSITY_MM2_S = {40.0: 60.0, 100.0: 9.5}


def oil_viscosity(temperature_c, oil=None):
    """Kinematic viscosity of the oil, mm^2/s, by the Walther equation
    (ASTM D341), ``log10 log10(nu + 0.7) = A - B log10(T)``, through the
    two points of ``oil`` (default :data:`OIL_VISCOSITY_MM2_S`)."""
    (t1, nu1), (t2, nu2) = sorted((oil or OIL_VISCOSITY_MM2_S).items())
    z1, z2 = (np.log10(np.log10(nu + 0.7)) for nu in (nu1, nu2))
    k1, k2 = t1 + 273.15, t2 + 273.15
    b = (z1 - z2) / (np.log10(k2) - np.log10(k1))
    a = z1 + b * np.log10(k1)
    kelvin = float(temperature_c) + 273.15
    if not kelvin > 0:
        raise JudderError(f"oil temperature {temperature_c:g} degC is below "
                          "absolute zero; allowed: above -273.15 degC")
    return float(10 ** 10 ** (a - b * np.log10(kelvin)) - 0.7)


def at_temperature(params, temperature, engine_rpm=None):
    """The parameter set at one oil temperature of :data:`TEMPERATURES`.

    The external damping of every body (drag of the bodies and bearings
    in the oil) is proportional to the oil's viscosity, relative to its
    value at :data:`REFERENCE_TEMPERATURE_C`. The bench's bounded friction
    curve is kept (the paper gives no data on its change with
    temperature); a friction table with a column per oil temperature
    (``params.friction``, :class:`drivelines.friction.FrictionTable`) is
    read at the temperature, and its value at the slip of
    ``engine_rpm`` (the motor's speed less the gearbox side's) is the
    ``mu0`` of the mean load (the table bench's REV clutch balances it).
    """
    ratio = oil_viscosity(TEMPERATURES[temperature]) \
        / oil_viscosity(REFERENCE_TEMPERATURE_C)
    changed = params.replace(**{name: params[name] * ratio for name in
                                params.driveline.external_damping_names()})
    table = params.friction
    if table is None:
        return changed
    if table.family:
        table = table.at_oil_temperature(TEMPERATURES[temperature])
    if engine_rpm is None:
        return changed.with_friction(table, table_slip(params, 1000.0))
    return changed.with_friction(table, table_slip(params, engine_rpm))


def table_slip(params, engine_rpm):
    """The bench's steady slip at the motor speed ``engine_rpm``, rad/s:
    the speed less the gearbox side's (its ``Judder.Data`` record's
    ``w_gearbox``)."""
    from drivelines.records import record_values
    gearbox = record_values(params.driveline.bench_table_records[0])[
        "w_gearbox"]
    return engine_rpm * RAD_S_PER_RPM - gearbox


INDEX_COLUMNS = ("run_id", "status", "freq_hz", "p_f_bar", "engine_rpm",
                 "oil_temperature", "files", "message")


def pickup_samples(time, angle, teeth, noise_rpm=0.0, rng=None):
    """Speed as a toothed-wheel pick-up measures it.

    Parameters
    ----------
    time, angle : ndarray, shape (n,)
        Finely sampled shaft angle, rad.
    teeth : int
        Teeth on the wheel.
    noise_rpm : float
        Standard deviation of the measurement noise, rpm.
    rng : numpy.random.Generator, optional

    Returns
    -------
    t, speed_rpm : ndarray
        Tooth-passage times and the speed over the last tooth pitch, rpm.
    """
    pitch = 2 * np.pi / teeth
    count = np.floor(np.asarray(angle) / pitch)
    change = np.flatnonzero(np.diff(count) != 0)
    if len(change) < 2:
        return np.empty(0), np.empty(0)
    # passage time by linear interpolation between the fine samples
    edge = np.where(np.diff(count)[change] > 0, count[change + 1],
                    count[change]) * pitch
    fraction = (edge - angle[change]) / (angle[change + 1] - angle[change])
    t = time[change] + fraction * (time[change + 1] - time[change])
    speed = pitch / np.diff(t) * 60 / (2 * np.pi)
    if noise_rpm > 0:
        rng = rng or np.random.default_rng()
        speed = speed + rng.normal(0.0, noise_rpm, len(speed))
    return t[1:], speed


@dataclass(frozen=True)
class Campaign:
    """A bench campaign.

    Attributes
    ----------
    freq_hz, p_f_bar : sequence of float
        Dither grid.
    engine_rpm : sequence of float
        Motor speeds (1000 and 1500 rpm on the bench).
    temperatures : sequence of str
        Keys of :data:`TEMPERATURES`.
    duration : float
        s per engagement.
    teeth : int
        Teeth of the pick-up wheels.
    noise_rpm, noise_bar : float
        Measurement noise (standard deviation).
    formats : tuple of str
        ``'csv'`` and/or ``'mf4'``.
    seed : int
    """

    freq_hz: tuple
    p_f_bar: tuple
    engine_rpm: tuple = (1000.0,)
    temperatures: tuple = ("65-70",)
    duration: float = 3.0
    teeth: int = 41
    noise_rpm: float = 0.5
    noise_bar: float = 0.01
    formats: tuple = ("csv", "mf4")
    seed: int = 1
    parameters: dict = field(default_factory=dict)

    def runs(self, params=None):
        """Run id and settings of every run, in a fixed order.

        The id reads the settings and ends with a digest of every input
        that changes the run's data (the grid values at full precision,
        engine speed, temperature, duration, pick-up, noise, seed, and
        ``params``: the parameter set), so that runs of other settings
        never take each other's place.
        """
        out = []
        for temp in self.temperatures:
            for rpm in self.engine_rpm:
                for f in self.freq_hz:
                    for p in self.p_f_bar:
                        digest = self._digest(float(f), float(p), float(rpm),
                                              temp, params)
                        run_id = (f"T{temp}_n{rpm:g}_f{f:g}_p{p:g}"
                                  .replace(".", "p") + f"_{digest}")
                        out.append((run_id, float(f), float(p), float(rpm),
                                    temp))
        return out

    def _digest(self, f, p, rpm, temp, params):
        identity = {"freq_hz": f.hex(), "p_f_bar": p.hex(),
                    "engine_rpm": rpm.hex(), "temperature": temp,
                    "duration": float(self.duration).hex(),
                    "teeth": self.teeth,
                    "noise_rpm": float(self.noise_rpm).hex(),
                    "noise_bar": float(self.noise_bar).hex(),
                    "seed": self.seed,
                    "model": None if params is None else params.model,
                    "parameters": None if params is None else {
                        k: float(v).hex() for k, v in
                        sorted(params.as_dict().items())}}
        if getattr(params, "friction", None) is not None:
            # the clutch's friction table, every column of it (a run of
            # the bench's curve keeps the digest it had before tables)
            identity["friction"] = repr(params.friction)
        text = json.dumps(identity, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:RUN_DIGEST_LENGTH]


def _acquire(job):
    """Simulate one run and write its files; returns the index row."""
    die_with_parent()
    campaign, params, fmu_path, folder, (run_id, f, p, rpm, temp) = job
    row = {"run_id": run_id, "status": "failed", "freq_hz": f,
           "p_f_bar": p, "engine_rpm": rpm, "oil_temperature": temp,
           "files": "", "message": ""}
    try:
        case = at_temperature(params, temp, rpm)
        run = run_fmu(fmu_path, f, p * PA_PER_BAR, params=case,
                      extra={"w_motor": rpm * RAD_S_PER_RPM,
                             **({} if case.friction is None else
                                case.friction.start_values())},
                      duration=campaign.duration, output_interval=1e-4,
                      variables=("inertia4.phi", "inertia3.phi"))
        # the noise follows the run's identity, not its place in the grid
        rng = np.random.default_rng([campaign.seed,
                                     int(run_id.rsplit("_", 1)[1], 16)])
        t_up, n_up = pickup_samples(run.time, run["inertia4.phi"],
                                    campaign.teeth, campaign.noise_rpm, rng)
        t_down, n_down = pickup_samples(run.time, run["inertia3.phi"],
                                        campaign.teeth, campaign.noise_rpm,
                                        rng)
        t_p = np.arange(0.0, run.time[-1], 1e-3)
        p_bar = np.interp(t_p, run.time, run["actuation_pressure"]) \
            / PA_PER_BAR \
            + rng.normal(0.0, campaign.noise_bar, len(t_p))
        metadata = {"run_id": run_id, "dither_frequency_hz": f,
                    "dither_amplitude_bar": p, "engine_speed_rpm": rpm,
                    "oil_temperature_degC": temp, "pickup_teeth":
                    campaign.teeth, "noise_rpm": campaign.noise_rpm,
                    "noise_bar": campaign.noise_bar,
                    "seed": campaign.seed,
                    "source": f"emulated: {params.driveline.bench_class}"}
        files = []
        if "csv" in campaign.formats:
            # one time base, the upstream pick-up (the judder indicator)
            n_down_i = np.interp(t_up, t_down, n_down, left=np.nan) \
                if len(t_down) > 1 else np.full(len(t_up), np.nan)
            write_csv(folder / f"{run_id}.csv", t_up,
                      {"n_upstream": n_up, "n_downstream": n_down_i,
                       "p_even": np.interp(t_up, t_p, p_bar)},
                      {"n_upstream": "rpm", "n_downstream": "rpm",
                       "p_even": "bar"}, metadata)
            files.append(f"{run_id}.csv")
        if "mf4" in campaign.formats:
            write_mdf(folder / f"{run_id}.mf4",
                      [("n_upstream", "rpm", t_up, n_up),
                       ("n_downstream", "rpm", t_down, n_down),
                       ("p_even", "bar", t_p, p_bar)], metadata)
            files.append(f"{run_id}.mf4")
        row.update(status="ok", files=" ".join(files))
    except Exception as exc:   # a failed run is recorded, not fatal
        row["message"] = f"{type(exc).__name__}: {exc}"
    return row


def _read_index(path):
    if not path.exists():
        return {}
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            return {row["run_id"]: row for row in csv.DictReader(stream)
                    if row.get("run_id")}
    except (UnicodeDecodeError, csv.Error, KeyError) as exc:
        raise JudderError(f"{path}: not an index written by judder "
                          f"campaign ({exc}); move it away to start a new "
                          "campaign in this folder") from None


def _write_index(path, rows):
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=INDEX_COLUMNS,
                            extrasaction="ignore")
    writer.writeheader()
    for row in rows:
        writer.writerow(row)
    atomic_write(path, lambda stream: stream.write(buffer.getvalue().encode()))


def _record(folder, index_path, row, order):
    """Add or replace one row of the index, under the folder's lock (other
    campaigns may write into the same folder): no row is lost or
    duplicated. Rows of other campaigns come first, then those of this
    one in the order of its run ids ``order``."""
    with FolderLock(folder):
        rows = _read_index(index_path)
        rows[row["run_id"]] = row
        mine = set(order)
        _write_index(index_path,
                     [r for k, r in rows.items() if k not in mine]
                     + [rows[k] for k in order if k in rows])


def _remove_stale_parts(folder):
    """``.part`` files older than :data:`STALE_PART_S`: left by a process
    killed mid-write (SIGKILL); a live writer's are younger."""
    now = time.time()
    for part in folder.glob(".*.part"):
        try:
            if now - part.stat().st_mtime > STALE_PART_S:
                part.unlink()
        except OSError:
            pass


def run_campaign(campaign, params, folder, workers=None, callback=None):
    """Run (or resume) a campaign into ``folder``.

    Runs already in the folder's index with status ok, their files
    present, are kept; the others are run. The index keeps the rows of
    every campaign run into the folder (run ids differ with the settings,
    see :meth:`Campaign.runs`).

    Returns
    -------
    list of dict
        The index rows (see :data:`INDEX_COLUMNS`) of this campaign's
        runs, in run order; a run found done in the folder has
        ``reused`` True.
    """
    bench_class = (params.driveline.bench_class if params.friction is None
                   else params.driveline.bench_table_class)
    if bench_class is None:
        raise JudderError(f"the {params.model} driveline has no bench "
                          "model; drivelines with one: " + ", ".join(
                              m.name for m in MODELS.values()
                              if m.bench_class is not None))
    unknown = sorted(set(campaign.temperatures) - set(TEMPERATURES))
    if unknown:
        raise JudderError(f"oil temperature {unknown[0]!r} is unknown; "
                          f"allowed: {', '.join(TEMPERATURES)}")
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise JudderError(f"cannot create the campaign folder {folder}: "
                          f"{exc.strerror}") from None
    fmu_path = ensure_fmu(bench_class)
    index_path = folder / "index.csv"
    plan = campaign.runs(params)
    with FolderLock(folder):
        _remove_stale_parts(folder)
        done = {k: v for k, v in _read_index(index_path).items()
                if v["status"] == "ok" and all(
                    (folder / name).exists() for name in v["files"].split())
                and {f"{k}.{s}" for s in campaign.formats}
                <= set(v["files"].split())}
    # runs already in the folder with these very settings: kept, and said so
    rows = {run_id: {**done[run_id], "reused": True}
            for run_id, *_ in plan if run_id in done}
    jobs = [(campaign, params, fmu_path, folder, settings)
            for settings in plan if settings[0] not in rows]
    if callback is not None:
        callback(len(rows), len(plan))
    for row in parallel_map(_acquire, jobs, workers, ordered=False):
        rows[row["run_id"]] = row
        _record(folder, index_path, row, [r[0] for r in plan])
        if callback is not None:
            callback(len(rows), len(plan))
    return [rows[r[0]] for r in plan]
