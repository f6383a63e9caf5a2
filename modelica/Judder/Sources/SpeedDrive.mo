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
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Rectangle(extent={{-80,50},{60,-50}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Rectangle(extent={{60,10},{100,-10}}, lineColor={0,0,0},
          fillPattern=FillPattern.HorizontalCylinder, fillColor={192,192,192}),
        Text(extent={{-80,30},{60,-30}}, textString="M"),
        Text(extent={{-150,100},{150,60}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-60},{150,-90}}, textString="w_ref=%w_ref")}),
    Documentation(info="<html>
<p>The 81 kW DC motor of the test bench (section 2.2) with its speed
control: a feed-forward torque plus a proportional controller on the
speed error, limited to the 680 N.m the motor delivers at low speed,</p>
<pre>
  w         = der(flange.phi)
  tau_motor = max(-tau_max, min(tau_max, tau_feedforward + d_control (w_ref - w)))
</pre>
<p>tau_motor acts on the connected body (flange.tau = -tau_motor).</p>
</html>"));
end SpeedDrive;
