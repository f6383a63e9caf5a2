model NonlinearInitial "An initial equation nonlinear in its state"
  Real x(fixed = false);
initial equation
  x*x = 4;
equation
  der(x) = -x;
end NonlinearInitial;
