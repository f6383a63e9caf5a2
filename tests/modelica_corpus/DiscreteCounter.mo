model DiscreteCounter "An Integer counted in a when-clause"
  Integer n(start = 0, fixed = true);
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  when x < 0.5 then
    n = pre(n) + 1;
  end when;
end DiscreteCounter;
