model TableClutchRig "A flywheel braked by Judder.Components.TableClutch against the housing"
  parameter Judder.Units.Inertia J = 0.5 "Inertia of the flywheel";
  parameter Judder.Units.Pressure p0 = 2e5 "Actuation pressure";
  Judder.Components.Inertia inertia(J = J, phi(start = 0, fixed = true),
    w(start = 250, fixed = true));
  Judder.Components.TableClutch clutch(
    mu_pos = {{0, 0.12}, {50, 0.10}, {150, 0.08}, {200, 0.07}});
  Judder.Components.Fixed fixed;
  output Judder.Units.AngularVelocity w = inertia.w "Flywheel speed";
  output Judder.Units.Torque clutch_torque = clutch.tau_c "Friction torque";
equation
  connect(inertia.flange_b, clutch.flange_a);
  connect(clutch.flange_b, fixed.flange);
  clutch.p = p0;
  annotation(experiment(StopTime = 1, Interval = 0.001));
end TableClutchRig;
