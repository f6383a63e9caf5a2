model TableMatrix "A table in matrix syntax, interpolated by a sum over its rows"
  parameter Real table[:, 2] = [0, 0.1; 1, 0.2; 2, 0.15] "Points (u, y)";
  Real x(start = 0.5, fixed = true);
  output Real y "Table value at x (0 outside)";
equation
  y = sum(noEvent(if x >= table[i, 1] and x < table[i + 1, 1]
    then table[i, 2] + (table[i + 1, 2] - table[i, 2])*(x - table[i, 1])
      /(table[i + 1, 1] - table[i, 1]) else 0) for i in 1:size(table, 1) - 1);
  der(x) = 1 - y;
  annotation(experiment(StopTime = 3, Interval = 0.01));
end TableMatrix;
