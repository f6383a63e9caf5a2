model SteadyStart "Initialised in steady state, der(x) = 0, beside a fixed state"
  parameter Real b = 4 "Source";
  parameter Real k = 0.5 "Rate";
  Real x(start = 100) "Started in steady state";
  Real w(start = 1, fixed = true) "Started at its start value";
initial equation
  der(x) = 0;
equation
  der(x) = b - k*x;
  der(w) = -w + 0*x;
  annotation(experiment(StopTime = 1, Interval = 0.01));
end SteadyStart;
