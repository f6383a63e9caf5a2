within Judder.Sensors;
model TorqueSensor "Ideal sensor of the torque transmitted between two flanges"
  extends Interfaces.PartialRelativeSensor;
  Interfaces.RealOutput tau(unit="N.m")
    "Torque in flange_a and flange_b (tau = flange_a.tau = -flange_b.tau)"
    annotation (Placement(transformation(origin={-80,-110}, extent={{10,-10},{-10,10}}, rotation=90)));
equation
  flange_a.phi = flange_b.phi;
  tau = flange_a.tau;
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
        Line(points={{-80,-100},{-80,0}}, color={0,0,127}),
        Text(extent={{-150,120},{150,80}}, textString="%name", textColor={0,0,255}),
        Text(extent={{10,-30},{90,-70}}, textString="tau")}),
    Documentation(info="<html>
<p>Measures the torque transmitted through it from flange_a to flange_b,
as Modelica.Mechanics.Rotational.Sensors.TorqueSensor. It is a rigid,
massless link: both flanges have the same angle, and the torque passes
unchanged,</p>
<pre>
  flange_a.phi = flange_b.phi
  flange_b.tau = -flange_a.tau
  tau = flange_a.tau
</pre>
<p>Inserted between the clutch's flange_b and the downstream body it
gives the friction torque T_c of Eq. (3), the torque the clutch
transmits to the gearbox side (tau_c of Interfaces.PartialWetClutch).</p>
</html>"));
end TorqueSensor;
