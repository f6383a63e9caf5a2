model BooleanArray "An array of Booleans"
  Boolean on[2];
  Real x(start = 1, fixed = true);
equation
  on[1] = x > 0.5;
  on[2] = x > 0.25;
  der(x) = if on[1] then -x else 0;
end BooleanArray;
