within Judder.Interfaces;
partial model PartialCompliant "Compliant connection of two flanges (as MSL PartialCompliant)"
  extends PartialTwoFlanges;
  Units.Angle phi_rel(start=0) "Relative rotation angle (flange_b.phi - flange_a.phi)";
  Units.Torque tau "Torque between the flanges (flange_b.tau)";
equation
  phi_rel = flange_b.phi - flange_a.phi;
  flange_b.tau = tau;
  flange_a.tau = -tau;
end PartialCompliant;
