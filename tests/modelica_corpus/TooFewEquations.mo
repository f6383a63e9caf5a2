model TooFewEquations "One equation missing: y and z share one"
  Real x(start=1, fixed=true);
  Real y;
  Real z;
  parameter Real k = 2;
equation
  der(x) = -k*x;
  y + z = x;
end TooFewEquations;
