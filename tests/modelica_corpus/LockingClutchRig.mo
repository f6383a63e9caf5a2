model LockingClutchRig "The clutch of LockUp as a component: its stuck branch der(w_rel) = 0 needs the relative speed differentiated a second time"
  model Clutch "Locks when the slip reaches zero"
    extends Judder.Interfaces.PartialCompliantWithRelativeStates;
    parameter Real tau_max = 30 "Torque capacity";
    Real locked(start = 0, fixed = true) "1 when stuck, 0 when slipping";
  equation
    der(locked) = 0;
    0 = if locked > 0.5 then der(w_rel) else tau + tau_max;
    when w_rel >= 0 then
      reinit(locked, 1);
    end when;
  end Clutch;
  Judder.Components.Inertia a(J = 1, phi(start = 0, fixed = true), w(start = 10, fixed = true));
  Judder.Components.Inertia b(J = 2, phi(start = 0, fixed = true), w(start = 0, fixed = true));
  Clutch clutch;
equation
  connect(a.flange_b, clutch.flange_a);
  connect(clutch.flange_b, b.flange_a);
end LockingClutchRig;
