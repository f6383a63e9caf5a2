model NonlinearLoop "An algebraic loop nonlinear in its unknown"
  Real x(start = 1, fixed = true);
  Real z;
equation
  z + z^3 = x;
  der(x) = -z;
end NonlinearLoop;
