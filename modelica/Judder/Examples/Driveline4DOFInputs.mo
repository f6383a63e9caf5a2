within Judder.Examples;
model Driveline4DOFInputs "Driveline4DOF with the clutch pressure and the engine torque as inputs, for a system simulation"
  extends Driveline4DOF(pressure(use_p_in=true), engine(use_tau_in=true));
  Interfaces.RealInput clutch_pressure(unit="Pa", displayUnit="bar", start=1e6)
    "Actuation pressure of the clutch (from the valve model)"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={60,90})));
  Interfaces.RealInput engine_torque(unit="N.m", start=540)
    "Engine torque on body 1 (from the engine model)"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-192,40})));
equation
  connect(clutch_pressure, pressure.p_in)
    annotation (Line(points={{60,80},{60,52}}, color={0,0,127}));
  connect(engine_torque, engine.tau_in)
    annotation (Line(points={{-192,30},{-192,0}}, color={0,0,127}));
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Documentation(info="<html>
<p>The 4-DOF driveline of Driveline4DOF for a colleague's system
simulation: the clutch's actuation pressure and the engine torque are
inputs of the FMU (clutch_pressure, Pa, from their valve model;
engine_torque, N m, from their engine model) instead of the dither
waveform p_m + p_f cos(2 pi f_dither t) and the constant T_e. The mean
pressure p_m stays a parameter: it sets the mean part of the clutch's
slip damping (mean_pressure_damping). The start values of the inputs are
the mean pressure and the mean clutch torque mu0 N_c R_m S p_m of the
default parameters, which the initial twist of the shafts assumes; the
outputs are those of Driveline4DOF.</p>
</html>"));
end Driveline4DOFInputs;
