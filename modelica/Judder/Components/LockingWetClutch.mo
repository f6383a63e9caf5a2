within Judder.Components;
model LockingWetClutch "Wet clutch with the straight-line law of Eq. (5) that locks at zero slip and breaks away by events (stuck or slipping, as MSL Clutch)"
  extends Interfaces.PartialWetClutch;
  extends Interfaces.PartialLockingClutch;
equation
  tau0_max = N_c*R_m*S*mu0*p;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-10,-72},{10,-72}}),
        Line(points={{-10,-80},{10,-80}}),
        Text(extent={{-150,-85},{150,-120}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch for engagements that end in lock-up: the straight-line
friction law of Eq. (3)-(5) (Interfaces.PartialWetClutch) while
slipping, and stuck plates from the instant the slip reaches zero,
switched by events (Interfaces.PartialLockingClutch):</p>
<pre>
  slipping: tau_c = N_c R_m S (mu0 sense p + mu_g slip (p - (1 - mean_pressure_damping) p_mean))
  stuck:    der(w_rel) = 0, tau_c is the torque that takes
  tau0_max = mu0 N_c R_m S p   (the law at zero slip)
</pre>
<p>While slipping, the torque is that of WetClutch away from zero slip
(there tanh(slip/w_small) is +-1). The straight line holds over the
whole slip: its dither torque (mu0 + mu_g slip) N_c R_m S p_f is 17
times that of the bench's bounded curve at the operating slip w_op, 14
times at 105 rad/s and up to 19 times (at 50 rad/s) over the slip an
engagement sweeps
(LockingCurveWetClutch, the same modes with the held-slip bench's
law).</p>
</html>"));
end LockingWetClutch;
