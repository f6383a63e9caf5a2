within Judder.Data;
record Driveline3DOFData "3-DOF driveline of Fig. 12 with its clutch: Appendix A, 3 DOFs model"
  extends ClutchData;
  parameter Units.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter Units.Inertia J24=0.353 "Inertia of the clutch damper and the parts up to the clutch pack";
  parameter Units.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter Units.RotationalSpringConstant k=3451 "Stiffness of the clutch damper";
  parameter Units.RotationalDampingConstant c=0.5 "Damping of the clutch damper";
  parameter Units.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter Units.RotationalDampingConstant c24=0.1 "External damping of body 2-4";
  parameter Units.RotationalDampingConstant c3=0.1 "External damping of body 3";
  annotation (Documentation(info="<html>
<p>The essential 3-DOF model of Fig. 12 with the values of the paper's
Appendix A (3 DOFs model): the engine-side body 1, the clutch damper k,
c, the body 2-4 up to the clutch pack and the gearbox side 3; the
external damping c_i of each body as in the 4-DOF table; with the clutch
of ClutchData. Examples.Driveline3DOF extends it; the tool's preset
<code>paper-3dof</code> is read from it.</p>
</html>"));
end Driveline3DOFData;
