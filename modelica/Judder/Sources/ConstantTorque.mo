within Judder.Sources;
model ConstantTorque "Constant torque acting on a flange (positive drives it forwards)"
  extends Interfaces.PartialOneFlange;
  parameter Units.Torque tau_constant=0 "Torque applied to the connected body";
equation
  flange.tau = -tau_constant;
end ConstantTorque;
