model WhenInitial "A when-clause on initial(), not compiled: refused from the source"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  when initial() then
    reinit(x, 2);
  end when;
end WhenInitial;
