within Judder.Examples;
partial model PartialTestBench "Test bench of Fig. 5 and section 2.2 without the choice of the EVEN clutch: motor at w_motor, REV clutch slipping as the load"
  parameter Units.Inertia J1=1.12 "Inertia of the motor-side body";
  parameter Units.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter Units.Inertia J4=0.122 "Inertia between clutch damper and the EVEN clutch discs";
  parameter Units.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter Units.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter Units.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter Units.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter Units.RotationalDampingConstant c2=0.1 "External damping of body 2";
  parameter Units.RotationalDampingConstant c3=0.1 "External damping of body 3";
  parameter Units.RotationalDampingConstant c4=0.1 "External damping of body 4";
  parameter Units.FrictionCoefficient mu0=0.09 "Friction coefficient of the EVEN clutch (at its operating slip)";
  parameter Units.FrictionGradient mu_g=0.017 "Gradient of the EVEN friction coefficient with slip speed (at its operating slip)";
  parameter Real N_c(min=1)=8 "Plate pairs of the EVEN clutch";
  parameter Units.Length R_m=0.075 "Mean radius of the EVEN clutch";
  parameter Units.Area S=0.01 "Piston area of the EVEN clutch";
  parameter Units.Pressure p_m=1e6 "Mean EVEN pressure after the ramp (685 mA, about 10 bar)";
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=102.9 "Dither frequency";
  parameter Units.Fraction mean_pressure_damping=0 "Share of p_m in the slip damping";
  parameter Units.Time t_engage=0.1 "Start of the EVEN pressure ramp";
  parameter Units.Time t_ramp(min=0)=0.5 "Duration of the EVEN and REV pressure ramps (clutch fill)";
  parameter Real N_c_load(min=1)=10 "Plate pairs of the REV clutch (two more than EVEN)";
  parameter Units.Pressure p_load(min=0)=0.98e6 "REV pressure (670 mA, about 9.8 bar)";
  parameter Real load_share(min=0)=1
    "REV torque over the EVEN clutch's mean torque mu0 N_c R_m S p_m (1: the slip stays steady; below 1 the gearbox side speeds up)";
  parameter Units.Area S_load=load_share*N_c*S*p_m/(N_c_load*p_load)
    "Piston area of the REV clutch";
  parameter Units.AngularVelocity w_motor(min=0)=104.71975511965977 "Motor speed (1000 rpm)";
  parameter Units.AngularVelocity w_gearbox(min=0)=20 "Initial speed of the gearbox side, at which the REV clutch slips";
  parameter Units.RotationalDampingConstant d_control=2000 "Gain of the motor speed controller";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_motor, fixed=true))
    annotation (Placement(transformation(extent={{-150,-10},{-130,10}})));
  Components.Inertia inertia2(J=J2, phi(start=0, fixed=true), w(start=w_motor, fixed=true))
    annotation (Placement(transformation(extent={{-70,-10},{-50,10}})));
  Components.Inertia inertia4(J=J4, phi(start=0, fixed=true), w(start=w_motor, fixed=true))
    annotation (Placement(transformation(extent={{10,-10},{30,10}})));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_gearbox, fixed=true))
    annotation (Placement(transformation(extent={{130,-10},{150,10}})));
  Components.SpringDamper damper12(c=k12, d=c12) "Clutch damper"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Components.SpringDamper shaft24(c=k24, d=c24) "Shaft and gear mesh to the clutch pack"
    annotation (Placement(transformation(extent={{-30,-10},{-10,10}})));
  replaceable Components.WetClutch even(mu0=mu0, mu_g=mu_g, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping) constrainedby Interfaces.PartialPressureClutch
    "EVEN clutch, engaging"
    annotation (Placement(transformation(extent={{50,-10},{70,10}})));
  Components.WetClutch rev(mu0=mu0, mu_g=0, N_c=N_c_load, R_m=R_m, S=S_load)
    "REV clutch, slipping against the housing as the load (flat friction curve)"
    annotation (Placement(transformation(extent={{170,-10},{190,10}})));
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
  Sources.SpeedDrive motor(w_ref=w_motor, d_control=d_control) "81 kW DC motor with speed control"
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Sources.DitherPressure evenPressure(p_m=p_m, p_f=p_f, f=f_dither, t_start=t_engage, t_ramp=t_ramp)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={60,40})));
  Sources.DitherPressure revPressure(p_m=p_load, p_f=0, f=0, t_start=t_engage, t_ramp=t_ramp)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={180,40})));
  Sensors.SpeedSensor speedUpstream "Speed of body 4, the EVEN clutch plates on the engine side"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={20,40})));
  Sensors.SpeedSensor speedDownstream "Speed of body 3, the EVEN clutch plates on the gearbox side"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={140,40})));
  Sensors.RelSpeedSensor slipSensor "Speed of the EVEN clutch's flange_b relative to its flange_a"
    annotation (Placement(transformation(extent={{50,-50},{70,-30}})));
  Sensors.TorqueSensor torqueSensor "Torque the EVEN clutch transmits to body 3"
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
  output Units.AngularVelocity w_upstream=speedUpstream.w "Speed upstream of the EVEN clutch";
  output Units.AngularVelocity w_downstream=speedDownstream.w "Speed downstream of the EVEN clutch";
  output Units.AngularVelocity slip=-slipSensor.w_rel "Slip speed of the EVEN clutch";
  output Units.Torque clutch_torque=torqueSensor.tau "Friction torque of the EVEN clutch";
  output Units.Pressure actuation_pressure=evenPressure.p "EVEN actuation pressure";
equation
  connect(motor.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
  connect(inertia1.flange_b, damper12.flange_a)
    annotation (Line(points={{-130,0},{-110,0}}));
  connect(damper12.flange_b, inertia2.flange_a)
    annotation (Line(points={{-90,0},{-70,0}}));
  connect(inertia2.flange_b, shaft24.flange_a)
    annotation (Line(points={{-50,0},{-30,0}}));
  connect(shaft24.flange_b, inertia4.flange_a)
    annotation (Line(points={{-10,0},{10,0}}));
  connect(inertia4.flange_b, even.flange_a)
    annotation (Line(points={{30,0},{50,0}}));
  connect(even.flange_b, torqueSensor.flange_a)
    annotation (Line(points={{70,0},{90,0}}));
  connect(torqueSensor.flange_b, inertia3.flange_a)
    annotation (Line(points={{110,0},{130,0}}));
  connect(inertia3.flange_b, rev.flange_a)
    annotation (Line(points={{150,0},{170,0}}));
  connect(rev.flange_b, housing.flange)
    annotation (Line(points={{190,0},{200,0},{200,-70},{0,-70},{0,-90}}));
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
  connect(evenPressure.p, even.p)
    annotation (Line(points={{64,29},{64,11}}, color={0,0,127}));
  connect(evenPressure.p_mean, even.p_mean)
    annotation (Line(points={{56,29},{56,11}}, color={0,0,127}));
  connect(revPressure.p, rev.p)
    annotation (Line(points={{184,29},{184,11}}, color={0,0,127}));
  connect(revPressure.p_mean, rev.p_mean)
    annotation (Line(points={{176,29},{176,11}}, color={0,0,127}));
  connect(speedUpstream.flange, inertia4.flange_b)
    annotation (Line(points={{20,30},{20,20},{30,20},{30,0}}));
  connect(speedDownstream.flange, inertia3.flange_b)
    annotation (Line(points={{140,30},{140,20},{150,20},{150,0}}));
  connect(slipSensor.flange_a, even.flange_a)
    annotation (Line(points={{50,-40},{40,-40},{40,0},{50,0}}));
  connect(slipSensor.flange_b, even.flange_b)
    annotation (Line(points={{70,-40},{80,-40},{80,0},{70,0}}));
  annotation (Documentation(info="<html>
<p>The test bench of section 2.2 (Fig. 5b) with the EVEN clutch left to
the extending model: TestBenchEngagement (a bounded friction curve,
steady slip) and TestBenchLockUp (an engagement ending in lock-up).
See TestBenchEngagement for the bench.</p>
</html>"));
end PartialTestBench;
