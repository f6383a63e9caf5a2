within Judder.Components;
model WetClutch "Wet clutch whose friction changes direction smoothly through zero slip (engagements)"
  extends Interfaces.PartialWetClutch;
  parameter Units.AngularVelocity w_small(min=0)=0.01
    "Slip speed over which the friction torque changes sign smoothly";
equation
  direction = noEvent(tanh(slip/w_small));
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Text(extent={{-150,-65},{150,-100}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch for engagements: the friction law of Eq. (3)-(5)
(Interfaces.PartialWetClutch) with a direction of friction that follows
the sign of the slip smoothly,</p>
<pre>
  direction = tanh(slip/w_small)
</pre>
<p>so the torque changes sign within a slip of a few w_small, without
events, and the slip can reach and cross zero (lock-up is approximated
by the steep slope of the torque there). For slip &gt;&gt; w_small it
equals SlippingClutch. Used on the test bench
(section 2.2) for the engaging EVEN clutch and for the REV clutch that
slips against the housing as the load.</p>
</html>"));
end WetClutch;
