model InitialEquation "State started by an initial equation (fixed = false)"
  parameter Real k = 2 "Rate";
  parameter Real x0 = 3 "Half the initial value";
  Real x(fixed = false);
initial equation
  x = 2*x0;
equation
  der(x) = -k*x;
  annotation(experiment(StopTime = 1, Interval = 0.01));
end InitialEquation;
