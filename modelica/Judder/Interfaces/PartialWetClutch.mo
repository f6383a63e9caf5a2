within Judder.Interfaces;
partial model PartialWetClutch "Wet clutch actuated by a pressure: friction law of Eq. (3)-(5); the direction of friction is left to the component"
  extends PartialCompliantWithRelativeStates;
  parameter Units.FrictionCoefficient mu0(min=0)=0.09
    "Friction coefficient at zero slip";
  parameter Units.FrictionGradient mu_g=0.017
    "Gradient of the friction coefficient with slip speed";
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter Units.Length R_m(min=0)=0.075 "Mean radius of the friction surfaces";
  parameter Units.Area S(min=0)=0.01 "Area the actuation pressure acts on";
  parameter Units.Fraction mean_pressure_damping=0
    "Share of the mean pressure in the slip damping mu_g*N_c*R_m*S*p (1: Eq. 2-4 literally, 0: dither part only)";
  RealInput p(unit="Pa") "Actuation pressure"
    annotation (Placement(transformation(origin={40,110}, extent={{-20,-20},{20,20}}, rotation=270)));
  RealInput p_mean(unit="Pa") "Mean part of the actuation pressure"
    annotation (Placement(transformation(origin={-40,110}, extent={{-20,-20},{20,20}}, rotation=270)));
  Units.AngularVelocity slip "Slip speed, flange_a minus flange_b";
  Real direction(unit="1") "Direction of the friction torque (+1 when slipping forwards)";
  Units.Torque tau_c "Friction torque transmitted from flange_a to flange_b";
equation
  slip = -w_rel;
  tau_c = N_c*R_m*S*(mu0*direction*p
    + mu_g*slip*(p - (1 - mean_pressure_damping)*p_mean));
  tau = -tau_c;
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
