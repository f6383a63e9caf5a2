within Judder.Examples;
model Driveline4DOFTwoClutches "4-DOF driveline of Fig. 13 with the REV clutch as a second slipping clutch (the load of the bench), both with dither"
  parameter Units.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter Units.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter Units.Inertia J4=0.122 "Inertia between clutch damper and clutch discs";
  parameter Units.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter Units.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter Units.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter Units.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter Units.RotationalDampingConstant c2=0.1 "External damping of body 2";
  parameter Units.RotationalDampingConstant c3=0.1 "External damping of body 3";
  parameter Units.RotationalDampingConstant c4=0.1 "External damping of body 4";
  parameter Units.FrictionCoefficient mu0=0.09 "Friction coefficient at zero slip";
  parameter Units.FrictionGradient mu_g=0.017 "Friction gradient with slip speed";
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter Units.Length R_m=0.075 "Mean radius of the friction surfaces";
  parameter Units.Area S=0.01 "Area the actuation pressure acts on";
  parameter Units.Pressure p_m=1e6 "Mean actuation pressure";
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=102.9 "Dither frequency";
  parameter Units.Fraction mean_pressure_damping=0 "Share of p_m in the slip damping";
  parameter Units.AngularVelocity w_in=104.71975511965977 "Initial speed of bodies 1, 2 and 4 (1000 rpm)";
  parameter Units.AngularVelocity w_out=52.35987755982988 "Speed of body 3, the slip of the REV clutch against the housing (500 rpm)";
  parameter Units.FrictionGradient mu_g_rev=0.017 "Friction gradient of the REV clutch";
  parameter Real dither_share_rev(min=0)=0.5 "Dither amplitude of the REV clutch as a share of p_f (same valve frequency)";
  parameter Units.Torque T_e=mu0*N_c*R_m*S*p_m "Engine torque on body 1 (default: the mean clutch torque)";
  parameter Units.Pressure p_m_rev=(mu0*N_c*R_m*S*p_m - c3*w_out)/(mu0*N_c*R_m*S)
    "Mean pressure of the REV clutch that holds body 3 at w_out (steady slip)";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-150,-10},{-130,10}})));
  Components.Inertia inertia2(J=J2, phi(start=-T_e/k12, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-70,-10},{-50,10}})));
  Components.Inertia inertia4(J=J4, phi(start=-T_e/k12 - T_e/k24, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{10,-10},{30,10}})));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_out, fixed=true))
    annotation (Placement(transformation(extent={{130,-10},{150,10}})));
  Components.SpringDamper damper12(c=k12, d=c12) "Clutch damper"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Components.SpringDamper shaft24(c=k24, d=c24) "Shaft and gear mesh to the clutch pack"
    annotation (Placement(transformation(extent={{-30,-10},{-10,10}})));
  Components.SlippingClutch clutch(mu0=mu0, mu_g=mu_g, N_c=N_c, R_m=R_m, S=S,
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
  Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={60,40})));
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Components.SlippingClutch clutchRev(mu0=mu0, mu_g=mu_g_rev, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping) "REV clutch, slipping against the housing"
    annotation (Placement(transformation(extent={{170,-10},{190,10}})));
  Sources.DitherPressure pressureRev(p_m=p_m_rev, p_f=dither_share_rev*p_f, f=f_dither)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={180,40})));
  Sensors.SpeedSensor speedUpstream "Speed of body 4"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={20,40})));
  Sensors.SpeedSensor speedDownstream "Speed of body 3"
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
  connect(engine.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
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
  connect(inertia3.flange_b, clutchRev.flange_a)
    annotation (Line(points={{150,0},{170,0}}));
  connect(clutchRev.flange_b, housing.flange)
    annotation (Line(points={{190,0},{196,0},{196,-70},{0,-70},{0,-90}}));
  connect(pressureRev.p, clutchRev.p)
    annotation (Line(points={{184,29},{184,11}}, color={0,0,127}));
  connect(pressureRev.p_mean, clutchRev.p_mean)
    annotation (Line(points={{176,29},{176,11}}, color={0,0,127}));
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
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>The 4-DOF driveline of Fig. 13 (Driveline4DOF) with the REV clutch,
which loads the bench (section 2.2), as a second slipping clutch between
body 3 and the housing instead of a resistant torque. Body 3 turns at
w_out, so the REV clutch slips at w_out; its mean pressure p_m_rev holds
that speed steady. Both clutches are fed by the same valve frequency:
the EVEN clutch with the dither p_f, the REV clutch with
dither_share_rev p_f, so the dither modulates the slip damping of two
clutches,</p>
<pre>
  C(t) = C0 + cos(2 pi f t) p_f N_c R_m S (mu_g e e^T + dither_share_rev mu_g_rev e3 e3^T)
</pre>
<p>a modulation of rank two (e = e4 - e3): neither the paper's matrices
nor its rank-one engines apply as written; the Floquet layer takes the
system from this class (drivelines.modelica) and its Dyson engine and
Hill's method handle any rank. With dither_share_rev = 0 the REV clutch
only adds its (unmodulated) friction and the map is that of
Driveline4DOF with the same mean_pressure_damping = 0.</p>
</html>"));
end Driveline4DOFTwoClutches;
