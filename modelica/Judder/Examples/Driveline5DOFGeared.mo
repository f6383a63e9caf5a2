within Judder.Examples;
model Driveline5DOFGeared "5-DOF driveline: the 4-DOF chain of Fig. 13, a gear and an output shaft to one more inertia; friction curve mu(slip)"
  extends PartialDriveline4DOF(
    f_dither=100,
    final mu_g=(mu_max - mu0)/w_char*(1 - tanh(w_slip/w_char)^2),
    inertia1(w(start=w_in + dw_start, fixed=true)),
    inertia2(phi(start=-(T_e - c1*w_in)/k12, fixed=true), w(start=w_in, fixed=true)),
    inertia4(phi(start=-(T_e - c1*w_in)/k12 - (T_c + c4*w_in)/k24, fixed=true), w(start=w_in, fixed=true)),
    inertia3(w(start=w_out, fixed=true)),
    redeclare model Clutch = Components.FrictionCurveClutch,
    clutch(mu_max=mu_max, w_char=w_char));
  parameter Units.Inertia J5=12.0 "Inertia of the output side, behind the gear and the output shaft";
  parameter Units.RotationalSpringConstant k35=20000 "Stiffness of the output shaft (behind the gear)";
  parameter Units.RotationalDampingConstant c35=0.5 "Damping of the output shaft";
  parameter Units.RotationalDampingConstant c5=0.1 "External damping of body 5";
  parameter Real ratio(min=1e-3)=3.5 "Gear ratio, speed of body 3 over speed of the output shaft";
  parameter Units.FrictionCoefficient mu_max=0.18 "Friction coefficient at large slip";
  parameter Units.AngularVelocity w_char(min=1e-6)=4 "Characteristic slip speed of the friction curve (slope mu_g = 0.0177 s/rad at w_slip = 2 rad/s)";
  parameter Units.AngularVelocity w_slip(min=0)=2 "Slip speed of the operating point (body 4 minus body 3)";
  parameter Units.AngularVelocity w_out=100 "Speed of body 3 at the operating point";
  parameter Units.AngularVelocity w_in=w_out + w_slip "Speed of bodies 1, 2 and 4 at the operating point";
  parameter Units.AngularVelocity dw_start=0 "Extra start speed of body 1, off the operating point (free-response runs: judder crosscheck --perturb dw_start)";
  parameter Units.Torque T_c=N_c*R_m*S*p_m*(mu0 + mean_pressure_damping*(mu_max - mu0)*tanh(w_slip/w_char))
    "Clutch torque at the operating point without dither";
  parameter Units.Torque T_e=T_c + (c1 + c2 + c4)*w_in "Engine torque on body 1 (steady slip)";
  parameter Units.Torque T_5=ratio*(T_c - c3*w_out) "Torque the gear passes to the output shaft";
  parameter Units.Torque T_r=T_5 - c5*w_out/ratio "Resistant torque on body 5 (steady slip)";
  Components.Inertia inertia5(J=J5, phi(start=-T_5/k35, fixed=true), w(start=w_out/ratio, fixed=true))
    annotation (Placement(transformation(extent={{250,-10},{270,10}})));
  Components.IdealGear gear(ratio=ratio) "Gear between body 3 and the output shaft"
    annotation (Placement(transformation(extent={{170,-10},{190,10}})));
  Components.SpringDamper shaft35(c=k35, d=c35) "Output shaft behind the gear"
    annotation (Placement(transformation(extent={{210,-10},{230,10}})));
  Components.Damper external5(d=c5)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={260,-40})));
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Sources.ConstantTorque load(tau_constant=-T_r)
    annotation (Placement(transformation(extent={{310,-10},{290,10}})));
equation
  connect(engine.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
  connect(inertia3.flange_b, gear.flange_a)
    annotation (Line(points={{150,0},{170,0}}));
  connect(gear.flange_b, shaft35.flange_a)
    annotation (Line(points={{190,0},{210,0}}));
  connect(shaft35.flange_b, inertia5.flange_a)
    annotation (Line(points={{230,0},{250,0}}));
  connect(inertia5.flange_b, load.flange)
    annotation (Line(points={{270,0},{290,0}}));
  connect(external5.flange_a, inertia5.flange_a)
    annotation (Line(points={{260,-30},{260,-20},{250,-20},{250,0}}));
  connect(external5.flange_b, housing.flange)
    annotation (Line(points={{260,-50},{260,-70},{0,-70},{0,-90}}));
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{320,100}})),
    Documentation(info="<html>
<p>A driveline that is not the paper's: the 4-DOF chain of Fig. 13
(PartialDriveline4DOF: bodies 1, 2, 4 and the EVEN clutch to body 3,
with the sensors of every example) followed by an ideal gear
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
Judder.Examples.Driveline5DOFGeared --set w_slip=...). That slope is
the model's mu_g, calculated from the curve (final): the clutch takes
mu_max and w_char, not mu_g.</p>
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
