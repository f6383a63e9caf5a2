within Judder.Components;
model SlippingClutch "Wet clutch slipping forwards, Eq. (3)-(5) as printed: linear in the slip speed"
  extends Interfaces.PartialWetClutch;
equation
  direction = 1;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Polygon(points={{-6,-72},{6,-76},{-6,-80},{-6,-72}}, lineColor={0,0,0},
          fillColor={0,0,0}, fillPattern=FillPattern.Solid),
        Line(points={{-30,-76},{-6,-76}}),
        Text(extent={{-150,-80},{150,-115}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch that keeps slipping forwards (flange_a faster than
flange_b): the friction law of Eq. (3)-(5)
(Interfaces.PartialWetClutch) with <code>direction = 1</code>,</p>
<pre>
  T_c = N_c R_m S (mu0 p + mu_g slip (p - (1 - mean_pressure_damping) p_mean))
</pre>
<p>which is linear in the slip speed, as the paper prints it: with
mean_pressure_damping = 1 it is T_c = mu N_c R_m S p with
mu = mu0 + mu_g (w4 - w3). It is the clutch of the 3-DOF (Fig. 12) and
4-DOF (Fig. 13) drivelines, valid while slip &gt; 0.</p>
</html>"));
end SlippingClutch;
