model Overdetermined "An initial equation for a state whose start is fixed"
  Real x(start = 1, fixed = true);
initial equation
  x = 2;
equation
  der(x) = -x;
end Overdetermined;
