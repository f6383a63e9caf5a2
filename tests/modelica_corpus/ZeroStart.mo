model ZeroStart "Every state starts at 0 (Co-Simulation at t = 0)"
  parameter Real a = 3 "Forcing";
  parameter Real T = 0.5 "Time constant";
  Real x(start = 0, fixed = true);
  Real v(start = 0, fixed = true);
equation
  der(x) = v;
  T*der(v) = a - v;
  annotation(experiment(StopTime = 2, Interval = 0.01));
end ZeroStart;
