within Judder.Interfaces;
partial model PartialCurveWetClutch "Wet clutch actuated by a pressure: the bounded friction curve mu(slip) whose value and slope at the operating slip are mu0 and mu_g; the direction of friction is left to the component"
  extends PartialDitheredClutch;
  parameter Units.FrictionGradient mu_g=0.017
    "Slope of the friction curve at the operating slip w_op (the mu_g of Eq. 5)";
  parameter Units.FrictionCoefficient delta_mu(min=1e-6)=0.04
    "Half the rise of the friction curve: mu stays within mu0 +- delta_mu";
  parameter Units.AngularVelocity w_op(min=0)=84.71975511965977
    "Operating slip speed, where the curve has the value mu0 and the slope mu_g";
  Units.FrictionCoefficient mu "Friction coefficient of the curve at the present slip";
equation
  mu = mu0 + delta_mu*tanh(mu_g*(noEvent(abs(slip)) - w_op)/delta_mu);
  tau_c = N_c*R_m*S*direction*(mu*(p - (1 - mean_pressure_damping)*p_mean)
    + (1 - mean_pressure_damping)*mu0*p_mean);
  annotation (Documentation(info="<html>
<p>Wet clutch whose friction coefficient is a bounded, rising curve of
the slip speed (the kind Fig. 9 shows: friction falling as the
engagement proceeds, i.e. a positive gradient in slip), parameterised
by its value mu0 and slope mu_g at the operating slip w_op, the two
numbers the stability model takes:</p>
<pre>
  mu(w) = mu0 + delta_mu tanh(mu_g (|w| - w_op)/delta_mu)
  tau_c = N_c R_m S direction (mu(w) (p - (1 - m) p_mean) + (1 - m) mu0 p_mean)
</pre>
<p>with m = mean_pressure_damping. mu stays within mu0 +- delta_mu
whatever the slip; the dither part of the torque is
mu N_c R_m S p_f cos(omega t), of the size of a wet clutch's friction
(not mu_g times the slip, which Eq. (5) taken as a law for the whole
slip would give, PartialWetClutch).</p>
<p>Linearised about a steady slip w_s (perturbation dw of the slip):</p>
<pre>
  tau_c = N_c R_m S (mu(w_s) p(t) + mu'(w_s) (m p_m + p_f cos(omega t)) dw)
</pre>
<p>with mu'(w_op) = mu_g: at w_s = w_op this is Eq. (2)-(5) of the
stability model with the mean-pressure option m, exactly. The share
1 - m of the mean load has the friction of the operating slip and does
not follow slip excursions; only the dither part of the load (and the
share m) does. With m = 1 the whole load follows the curve: the clutch
then dissipates mu' N_c R_m S p(t) dw^2 &gt;= 0 at every instant, and no
parametric instability is possible at any p_f &lt; p_m (docs/theory.md).
The paper's maps are m = 0.</p>
<p>A measured curve mu(slip) gives mu0 and mu_g as its value and slope at
the operating slip, and delta_mu as half its range
(stability.friction.curve_from_table). <code>direction</code>, the sign
of friction, is left to the extending component: a smooth sign of the
slip (Components.CurveWetClutch) or the stuck and slipping modes of
PartialLockingClutch (Components.LockingCurveWetClutch).</p>
</html>"));
end PartialCurveWetClutch;
