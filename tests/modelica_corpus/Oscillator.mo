model Oscillator "Mass on a spring; a parameter bound to others, constants, units"
  type Length = Real(final quantity = "Length", final unit = "m");
  type Velocity = Real(final quantity = "Velocity", final unit = "m/s");
  constant Real two = 2;
  parameter Real m(unit = "kg", min = 0) = 0.5 "Mass";
  parameter Real c(unit = "N/m", min = 0) = 8 "Stiffness";
  parameter Real omega(unit = "rad/s") = sqrt(c/m) "Natural angular frequency";
  parameter Length x0 = 0.1 "Initial position";
  Length x(start = x0, fixed = true) "Position";
  Velocity v(start = 0, fixed = true) "Velocity";
  output Real energy(unit = "J") "Stored energy";
equation
  der(x) = v;
  m*der(v) = -c*x;
  energy = (m*v^2 + c*x^2)/two;
  annotation(experiment(StopTime = 2, Interval = 0.01));
end Oscillator;
