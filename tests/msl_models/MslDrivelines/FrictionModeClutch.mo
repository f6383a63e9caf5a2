within MslDrivelines;
model FrictionModeClutch "MSL's Coulomb friction with stuck and sliding modes (Rotational.Interfaces.PartialFriction, unchanged) around a friction table written in Modelica"
  extends Modelica.Mechanics.Rotational.Interfaces.PartialCompliantWithRelativeStates;
  import Modelica.Units.SI;
  parameter Real mu_pos[:, 2] = [0, 0.5]
    "Positive sliding friction coefficient (column 2) against w_rel (column 1, rad/s, increasing), as Clutch's mu_pos";
  parameter Real peak(final min=1) = 1 "Peak for maximum value of mu at w==0 (mu0_max = peak*mu_pos[1,2])";
  parameter Real cgeo(final min=0) = 1 "Geometry constant containing friction distribution assumption";
  parameter SI.Force fn_max(final min=0, start=1) "Maximum normal force";
  extends Modelica.Mechanics.Rotational.Interfaces.PartialFriction;
  Real mu "Friction coefficient";
  SI.Force fn "Normal force (fn=fn_max*f_normalized)";
  Modelica.Blocks.Interfaces.RealInput f_normalized
    "Normalized force signal 0..1 (normal force = fn_max*f_normalized; clutch is engaged if > 0)";
  Real w_table "Speed at which mu_pos is read (|w_rel| while sliding)";
  Real mu_table "mu_pos interpolated at w_table";
protected
  final parameter Real mu0 = mu_pos[1, 2] "Friction coefficient for w=0 and forward sliding";
equation
  w_relfric = w_rel;
  a_relfric = a_rel;
  fn = fn_max*f_normalized;
  free = fn <= 0;
  tau0 = mu0*cgeo*fn;
  tau0_max = peak*tau0;
  // Clutch's table_signs {1, 1} / {1, -1} / {-1, -1}, as two scalars
  w_table = if startForward then w_rel elseif startBackward then w_rel
    elseif pre(mode) == Forward then w_rel else -w_rel;
  // linear interpolation in mu_pos (LinearSegments, the end rows extrapolated)
  mu_table = noEvent(if w_table < mu_pos[2, 1] then mu_pos[1, 2] + (mu_pos[2, 2] - mu_pos[1, 2])
      *(w_table - mu_pos[1, 1])/(mu_pos[2, 1] - mu_pos[1, 1]) else 0)
    + sum(noEvent(if w_table >= mu_pos[i, 1] and w_table < mu_pos[i + 1, 1]
      then mu_pos[i, 2] + (mu_pos[i + 1, 2] - mu_pos[i, 2])
        *(w_table - mu_pos[i, 1])/(mu_pos[i + 1, 1] - mu_pos[i, 1])
      else 0) for i in 2:size(mu_pos, 1) - 2)
    + noEvent(if w_table >= mu_pos[size(mu_pos, 1) - 1, 1] then mu_pos[size(mu_pos, 1) - 1, 2]
      + (mu_pos[size(mu_pos, 1), 2] - mu_pos[size(mu_pos, 1) - 1, 2])
        *(w_table - mu_pos[size(mu_pos, 1) - 1, 1])/(mu_pos[size(mu_pos, 1), 1] - mu_pos[size(mu_pos, 1) - 1, 1])
      else 0);
  mu = if startForward then mu_table elseif startBackward then -mu_table
    elseif pre(mode) == Forward then mu_table else -mu_table;
  tau = if locked then sa*unitTorque elseif free then 0 else mu*cgeo*fn;
  annotation (Documentation(info="<html>
<p>The stuck, forward and backward sliding modes of
Modelica.Mechanics.Rotational.Components.Clutch, from MSL's own
Interfaces.PartialFriction (Booleans free, startForward, startBackward,
locked and the Integer mode with pre()), with Clutch's equations for the
friction torque; only the friction table differs: Clutch reads mu_pos
through ExternalCombiTable1D (an external C object rumoca 0.10.2 cannot
flatten, docs/compiler.md), this model interpolates mu_pos linearly in
Modelica (Clutch's LinearSegments with LastTwoPoints extrapolation, at
least three rows). judder linearises it in the mode of the operating
point (sources/modelica.py).</p>
</html>"));
end FrictionModeClutch;
