within Judder.Components;
model SpringDamper "Linear torsional spring and damper in parallel"
  extends Interfaces.PartialCompliantWithRelativeStates;
  parameter Units.RotationalSpringConstant c(min=0, start=1e5) "Spring constant";
  parameter Units.RotationalDampingConstant d(min=0, start=0) "Damping constant";
equation
  tau = c*phi_rel + d*w_rel;
end SpringDamper;
