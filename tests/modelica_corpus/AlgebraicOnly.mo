model AlgebraicOnly "No state: outputs are formulas in time"
  parameter Real A = 2 "Amplitude";
  parameter Real f = 1.5 "Frequency in Hz";
  output Real y "A sin(2 pi f t)";
  output Real z "y squared";
equation
  y = A*sin(2*3.141592653589793*f*time);
  z = y*y;
  annotation(experiment(StopTime = 1, Interval = 0.01));
end AlgebraicOnly;
