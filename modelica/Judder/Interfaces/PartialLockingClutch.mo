within Judder.Interfaces;
partial model PartialLockingClutch "Stuck and slipping modes of a dithered wet clutch, switched by events (as MSL PartialFriction); the friction law and the stuck capacity tau0_max are left to the component"
  extends PartialDitheredClutch;
  Real lockups(start=0, fixed=true) "Number of lock-ups so far";
  Real breakaways(start=0, fixed=true) "Number of break-aways so far";
  Real sense(start=1, fixed=true)
    "Direction of the slip while slipping: +1 forwards (flange_a faster), -1 backwards";
  Real locked "1 while stuck, 0 while slipping";
  Units.Torque tau0_max "Largest torque the stuck clutch transmits: the friction law's torque at zero slip";
equation
  der(lockups) = 0;
  der(breakaways) = 0;
  der(sense) = 0;
  locked = lockups - breakaways;
  // slipping: the component's friction law in the direction of the
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
  annotation (Documentation(info="<html>
<p>The two modes of a wet clutch that locks at zero slip, switched by
events as Modelica.Mechanics.Rotational.Components.Clutch switches
between its stuck and slipping modes (MSL's
Interfaces.PartialFriction: the modes here, the friction law in the
component):</p>
<pre>
  slipping: direction = sense (+1 forwards, -1 backwards), tau_c by the friction law
  stuck:    der(w_rel) = 0, tau_c is the torque that takes
</pre>
<p>The clutch locks when the slip reaches zero, and breaks away, in the
direction of its torque, when |tau_c| reaches the static capacity
tau0_max, which the extending component states: its friction law's
torque at zero slip (with direction +1), so the capacity follows the
dithered pressure and the stuck clutch holds what the slipping clutch
transmits as the slip reaches zero, as MSL's Clutch takes its stuck
capacity from its friction table at zero slip. The break-away test is
made again in the event iteration of each lock-up, so a lock that would
need more than the capacity does not hold: the slip goes on through zero
with the friction reversed. While slipping, the direction is +-1
exactly; instead of a steep slope of the torque through zero slip
(tanh(slip/w_small)), the plates stick, and the slip stays at its value
at the lock event (zero to the precision of the event location). The
mode is <code>locked = lockups - breakaways</code>, two Real states
counted up by one when-clause each (one variable takes its reinit from
one clause only, in rumoca; Boolean and Integer variables are compiled
too, see docs/compiler.md); they count the stick-slip cycles.
Components: LockingWetClutch (the straight line of Eq. 5),
LockingCurveWetClutch (the bounded curve of the held-slip bench).</p>
</html>"));
end PartialLockingClutch;
