within Judder.Interfaces;
partial model PartialCompliant "Compliant connection of two flanges (as MSL PartialCompliant)"
  extends PartialTwoFlanges;
  Units.Angle phi_rel(start=0) "Relative rotation angle (flange_b.phi - flange_a.phi)";
  Units.Torque tau "Torque between the flanges (flange_b.tau)";
equation
  phi_rel = flange_b.phi - flange_a.phi;
  flange_b.tau = tau;
  flange_a.tau = -tau;
  annotation (Documentation(info="<html>
<p>Massless connection of two flanges, as
Modelica.Mechanics.Rotational.Interfaces.PartialCompliant:</p>
<pre>
  phi_rel = flange_b.phi - flange_a.phi
  flange_b.tau = tau
  flange_a.tau = -tau
</pre>
<p>The component that extends it gives tau as a function of the relative
motion (spring, damper, clutch).</p>
</html>"));
end PartialCompliant;
