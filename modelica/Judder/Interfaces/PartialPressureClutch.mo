within Judder.Interfaces;
partial model PartialPressureClutch "Wet clutch actuated by a pressure: flanges, pressure inputs and the parameters of Eq. (3)-(5); the friction law is left to the component"
  extends PartialCompliantWithRelativeStates;
  parameter Units.FrictionCoefficient mu0(min=0)=0.09
    "Friction coefficient of Eq. (5): at zero slip (linear law) or at the operating slip (curve)";
  parameter Units.FrictionGradient mu_g=0.017
    "Gradient of the friction coefficient with slip speed (Eq. 5)";
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
  tau = -tau_c;
  annotation (Documentation(info="<html>
<p>What every pressure-actuated wet clutch of the library shares: the
flanges (flange_a engine side, flange_b gearbox side), the actuation
pressure p and its mean part p_mean (Sources.DitherPressure), the slip
speed, the torque tau_c transmitted from flange_a to flange_b, and the
parameters of Eq. (3)-(5). The friction law tau_c(slip, p, p_mean) and
the direction of friction are left to the extending component:
PartialWetClutch (the linear law of Eq. 5) or
Components.CurveWetClutch (a bounded curve).</p>
</html>"));
end PartialPressureClutch;
