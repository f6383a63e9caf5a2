within Judder.Interfaces;
partial model PartialWetClutch "Wet clutch actuated by a pressure: friction law of Eq. (3)-(5); the direction of friction is left to the component"
  extends PartialDitheredClutch;
  parameter Units.FrictionGradient mu_g=0.017
    "Gradient of the friction coefficient with slip speed (Eq. 5)";
equation
  tau_c = N_c*R_m*S*(mu0*direction*p
    + mu_g*slip*(p - (1 - mean_pressure_damping)*p_mean));
  annotation (Documentation(info="<html>
<p>Wet multi-plate clutch between flange_a (engine side, body 4 of
Fig. 13) and flange_b (gearbox side, body 3), actuated by the pressure
<code>p</code>. The friction torque follows Eq. (3)-(5) of the paper,
T_c = mu N_c R_m S p with mu = mu0 + mu_g (w4 - w3) and p from Eq. (4):</p>
<pre>
  slip  = der(flange_a.phi) - der(flange_b.phi)
  tau_c = N_c R_m S (mu0 direction p
                     + mu_g slip (p - (1 - mean_pressure_damping) p_mean))
  flange_a.tau = tau_c,  flange_b.tau = -tau_c
</pre>
<p>tau_c is the torque transmitted from flange_a to flange_b: it brakes
the upstream body and drives the downstream one. With
mean_pressure_damping = 1 the slip damping is mu_g N_c R_m S p, Eq. (2)-(4)
taken literally, and the mean pressure damps the slip. With the
default 0 only the dither part p - p_mean of the pressure multiplies
the slip, which gives the paper's stability maps (Fig. 12, 14, 16-18).
<code>direction</code>, the sign of friction, is left to the extending
component: +1 (SlippingClutch) or a smooth sign of the slip (WetClutch).
The inputs <code>p</code> and <code>p_mean</code> come from
Sources.DitherPressure.</p>
</html>"));
end PartialWetClutch;
