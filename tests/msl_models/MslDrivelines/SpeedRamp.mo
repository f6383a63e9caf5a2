within MslDrivelines;
model SpeedRamp "A speed source following a ramp drives an inertia through a damper"
  import Modelica.Mechanics.Rotational;
  import Modelica.Units.SI;
  parameter SI.AngularVelocity w_end=100 "Speed at the end of the ramp";
  parameter SI.Time duration=0.5 "Duration of the ramp";
  parameter SI.Inertia J=0.3 "Driven inertia";
  parameter SI.RotationalDampingConstant d=2 "Damping between drive and inertia";
  Modelica.Blocks.Sources.Ramp ramp(height=w_end, duration=duration);
  Rotational.Sources.Speed speed(exact=true);
  Rotational.Components.Inertia drive(J=1);
  Rotational.Components.Damper damper(d=d);
  Rotational.Components.Inertia inertia(J=J, w(start=0, fixed=true));
  Rotational.Sources.ConstantTorque load(tau_constant=0);
equation
  connect(ramp.y, speed.w_ref);
  connect(speed.flange, drive.flange_a);
  connect(drive.flange_b, damper.flange_a);
  connect(damper.flange_b, inertia.flange_a);
  connect(inertia.flange_b, load.flange);
  annotation(experiment(StopTime=1, Interval=1e-3));
end SpeedRamp;
