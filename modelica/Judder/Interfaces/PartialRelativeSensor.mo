within Judder.Interfaces;
partial model PartialRelativeSensor "Sensor between two flanges (as MSL PartialRelativeSensor)"
  Flange_a flange_a "Left flange of the sensor"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Flange_b flange_b "Right flange of the sensor"
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
equation
  0 = flange_a.tau + flange_b.tau;
  annotation (Documentation(info="<html>
<p>Base of a sensor between two flanges, as
Modelica.Mechanics.Rotational.Interfaces.PartialRelativeSensor: the
sensor has no inertia, so the torques in its flanges balance,
<code>0 = flange_a.tau + flange_b.tau</code>. The sensor that extends it
adds one more flange equation and its output signal at the bottom.</p>
</html>"));
end PartialRelativeSensor;
