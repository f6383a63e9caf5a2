within Judder.Examples;
partial model PartialTestBench "Test bench of Fig. 5 and section 2.2 without the choice of the EVEN clutch: motor at w_motor, REV clutch slipping as the load"
  extends PartialDriveline4DOF(
    pressure(t_start=t_engage, t_ramp=t_ramp),
    inertia1(w(start=w_motor, fixed=true)),
    inertia2(w(start=w_motor, fixed=true)),
    inertia4(w(start=w_motor, fixed=true)),
    inertia3(w(start=w_gearbox, fixed=true)));
  extends Data.TestBenchData;
  parameter Units.Area S_load=load_share*N_c*S*p_m/(N_c_load*p_load)
    "Piston area of the REV clutch";
  Components.WetClutch rev(mu0=mu0, mu_g=0, N_c=N_c_load, R_m=R_m, S=S_load)
    "REV clutch, slipping against the housing as the load (flat friction curve)"
    annotation (Placement(transformation(extent={{170,-10},{190,10}})));
  Sources.SpeedDrive motor(w_ref=w_motor, d_control=d_control, tau_max=tau_max) "81 kW DC motor with speed control"
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Sources.DitherPressure revPressure(p_m=p_load, p_f=0, f=0, t_start=t_engage, t_ramp=t_ramp)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={180,40})));
equation
  connect(motor.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
  connect(inertia3.flange_b, rev.flange_a)
    annotation (Line(points={{150,0},{170,0}}));
  connect(rev.flange_b, housing.flange)
    annotation (Line(points={{190,0},{200,0},{200,-70},{0,-70},{0,-90}}));
  connect(revPressure.p, rev.p)
    annotation (Line(points={{184,29},{184,11}}, color={0,0,127}));
  connect(revPressure.p_mean, rev.p_mean)
    annotation (Line(points={{176,29},{176,11}}, color={0,0,127}));
  annotation (
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>The test bench of section 2.2 (Fig. 5b): the 4-DOF chain of
PartialDriveline4DOF driven by the motor under speed control at
w_motor, with the REV clutch slipping against the housing as the load of
body 3 and the EVEN clutch (<code>clutch</code>) engaging with the
pressure ramp from t_engage over t_ramp. The extending models choose the
EVEN clutch by <code>redeclare</code>: TestBenchEngagement (a bounded
friction curve, held at a steady slip: a held-slip bench run, which
never engages), TestBenchCurveLockUp (the same curve, an engagement
ending in lock-up), TestBenchFullEngagement (WetClutch, the straight
line of Eq. 5) and TestBenchLockUp (the straight line, ending in
lock-up). See TestBenchEngagement for the bench.</p>
</html>"));
end PartialTestBench;
