within Judder.Components;
model LockingCurveWetClutch "Wet clutch with the held-slip bench's bounded friction curve that locks at zero slip and breaks away by events (stuck or slipping, as MSL Clutch)"
  extends Interfaces.PartialCurveWetClutch;
  extends Interfaces.PartialLockingClutch;
  final parameter Units.FrictionCoefficient mu_stuck=mu0 - delta_mu*tanh(mu_g*w_op/delta_mu)
    "Friction coefficient of the curve at zero slip, mu(0)";
equation
  tau0_max = N_c*R_m*S*(mu_stuck*(p - (1 - mean_pressure_damping)*p_mean)
    + (1 - mean_pressure_damping)*mu0*p_mean);
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-60,-85},{-20,-84},{0,-75},{20,-66},{60,-65}}),
        Line(points={{-10,-72},{10,-72}}),
        Line(points={{-10,-80},{10,-80}}),
        Text(extent={{-150,-85},{150,-120}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch for engagements that end in lock-up with the friction law
of the held-slip bench (CurveWetClutch): the bounded curve of
Interfaces.PartialCurveWetClutch while slipping, and stuck plates from
the instant the slip reaches zero, switched by events
(Interfaces.PartialLockingClutch):</p>
<pre>
  mu(w)    = mu0 + delta_mu tanh(mu_g (|w| - w_op)/delta_mu)
  slipping: tau_c = N_c R_m S sense (mu(w) (p - (1 - m) p_mean) + (1 - m) mu0 p_mean)
  stuck:    der(w_rel) = 0, tau_c is the torque that takes
  tau0_max = N_c R_m S (mu(0) (p - (1 - m) p_mean) + (1 - m) mu0 p_mean)
</pre>
<p>with m = mean_pressure_damping and mu(0) = mu_stuck, the curve at
zero slip (mu0 - delta_mu to 1e-15 with the defaults, mu_g w_op/delta_mu
= 36). The capacity is the law's torque at zero slip: with m = 1 it is
mu(0) N_c R_m S p; with the paper's m = 0 the mean load keeps the
friction mu0 of the operating slip (PartialCurveWetClutch), and so does
the capacity's mean part. With the same mu0, mu_g, delta_mu and w_op
its torque while slipping is CurveWetClutch's wherever |slip| &gt;&gt;
w_small.</p>
</html>"));
end LockingCurveWetClutch;
