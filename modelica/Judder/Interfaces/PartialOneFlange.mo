within Judder.Interfaces;
partial model PartialOneFlange "Component with one rotational flange"
  Flange_b flange "Flange"
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
  annotation (Documentation(info="<html>
<p>Base of a component with one flange on the right, as the torque
sources of Modelica.Mechanics.Rotational.Sources: the driving torque
sources and the speed-controlled motor. It adds no equation.</p>
</html>"));
end PartialOneFlange;
