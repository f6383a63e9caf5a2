within Judder.Components;
model FrictionCurveClutch "Wet clutch slipping forwards with a saturating friction curve mu(slip)"
  extends Interfaces.PartialDitheredClutch;
  parameter Units.FrictionCoefficient mu_max(min=0)=0.12
    "Friction coefficient the curve tends to at large slip";
  parameter Units.AngularVelocity w_char(min=1e-6)=1
    "Characteristic slip speed of the curve (its slope at zero slip is (mu_max - mu0)/w_char)";
  Units.FrictionCoefficient mu "Friction coefficient at the present slip";
equation
  direction = 1;
  mu = mu0 + (mu_max - mu0)*tanh(slip/w_char);
  tau_c = N_c*R_m*S*direction*(mu0*p + (mu - mu0)*(p - (1 - mean_pressure_damping)*p_mean));
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-40,-90},{-30,-75},{-10,-70},{40,-68}}),
        Text(extent={{-150,-95},{150,-130}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch slipping forwards whose friction coefficient follows a
smooth saturating curve of the slip speed instead of the straight line
of Eq. (5):</p>
<pre>
  mu(slip) = mu0 + (mu_max - mu0) tanh(slip/w_char)
  tau_c    = N_c R_m S (mu0 p + (mu(slip) - mu0) (p - (1 - mean_pressure_damping) p_mean))
</pre>
<p>With a straight line mu - mu0 = mu_g slip this is SlippingClutch.
Linearised about a steady slip w_s, the slip damping is
N_c R_m S mu_g(w_s) (p - (1 - mean_pressure_damping) p_m) with the local
slope</p>
<pre>
  mu_g(w_s) = (mu_max - mu0)/w_char (1 - tanh(w_s/w_char)^2)
</pre>
<p>which is the paper's mu_g: the slip speed of the operating point
(hence the engine speed of section 3.2) becomes a parameter of the
stability map. The slope decreases with the slip, so a clutch that
slips faster is damped less by its own friction curve. Valid while
slip &gt; 0.</p>
</html>"));
end FrictionCurveClutch;
