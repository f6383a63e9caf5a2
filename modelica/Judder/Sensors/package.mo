within Judder;
package Sensors "Ideal sensors of speed, relative speed and torque"
  annotation (Documentation(info="<html>
<p>Ideal sensors with the names and equations of
Modelica.Mechanics.Rotational.Sensors. They apply no torque to the
bodies they measure (the torque sensor passes its torque through
unchanged) and so leave the dynamics as they are. The examples take
their outputs from them: the speeds on each side of the clutch (the two
quantities the bench of section 2.2 acquires), the slip and the clutch
torque.</p>
</html>"));
end Sensors;
