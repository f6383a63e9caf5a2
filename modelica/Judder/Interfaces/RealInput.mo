within Judder.Interfaces;
connector RealInput = input Real "Real input signal"
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={Polygon(points={{-100,100},{100,0},{-100,-100},{-100,100}},
        lineColor={0,0,127}, fillColor={0,0,127}, fillPattern=FillPattern.Solid)}),
    Documentation(info="<html>
<p>Connector of a Real input signal, as Modelica.Blocks.Interfaces.RealInput
(filled triangle). The unit is given where it is declared, e.g.
<code>RealInput p(unit=&quot;Pa&quot;)</code> for the actuation pressure of the
clutch.</p>
</html>"));
