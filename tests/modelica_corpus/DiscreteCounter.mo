model DiscreteCounter "An Integer variable"
  Integer n;
  Real x(start = 1, fixed = true);
equation
  n = 1;
  der(x) = -n*x;
end DiscreteCounter;
