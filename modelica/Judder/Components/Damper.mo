within Judder.Components;
model Damper "Linear torsional damper (to ground when flange_b is fixed)"
  extends Interfaces.PartialCompliantWithRelativeStates;
  parameter Units.RotationalDampingConstant d(min=0, start=0) "Damping constant";
equation
  tau = d*w_rel;
end Damper;
