within Judder.Icons;
model Clutch "Icon of a wet clutch: two shafts, two plates and the actuation pressure"
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Rectangle(extent={{-100,10},{-30,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{30,10},{100,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{-30,60},{-10,-60}}, lineColor={0,0,0},
          fillPattern=FillPattern.Solid, fillColor={192,192,192}),
        Rectangle(extent={{10,60},{30,-60}}, lineColor={0,0,0},
          fillPattern=FillPattern.Solid, fillColor={192,192,192}),
        Line(points={{40,90},{40,70},{20,70},{20,60}}, color={0,0,127})}),
    Documentation(info="<html>
<p>The icon of every pressure-actuated wet clutch of the library
(Interfaces.PartialPressureClutch and the components that extend it):
the engine-side shaft (flange_a) and the gearbox-side shaft (flange_b),
the two plates of the pack of Eq. (3), the actuation pressure p
entering from above on the right, as
Modelica.Mechanics.Rotational.Icons.Clutch. A component draws on top of
it what tells it apart (the mean-pressure input on the left, the shape
of its friction law) and its name.</p>
</html>"));
end Clutch;
