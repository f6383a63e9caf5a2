within Judder.Interfaces;
partial model PartialCompliantWithRelativeStates "Compliant connection with relative angle and speed"
  extends PartialCompliant;
  Units.AngularVelocity w_rel(start=0) "Relative speed (der(phi_rel))";
equation
  w_rel = der(phi_rel);
  annotation (Documentation(info="<html>
<p>Compliant connection that also defines the relative speed,
<code>w_rel = der(phi_rel)</code>, as
Modelica.Mechanics.Rotational.Interfaces.PartialCompliantWithRelativeStates.
phi_rel and w_rel are not independent of the absolute angles of the
bodies: a compiler with index reduction keeps the bodies' angles and
speeds as states.</p>
</html>"));
end PartialCompliantWithRelativeStates;
