model Decay "First-order decay, literal parameters only, no units"
  parameter Real k(min = 0) = 2 "Rate";
  Real x(start = 1, fixed = true);
equation
  der(x) = -k*x;
  annotation(experiment(StopTime = 2, Interval = 0.01));
end Decay;
