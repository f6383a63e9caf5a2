within Judder;
package Units "Unit types of the library (SI, as Modelica.Units.SI)"
  type Angle = Real(final quantity="Angle", final unit="rad", displayUnit="deg");
  type AngularVelocity = Real(final quantity="AngularVelocity", final unit="rad/s", displayUnit="rpm");
  type AngularAcceleration = Real(final quantity="AngularAcceleration", final unit="rad/s2");
  type Torque = Real(final quantity="Torque", final unit="N.m");
  type Inertia = Real(final quantity="MomentOfInertia", final unit="kg.m2", min=0);
  type RotationalSpringConstant = Real(final quantity="RotationalSpringConstant", final unit="N.m/rad", min=0);
  type RotationalDampingConstant = Real(final quantity="RotationalDampingConstant", final unit="N.m.s/rad", min=0);
  type Pressure = Real(final quantity="Pressure", final unit="Pa", displayUnit="bar");
  type Frequency = Real(final quantity="Frequency", final unit="Hz");
  type Time = Real(final quantity="Time", final unit="s");
  type Length = Real(final quantity="Length", final unit="m");
  type Area = Real(final quantity="Area", final unit="m2");
  type FrictionCoefficient = Real(final quantity="FrictionCoefficient", final unit="1");
  type FrictionGradient = Real(final quantity="FrictionGradient", final unit="s/rad")
    "Change of the friction coefficient per unit slip speed";
  type Fraction = Real(final quantity="Fraction", final unit="1", min=0, max=1);
  annotation (Documentation(info="<html>
<p>Real types with quantity and unit, named and defined as in
Modelica.Units.SI, so that every variable and every value in the models
carries its SI unit (rad, rad/s, N.m, kg.m2, Pa, Hz, s, m).
Pressures are displayed in bar, angles in degrees and angular velocities
in rpm.</p>
<p>Two types are specific to the friction law of Eq. (5),
mu = mu0 + mu_g (w4 - w3): <code>FrictionCoefficient</code> (mu0, unit 1)
and <code>FrictionGradient</code> (mu_g, unit s/rad).</p>
</html>"));
end Units;
