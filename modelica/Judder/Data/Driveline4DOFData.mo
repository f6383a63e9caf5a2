within Judder.Data;
record Driveline4DOFData "4-DOF driveline of Fig. 13 with its clutch: Appendix A, 4 DOFs model"
  extends ClutchData;
  parameter Units.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter Units.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter Units.Inertia J4=0.122 "Inertia between clutch damper and clutch discs";
  parameter Units.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter Units.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter Units.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter Units.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter Units.RotationalDampingConstant c2=0.1 "External damping of body 2";
  parameter Units.RotationalDampingConstant c3=0.1 "External damping of body 3";
  parameter Units.RotationalDampingConstant c4=0.1 "External damping of body 4";
  annotation (Documentation(info="<html>
<p>The minimal 4-DOF model of Fig. 13 and Eq. (1)-(5) with the values of
the paper's Appendix A (4 DOFs model): engine-side body 1, clutch damper
2 behind the damper k12, c12, body 4 between the damper and the clutch
pack behind k24, c24, the gearbox side 3, and the external damping c_i
of each body to the housing; with the clutch of ClutchData. The examples
on the 4-DOF chain (Examples.PartialDriveline4DOF) extend it; the tool's
preset <code>paper-4dof</code> is read from it.</p>
</html>"));
end Driveline4DOFData;
