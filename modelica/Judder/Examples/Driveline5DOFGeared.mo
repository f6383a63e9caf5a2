within Judder.Examples;
model Driveline5DOFGeared "5-DOF driveline: the 4-DOF chain of Fig. 13, a gear and an output shaft to one more inertia; friction curve mu(slip)"
  parameter Units.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter Units.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body (input of the gear)";
  parameter Units.Inertia J4=0.122 "Inertia between clutch damper and clutch discs";
  parameter Units.Inertia J5=12.0 "Inertia of the output side, behind the gear and the output shaft";
  parameter Units.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter Units.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter Units.RotationalSpringConstant k35=20000 "Stiffness of the output shaft (behind the gear)";
  parameter Units.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter Units.RotationalDampingConstant c35=0.5 "Damping of the output shaft";
  parameter Units.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter Units.RotationalDampingConstant c2=0.1 "External damping of body 2";
  parameter Units.RotationalDampingConstant c3=0.1 "External damping of body 3";
  parameter Units.RotationalDampingConstant c4=0.1 "External damping of body 4";
  parameter Units.RotationalDampingConstant c5=0.1 "External damping of body 5";
  parameter Real ratio(min=1e-3)=3.5 "Gear ratio, speed of body 3 over speed of the output shaft";
  parameter Units.FrictionCoefficient mu0=0.09 "Friction coefficient at zero slip";
  parameter Units.FrictionCoefficient mu_max=0.18 "Friction coefficient at large slip";
  parameter Units.AngularVelocity w_char(min=1e-6)=4 "Characteristic slip speed of the friction curve (slope mu_g = 0.0177 s/rad at w_slip = 2 rad/s)";
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter Units.Length R_m=0.075 "Mean radius of the friction surfaces";
  parameter Units.Area S=0.01 "Area the actuation pressure acts on";
  parameter Units.Pressure p_m=1e6 "Mean actuation pressure";
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=100 "Dither frequency";
  parameter Units.Fraction mean_pressure_damping=0 "Share of p_m in the slip-dependent friction";
  parameter Units.AngularVelocity w_slip(min=0)=2 "Slip speed of the operating point (body 4 minus body 3)";
  parameter Units.AngularVelocity w_out=100 "Speed of body 3 at the operating point";
  parameter Units.AngularVelocity w_in=w_out + w_slip "Speed of bodies 1, 2 and 4 at the operating point";
  parameter Units.AngularVelocity dw_start=0 "Extra start speed of body 1, off the operating point (free-response runs: judder crosscheck --perturb dw_start)";
  parameter Units.Torque T_c=N_c*R_m*S*p_m*(mu0 + mean_pressure_damping*(mu_max - mu0)*tanh(w_slip/w_char))
    "Clutch torque at the operating point without dither";
  parameter Units.Torque T_e=T_c + (c1 + c2 + c4)*w_in "Engine torque on body 1 (steady slip)";
  parameter Units.Torque T_5=ratio*(T_c - c3*w_out) "Torque the gear passes to the output shaft";
  parameter Units.Torque T_r=T_5 - c5*w_out/ratio "Resistant torque on body 5 (steady slip)";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_in + dw_start, fixed=true))
    annotation (Placement(transformation(extent={{-150,-10},{-130,10}})));
  Components.Inertia inertia2(J=J2, phi(start=-(T_e - c1*w_in)/k12, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-90,-10},{-70,10}})));
  Components.Inertia inertia4(J=J4, phi(start=-(T_e - c1*w_in)/k12 - (T_c + c4*w_in)/k24, fixed=true), w(start=w_in, fixed=true))
    annotation (Placement(transformation(extent={{-30,-10},{-10,10}})));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_out, fixed=true))
    annotation (Placement(transformation(extent={{30,-10},{50,10}})));
  Components.Inertia inertia5(J=J5, phi(start=-T_5/k35, fixed=true), w(start=w_out/ratio, fixed=true))
    annotation (Placement(transformation(extent={{160,-10},{180,10}})));
  Components.SpringDamper damper12(c=k12, d=c12) "Clutch damper"
    annotation (Placement(transformation(extent={{-120,-10},{-100,10}})));
  Components.SpringDamper shaft24(c=k24, d=c24) "Shaft and gear mesh to the clutch pack"
    annotation (Placement(transformation(extent={{-60,-10},{-40,10}})));
  Components.FrictionCurveClutch clutch(mu0=mu0, mu_max=mu_max, w_char=w_char, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping) "EVEN clutch with a friction curve"
    annotation (Placement(transformation(extent={{0,-10},{20,10}})));
  Components.IdealGear gear(ratio=ratio) "Gear between body 3 and the output shaft"
    annotation (Placement(transformation(extent={{70,-10},{90,10}})));
  Components.SpringDamper shaft35(c=k35, d=c35) "Output shaft behind the gear"
    annotation (Placement(transformation(extent={{130,-10},{150,10}})));
  Components.Damper external1(d=c1)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-140,-40})));
  Components.Damper external2(d=c2)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-80,-40})));
  Components.Damper external4(d=c4)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={-20,-40})));
  Components.Damper external3(d=c3)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={40,-40})));
  Components.Damper external5(d=c5)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={170,-40})));
  Components.Fixed housing
    annotation (Placement(transformation(extent={{-10,-100},{10,-80}})));
  Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={10,40})));
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Sources.ConstantTorque load(tau_constant=-T_r)
    annotation (Placement(transformation(extent={{200,-10},{180,10}})));
  Sensors.SpeedSensor speedUpstream "Speed of body 4"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={-20,40})));
  Sensors.SpeedSensor speedDownstream "Speed of body 3"
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=90, origin={40,40})));
  output Units.AngularVelocity w_upstream=speedUpstream.w "Speed upstream of the clutch (body 4)";
  output Units.AngularVelocity w_downstream=speedDownstream.w "Speed downstream of the clutch (body 3)";
  output Units.AngularVelocity slip=clutch.slip "Slip speed of the clutch";
  output Units.Torque clutch_torque=clutch.tau_c "Friction torque of the clutch";
  output Units.Pressure actuation_pressure=pressure.p "Actuation pressure";
equation
  connect(engine.flange, inertia1.flange_a);
  connect(inertia1.flange_b, damper12.flange_a);
  connect(damper12.flange_b, inertia2.flange_a);
  connect(inertia2.flange_b, shaft24.flange_a);
  connect(shaft24.flange_b, inertia4.flange_a);
  connect(inertia4.flange_b, clutch.flange_a);
  connect(clutch.flange_b, inertia3.flange_a);
  connect(inertia3.flange_b, gear.flange_a);
  connect(gear.flange_b, shaft35.flange_a);
  connect(shaft35.flange_b, inertia5.flange_a);
  connect(inertia5.flange_b, load.flange);
  connect(external1.flange_a, inertia1.flange_a);
  connect(external2.flange_a, inertia2.flange_a);
  connect(external4.flange_a, inertia4.flange_a);
  connect(external3.flange_a, inertia3.flange_a);
  connect(external5.flange_a, inertia5.flange_a);
  connect(external1.flange_b, housing.flange);
  connect(external2.flange_b, housing.flange);
  connect(external4.flange_b, housing.flange);
  connect(external3.flange_b, housing.flange);
  connect(external5.flange_b, housing.flange);
  connect(pressure.p, clutch.p);
  connect(pressure.p_mean, clutch.p_mean);
  connect(speedUpstream.flange, inertia4.flange_b);
  connect(speedDownstream.flange, inertia3.flange_b);
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>A driveline that is not the paper's: the 4-DOF chain of Fig. 13
(bodies 1, 2, 4 and the EVEN clutch to body 3) followed by an ideal gear
of ratio <code>ratio</code> and an output shaft k35, c35 to the vehicle
side J5: five degrees of freedom, ten states. The clutch has the friction curve of
Components.FrictionCurveClutch,</p>
<pre>
  mu(slip) = mu0 + (mu_max - mu0) tanh(slip/w_char)
</pre>
<p>whose local slope at the operating slip w_slip is the friction
gradient of the stability analysis,
mu_g = (mu_max - mu0)/w_char (1 - tanh(w_slip/w_char)^2): the slip
speed is a parameter of the map (judder map --modelica
Judder.Examples.Driveline5DOFGeared --set w_slip=...).</p>
<p>The start values are the steady slip without dither: bodies 1, 2, 4
at w_in = w_out + w_slip, body 3 at w_out, body 5 at w_out/ratio, every
spring twisted to carry the torque that reaches it (the engine torque
T_e covers the clutch torque and the external damping; the resistant
torque T_r on body 5 balances what the gear passes on). The Floquet
layer linearises the model about this state (drivelines.modelica);
dw_start moves body 1 off it, for the second run of a free-response
cross-check.</p>
</html>"));
end Driveline5DOFGeared;
