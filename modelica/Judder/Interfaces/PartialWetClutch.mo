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
  RealInput p(unit="Pa") "Actuation pressure";
  RealInput p_mean(unit="Pa") "Mean part of the actuation pressure";
  Units.AngularVelocity slip "Slip speed, flange_a minus flange_b";
  Real direction(unit="1") "Direction of the friction torque (+1 when slipping forwards)";
  Units.Torque tau_c "Friction torque transmitted from flange_a to flange_b";
equation
  slip = -w_rel;
  tau_c = N_c*R_m*S*(mu0*direction*p
    + mu_g*slip*(p - (1 - mean_pressure_damping)*p_mean));
  tau = -tau_c;
end PartialWetClutch;
