within Judder.Interfaces;
connector Flange_b "Rotational flange (open icon in the MSL)"
  Units.Angle phi "Absolute rotation angle of the flange";
  flow Units.Torque tau "Cut torque in the flange";
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={Ellipse(extent={{-98,100},{102,-100}}, lineColor={0,0,0},
        fillColor={255,255,255}, fillPattern=FillPattern.Solid)}),
    Documentation(info="<html>
<p>Flange of a 1D rotational shaft, as
Modelica.Mechanics.Rotational.Interfaces.Flange_b: the absolute rotation
angle <code>phi</code> (potential variable) and the cut torque
<code>tau</code> (flow variable, positive when it acts on the component
the flange belongs to). By convention flange_b is the right (driven) side
of a component and is drawn open. Flange_a and Flange_b have the same
variables and may be connected to each other.</p>
</html>"));
end Flange_b;
