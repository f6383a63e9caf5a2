within Judder;
package Components "Inertias, couplings, ground and the wet clutch"
  annotation (Documentation(info="<html>
<p>The elements of the drivelines of Fig. 12 and 13, as in
Modelica.Mechanics.Rotational.Components: a rigid body
(<code>Inertia</code>, J_i), a spring and damper in parallel
(<code>SpringDamper</code>, k_ij and c_ij), a damper
(<code>Damper</code>, with flange_b fixed: the external damping c_i),
the housing (<code>Fixed</code>) and the wet clutch of Eq. (3)-(5), in
two forms: <code>SlippingClutch</code>, linear as printed in the paper,
and <code>WetClutch</code>, whose friction changes direction smoothly
through zero slip (engagements). For drivelines beyond the paper's:
<code>IdealGear</code> (a ratio, MSL equations) and
<code>FrictionCurveClutch</code>, whose friction coefficient is a smooth
saturating curve of the slip; its local slope at the operating slip is
the paper's mu_g. <code>CurveWetClutch</code> has the bench's bounded
friction curve; <code>LockingWetClutch</code> (the straight line of
Eq. 5) and <code>LockingCurveWetClutch</code> (the bench's curve) stick
at zero slip by events (Interfaces.PartialLockingClutch). Every wet
clutch (also TableClutch) extends
Interfaces.PartialPressureClutch, which declares the plate pack and the
pressure input once and draws Icons.Clutch.</p>
</html>"));
end Components;
