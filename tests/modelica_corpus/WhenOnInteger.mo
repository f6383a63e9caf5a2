model WhenOnInteger "A when-condition on an Integer defined by an equation"
  Real x(start = 0, fixed = true);
  Integer n;
equation
  der(x) = 1;
  n = if x > 1 then 2 else 0;
  when n == 2 then
    reinit(x, 0);
  end when;
end WhenOnInteger;
