within Judder;
package Units "Unit types of the library (SI, as Modelica.Units.SI)"
  type Angle = Real(final quantity="Angle", final unit="rad", displayUnit="deg");
  type AngularVelocity = Real(final quantity="AngularVelocity", final unit="rad/s");
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
end Units;
