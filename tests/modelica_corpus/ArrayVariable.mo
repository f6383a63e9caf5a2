model ArrayVariable "An array of variables (arrays of parameters are compiled)"
  parameter Real k[2] = {1, 2} "Rates";
  Real x[2](each start = 1, each fixed = true);
equation
  der(x) = -k .* x;
end ArrayVariable;
