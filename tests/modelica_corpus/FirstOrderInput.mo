model FirstOrderInput "First-order lag driven by an input"
  parameter Real T(min = 1e-6) = 0.2 "Time constant";
  parameter Real K = 2 "Gain";
  input Real u(start = 1) "Input";
  output Real y "Output";
  Real x(start = 0, fixed = true);
equation
  T*der(x) = u - x;
  y = K*x;
  annotation(experiment(StopTime = 2, Interval = 0.01));
end FirstOrderInput;
