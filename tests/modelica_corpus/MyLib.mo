package MyLib "A whole package in one file"
  model Decay "First-order decay"
    parameter Real k = 1.5 "Rate";
    Real x(start = 2, fixed = true);
  equation
    der(x) = -k*x;
    annotation(experiment(StopTime = 1, Interval = 0.01));
  end Decay;
  annotation(version = "2.1.0");
end MyLib;
