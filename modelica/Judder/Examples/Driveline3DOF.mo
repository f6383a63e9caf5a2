within Judder.Examples;
model Driveline3DOF "3-DOF driveline of Fig. 12: steady slipping with dither (Appendix A values)"
  extends Data.Driveline3DOFData;
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=18.05 "Dither frequency";
  parameter Units.AngularVelocity w_in=104.71975511965977 "Initial speed of bodies 1 and 2-4 (1000 rpm)";
  parameter Units.AngularVelocity w_out=0 "Initial speed of body 3";
  parameter Units.Torque T_e=mu0*N_c*R_m*S*p_m "Engine torque on body 1";
  parameter Units.Torque T_r=mu0*N_c*R_m*S*p_m "Resistant torque on body 3";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Components.Inertia inertia24(J=J24, phi(start=-T_e/k, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-30,-10},{-10,10}})));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_out, fixed=true))
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
  Components.SpringDamper damper(c=k, d=c) "Clutch damper"
    annotation (Placement(transformation(extent={{-70,-10},{-50,10}})));
  Components.SlippingClutch clutch(mu0=mu0, mu_g=mu_g, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping)
    annotation (Placement(transformation(extent={{10,-10},{30,10}})));
  Components.Damper external1(d=c1)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-100,-40})));
  Components.Damper external24(d=c24)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-20,-40})));
  Components.Damper external3(d=c3)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={100,-40})));
  Components.Fixed housing
    annotation (Placement(transformation(extent={{-10,-100},{10,-80}})));
  Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={20,40})));
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-150,-10},{-130,10}})));
  Sources.ConstantTorque load(tau_constant=-T_r)
    annotation (Placement(transformation(extent={{150,-10},{130,10}})));
  Sensors.SpeedSensor speedUpstream "Speed of body 2-4"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={-20,40})));
  Sensors.SpeedSensor speedDownstream "Speed of body 3"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={100,40})));
  Sensors.RelSpeedSensor slipSensor "Speed of the clutch's flange_b relative to its flange_a"
    annotation (Placement(transformation(extent={{10,-50},{30,-30}})));
  Sensors.TorqueSensor torqueSensor "Torque the clutch transmits to body 3"
    annotation (Placement(transformation(extent={{50,-10},{70,10}})));
  output Units.AngularVelocity w_upstream=speedUpstream.w "Speed upstream of the clutch";
  output Units.AngularVelocity w_downstream=speedDownstream.w "Speed downstream of the clutch";
  output Units.AngularVelocity slip=-slipSensor.w_rel "Slip speed of the clutch";
  output Units.Torque clutch_torque=torqueSensor.tau "Friction torque of the clutch";
  output Units.Pressure actuation_pressure=pressure.p "Actuation pressure";
equation
  connect(engine.flange, inertia1.flange_a)
    annotation (Line(points={{-130,0},{-110,0}}));
  connect(inertia1.flange_b, damper.flange_a)
    annotation (Line(points={{-90,0},{-70,0}}));
  connect(damper.flange_b, inertia24.flange_a)
    annotation (Line(points={{-50,0},{-30,0}}));
  connect(inertia24.flange_b, clutch.flange_a)
    annotation (Line(points={{-10,0},{10,0}}));
  connect(clutch.flange_b, torqueSensor.flange_a)
    annotation (Line(points={{30,0},{50,0}}));
  connect(torqueSensor.flange_b, inertia3.flange_a)
    annotation (Line(points={{70,0},{90,0}}));
  connect(inertia3.flange_b, load.flange)
    annotation (Line(points={{110,0},{130,0}}));
  connect(external1.flange_a, inertia1.flange_a)
    annotation (Line(points={{-100,-30},{-100,-20},{-110,-20},{-110,0}}));
  connect(external24.flange_a, inertia24.flange_a)
    annotation (Line(points={{-20,-30},{-20,-20},{-30,-20},{-30,0}}));
  connect(external3.flange_a, inertia3.flange_a)
    annotation (Line(points={{100,-30},{100,-20},{90,-20},{90,0}}));
  connect(external1.flange_b, housing.flange)
    annotation (Line(points={{-100,-50},{-100,-70},{0,-70},{0,-90}}));
  connect(external24.flange_b, housing.flange)
    annotation (Line(points={{-20,-50},{-20,-70},{0,-70},{0,-90}}));
  connect(external3.flange_b, housing.flange)
    annotation (Line(points={{100,-50},{100,-70},{0,-70},{0,-90}}));
  connect(pressure.p, clutch.p)
    annotation (Line(points={{24,29},{24,11}}, color={0,0,127}));
  connect(pressure.p_mean, clutch.p_mean)
    annotation (Line(points={{16,29},{16,11}}, color={0,0,127}));
  connect(speedUpstream.flange, inertia24.flange_b)
    annotation (Line(points={{-20,30},{-20,20},{-10,20},{-10,0}}));
  connect(speedDownstream.flange, inertia3.flange_b)
    annotation (Line(points={{100,30},{100,20},{110,20},{110,0}}));
  connect(slipSensor.flange_a, clutch.flange_a)
    annotation (Line(points={{10,-40},{0,-40},{0,0},{10,0}}));
  connect(slipSensor.flange_b, clutch.flange_b)
    annotation (Line(points={{30,-40},{40,-40},{40,0},{30,0}}));
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-160,-100},{160,100}})),
    Documentation(info="<html>
<p>The essential 3-DOF model of Fig. 12 (the authors' earlier model,
reference [26] of the paper), with the values of its Appendix
(Data.Driveline3DOFData, which it extends):
engine-side body 1 (J1), body 2-4 (J24: the clutch damper and all the
parts up to the clutch pack) behind the clutch damper k, c, and the
gearbox side 3 (J3); each body has an external damper c_i to the
housing. The engine torque T_e drives body 1, the resistant torque T_r
brakes body 3, and the clutch (SlippingClutch) transmits the friction
torque of Eq. (3)-(5), with body 2-4 in place of body 4 and the
pressure p(t) = p_m + p_f cos(2 pi f_dither t) of Eq. (4).</p>
<p>The driveline starts in steady slipping at 1000 rpm (body 3 at rest).
Its single-period tongue has its tip near the one non-zero natural
frequency of the model, about 18.05 Hz, the default dither frequency.</p>
<p>Outputs, from the sensors: w_upstream and w_downstream, the speeds of
bodies 2-4 and 3 (speed sensors), slip = w24 - w3 (relative speed sensor
across the clutch, whose w_rel is w3 - w24), clutch_torque = T_c (torque
sensor between the clutch and body 3) and actuation_pressure = p.</p>
</html>"));
end Driveline3DOF;
