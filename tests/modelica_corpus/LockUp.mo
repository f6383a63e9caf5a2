model LockUp "Two flywheels and a clutch that locks and breaks away by events"
  parameter Real J1 = 1 "Inertia of the driven flywheel";
  parameter Real J2 = 2 "Inertia of the load flywheel";
  parameter Real T2 = 1 "Load torque";
  parameter Real tau_max = 30 "Torque capacity of the clutch";
  Real w1(start = 10, fixed = true) "Speed of the driven flywheel";
  Real w2(start = 0, fixed = true) "Speed of the load flywheel";
  Real locked(start = 0, fixed = true) "1 when stuck, 0 when slipping";
  Real tau "Torque the clutch transmits";
  Real slip "w1 - w2";
equation
  der(locked) = 0;
  slip = w1 - w2;
  J1*der(w1) = 10 + 20*time - tau;
  J2*der(w2) = tau - T2;
  0 = if locked > 0.5 then der(w1) - der(w2) else tau - tau_max;
  when (1 - locked)*(-slip) + locked*(abs(tau) - tau_max) >= 0 then
    reinit(locked, 1 - pre(locked));
  end when;
  annotation(experiment(StopTime = 3, Interval = 0.01));
end LockUp;
