within Judder.Components;
model IdealGear "Ideal gear without inertia (flange_a.phi = ratio*flange_b.phi)"
  extends Interfaces.PartialTwoFlanges;
  parameter Real ratio(start=1) "Transmission ratio (flange_a.phi/flange_b.phi)";
equation
  flange_a.phi = ratio*flange_b.phi;
  0 = ratio*flange_a.tau + flange_b.tau;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Rectangle(extent={{-100,10},{-40,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{-40,60},{-20,-20}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{20,20},{40,-60}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{40,10},{100,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Line(points={{-20,20},{20,20}}),
        Text(extent={{-150,110},{150,70}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-70},{150,-100}}, textString="ratio=%ratio")}),
    Documentation(info="<html>
<p>Ideal gear without inertia, elasticity, backlash or losses, as
Modelica.Mechanics.Rotational.Components.IdealGear (without the support
flange, which is the housing here):</p>
<pre>
  flange_a.phi = ratio flange_b.phi
  0 = ratio flange_a.tau + flange_b.tau
</pre>
<p>A ratio above 1 reduces the speed and multiplies the torque from
flange_a to flange_b. Connected between an inertia and a spring it adds
no state (Examples.Driveline5DOFGeared); between two inertias it joins
them into one body, and the compiler's index reduction keeps one
angle.</p>
</html>"));
end IdealGear;
