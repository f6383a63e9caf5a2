within Judder.Sensors;
model SpeedSensor "Ideal sensor of the absolute angular velocity of a flange"
  extends Interfaces.PartialAbsoluteSensor;
  Interfaces.RealOutput w(unit="rad/s") "Absolute angular velocity of the flange"
    annotation (Placement(transformation(extent={{100,-10},{120,10}})));
equation
  w = der(flange.phi);
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
        Line(points={{70,0},{100,0}}, color={0,0,127}),
        Text(extent={{-150,120},{150,80}}, textString="%name", textColor={0,0,255}),
        Text(extent={{20,-30},{90,-70}}, textString="w")}),
    Documentation(info="<html>
<p>Measures the absolute angular velocity of the flange, as
Modelica.Mechanics.Rotational.Sensors.SpeedSensor:</p>
<pre>
  w = der(flange.phi)
  0 = flange.tau
</pre>
<p>In the examples it gives w_upstream (the body on the engine side of
the clutch, theta_4' in Eq. (5)) and w_downstream (the body on the
gearbox side, theta_3'), the two speeds the bench acquires.</p>
</html>"));
end SpeedSensor;
