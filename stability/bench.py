"""The test bench of a registry driveline, as the stability views see it.

The bench is a Modelica class of the library (``PartialTestBench`` and
its engagement models) around the driveline; its own parameters (the
motor and its speed control, the load clutch, the pressure ramp, the
EVEN clutch's friction curve) are the ``Judder.Data`` records the class
extends (the registry entry's ``bench_records``), read here with their
units and allowed ranges (:func:`bench_parameters`), without building
the bench's FMU. From them come the bench's linearisation at its steady
slip (:func:`bench_linearisation`: the damping its motor's speed control
adds, :func:`added_damping`, and the friction curve's value and slope at
the slip, :func:`operating_friction`) and its periodic-orbit model
(:func:`engagement_model`, :class:`stability.orbit.EngagementModel`):
the Floquet and the orbit view of the bench that ``simulate`` runs.
"""

import dataclasses
from dataclasses import dataclass
import math
import re

import numpy as np

from drivelines.records import experiment_stop_time, record_parameters
from infra.errors import JudderError
from infra.units import UNITS

from .friction import curve_at, forced_slip_amplitude, linear_range
from .orbit import EngagementModel
from .source import build_driveline

__all__ = ["DRIVELINES", "BenchParameter", "bench_class", "bench_parameters",
           "check_bench", "bench_damping", "added_damping",
           "operating_friction", "operating_slip", "friction_at",
           "linearisation_at", "linear_validity",
           "engagement_model",
           "bench_linearisation", "default_driveline", "driveline_view",
           "driveline_words", "drive_torque"]

#: The drivelines a Floquet view can be of: the paper's chain (Eq. 6,
#: free, as Fig. 14) or the registry driveline on its test bench (the
#: chain with the bench motor's speed control and its friction curve at
#: the bench's slip: what ``simulate``, ``orbit`` and ``chart`` see).
DRIVELINES = ("chain", "bench")


@dataclass(frozen=True)
class BenchParameter:
    """One parameter of the bench, as its ``Judder.Data`` record declares
    it.

    Attributes
    ----------
    name : str
    unit : str
        A unit of :data:`infra.units.UNITS` (SI).
    low, high : float
        The declared ``min`` and ``max`` (infinite where not declared).
    default : float
        The declared value.
    description : str
    """

    name: str
    unit: str
    low: float
    high: float
    default: float
    description: str

    def allowed(self):
        """The allowed range in words."""
        if math.isinf(self.high):
            return f"at least {self.low:g} {self.unit}" \
                if math.isfinite(self.low) else f"any number in {self.unit}"
        return f"{self.low:g} to {self.high:g} {self.unit}"


def bench_class(values):
    """The Modelica class of the bench of ``values``' driveline.

    Raises
    ------
    JudderError
        For a Modelica class or an FMU (the bench belongs to the
        registry's 4-DOF driveline), or a driveline without a bench.
    """
    if not values.source_kind.is_chain:
        raise JudderError(f"{values.model} (a Modelica class or an FMU) "
                          "has no bench engagement model: the bench belongs "
                          "to the registry's 4-DOF driveline; allowed: a "
                          "preset or its parameter file (or add the bench's "
                          "damping to the class with `changes`)")
    if values.driveline.bench_class is None:
        raise JudderError(f"the {values.model} driveline has no bench "
                          "engagement model; give a parameter set of a "
                          "driveline that has one (4-DOF)")
    return (values.driveline.bench_class if values.friction is None
            else values.driveline.bench_table_class)


def _bench_records(values):
    """The ``Judder.Data`` records of the bench :func:`bench_class`
    names."""
    return (values.driveline.bench_records if values.friction is None
            else values.driveline.bench_table_records)


def _unit(modelica_unit):
    """The :data:`infra.units.UNITS` name of a Modelica unit string
    (``N.m.s/rad`` -> ``N m s/rad``, ``kg.m2`` -> ``kg m^2``)."""
    name = re.sub(r"(?<=[A-Za-z])(\d+)", r"^\1",
                  modelica_unit.replace(".", " "))
    if name not in UNITS:
        raise JudderError(f"bench unit {modelica_unit!r} is not allowed; "
                          f"allowed: {', '.join(UNITS)}")
    return name


def bench_parameters(values):
    """The bench's own parameters, from its ``Judder.Data`` records.

    Parameters
    ----------
    values : sources.Parameters
        A parameter set of a registry driveline with a bench.

    Returns
    -------
    dict of str -> BenchParameter
        In the order the records declare them. A time of the bench (the
        ramp's start, its duration) is no earlier than the run's start.
    """
    bench_class(values)
    return {name: BenchParameter(name, _unit(declared.unit), declared.low,
                                 declared.high, declared.value,
                                 declared.description)
            for record in _bench_records(values)
            for name, declared in record_parameters(record).items()}


def check_bench(values, bench):
    """Refuse a bench parameter the bench does not have, or a value
    outside the range its record declares.

    Returns
    -------
    dict
        ``bench`` as floats (SI).
    """
    bench = dict(bench or {})
    parameters = bench_parameters(values) if bench else {}
    for name, value in bench.items():
        if name not in parameters:
            raise JudderError(f"`bench` parameter {name!r} is not allowed; "
                              f"allowed: {', '.join(parameters)}")
        parameter = parameters[name]
        try:
            number = float(value)
        except (TypeError, ValueError):
            number = math.nan
        if not parameter.low <= number <= parameter.high:
            raise JudderError(f"`bench` parameter {name} {value!r} "
                              f"{parameter.unit} is not allowed; allowed: "
                              f"{parameter.allowed()}")
        bench[name] = number
    return bench


def operating_slip(values):
    """The slip the chain is linearised at where its clutch has a
    friction characteristic, rad/s: the bench's steady slip ``w_motor -
    w_gearbox`` by its records' defaults (the paper's 1000 rpm operating
    point), for a driveline with or without a bench."""
    from drivelines.records import record_values
    bench = record_values(values.driveline.bench_table_records[0]
                          if values.driveline.bench_table_records
                          else "TestBenchData")
    return bench["w_motor"] - bench["w_gearbox"]


def _bench_values(values, bench):
    """Every bench parameter's value (SI): ``bench``'s where it sets one,
    else its record's default."""
    return {name: float(dict(bench or {}).get(name, parameter.default))
            for name, parameter in bench_parameters(values).items()}


def bench_damping(values, bench=None):
    """What the bench's linearisation adds to the driveline's parameters.

    The bench's motor holds its speed by a proportional control, which
    acts on body 1 as a damping to ground about the set speed
    (:attr:`drivelines.DrivelineModel.bench_damping`): the Floquet model of
    the bench is the driveline with ``c1 + d_control``.

    Parameters
    ----------
    values : drivelines.Parameters
    bench : dict, optional
        Bench parameters (SI); the others are the bench's defaults.

    Returns
    -------
    dict
        ``{driveline parameter: added value}``, SI.

    Raises
    ------
    JudderError
        Where the bench's slip (``w_motor - w_gearbox``) is not its
        friction curve's ``w_op``: there the linearisation also takes the
        curve's value and slope at that slip (:func:`bench_linearisation`
        does), which a sum cannot say.
    """
    friction, _ = operating_friction(values, bench)
    if not np.isclose(friction["mu_g"], values["mu_g"], rtol=1e-9):
        raise JudderError(
            "`bench`: the bench's slip w_motor - w_gearbox is not its "
            "friction curve's w_op, where mu0 and mu_g are the curve's; "
            "its linearisation there has the slope "
            f"{friction['mu_g']:.3g} s/rad, not a fitted mu_g; allowed: "
            "a chart at the curve's operating slip (1000 rpm by default), "
            "or `bench` w_op set to that chart's slip")
    return added_damping(values, bench)


def added_damping(values, bench=None):
    """The damping the bench's motor control adds to the driveline's
    parameters, ``{driveline parameter: added value}`` (SI)."""
    bench = check_bench(values, bench)
    given = _bench_values(values, bench)
    return {name: given[added]
            for name, added in values.driveline.bench_damping}


def operating_friction(values, bench=None):
    """The bench's friction at its operating point.

    Returns ``({'mu0': ..., 'mu_g': ...}, linear range)``: the value and
    slope of its EVEN clutch's friction curve
    (:func:`stability.friction.curve_at`) at its steady slip, ``w_motor
    - w_gearbox`` (``values``' own when that slip is the curve's
    ``w_op``, as at the bench's default 1000 rpm), and the slip offset,
    rad/s, over which the curve keeps that slope
    (:func:`stability.friction.linear_range`).
    """
    given = _bench_values(values, bench)
    if given["w_gearbox"] >= given["w_motor"]:
        raise JudderError(
            f"`bench` w_gearbox {given['w_gearbox']:g} rad/s is not "
            f"allowed with w_motor {given['w_motor']:g} rad/s; "
            "allowed: below w_motor (the EVEN clutch slips forwards, "
            "at w_motor - w_gearbox)")
    slip = given["w_motor"] - given["w_gearbox"]
    if values.friction is not None:
        return (friction_at(values, slip, bench),
                values.friction.linear_range(slip))
    return (friction_at(values, slip, bench),
            linear_range(slip, values["mu_g"], given["delta_mu"],
                         given["w_op"]))


def friction_at(values, slip, bench=None):
    """``{'mu0': ..., 'mu_g': ...}``: the value and slope of the bench's
    EVEN clutch's friction characteristic at the slip ``slip`` (rad/s):
    its table's (:meth:`drivelines.friction.FrictionTable.at`) where
    ``values`` carry one, else the bounded curve's
    (:func:`stability.friction.curve_at`, ``values``' ``mu0`` and ``mu_g``
    at the bench's ``w_op``)."""
    if values.friction is not None:
        mu, slope = values.friction.at(slip)
        return {"mu0": mu, "mu_g": slope}
    given = _bench_values(values, bench)
    point = curve_at(slip, values["mu0"], values["mu_g"], given["delta_mu"],
                     given["w_op"])
    return {"mu0": point.mu, "mu_g": point.slope}


def linearisation_at(values, bench=None):
    """``slip -> stability.model.Driveline``: the bench linearised at a
    steady slip (rad/s), the friction characteristic's value and slope
    there and the motor control's damping
    (:func:`stability.engagement_path.engagement_path` follows an
    engagement with it). The value ``mu0`` of the mean load's share (1 -
    m) stays ``values``' own, as in the bench's clutch."""
    damped = values.replace(**{name: values[name] + value for name, value
                               in added_damping(values, bench).items()})

    def at(slip):
        return build_driveline(damped.replace(
            mu_g=friction_at(values, slip, bench)["mu_g"]))
    return at


def linear_validity(driveline, run, linear_slip):
    """Whether the dither's forced slip swing stays within the friction
    curve's linear range (the run can then follow its linearisation):
    ``forced_slip_amplitude_rad_s``, ``friction_linear_range_rad_s`` and
    ``linearisation_holds`` (None for a model without the curve)."""
    if linear_slip is None or run.p_f == 0:
        return {"forced_slip_amplitude_rad_s": None,
                "friction_linear_range_rad_s": linear_slip,
                "linearisation_holds": None}
    forced = forced_slip_amplitude(driveline, run.freq_hz, run.p_f)
    return {"forced_slip_amplitude_rad_s": forced,
            "friction_linear_range_rad_s": linear_slip,
            "linearisation_holds": bool(forced <= linear_slip)}


def engagement_model(values, bench=None, duration=None):
    """The bench's engagement about its steady slip, for the periodic
    orbit (:class:`stability.orbit.EngagementModel`): the driveline with
    the damping the bench adds (:func:`added_damping`), the EVEN clutch's
    friction curve (``mu0``, ``mu_g`` at ``w_op``, ``delta_mu``), the slip
    ``w_motor - w_gearbox`` and the motor's torque limit ``tau_max`` with
    its steady torque (:func:`drive_torque`), from the bench's records
    where ``bench`` does not set them; and the gearbox side's inertia with
    the time the held slip drifts before a run of ``duration`` seconds
    (the bench class's StopTime by default) is read, from the middle of
    the pressure ramp (:func:`stability.orbit.drifted_orbit`).

    Returns
    -------
    (EngagementModel, stability.model.Driveline)
        The model and the bench's linearisation at its slip (the Floquet
        view of the same bench, as ``simulate`` prints it).
    """
    bench = check_bench(values, bench)
    given = _bench_values(values, bench)
    added = added_damping(values, bench)
    damped = values.replace(**{name: values[name] + value
                               for name, value in added.items()})
    slip = given["w_motor"] - given["w_gearbox"]
    if values.friction is not None:
        # mu0: the characteristic's value at the steady slip, the friction
        # of the mean load (the table bench's clutch.mu0 is values' mu0)
        model = EngagementModel.from_driveline(
            build_driveline(damped), delta_mu=math.nan, w_op=slip,
            slip=slip, table=values.friction)
    else:
        model = EngagementModel.from_driveline(
            build_driveline(damped), delta_mu=given["delta_mu"],
            w_op=given["w_op"], slip=slip)
    # the motor (body 1): its control's gain is in the damping, its
    # torque limit is the orbit's second nonlinearity
    gain = sum(added.values())
    torque, damping = drive_torque(model, gain, given["w_motor"])
    if duration is None:
        duration = experiment_stop_time(bench_class(values))
    model = dataclasses.replace(
        model, drive=0, drive_gain=gain, drive_limit=given["tau_max"],
        drive_torque=torque, drive_damping=damping,
        load_inertia=float(np.diag(model.mass) @ _group(
            model.stiffness, int(np.flatnonzero(model.clutch < 0)[0]))),
        drift_time=max(duration - given["t_engage"] - 0.5 * given["t_ramp"],
                       0.0))
    return model, build_driveline(bench_linearisation(values, bench))


def bench_linearisation(values, bench=None):
    """The parameter set of the bench's linearisation at its steady slip:
    the driveline with the damping its motor's speed control adds to body
    1 (:func:`added_damping`) and the EVEN clutch's friction curve's value
    and slope at the slip (:func:`operating_friction`) as ``mu0`` and
    ``mu_g``. The Floquet view of the bench, whose orbit is
    :func:`engagement_model`."""
    friction, _ = operating_friction(values, bench)
    return values.replace(**{name: values[name] + value for name, value
                             in added_damping(values, bench).items()},
                          **friction)


def default_driveline(values):
    """The driveline a view of ``values`` judges unless told:
    ``'bench'`` where its registry driveline has a test bench (the one
    ``simulate``, ``orbit`` and ``chart`` run), else ``'chain'``."""
    has_bench = values.source_kind.is_chain and \
        values.driveline.bench_class is not None
    return "bench" if has_bench else "chain"


def driveline_view(values, driveline=None):
    """``values`` as the driveline a Floquet view is of
    (:data:`DRIVELINES`; None: :func:`default_driveline`), and its name:
    ``'chain'`` as given, ``'bench'`` its bench's linearisation
    (:func:`bench_linearisation`)."""
    if driveline is None:
        driveline = default_driveline(values)
    if driveline not in DRIVELINES:
        raise JudderError(f"`driveline` {driveline!r} is not allowed; "
                          f"allowed: {', '.join(DRIVELINES)}")
    return (values if driveline == "chain" else
            bench_linearisation(values)), driveline


def driveline_words(values, driveline="chain"):
    """Which driveline a view is of, in words: with a friction
    characteristic (:meth:`sources.Parameters.with_friction`), which one;
    for the registry's chains, the share ``m`` of the clamping load that
    feels the friction's slope, and what it means for the tongues
    (docs/theory.md: with ``m = 1`` and a rising characteristic the
    damping stays positive semi-definite below ``p_f = p_m``)."""
    if not values.source_kind.is_chain:
        return f"{values.model}"
    share = values["mean_pressure_damping"]
    friction = ("" if values.friction is None else
                f"; {values.friction.words()}")
    friction += (f"; m = {share:g} of the clamping load on the friction's "
                 "slope" + (" (the paper's maps; with m = 1 and a rising "
                            "curve no tongue exists below p_f = p_m)"
                            if share < 1 else
                            ": with a rising curve no tongue exists below "
                            "p_f = p_m"))
    if driveline == "bench":
        return (f"the {values.model} driveline on its test bench (motor "
                "speed control on body 1, friction curve's value and "
                f"slope at the bench's slip{friction})")
    return (f"the {values.model} chain alone (Eq. 6, free, as Fig. 14"
            f"{friction})")


def drive_torque(model, gain, w_ref):
    """The bench motor's torque at the steady slip, N m, and the damping
    to ground of the bodies it turns, N m s/rad: the clutch's
    steady torque plus the external damping of the bodies the motor
    turns (``Judder.Sources.SpeedDrive`` with no feed-forward torque
    holds them at ``w_ref - T/gain``), ``T = (tau_s + c w_ref) / (1 +
    c/gain)`` with ``c`` their external damping without the control's
    ``gain``."""
    ones = _group(model.stiffness, 0)
    external = float(ones @ model.damping @ ones) - gain
    torque = ((model.steady_torque() + external * w_ref)
              / (1.0 + external / gain))
    return torque, external + gain


def _group(stiffness, body):
    """Indicator (0 or 1 per body) of the bodies joined to ``body`` by
    springs: those that turn with it on average."""
    joined = np.abs(stiffness) > 0
    group = {body}
    while True:
        grown = group | {j for i in group for j in np.flatnonzero(joined[i])}
        if grown == group:
            break
        group = grown
    ones = np.zeros(len(stiffness))
    ones[sorted(group)] = 1.0
    return ones
