within Judder.Components;
model LockingWetClutch "Wet clutch that locks at zero slip and breaks away by events (stuck or slipping, as MSL Clutch)"
  extends Interfaces.PartialWetClutch;
  Real lockups(start=0, fixed=true) "Number of lock-ups so far";
  Real breakaways(start=0, fixed=true) "Number of break-aways so far";
  Real sense(start=1, fixed=true)
    "Direction of the slip while slipping: +1 forwards (flange_a faster), -1 backwards";
  Real locked "1 while stuck, 0 while slipping";
  Units.Torque tau0_max "Largest torque the stuck clutch transmits, mu0 N_c R_m S p";
equation
  der(lockups) = 0;
  der(breakaways) = 0;
  der(sense) = 0;
  locked = lockups - breakaways;
  tau0_max = N_c*R_m*S*mu0*p;
  // slipping: the friction law of Eq. (3)-(5) in the direction of the
  // slip; stuck: no relative acceleration, the torque is what that takes
  0 = locked*der(w_rel) + (1 - locked)*(direction - sense);
  // lock when the slip reaches zero (the indicator stays positive while
  // stuck, so a break-away at zero slip does not lock again at once)
  when (1 - locked)*(-sense*slip) + locked >= 0 then
    reinit(lockups, pre(lockups) + 1);
  end when;
  // break away, in the direction of the torque, when it reaches the
  // capacity; evaluated again right after a lock-up, in the same event
  when locked*(abs(tau_c) - tau0_max) - (1 - locked) >= 0 then
    reinit(breakaways, pre(breakaways) + 1);
    reinit(sense, noEvent(if tau_c >= 0 then 1 else -1));
  end when;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-10,-72},{10,-72}}),
        Line(points={{-10,-80},{10,-80}}),
        Text(extent={{-150,-85},{150,-120}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch for engagements that end in lock-up: the friction law of
Eq. (3)-(5) (Interfaces.PartialWetClutch) while slipping, and stuck
plates from the instant the slip reaches zero, switched by events as
Modelica.Mechanics.Rotational.Components.Clutch switches between its
stuck and slipping modes:</p>
<pre>
  slipping: direction = sense (+1 forwards, -1 backwards)
            tau_c = N_c R_m S (mu0 sense p + mu_g slip (p - (1 - mean_pressure_damping) p_mean))
  stuck:    der(w_rel) = 0, tau_c is the torque that takes
  tau0_max = mu0 N_c R_m S p
</pre>
<p>The clutch locks when the slip reaches zero, and breaks away, in the
direction of its torque, when |tau_c| reaches the static capacity
tau0_max (which follows the dithered pressure). The break-away test is
made again in the event iteration of each lock-up, so a lock that would
need more than the capacity does not hold: the slip goes on through
zero with the friction reversed. While slipping, the
torque is that of WetClutch away from zero slip (there tanh(slip/w_small)
is +-1); instead of WetClutch's steep slope through zero slip, the plates
stick, and the slip stays at its value at the lock event (zero to the
precision of the event location). The mode is
<code>locked = lockups - breakaways</code>, two Real states counted up by
one when-clause each (Boolean and Integer variables are not compiled,
and one variable takes its reinit from one clause only; see
docs/compiler.md); they count the stick-slip cycles.</p>
</html>"));
end LockingWetClutch;
