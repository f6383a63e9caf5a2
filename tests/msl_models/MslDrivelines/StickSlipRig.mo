within MslDrivelines;
model StickSlipRig "Two inertias joined by FrictionModeClutch (MSL's PartialFriction): slips, locks, then breaks away under a rising torque"
  import Modelica.Mechanics.Rotational;
  import Modelica.Units.SI;
  parameter SI.Inertia J1=1 "Driven inertia";
  parameter SI.Inertia J2=2 "Load inertia";
  parameter SI.RotationalDampingConstant d2=2 "Damping of the load to the housing";
  parameter SI.Torque T0=0 "Drive torque at t = 0";
  parameter Real T_rate(unit="N.m/s")=30 "Rise of the drive torque";
  parameter SI.AngularVelocity w_start=20 "Initial speed of the driven inertia (the load starts at rest)";
  parameter SI.Force fn_max=100 "Normal force of the clutch";
  parameter Real mu_pos[4, 2]=[0, 0.5; 10, 0.3; 20, 0.3; 30, 0.3]
    "Friction coefficient against the slip speed (rad/s)";
  parameter Real peak=1.2 "Static over sliding friction at zero slip";
  Rotational.Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_start, fixed=true));
  Rotational.Components.Inertia inertia2(J=J2, phi(start=0, fixed=true), w(start=0, fixed=true));
  FrictionModeClutch clutch(mu_pos=mu_pos, peak=peak, cgeo=1, fn_max=fn_max)
    "flange_b on the driven inertia: w_rel = inertia1.w - inertia2.w > 0 is forward sliding";
  Rotational.Components.Damper damper(d=d2);
  Rotational.Components.Fixed housing;
  Rotational.Sources.Torque drive;
  Modelica.Blocks.Sources.Constant engaged(k=1) "Normalised normal force";
equation
  drive.tau = T0 + T_rate*time;
  connect(drive.flange, inertia1.flange_a);
  connect(inertia1.flange_b, clutch.flange_b);
  connect(clutch.flange_a, inertia2.flange_a);
  connect(inertia2.flange_b, damper.flange_a);
  connect(damper.flange_b, housing.flange);
  connect(engaged.y, clutch.f_normalized);
  annotation(experiment(StopTime=3, Interval=1e-3));
end StickSlipRig;
