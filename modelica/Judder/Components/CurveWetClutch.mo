within Judder.Components;
model CurveWetClutch "Wet clutch with a bounded friction curve mu(slip) whose value and slope at the operating slip are mu0 and mu_g, its direction following the slip smoothly (held-slip bench)"
  extends Interfaces.PartialCurveWetClutch;
  parameter Units.AngularVelocity w_small(min=0)=0.01
    "Slip speed over which the friction torque changes sign smoothly";
equation
  direction = noEvent(tanh(slip/w_small));
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-60,-85},{-20,-84},{0,-75},{20,-66},{60,-65}}),
        Text(extent={{-150,-65},{150,-100}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch with the bounded friction curve of
Interfaces.PartialCurveWetClutch,</p>
<pre>
  mu(w) = mu0 + delta_mu tanh(mu_g (|w| - w_op)/delta_mu)
  tau_c = N_c R_m S direction (mu(w) (p - (1 - m) p_mean) + (1 - m) mu0 p_mean)
</pre>
<p>with a direction of friction that follows the sign of the slip
smoothly, direction = tanh(slip/w_small). The EVEN clutch of the
held-slip bench run (Examples.TestBenchEngagement); the same law in a
clutch that locks at zero slip is Components.LockingCurveWetClutch.</p>
</html>"));
end CurveWetClutch;
