within BenchLib;
model Driveline6DOF "6-DOF driveline, 12 states: the 4-DOF chain, the REV clutch slipping with dither, a gear, two output shafts"
  import Judder.Components;
  import Judder.Sources;
  import Judder.Units;
  parameter Units.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter Units.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter Units.Inertia J4=0.122 "Inertia between clutch damper and clutch discs";
  parameter Units.Inertia J5=2.0 "Inertia of the differential";
  parameter Units.Inertia J6=12.0 "Inertia of the wheels and vehicle";
  parameter Units.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter Units.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter Units.RotationalSpringConstant k35=20000 "Stiffness of the propeller shaft (behind the gear)";
  parameter Units.RotationalSpringConstant k56=8000 "Stiffness of the drive shafts";
  parameter Units.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter Units.RotationalDampingConstant c35=0.5 "Damping of the propeller shaft";
  parameter Units.RotationalDampingConstant c56=0.5 "Damping of the drive shafts";
  parameter Units.RotationalDampingConstant c_ext=0.1 "External damping of every body";
  parameter Real ratio(min=1e-3)=3.5 "Gear ratio";
  parameter Units.FrictionCoefficient mu0=0.09 "Friction coefficient at zero slip";
  parameter Units.FrictionGradient mu_g=0.017 "Friction gradient of the EVEN clutch";
  parameter Units.FrictionGradient mu_g_rev=0.017 "Friction gradient of the REV clutch";
  parameter Real dither_share_rev(min=0)=0.5 "Dither amplitude of the REV clutch as a share of p_f";
  parameter Units.Pressure p_m=1e6 "Mean actuation pressure of the EVEN clutch";
  parameter Units.Pressure p_m_rev=2e5 "Mean actuation pressure of the REV clutch";
  parameter Units.Pressure p_f=0.3e5 "Dither amplitude";
  parameter Units.Frequency f_dither=100 "Dither frequency";
  parameter Units.AngularVelocity w_in=104.71975511965977 "Start speed of bodies 1, 2 and 4";
  parameter Units.AngularVelocity w_out=52.35987755982988 "Start speed of body 3";
  Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_in, fixed=true));
  Components.Inertia inertia2(J=J2, phi(start=0, fixed=true), w(start=w_in, fixed=true));
  Components.Inertia inertia4(J=J4, phi(start=0, fixed=true), w(start=w_in, fixed=true));
  Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_out, fixed=true));
  Components.Inertia inertia5(J=J5, phi(start=0, fixed=true), w(start=w_out/ratio, fixed=true));
  Components.Inertia inertia6(J=J6, phi(start=0, fixed=true), w(start=w_out/ratio, fixed=true));
  Components.SpringDamper damper12(c=k12, d=c12);
  Components.SpringDamper shaft24(c=k24, d=c24);
  Components.SlippingClutch clutch(mu0=mu0, mu_g=mu_g) "EVEN clutch";
  Components.SlippingClutch clutchRev(mu0=mu0, mu_g=mu_g_rev) "REV clutch against the housing";
  Components.IdealGear gear(ratio=ratio);
  Components.SpringDamper shaft35(c=k35, d=c35);
  Components.SpringDamper shaft56(c=k56, d=c56);
  Components.Damper external1(d=c_ext);
  Components.Damper external2(d=c_ext);
  Components.Damper external3(d=c_ext);
  Components.Damper external4(d=c_ext);
  Components.Damper external5(d=c_ext);
  Components.Damper external6(d=c_ext);
  Components.Fixed housing;
  Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither);
  Sources.DitherPressure pressureRev(p_m=p_m_rev, p_f=dither_share_rev*p_f, f=f_dither);
equation
  connect(inertia1.flange_b, damper12.flange_a);
  connect(damper12.flange_b, inertia2.flange_a);
  connect(inertia2.flange_b, shaft24.flange_a);
  connect(shaft24.flange_b, inertia4.flange_a);
  connect(inertia4.flange_b, clutch.flange_a);
  connect(clutch.flange_b, inertia3.flange_a);
  connect(inertia3.flange_b, gear.flange_a);
  connect(gear.flange_b, shaft35.flange_a);
  connect(shaft35.flange_b, inertia5.flange_a);
  connect(inertia5.flange_b, shaft56.flange_a);
  connect(shaft56.flange_b, inertia6.flange_a);
  connect(inertia3.flange_a, clutchRev.flange_a);
  connect(clutchRev.flange_b, housing.flange);
  connect(external1.flange_a, inertia1.flange_a);
  connect(external2.flange_a, inertia2.flange_a);
  connect(external3.flange_a, inertia3.flange_a);
  connect(external4.flange_a, inertia4.flange_a);
  connect(external5.flange_a, inertia5.flange_a);
  connect(external6.flange_a, inertia6.flange_a);
  connect(external1.flange_b, housing.flange);
  connect(external2.flange_b, housing.flange);
  connect(external3.flange_b, housing.flange);
  connect(external4.flange_b, housing.flange);
  connect(external5.flange_b, housing.flange);
  connect(external6.flange_b, housing.flange);
  connect(pressure.p, clutch.p);
  connect(pressure.p_mean, clutch.p_mean);
  connect(pressureRev.p, clutchRev.p);
  connect(pressureRev.p_mean, clutchRev.p_mean);
  annotation (
    experiment(StopTime=1, Interval=1e-4),
    Documentation(info="<html>
<p>Benchmark driveline of 12 states: bodies 1, 2, 4 and the EVEN clutch
of Fig. 13 to body 3, the REV clutch slipping between body 3 and the
housing (both clutches dithered: a rank-2 modulation), an ideal gear and
two shafts to a differential J5 and the vehicle J6. Both clutches have
the linear law of Eq. (5), so the linearisation does not depend on the
state; the start values are not a steady slip (no engine torque).</p>
</html>"));
end Driveline6DOF;
