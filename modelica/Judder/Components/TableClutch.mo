within Judder.Components;
model TableClutch "Wet clutch whose friction coefficient is a table of the slip speed (as MSL Clutch mu_pos)"
  extends Interfaces.PartialPressureClutch;
  extends Interfaces.PartialFrictionTable;
  parameter Units.AngularVelocity w_small(min=0)=0.01
    "Slip speed over which the friction torque changes sign smoothly";
equation
  direction = noEvent(tanh(slip/w_small));
  w_table = noEvent(abs(slip));
  tau_c = N_c*R_m*S*mu*direction*p;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-80,-40},{-40,-30},{0,-25},{60,-22}}, color={0,0,255}),
        Text(extent={{-150,-65},{150,-100}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Wet clutch between flange_a and flange_b, actuated by the pressure
<code>p</code>, whose friction coefficient is given as a table of the
slip speed, the way Modelica.Mechanics.Rotational.Components.Clutch
takes its <code>mu_pos</code>:</p>
<pre>
  slip  = der(flange_a.phi) - der(flange_b.phi)
  mu    = linear interpolation in mu_pos at |slip|
          (the first and last values held outside the table)
  tau_c = N_c R_m S mu(|slip|) tanh(slip/w_small) p
  flange_a.tau = tau_c,  flange_b.tau = -tau_c
</pre>
<p>Column 1 of <code>mu_pos</code> is the absolute slip speed in rad/s,
in increasing order; column 2 the friction coefficient (unit 1). A
measured friction curve mu(slip) goes into the model without fitting
the linear law mu = mu0 + mu_g slip of Eq. (5) (Components.WetClutch);
a rising curve damps the slip, a falling one excites it. The direction
of friction follows the sign of the slip smoothly, as in WetClutch,
without events. The interpolation is written with noEvent if-expressions
and a sum over the rows of the table, which the project's compiler turns
into an FMU with one tunable parameter per table entry
(<code>mu_pos[i,j]</code>).</p>
</html>"));
end TableClutch;
