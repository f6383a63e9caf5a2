within Judder.Interfaces;
partial model PartialAbsoluteSensor "Sensor of an absolute quantity of one flange (as MSL PartialAbsoluteSensor)"
  Flange_a flange "Flange of the shaft the sensor measures"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
equation
  0 = flange.tau;
  annotation (Documentation(info="<html>
<p>Base of a sensor of one flange, as
Modelica.Mechanics.Rotational.Interfaces.PartialAbsoluteSensor: the
sensor is ideal and applies no torque, <code>0 = flange.tau</code>, so
connecting it does not change the dynamics. The sensor that extends it
adds its output signal on the right.</p>
</html>"));
end PartialAbsoluteSensor;
