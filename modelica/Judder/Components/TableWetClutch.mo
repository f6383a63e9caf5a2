within Judder.Components;
model TableWetClutch "Wet clutch fed by a dither pressure whose friction coefficient is the clutch's measured characteristic, a table of the slip speed"
  extends Interfaces.PartialDitheredClutch;
  extends Interfaces.PartialFrictionTable;
  parameter Units.AngularVelocity w_small(min=0)=0.01
    "Slip speed over which the friction torque changes sign smoothly";
equation
  direction = noEvent(tanh(slip/w_small));
  w_table = noEvent(abs(slip));
  tau_c = N_c*R_m*S*direction*(mu*(p - (1 - mean_pressure_damping)*p_mean)
    + (1 - mean_pressure_damping)*mu0*p_mean);
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-80,-40},{-40,-30},{0,-25},{60,-22}}, color={0,0,255}),
        Text(extent={{-150,-65},{150,-100}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>The wet clutch of Eq. (3)-(5) with the friction characteristic the
clutch has, a table <code>mu_pos</code> of the absolute slip speed
(Interfaces.PartialFrictionTable), fed by Sources.DitherPressure:</p>
<pre>
  mu    = linear interpolation in mu_pos at |slip|
  tau_c = N_c R_m S tanh(slip/w_small)
          (mu(|slip|) (p - (1 - m) p_mean) + (1 - m) mu0 p_mean)
</pre>
<p>with m = mean_pressure_damping, the share of the clamping load that
feels the characteristic: 0 (the paper's maps) gives the mean load the
friction mu0 and only the dither part the characteristic; 1 gives the
whole load the characteristic (Eq. 2-4 taken literally). With m = 0,
mu0 is the characteristic's value at the operating slip, so that the
mean torque is the clutch's there. Linearised about a steady slip
w_s, it is the model of Eq. (6) with mu_g the slope of the table's
segment at w_s.</p>
</html>"));
end TableWetClutch;
