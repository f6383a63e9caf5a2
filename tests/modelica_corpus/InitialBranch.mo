model InitialBranch "An if-equation on initial(): y = 2 x while initialising, y = x after; y(0) = 4 fixes x(0)"
  Real x(fixed = false) "Relaxes to 1";
  Real y "2 x at the initialisation, x after";
initial equation
  y = 4;
equation
  der(x) = 1 - x;
  if initial() then
    y = 2*x;
  else
    y = x;
  end if;
end InitialBranch;
