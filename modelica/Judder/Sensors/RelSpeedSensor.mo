within Judder.Sensors;
model RelSpeedSensor "Ideal sensor of the relative angular velocity between two flanges"
  extends Interfaces.PartialRelativeSensor;
  Units.Angle phi_rel(start=0) "Relative angle between the flanges (flange_b.phi - flange_a.phi)";
  Interfaces.RealOutput w_rel(unit="rad/s")
    "Relative angular velocity between the flanges (der(flange_b.phi - flange_a.phi))"
    annotation (Placement(transformation(origin={0,-110}, extent={{10,-10},{-10,10}}, rotation=90)));
equation
  phi_rel = flange_b.phi - flange_a.phi;
  w_rel = der(phi_rel);
  0 = flange_a.tau;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Ellipse(extent={{-70,70},{70,-70}}, lineColor={0,0,0},
          fillColor={255,255,255}, fillPattern=FillPattern.Solid),
        Line(points={{0,70},{0,40}}),
        Line(points={{22.9,32.8},{40.2,57.3}}),
        Line(points={{-22.9,32.8},{-40.2,57.3}}),
        Line(points={{37.6,13.7},{65.8,23.9}}),
        Line(points={{-37.6,13.7},{-65.8,23.9}}),
        Polygon(points={{-5,0},{-2,60},{0,65},{2,60},{5,0},{-5,0}}, lineColor={64,64,64},
          fillColor={64,64,64}, fillPattern=FillPattern.Solid),
        Ellipse(extent={{-12,12},{12,-12}}, lineColor={64,64,64},
          fillColor={255,255,255}, fillPattern=FillPattern.Solid),
        Line(points={{-90,0},{-70,0}}),
        Line(points={{70,0},{90,0}}),
        Line(points={{0,-70},{0,-100}}, color={0,0,127}),
        Text(extent={{-150,120},{150,80}}, textString="%name", textColor={0,0,255}),
        Text(extent={{10,-30},{90,-70}}, textString="w_rel")}),
    Documentation(info="<html>
<p>Measures the relative angular velocity of flange_b with respect to
flange_a, as Modelica.Mechanics.Rotational.Sensors.RelSpeedSensor:</p>
<pre>
  phi_rel = flange_b.phi - flange_a.phi
  w_rel   = der(phi_rel)
  0 = flange_a.tau,  0 = flange_b.tau
</pre>
<p>Connected across a clutch (flange_a to the clutch's flange_a,
flange_b to its flange_b) it gives w_rel = -slip: the slip of
Eq. (5), theta_4' - theta_3', is -w_rel.</p>
</html>"));
end RelSpeedSensor;
