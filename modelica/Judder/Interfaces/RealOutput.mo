within Judder.Interfaces;
connector RealOutput = output Real "Real output signal"
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={Polygon(points={{-100,100},{100,0},{-100,-100},{-100,100}},
        lineColor={0,0,127}, fillColor={255,255,255}, fillPattern=FillPattern.Solid)}),
    Documentation(info="<html>
<p>Connector of a Real output signal, as Modelica.Blocks.Interfaces.RealOutput
(open triangle). The unit is given where it is declared, e.g.
<code>RealOutput w(unit=&quot;rad/s&quot;)</code> in the speed sensor.</p>
</html>"));
