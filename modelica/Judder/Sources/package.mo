within Judder;
package Sources "Pressure and torque sources, speed-controlled drive"
  annotation (Documentation(info="<html>
<p>What drives the drivelines: the actuation pressure of the clutch with
dither, Eq. (4) (<code>DitherPressure</code>), the engine and resistant
torques T_e and T_r of Eq. (1) (<code>ConstantTorque</code>), and the
speed-controlled DC motor of the test bench, section 2.2
(<code>SpeedDrive</code>).</p>
</html>"));
end Sources;
