within Judder.Interfaces;
partial model PartialCompliantWithRelativeStates "Compliant connection with relative angle and speed"
  extends PartialCompliant;
  Units.AngularVelocity w_rel(start=0) "Relative speed (der(phi_rel))";
equation
  w_rel = der(phi_rel);
end PartialCompliantWithRelativeStates;
