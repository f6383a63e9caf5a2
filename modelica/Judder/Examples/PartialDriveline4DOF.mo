within Judder.Examples;
partial model PartialDriveline4DOF "4-DOF chain of Fig. 13 with a replaceable EVEN clutch, its dither pressure and the sensors; what drives body 1 and loads body 3 is left to the extending model"
  extends Data.Driveline4DOFData;
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=102.9 "Dither frequency";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(fixed=true))
    annotation (Placement(transformation(extent={{-150,-10},{-130,10}})));
  Components.Inertia inertia2(J=J2, phi(fixed=true), w(fixed=true))
    annotation (Placement(transformation(extent={{-70,-10},{-50,10}})));
  Components.Inertia inertia4(J=J4, phi(fixed=true), w(fixed=true))
    annotation (Placement(transformation(extent={{10,-10},{30,10}})));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(fixed=true))
    annotation (Placement(transformation(extent={{130,-10},{150,10}})));
  Components.SpringDamper damper12(c=k12, d=c12) "Clutch damper"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Components.SpringDamper shaft24(c=k24, d=c24) "Shaft and gear mesh to the clutch pack"
    annotation (Placement(transformation(extent={{-30,-10},{-10,10}})));
  replaceable model Clutch = Components.SlippingClutch
    constrainedby Interfaces.PartialDitheredClutch
    "Type of the EVEN clutch: any clutch fed by a dither pressure";
  Clutch clutch(mu0=mu0, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping) "EVEN clutch"
    annotation (Placement(transformation(extent={{50,-10},{70,10}})));
  Components.Damper external1(d=c1)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-140,-40})));
  Components.Damper external2(d=c2)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-60,-40})));
  Components.Damper external4(d=c4)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={20,-40})));
  Components.Damper external3(d=c3)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={140,-40})));
  Components.Fixed housing
    annotation (Placement(transformation(extent={{-10,-100},{10,-80}})));
  Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither) "Actuation pressure of the EVEN clutch"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={60,40})));
  Sensors.SpeedSensor speedUpstream "Speed of body 4, the clutch plates on the engine side"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={20,40})));
  Sensors.SpeedSensor speedDownstream "Speed of body 3, the clutch plates on the gearbox side"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={140,40})));
  Sensors.RelSpeedSensor slipSensor "Speed of the clutch's flange_b relative to its flange_a"
    annotation (Placement(transformation(extent={{50,-50},{70,-30}})));
  Sensors.TorqueSensor torqueSensor "Torque the clutch transmits to body 3"
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
  output Units.AngularVelocity w_upstream=speedUpstream.w "Speed upstream of the clutch (body 4)";
  output Units.AngularVelocity w_downstream=speedDownstream.w "Speed downstream of the clutch (body 3)";
  output Units.AngularVelocity slip=-slipSensor.w_rel "Slip speed of the clutch";
  output Units.Torque clutch_torque=torqueSensor.tau "Friction torque of the clutch";
  output Units.Pressure actuation_pressure=pressure.p "Actuation pressure";
equation
  connect(inertia1.flange_b, damper12.flange_a)
    annotation (Line(points={{-130,0},{-110,0}}));
  connect(damper12.flange_b, inertia2.flange_a)
    annotation (Line(points={{-90,0},{-70,0}}));
  connect(inertia2.flange_b, shaft24.flange_a)
    annotation (Line(points={{-50,0},{-30,0}}));
  connect(shaft24.flange_b, inertia4.flange_a)
    annotation (Line(points={{-10,0},{10,0}}));
  connect(inertia4.flange_b, clutch.flange_a)
    annotation (Line(points={{30,0},{50,0}}));
  connect(clutch.flange_b, torqueSensor.flange_a)
    annotation (Line(points={{70,0},{90,0}}));
  connect(torqueSensor.flange_b, inertia3.flange_a)
    annotation (Line(points={{110,0},{130,0}}));
  connect(external1.flange_a, inertia1.flange_a)
    annotation (Line(points={{-140,-30},{-140,-20},{-150,-20},{-150,0}}));
  connect(external2.flange_a, inertia2.flange_a)
    annotation (Line(points={{-60,-30},{-60,-20},{-70,-20},{-70,0}}));
  connect(external4.flange_a, inertia4.flange_a)
    annotation (Line(points={{20,-30},{20,-20},{10,-20},{10,0}}));
  connect(external3.flange_a, inertia3.flange_a)
    annotation (Line(points={{140,-30},{140,-20},{130,-20},{130,0}}));
  connect(external1.flange_b, housing.flange)
    annotation (Line(points={{-140,-50},{-140,-70},{0,-70},{0,-90}}));
  connect(external2.flange_b, housing.flange)
    annotation (Line(points={{-60,-50},{-60,-70},{0,-70},{0,-90}}));
  connect(external4.flange_b, housing.flange)
    annotation (Line(points={{20,-50},{20,-70},{0,-70},{0,-90}}));
  connect(external3.flange_b, housing.flange)
    annotation (Line(points={{140,-50},{140,-70},{0,-70},{0,-90}}));
  connect(pressure.p, clutch.p)
    annotation (Line(points={{64,29},{64,11}}, color={0,0,127}));
  connect(pressure.p_mean, clutch.p_mean)
    annotation (Line(points={{56,29},{56,11}}, color={0,0,127}));
  connect(speedUpstream.flange, inertia4.flange_b)
    annotation (Line(points={{20,30},{20,20},{30,20},{30,0}}));
  connect(speedDownstream.flange, inertia3.flange_b)
    annotation (Line(points={{140,30},{140,20},{150,20},{150,0}}));
  connect(slipSensor.flange_a, clutch.flange_a)
    annotation (Line(points={{50,-40},{40,-40},{40,0},{50,0}}));
  connect(slipSensor.flange_b, clutch.flange_b)
    annotation (Line(points={{70,-40},{80,-40},{80,0},{70,0}}));
  annotation (
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>The 4-DOF chain of Fig. 13, wired once for every example built on it
(Driveline4DOF, Driveline4DOFTwoClutches, Driveline5DOFGeared and the
test bench, PartialTestBench): engine-side body 1 (J1), clutch damper 2
(J2) behind the damper k12, c12, body 4 (J4) between the damper and the
EVEN clutch pack behind the stiffness k24, c24, and the gearbox side 3
(J3); each body has an external damper c_i to the housing. The values
are those of Appendix A (Data.Driveline4DOFData, which this class
extends). The type of the EVEN clutch between bodies 4 and 3 is the
replaceable model <code>Clutch</code>: the SlippingClutch of Eq. (3)-(5)
by default, any clutch fed by a dither pressure
(Interfaces.PartialDitheredClutch) with <code>redeclare model Clutch =
...</code>, as the replaceable models of MSL's Fluid library. The
parameters every such clutch has (mu0, N_c, R_m, S,
mean_pressure_damping) are bound here; the extending model binds those
of its clutch's law by a modifier of <code>clutch</code> (mu_g of the
linear law, the curve of FrictionCurveClutch). A replaceable class
rather than a replaceable component: the project's compiler (rumoca)
applies a redeclared class through an intermediate base class
(PartialTestBench), not a redeclared component. Its pressure p(t) = p_m + p_f cos(2 pi f_dither t), Eq. (4),
comes from Sources.DitherPressure.</p>
<p>The extending model drives body 1 (flange_a of inertia1) and loads
body 3 (flange_b of inertia3), and gives the start values of the bodies'
speeds, and of the angles of bodies 2 and 4 (twisted springs), with
<code>fixed=true</code>.</p>
<p>Outputs, from the sensors: w_upstream and w_downstream, the speeds of
bodies 4 and 3 (speed sensors), slip = w4 - w3 (relative speed sensor
across the clutch, whose w_rel is w3 - w4), clutch_torque = T_c (torque
sensor between the clutch and body 3) and actuation_pressure = p.</p>
</html>"));
end PartialDriveline4DOF;
