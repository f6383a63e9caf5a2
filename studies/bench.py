"""The test bench of a registry driveline: everything the tool knows of it.

The bench is a Modelica class of the library (``PartialTestBench`` and
its engagement models), named by the driveline's registry entry and
built to an FMU. Its parameters, their units and allowed ranges are the
ones that FMU's model description declares (:func:`bench_parameters`,
read by ``--bench NAME=VALUE``: :func:`parse_bench`). ``simulate`` and
``orbit`` run an engagement on it, and ``fit(bench=...)`` compares with
what it measures: the damping it adds to the driveline's model
(:func:`bench_damping`), the friction at its operating point, and
whether the dither's forced slip stays where the linear model holds.
Campaigns of bench runs written as acquisitions are
:mod:`pysim.simulation.campaigns`.
"""

import dataclasses
from dataclasses import dataclass
import math

import numpy as np

from infra.errors import JudderError
from infra.units import UNITS

__all__ = ["BenchParameter", "bench_fmu", "bench_parameters",
           "check_bench", "refuse_bench_of_class", "bench_damping",
           "added_damping", "operating_friction", "linear_validity",
           "engagement_model", "DRIVELINES", "bench_linearisation",
           "driveline_view", "driveline_words"]

#: The drivelines a Floquet view can be of: the paper's chain (Eq. 6,
#: free, as Fig. 14) or the registry driveline on its test bench (the
#: chain with the bench motor's speed control and its friction curve at
#: the bench's slip: what ``simulate``, ``orbit`` and ``chart`` see).
DRIVELINES = ("chain", "bench")

#: Parameters of the bench class that are the dither's, set by
#: ``--freq`` and ``--pf``, not by ``--bench``.
DITHER_PARAMETERS = ("f_dither", "p_f")


@dataclass(frozen=True)
class BenchParameter:
    """One parameter of the bench, as its FMU declares it.

    Attributes
    ----------
    name : str
    unit : str
        A unit of :data:`infra.units.UNITS` (SI).
    low, high : float
        The declared ``min`` and ``max`` (infinite where not declared).
    default : float
        The declared start value.
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


def bench_fmu(values):
    """The driveline's bench engagement model and its FMU (built if
    needed)."""
    from fmu.store import ensure_fmu
    if not values.source_kind.is_chain:
        raise JudderError(f"{values.model} (a Modelica class or an FMU) "
                          "has no bench engagement model: the bench belongs "
                          "to the registry's 4-DOF driveline; allowed: a "
                          "preset or its parameter file (or add the bench's "
                          "damping to the class with `changes`)")
    model_class = values.driveline.bench_class
    if model_class is None:
        raise JudderError(f"the {values.model} driveline has no bench "
                          "engagement model; give a parameter set of a "
                          "driveline that has one (4-DOF)")
    return model_class, ensure_fmu(model_class)


def _unit(modelica_unit):
    """The :data:`infra.units.UNITS` name of a Modelica unit string
    (``N.m.s/rad`` -> ``N m s/rad``)."""
    from fmu.units import base_exponents
    if not modelica_unit or modelica_unit == "1":
        return "1"
    exponents, factor = base_exponents(modelica_unit)
    return next(name for name, unit in UNITS.items()
                if unit.dimension == exponents and unit.factor == factor
                and not unit.offset)


def bench_parameters(values):
    """The bench's own parameters, from its FMU's model description.

    They are the top-level parameters of the bench class that are neither
    the driveline's (``values``) nor the dither's: the motor and gearbox
    speeds, the pressure ramp, the load clutch, the friction curve's
    shape, the speed control.

    Parameters
    ----------
    values : sources.Parameters
        A parameter set of a registry driveline with a bench.

    Returns
    -------
    dict of str -> BenchParameter
        In the order the class declares them.
    """
    from fmu.store import model_description
    description = model_description(bench_fmu(values)[1])
    own = set(values.values) | set(DITHER_PARAMETERS)
    parameters = {v.name: BenchParameter(
                      v.name, _unit(v.unit),
                      -math.inf if v.min is None else float(v.min),
                      math.inf if v.max is None else float(v.max),
                      float(v.start), v.description or "")
                  for v in description.modelVariables
                  if v.causality == "parameter" and "." not in v.name
                  and v.name not in own}
    # a time of the bench (the ramp's start, its duration) is no earlier
    # than the run's start: t_engage = -1 s was run from -0.5 s
    return {name: p if p.unit != "s" or p.low >= 0 else
            BenchParameter(p.name, p.unit, 0.0, p.high, p.default,
                           p.description)
            for name, p in parameters.items()}


def refuse_bench_of_class(values, names):
    """Bench parameters given with a Modelica class or an FMU, which has
    no bench model: refused, saying where its parameters go."""
    raise JudderError(f"`bench` {', '.join(names)} is not allowed with the "
                      f"class {values.model}; allowed: its parameters with "
                      "`changes` (the bench parameters belong to the bench "
                      "model)")



def check_bench(values, bench):
    """Refuse a bench parameter the bench does not have, or a value
    outside the range its model declares.

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
        Bench parameters (SI); the others are the bench model's defaults.

    Returns
    -------
    dict
        ``{driveline parameter: added value}``, SI.

    Raises
    ------
    JudderError
        Where the bench's slip (``w_motor - w_gearbox``) is not its
        friction curve's ``w_op``: there the linearisation also takes the
        curve's value and slope at that slip (:func:`simulate` does), which
        a sum cannot say.
    """
    fmu = bench_fmu(values)[1]
    friction, _ = operating_friction(values, fmu, dict(bench or {}))
    if not np.isclose(friction["mu_g"], values["mu_g"], rtol=1e-9):
        raise JudderError(
            "`bench`: the bench's slip w_motor - w_gearbox is not its "
            "friction curve's w_op, where mu0 and mu_g are the curve's; "
            "its linearisation there has the slope "
            f"{friction['mu_g']:.3g} s/rad, not a fitted mu_g; allowed: "
            "a chart at the curve's operating slip (1000 rpm by default), "
            "or `bench` w_op set to that chart's slip")
    return added_damping(values, fmu, bench)



def added_damping(values, fmu, bench):
    """:func:`bench_damping` with the bench's FMU ``fmu`` known."""
    from fmu.store import parameter_default
    bench = dict(bench or {})
    for name in bench:
        parameter_default(fmu, name)    # the bench model must have it
    return {name: float(bench.get(added, parameter_default(fmu, added)))
            for name, added in values.driveline.bench_damping}



def operating_friction(values, fmu, bench):
    """The bench's friction at its operating point.

    Returns ``({'mu0': ..., 'mu_g': ...}, linear range)``: the value and
    slope of its EVEN clutch's friction curve
    (:func:`stability.friction.curve_at`) at its steady slip, ``w_motor
    - w_gearbox`` (``values``' own when that slip is the curve's
    ``w_op``, as at the bench's default 1000 rpm), and the slip offset,
    rad/s, over which the curve keeps that slope
    (:func:`stability.friction.linear_range`).
    """
    from fmu.store import parameter_default
    from stability.friction import curve_at, linear_range

    def bench_value(name):
        return float(bench.get(name, parameter_default(fmu, name)))
    if bench_value("w_gearbox") >= bench_value("w_motor"):
        raise JudderError(
            f"`bench` w_gearbox {bench_value('w_gearbox'):g} rad/s is not "
            f"allowed with w_motor {bench_value('w_motor'):g} rad/s; "
            "allowed: below w_motor (the EVEN clutch slips forwards, "
            "at w_motor - w_gearbox)")
    delta_mu = bench_value("delta_mu")
    point = curve_at(bench_value("w_motor") - bench_value("w_gearbox"),
                     values["mu0"], values["mu_g"], delta_mu,
                     bench_value("w_op"))
    return ({"mu0": point.mu, "mu_g": point.slope},
            linear_range(bench_value("w_motor") - bench_value("w_gearbox"),
                         values["mu_g"], delta_mu, bench_value("w_op")))



def linear_validity(driveline, run, linear_slip):
    """Whether the dither's forced slip swing stays within the friction
    curve's linear range (the run can then follow its linearisation):
    ``forced_slip_amplitude_rad_s``, ``friction_linear_range_rad_s`` and
    ``linearisation_holds`` (None for a model without the curve)."""
    from stability.friction import forced_slip_amplitude
    if linear_slip is None or run.p_f == 0:
        return {"forced_slip_amplitude_rad_s": None,
                "friction_linear_range_rad_s": linear_slip,
                "linearisation_holds": None}
    forced = forced_slip_amplitude(driveline, run.freq_hz, run.p_f)
    return {"forced_slip_amplitude_rad_s": forced,
            "friction_linear_range_rad_s": linear_slip,
            "linearisation_holds": bool(forced <= linear_slip)}


def engagement_model(values, bench=None, fmu=None, duration=None):
    """The bench's engagement about its steady slip, for the periodic
    orbit (:class:`stability.orbit.EngagementModel`): the driveline with
    the damping the bench adds (:func:`added_damping`), the EVEN clutch's
    friction curve (``mu0``, ``mu_g`` at ``w_op``, ``delta_mu``,
    ``clutch.w_small``), the slip ``w_motor - w_gearbox`` and the motor's
    torque limit (``motor.tau_max``, 680 N m) with its steady torque
    (:func:`drive_torque`), all read from the bench model's FMU where
    ``bench`` does not set them; and the gearbox side's inertia with the
    time the held slip drifts before a run of ``duration`` seconds (the
    FMU's StopTime by default) is read, from the middle of the pressure
    ramp (:func:`stability.orbit.drifted_orbit`).

    Returns
    -------
    (EngagementModel, stability.model.Driveline)
        The model and the bench's linearisation at its slip (the Floquet
        view of the same bench, as ``simulate`` prints it).
    """
    from fmu.store import parameter_default
    from stability.orbit import EngagementModel
    from stability.source import build_driveline
    bench = dict(bench or {})
    fmu = fmu or bench_fmu(values)[1]

    def bench_value(name):
        return float(bench.get(name, parameter_default(fmu, name)))
    added = added_damping(values, fmu, bench)
    damped = values.replace(**{name: values[name] + value
                               for name, value in added.items()})
    driveline = build_driveline(damped)
    model = EngagementModel.from_driveline(
        driveline, delta_mu=bench_value("delta_mu"),
        w_op=bench_value("w_op"),
        slip=bench_value("w_motor") - bench_value("w_gearbox"),
        w_small=float(parameter_default(fmu, "clutch.w_small")))
    # the motor (body 1): its control's gain is in the damping, its
    # torque limit is the orbit's second nonlinearity
    gain = sum(added.values())
    torque, damping = drive_torque(model, gain, bench_value("w_motor"))
    if duration is None:
        from fmu.store import model_description
        duration = float(model_description(fmu).defaultExperiment.stopTime)
    model = dataclasses.replace(
        model, drive=0, drive_gain=gain,
        drive_limit=float(parameter_default(fmu, "motor.tau_max")),
        drive_torque=torque, drive_damping=damping,
        load_inertia=float(np.diag(model.mass) @ _group(
            model.stiffness, int(np.flatnonzero(model.clutch < 0)[0]))),
        drift_time=max(duration - bench_value("t_engage")
                       - 0.5 * bench_value("t_ramp"), 0.0))
    return model, build_driveline(bench_linearisation(values, bench, fmu))


def bench_linearisation(values, bench=None, fmu=None):
    """The parameter set of the bench's linearisation at its steady slip:
    the driveline with the damping its motor's speed control adds to body
    1 (:func:`added_damping`) and the EVEN clutch's friction curve's value
    and slope at the slip (:func:`operating_friction`) as ``mu0`` and
    ``mu_g``. The Floquet view of the bench, whose orbit is
    :func:`engagement_model`."""
    bench = dict(bench or {})
    fmu = fmu or bench_fmu(values)[1]
    friction, _ = operating_friction(values, fmu, bench)
    return values.replace(**{name: values[name] + value for name, value
                             in added_damping(values, fmu, bench).items()},
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
    """Which driveline a view is of, in words."""
    if driveline == "bench":
        return (f"the {values.model} driveline on its test bench (motor "
                "speed control on body 1, friction curve's value and "
                "slope at the bench's slip)")
    if values.source_kind.is_chain:
        return f"the {values.model} chain alone (Eq. 6, free, as Fig. 14)"
    return f"{values.model}"


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
