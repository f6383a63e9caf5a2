within Judder.Interfaces;
connector Flange_a "Rotational flange (filled icon in the MSL)"
  Units.Angle phi "Absolute rotation angle of the flange";
  flow Units.Torque tau "Cut torque in the flange";
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={Ellipse(extent={{-100,100},{100,-100}}, lineColor={0,0,0},
        fillColor={95,95,95}, fillPattern=FillPattern.Solid)}),
    Documentation(info="<html>
<p>Flange of a 1D rotational shaft, as
Modelica.Mechanics.Rotational.Interfaces.Flange_a: the absolute rotation
angle <code>phi</code> (potential variable) and the cut torque
<code>tau</code> (flow variable, positive when it acts on the component
the flange belongs to). By convention flange_a is the left (driving) side
of a component and is drawn filled. Flange_a and Flange_b have the same
variables and may be connected to each other.</p>
</html>"));
end Flange_a;
