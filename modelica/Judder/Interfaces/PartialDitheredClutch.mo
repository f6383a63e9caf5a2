within Judder.Interfaces;
partial model PartialDitheredClutch "Wet clutch fed by a dither pressure: the mean part of the pressure, mu0 and the share of the mean pressure in the slip-dependent friction (Eq. 3-5)"
  extends PartialPressureClutch;
  parameter Units.FrictionCoefficient mu0(min=0)=0.09
    "Friction coefficient of Eq. (5): at zero slip (linear law) or at the operating slip (curve)";
  parameter Units.Fraction mean_pressure_damping=0
    "Share of the mean pressure in the slip-dependent friction (1: Eq. 2-4 literally, 0: dither part only)";
  RealInput p_mean(unit="Pa") "Mean part of the actuation pressure"
    annotation (Placement(transformation(origin={-40,110}, extent={{-20,-20},{20,20}}, rotation=270)));
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={Line(points={{-40,90},{-40,70},{-20,70},{-20,60}}, color={0,0,127})}),
    Documentation(info="<html>
<p>A pressure clutch (PartialPressureClutch) fed by
Sources.DitherPressure, which gives the actuation pressure p of Eq. (4)
and its mean part p_mean. The friction coefficient mu0 of Eq. (5)
multiplies the whole pressure; the slip-dependent part of the friction
multiplies the dither part p - (1 - mean_pressure_damping) p_mean
only, which gives the paper's stability maps with the default
mean_pressure_damping = 0 and Eq. (2)-(4) taken literally with 1. The
slip-dependent law is left to the extending component:
PartialWetClutch (the straight line of Eq. 5), PartialCurveWetClutch
and Components.FrictionCurveClutch (bounded curves); the stuck and
slipping modes of a clutch that locks, PartialLockingClutch.</p>
</html>"));
end PartialDitheredClutch;
