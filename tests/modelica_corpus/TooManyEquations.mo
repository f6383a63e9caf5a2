model TooManyEquations "One equation too many: y is given twice"
  Real x(start=1, fixed=true);
  Real y;
  parameter Real k = 2;
equation
  der(x) = -k*x;
  y = 2*x;
  y = x + 1;
end TooManyEquations;
