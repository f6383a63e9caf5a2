within Judder.Sources;
model SpeedDrive "Speed-controlled motor: feed-forward torque plus proportional speed control"
  extends Interfaces.PartialOneFlange;
  parameter Units.AngularVelocity w_ref=104.71975511965977 "Speed set-point (1000 rpm)";
  parameter Units.RotationalDampingConstant d_control(min=0)=2000
    "Proportional gain of the speed controller";
  parameter Units.Torque tau_max(min=0)=680 "Largest torque the motor delivers";
  parameter Units.Torque tau_feedforward=0 "Torque applied at the set-point speed";
  Units.AngularVelocity w "Speed of the flange";
  Units.Torque tau_motor "Torque applied to the connected body";
equation
  w = der(flange.phi);
  tau_motor = noEvent(max(-tau_max, min(tau_max, tau_feedforward + d_control*(w_ref - w))));
  flange.tau = -tau_motor;
end SpeedDrive;
