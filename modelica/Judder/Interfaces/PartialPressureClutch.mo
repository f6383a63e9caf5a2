within Judder.Interfaces;
partial model PartialPressureClutch "Wet clutch actuated by a pressure: flanges, the pressure input and the plate pack of Eq. (3); the friction law is left to the component"
  extends Icons.Clutch;
  extends PartialCompliantWithRelativeStates;
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter Units.Length R_m(min=0)=0.075 "Mean radius of the friction surfaces";
  parameter Units.Area S(min=0)=0.01 "Area the actuation pressure acts on";
  RealInput p(unit="Pa") "Actuation pressure"
    annotation (Placement(transformation(origin={40,110}, extent={{-20,-20},{20,20}}, rotation=270)));
  Units.AngularVelocity slip "Slip speed, flange_a minus flange_b";
  Real direction(unit="1") "Direction of the friction torque (+1 when slipping forwards)";
  Units.Torque tau_c "Friction torque transmitted from flange_a to flange_b";
equation
  slip = -w_rel;
  tau = -tau_c;
  annotation (Documentation(info="<html>
<p>What every pressure-actuated wet clutch of the library shares: the
flanges (flange_a engine side, flange_b gearbox side), the actuation
pressure p, the plate pack of Eq. (3) (N_c pairs of plates of mean
radius R_m, the pressure acting on the area S), the slip speed, the
direction of friction and the torque tau_c transmitted from flange_a to
flange_b, and the icon (Icons.Clutch). The friction law tau_c(slip, p)
and the direction of friction are left to the extending component:
PartialDitheredClutch (the clutches fed by Sources.DitherPressure) or
Components.TableClutch (a friction table, as MSL's Clutch).</p>
</html>"));
end PartialPressureClutch;
