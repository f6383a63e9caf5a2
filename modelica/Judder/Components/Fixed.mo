within Judder.Components;
model Fixed "Flange fixed in the housing at a given angle"
  parameter Units.Angle phi0=0 "Fixed angle of the housing";
  Interfaces.Flange_b flange "Flange fixed in the housing"
    annotation (Placement(transformation(extent={{10,-10},{-10,10}}, rotation=180)));
equation
  flange.phi = phi0;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Text(extent={{-150,-90},{150,-130}}, textString="%name", textColor={0,0,255}),
        Line(points={{-80,-40},{80,-40}}),
        Line(points={{80,-40},{40,-80}}),
        Line(points={{40,-40},{0,-80}}),
        Line(points={{0,-40},{-40,-80}}),
        Line(points={{-40,-40},{-80,-80}}),
        Line(points={{0,-40},{0,-10}})}),
    Documentation(info="<html>
<p>The transmission housing, as
Modelica.Mechanics.Rotational.Components.Fixed: the flange does not
rotate, <code>flange.phi = phi0</code>, and takes whatever reaction
torque it is given. The external dampers c_i of the drivelines and, on
the bench, the REV clutch used as the load act against it.</p>
</html>"));
end Fixed;
