within Judder.Interfaces;
partial model PartialFrictionTable "Friction coefficient as a table of the absolute slip speed, interpolated linearly with its end values held (as MSL Clutch mu_pos)"
  parameter Real mu_pos[:, 2]={{0, 0.09}, {50, 0.1}, {100, 0.11}, {200, 0.115}}
    "Friction coefficient (column 2, 1) against the absolute slip speed (column 1, rad/s, increasing)";
  Units.AngularVelocity w_table "Absolute slip speed at which the table is read";
  Units.FrictionCoefficient mu "Friction coefficient at w_table";
equation
  // linear interpolation in mu_pos at w_table, the end values held outside
  mu = noEvent(if w_table < mu_pos[1, 1] then mu_pos[1, 2] else 0)
    + sum(noEvent(if w_table >= mu_pos[i, 1] and w_table < mu_pos[i + 1, 1]
      then mu_pos[i, 2] + (mu_pos[i + 1, 2] - mu_pos[i, 2])
        *(w_table - mu_pos[i, 1])/(mu_pos[i + 1, 1] - mu_pos[i, 1])
      else 0) for i in 1:size(mu_pos, 1) - 1)
    + noEvent(if w_table >= mu_pos[size(mu_pos, 1), 1]
      then mu_pos[size(mu_pos, 1), 2] else 0);
  annotation (Documentation(info="<html>
<p>A friction characteristic as the clutch has it, measured on a
friction rig (SAE No. 2, mu-v): column 1 of <code>mu_pos</code> is the
absolute slip speed in rad/s, in increasing order, column 2 the
friction coefficient. <code>mu</code> is its linear interpolation at
<code>w_table</code>, which the extending clutch sets to the absolute
slip; outside the table the end values hold. Written with noEvent
if-expressions and a sum over the rows, which the project's compiler
turns into one tunable parameter per table entry
(<code>mu_pos[i,j]</code>). The slope of the characteristic at a slip
is the slope of its segment there: the mu_g of the linearisation
(Eq. 5) at that slip.</p>
</html>"));
end PartialFrictionTable;
