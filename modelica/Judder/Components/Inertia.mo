within Judder.Components;
model Inertia "1D rotational component with inertia"
  extends Interfaces.PartialTwoFlanges;
  parameter Units.Inertia J(min=0, start=1) "Moment of inertia";
  Units.Angle phi(start=0) "Absolute rotation angle";
  Units.AngularVelocity w(start=0) "Absolute angular velocity";
  Units.AngularAcceleration a "Absolute angular acceleration";
equation
  phi = flange_a.phi;
  phi = flange_b.phi;
  w = der(phi);
  a = der(w);
  J*a = flange_a.tau + flange_b.tau;
end Inertia;
