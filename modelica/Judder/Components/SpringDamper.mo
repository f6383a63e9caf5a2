within Judder.Components;
model SpringDamper "Linear torsional spring and damper in parallel"
  extends Interfaces.PartialCompliantWithRelativeStates;
  parameter Units.RotationalSpringConstant c(min=0, start=1e5) "Spring constant";
  parameter Units.RotationalDampingConstant d(min=0, start=0) "Damping constant";
equation
  tau = c*phi_rel + d*w_rel;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-80,32},{-58,32},{-48,62},{-28,2},{-8,62},{12,2},{32,62},{42,32},{80,32}}),
        Line(points={{-80,32},{-80,-40}}),
        Line(points={{80,32},{80,-40}}),
        Line(points={{-90,0},{-80,0}}),
        Line(points={{80,0},{90,0}}),
        Line(points={{-80,-40},{-60,-40}}),
        Rectangle(extent={{-60,-20},{30,-60}}, lineColor={0,0,0},
          fillColor={192,192,192}, fillPattern=FillPattern.Solid),
        Line(points={{-60,-20},{60,-20}}),
        Line(points={{-60,-60},{60,-60}}),
        Line(points={{30,-40},{80,-40}}),
        Text(extent={{-150,110},{150,70}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-70},{150,-100}}, textString="c=%c, d=%d")}),
    Documentation(info="<html>
<p>Massless torsional spring and damper in parallel between two bodies,
as Modelica.Mechanics.Rotational.Components.SpringDamper:</p>
<pre>
  tau = c phi_rel + d w_rel
</pre>
<p>with phi_rel = flange_b.phi - flange_a.phi and w_rel = der(phi_rel).
In the drivelines it is the clutch damper (k12, c12 of Fig. 13, k, c of
Fig. 12) and the shaft and gear mesh to the clutch pack (k24, c24),
the K and relative C terms of Eq. (2).</p>
</html>"));
end SpringDamper;
