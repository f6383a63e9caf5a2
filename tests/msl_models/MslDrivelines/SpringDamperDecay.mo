within MslDrivelines;
model SpringDamperDecay "An inertia on a spring-damper to the housing, released from a twist"
  import Modelica.Mechanics.Rotational;
  import Modelica.Units.SI;
  parameter SI.Inertia J=0.2 "Inertia";
  parameter SI.RotationalSpringConstant c=800 "Stiffness";
  parameter SI.RotationalDampingConstant d=1.5 "Damping";
  parameter SI.Angle phi0=0.1 "Initial twist";
  Rotational.Components.Fixed fixed;
  Rotational.Components.SpringDamper springDamper(c=c, d=d);
  Rotational.Components.Inertia inertia(J=J, phi(start=phi0, fixed=true), w(start=0, fixed=true));
equation
  connect(fixed.flange, springDamper.flange_a);
  connect(springDamper.flange_b, inertia.flange_a);
  annotation(experiment(StopTime=1, Interval=1e-3));
end SpringDamperDecay;
