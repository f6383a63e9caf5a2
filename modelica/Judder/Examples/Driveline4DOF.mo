within Judder.Examples;
model Driveline4DOF "4-DOF driveline of Fig. 13, Eq. (1)-(5): steady slipping with dither (Appendix A values)"
  extends PartialDriveline4DOF(
    clutch(mu_g=mu_g),
    inertia1(w(start=w_in, fixed=true)),
    inertia2(phi(start=-T_e/k12, fixed=true), w(start=w_in, fixed=true)),
    inertia4(phi(start=-T_e/k12 - T_e/k24, fixed=true), w(start=w_in, fixed=true)),
    inertia3(w(start=w_out, fixed=true)));
  parameter Units.AngularVelocity w_in=104.71975511965977 "Initial speed of bodies 1, 2 and 4 (1000 rpm)";
  parameter Units.AngularVelocity w_out=0 "Initial speed of body 3";
  parameter Units.Torque T_e=mu0*N_c*R_m*S*p_m "Engine torque on body 1 (default: the mean clutch torque)";
  parameter Units.Torque T_r=mu0*N_c*R_m*S*p_m "Resistant torque on body 3";
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Sources.ConstantTorque load(tau_constant=-T_r)
    annotation (Placement(transformation(extent={{190,-10},{170,10}})));
equation
  connect(engine.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
  connect(inertia3.flange_b, load.flange)
    annotation (Line(points={{150,0},{170,0}}));
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>The minimal 4-DOF model of the transmission, Fig. 13 and Eq. (1)-(5)
of the paper, with the values of its Appendix (the chain of
PartialDriveline4DOF with its default clutch): engine-side body 1 (J1),
clutch damper 2 (J2) behind the damper k12, c12, body 4 (J4) between
the damper and the EVEN clutch pack behind the stiffness k24, c24, and
the gearbox side 3 (J3); each body has an external damper c_i to the
housing. The engine torque T_e drives body 1, the resistant torque T_r
brakes body 3, and the EVEN clutch (SlippingClutch) transmits</p>
<pre>
  T_c = N_c R_m S (mu0 p + mu_g (w4 - w3) (p - (1 - mean_pressure_damping) p_m))
  p(t) = p_m + p_f cos(2 pi f_dither t)                          (Eq. 4)
</pre>
<p>Bodies 1, 2 and 4 start at 1000 rpm with the springs twisted to
carry T_e, body 3 at rest. T_e = T_r = mu0 N_c R_m S p_m by default, the
clutch torque without dither, so that the slip stays nearly steady.
Dither at f_dither and p_f inside an Arnold tongue of Fig. 14 (e.g.
102.9 Hz, 0.3 bar) makes the oscillation grow; outside it decays.</p>
<p>Outputs, from the sensors: w_upstream and w_downstream, the speeds of
bodies 4 and 3 (speed sensors), slip = w4 - w3 (relative speed sensor
across the clutch, whose w_rel is w3 - w4), clutch_torque = T_c (torque
sensor between the clutch and body 3) and actuation_pressure = p.</p>
</html>"));
end Driveline4DOF;
