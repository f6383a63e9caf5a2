within Judder.Sources;
model ConstantTorque "Constant torque acting on a flange (positive drives it forwards)"
  extends Interfaces.PartialOneFlange;
  parameter Units.Torque tau_constant=0 "Torque applied to the connected body";
  parameter Boolean use_tau_in=false
    "= true: the torque is the input tau_in (an engine model's), not tau_constant"
    annotation (Evaluate=true);
  Interfaces.RealInput tau_in(unit="N.m") if use_tau_in "Torque given from outside (use_tau_in = true)"
    annotation (Placement(transformation(extent={{-140,-20},{-100,20}})));
protected
  Interfaces.RealInput tau(unit="N.m") "Torque applied: tau_in or tau_constant"
    annotation (Placement(transformation(extent={{-60,-10},{-40,10}})));
equation
  connect(tau_in, tau);
  if not use_tau_in then
    tau = tau_constant;
  end if;
  flange.tau = -tau;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-80,-30},{-64,14},{-34,42},{0,52},{34,42},{60,18}},
          smooth=Smooth.Bezier),
        Polygon(points={{80,-10},{50,30},{70,40},{80,-10}}, lineColor={0,0,0},
          fillColor={0,0,0}, fillPattern=FillPattern.Solid),
        Line(points={{0,0},{90,0}}),
        Text(extent={{-150,110},{150,70}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-40},{150,-70}}, textString="tau=%tau_constant")}),
    Documentation(info="<html>
<p>Constant torque on the connected body, <code>flange.tau =
-tau_constant</code>: tau_constant &gt; 0 drives the body forwards. In
the drivelines it is the engine torque T_e on body 1 and, with a
negative value, the resistant torque T_r on body 3 (the vector g of
Eq. (1)). In the examples both are by default the mean clutch torque
mu0 N_c R_m S p_m, which the clutch transmits without dither. With
use_tau_in = true the torque is the input tau_in instead (an engine
model's torque through an FMU input, Examples.Driveline4DOFInputs).</p>
</html>"));
end ConstantTorque;
