within Judder.Examples;
model Driveline4DOFTwoClutches "4-DOF driveline of Fig. 13 with the REV clutch as a second slipping clutch (the load of the bench), both with dither"
  extends PartialDriveline4DOF(
    clutch(mu_g=mu_g),
    inertia1(w(start=w_in, fixed=true)),
    inertia2(phi(start=-T_e/k12, fixed=true), w(start=w_in, fixed=true)),
    inertia4(phi(start=-T_e/k12 - T_e/k24, fixed=true), w(start=w_in, fixed=true)),
    inertia3(w(start=w_out, fixed=true)));
  parameter Units.AngularVelocity w_in=104.71975511965977 "Initial speed of bodies 1, 2 and 4 (1000 rpm)";
  parameter Units.AngularVelocity w_out=52.35987755982988 "Speed of body 3, the slip of the REV clutch against the housing (500 rpm)";
  parameter Units.FrictionGradient mu_g_rev=0.017 "Friction gradient of the REV clutch";
  parameter Real dither_share_rev(min=0)=0.5 "Dither amplitude of the REV clutch as a share of p_f (same valve frequency)";
  parameter Units.Torque T_e=mu0*N_c*R_m*S*p_m "Engine torque on body 1 (default: the mean clutch torque)";
  parameter Units.Pressure p_m_rev=(mu0*N_c*R_m*S*p_m - c3*w_out)/(mu0*N_c*R_m*S)
    "Mean pressure of the REV clutch that holds body 3 at w_out (steady slip)";
  Sources.ConstantTorque engine(tau_constant=T_e)
    annotation (Placement(transformation(extent={{-190,-10},{-170,10}})));
  Components.SlippingClutch clutchRev(mu0=mu0, mu_g=mu_g_rev, N_c=N_c, R_m=R_m, S=S,
    mean_pressure_damping=mean_pressure_damping) "REV clutch, slipping against the housing"
    annotation (Placement(transformation(extent={{170,-10},{190,10}})));
  Sources.DitherPressure pressureRev(p_m=p_m_rev, p_f=dither_share_rev*p_f, f=f_dither)
    annotation (Placement(transformation(extent={{-10,-10},{10,10}}, rotation=270, origin={180,40})));
equation
  connect(engine.flange, inertia1.flange_a)
    annotation (Line(points={{-170,0},{-150,0}}));
  connect(inertia3.flange_b, clutchRev.flange_a)
    annotation (Line(points={{150,0},{170,0}}));
  connect(clutchRev.flange_b, housing.flange)
    annotation (Line(points={{190,0},{196,0},{196,-70},{0,-70},{0,-90}}));
  connect(pressureRev.p, clutchRev.p)
    annotation (Line(points={{184,29},{184,11}}, color={0,0,127}));
  connect(pressureRev.p_mean, clutchRev.p_mean)
    annotation (Line(points={{176,29},{176,11}}, color={0,0,127}));
  annotation (
    experiment(StopTime=2, Interval=1e-4),
    Diagram(coordinateSystem(preserveAspectRatio=true, extent={{-200,-100},{200,100}})),
    Documentation(info="<html>
<p>The 4-DOF driveline of Fig. 13 (Driveline4DOF, on the same
PartialDriveline4DOF) with the REV clutch,
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
