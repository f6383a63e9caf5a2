"""The drivelines the tool knows: topology, parameters, Modelica class, FMU.

Each :class:`DrivelineModel` says everything the other packages need to
know about one driveline, so none of them branches on a model's name:

* its bodies and couplings by parameter name (the stability layer builds
  the matrices of Eq. (1)-(9) from them), and the wet clutch between two
  bodies;
* the clutch damper whose damping factor Eq. (16) reports, and the closed
  form of the natural frequencies (Eq. 15);
* its parameter specifications and presets (Appendix A, section 4.2),
  read from the parameter records of the Modelica library
  (``modelica/Judder/Data``, :mod:`drivelines.records`), which the
  Modelica examples extend: the values are written once;
* the Modelica class it is written as, hence its FMU, the bench model of
  its engagements, and the signals a run reports.

Calibration of ``N_c``, ``R_m`` and ``S``
-----------------------------------------
The paper keeps the number of plate pairs, the mean radius and the piston
area confidential. They enter Eq. (3) only as the product
``N_c * R_m * S``. The defaults (8 pairs, 75 mm, 0.01 m^2) give
``N_c R_m S = 6e-3 m^3``, chosen from two statements of the paper:

* the EVEN clutch then transmits ``mu0 N_c R_m S p_m = 540 N m`` at the
  bench pressure of about 10 bar (section 2.2), below the 680 N m the bench
  motor delivers, as an engaging clutch that does not stall the motor must;
* with this product the tongue tips lie between 0.03 and 0.19 bar (Fig.
  14), inside the bench's dither range, and with the clutch damper at
  16.8 % damping (c12 = 10) the combination tongues 5 and 6 lie above the
  0.7 bar the paper states (at 1.45 bar).

The record ``Judder.Data.ClutchData`` holds these values.
"""

from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from infra.errors import ParameterError

from .records import record_values
from .specs import CLUTCH_SPECS, nonnegative, positive

__all__ = ["Body", "Coupling", "Preset", "DrivelineModel", "MODELS",
           "DEFAULT_MODEL", "SPECS", "PRESETS", "SIGNALS",
           "get_model"]

#: Outputs of every example model, with units (SI).
SIGNALS = MappingProxyType({
    "w_upstream": "rad/s", "w_downstream": "rad/s", "slip": "rad/s",
    "clutch_torque": "N.m", "actuation_pressure": "Pa"})


@dataclass(frozen=True)
class Body:
    """A rigid body of the chain.

    Attributes
    ----------
    label : str
        Its number in the paper's figures ('1', '24', ...).
    inertia, external_damping : str
        Names of its moment of inertia (kg m^2) and of its damping to
        ground (N m s/rad).
    instance : str
        Name of its ``Inertia`` in the Modelica examples.
    """

    label: str
    inertia: str
    external_damping: str
    instance: str


@dataclass(frozen=True)
class Coupling:
    """A spring-damper between two bodies (labels), by parameter name."""

    body_a: str
    body_b: str
    stiffness: str
    damping: str


@dataclass(frozen=True)
class Preset:
    """A named parameter set: what it is, and its values (SI)."""

    description: str
    values: MappingProxyType


@dataclass(frozen=True)
class DrivelineModel:
    """One driveline: topology, parameters, Modelica class and signals.

    Attributes
    ----------
    name : str
        Key of the registry ('4dof').
    title : str
    bodies : tuple of Body
        In the order of the coordinates of Eq. (6).
    couplings : tuple of Coupling
    clutch : (str, str)
        Labels of the clutch's input (engine-side) and output bodies.
    clutch_damper : Coupling
        The coupling whose damping factor Eq. (16) gives, with the inertia
        of its ``body_b``.
    specs : mapping of str to ParameterSpec
        Every parameter, in display order.
    presets : mapping of str to Preset
    default_preset : str
    modelica_class : str
        The example model of the same driveline and parameter names.
    bench_class : str or None
        The test-bench engagement model of this driveline, if any.
    bench_records : tuple of str
        The ``Judder.Data`` records the bench class extends for its own
        parameters (motor, load clutch, ramp, friction curve): their
        defaults, units and allowed ranges are the bench's.
    bench_table_class : str or None
        The same bench with the EVEN clutch's friction characteristic as
        a table (``--friction``), if any.
    bench_table_records : tuple of str
        Its records (the bench's without the curve's).
    bench_damping : tuple of (str, str)
        ``(parameter, bench parameter)``: damping the bench adds to a
        parameter of the driveline in its linearisation (the motor's
        proportional speed control acts on body 1 as a damping to ground
        ``d_control`` about the set speed), so the bench's Floquet model
        has ``parameter + bench parameter``.
    free_response_speeds : tuple of str
        FMU variables whose difference between two runs gives the free
        response (enough to see every mode).
    paper_sensitivity : bool
        Whether the statements of section 4.3 (about this driveline) can
        be judged on its sensitivity studies.
    closed_form_omega2 : callable
        ``values -> ndarray`` of the squared natural frequencies,
        (rad/s)^2, in closed form.
    """

    name: str
    title: str
    bodies: tuple
    couplings: tuple
    clutch: tuple
    clutch_damper: Coupling
    specs: MappingProxyType
    presets: MappingProxyType
    default_preset: str
    modelica_class: str
    bench_class: object
    bench_records: tuple
    bench_table_class: object
    bench_table_records: tuple
    bench_damping: tuple
    free_response_speeds: tuple
    paper_sensitivity: bool
    closed_form_omega2: object

    @property
    def signals(self):
        """Outputs a run of its FMU reports, ``{name: unit}``."""
        return SIGNALS

    @property
    def fmu_name(self):
        """File stem of its FMU (the class name without the package)."""
        return self.modelica_class.rsplit(".", 1)[-1]

    @property
    def bench_fmu_name(self):
        """File stem of its bench model's FMU, or None."""
        return (None if self.bench_class is None
                else self.bench_class.rsplit(".", 1)[-1])

    def body_index(self, label):
        """Position of the body ``label`` in the coordinates."""
        return [b.label for b in self.bodies].index(label)

    def external_damping_names(self):
        """Names of the damping to ground of every body (Fig. 19b)."""
        return tuple(b.external_damping for b in self.bodies)


def _specs(*items):
    return MappingProxyType({s.name: s for s in items + CLUTCH_SPECS})


def _presets(**items):
    return MappingProxyType({
        name: Preset(description, MappingProxyType(values))
        for name, (description, values) in items.items()})


def _omega2_4dof(p):
    """Eq. (15): the two non-zero eigenvalues of the undamped 4-DOF chain."""
    J1, J2, J4 = p["J1"], p["J2"], p["J4"]
    k12, k24 = p["k12"], p["k24"]
    a = J4 * k12 * (J1 + J2)
    b = J1 * k24 * (J2 + J4)
    delta = (a ** 2 + b ** 2
             + 2 * J1 * J4 * k12 * k24 * (J4 * (J1 - J2) - J2 * (J1 + J2)))
    return (a + b + np.array([-1.0, 1.0]) * np.sqrt(delta)) \
        / (2 * J1 * J2 * J4)


def _omega2_3dof(p):
    """Two-inertia oscillator: ``w^2 = k (J1 + J24) / (J1 J24)``."""
    return np.array([p["k"] * (p["J1"] + p["J24"]) / (p["J1"] * p["J24"])])


_DAMPER_12 = Coupling("1", "2", "k12", "c12")
_DAMPER_3DOF = Coupling("1", "24", "k", "c")

FOUR_DOF = DrivelineModel(
    name="4dof",
    title="4-DOF driveline of Fig. 13, Eq. (1)-(5)",
    bodies=(Body("1", "J1", "c1", "inertia1"),
            Body("2", "J2", "c2", "inertia2"),
            Body("4", "J4", "c4", "inertia4"),
            Body("3", "J3", "c3", "inertia3")),
    couplings=(_DAMPER_12, Coupling("2", "4", "k24", "c24")),
    clutch=("4", "3"),
    clutch_damper=_DAMPER_12,
    specs=_specs(
        positive("J1", "kg m^2", "inertia of the engine-side body"),
        positive("J2", "kg m^2", "inertia of the clutch damper"),
        positive("J3", "kg m^2", "inertia of the gearbox-side body"),
        positive("J4", "kg m^2",
                 "inertia between clutch damper and clutch discs"),
        positive("k12", "N m/rad", "torsional stiffness of the clutch damper"),
        positive("k24", "N m/rad",
                 "equivalent stiffness between damper and clutch pack"),
        nonnegative("c12", "N m s/rad", "damping of the clutch damper"),
        nonnegative("c24", "N m s/rad", "internal damping between 2 and 4"),
        nonnegative("c1", "N m s/rad", "external damping of body 1"),
        nonnegative("c2", "N m s/rad", "external damping of body 2"),
        nonnegative("c3", "N m s/rad", "external damping of body 3"),
        nonnegative("c4", "N m s/rad", "external damping of body 4")),
    presets=_presets(**{
        "paper-4dof": ("4-DOF model, Appendix A of the paper",
                       record_values("Driveline4DOFData")),
        # Section 4.2, solid line of Fig. 16.
        "paper-4dof-fitted": ("4-DOF model fitted to the bench (section "
                              "4.2): c12 = 10, mu_g = 0.022, k24 + 6 %",
                              record_values("Driveline4DOFFitted"))}),
    default_preset="paper-4dof",
    modelica_class="Judder.Examples.Driveline4DOF",
    bench_class="Judder.Examples.TestBenchEngagement",
    bench_records=("TestBenchData", "BoundedCurveData"),
    bench_table_class="Judder.Examples.TestBenchTable",
    bench_table_records=("TestBenchData",),
    bench_damping=(("c1", "d_control"),),
    free_response_speeds=("w_upstream", "w_downstream", "inertia1.w",
                          "inertia2.w"),
    paper_sensitivity=True,
    closed_form_omega2=_omega2_4dof,
)

THREE_DOF = DrivelineModel(
    name="3dof",
    title="3-DOF driveline of Fig. 12",
    bodies=(Body("1", "J1", "c1", "inertia1"),
            Body("24", "J24", "c24", "inertia24"),
            Body("3", "J3", "c3", "inertia3")),
    couplings=(_DAMPER_3DOF,),
    clutch=("24", "3"),
    clutch_damper=_DAMPER_3DOF,
    specs=_specs(
        positive("J1", "kg m^2", "inertia of the engine-side body"),
        positive("J24", "kg m^2",
                 "inertia of the clutch damper and everything up to the "
                 "clutch pack"),
        positive("J3", "kg m^2", "inertia of the gearbox-side body"),
        positive("k", "N m/rad", "torsional stiffness of the clutch damper"),
        nonnegative("c", "N m s/rad", "damping of the clutch damper"),
        nonnegative("c1", "N m s/rad", "external damping of body 1"),
        nonnegative("c24", "N m s/rad", "external damping of body 2-4"),
        nonnegative("c3", "N m s/rad", "external damping of body 3")),
    presets=_presets(**{
        "paper-3dof": ("3-DOF model, Appendix A of the paper",
                       record_values("Driveline3DOFData"))}),
    default_preset="paper-3dof",
    modelica_class="Judder.Examples.Driveline3DOF",
    bench_class=None,
    bench_records=(),
    bench_table_class=None,
    bench_table_records=(),
    bench_damping=(),
    free_response_speeds=("w_upstream", "w_downstream", "inertia1.w"),
    paper_sensitivity=False,
    closed_form_omega2=_omega2_3dof,
)

#: Every driveline, by name; the first is the default.
MODELS = MappingProxyType({m.name: m for m in (FOUR_DOF, THREE_DOF)})
#: Name of the driveline used when none is named.
DEFAULT_MODEL = FOUR_DOF.name
#: Parameter specifications of each model, in display order.
SPECS = MappingProxyType({name: m.specs for name, m in MODELS.items()})
#: Description of every preset, by name.
PRESETS = MappingProxyType({name: preset.description
                            for m in MODELS.values()
                            for name, preset in m.presets.items()})


def get_model(name):
    """The :class:`DrivelineModel` called ``name``.

    Raises
    ------
    ParameterError
        If there is none; the message lists the models.

    Examples
    --------
    >>> get_model("4dof").fmu_name
    'Driveline4DOF'
    """
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ParameterError(f"model = {name!r} is unknown; allowed: "
                             f"{', '.join(MODELS)}") from None
