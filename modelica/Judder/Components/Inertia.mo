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
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Rectangle(extent={{-100,10},{-50,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{50,10},{100,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{-50,50},{50,-50}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}, radius=10),
        Text(extent={{-150,100},{150,60}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-60},{150,-90}}, textString="J=%J")}),
    Documentation(info="<html>
<p>Rigid rotating body with moment of inertia J, as
Modelica.Mechanics.Rotational.Components.Inertia: both flanges have the
angle phi of the body, and</p>
<pre>
  w = der(phi),  a = der(w)
  J a = flange_a.tau + flange_b.tau
</pre>
<p>This is one row of M theta'' = ... in Eq. (1): bodies 1, 2, 4 and 3
of Fig. 13 (J1, J2, J4, J3), or 1, 2-4 and 3 of Fig. 12. phi and w are
the states of the drivelines.</p>
</html>"));
end Inertia;
