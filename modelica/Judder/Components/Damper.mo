within Judder.Components;
model Damper "Linear torsional damper (to ground when flange_b is fixed)"
  extends Interfaces.PartialCompliantWithRelativeStates;
  parameter Units.RotationalDampingConstant d(min=0, start=0) "Damping constant";
equation
  tau = d*w_rel;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Line(points={{-90,0},{-60,0}}),
        Line(points={{-60,-30},{-60,30}}),
        Line(points={{-60,-30},{60,-30}}),
        Line(points={{-60,30},{60,30}}),
        Rectangle(extent={{-60,30},{30,-30}}, lineColor={0,0,0},
          fillColor={192,192,192}, fillPattern=FillPattern.Solid),
        Line(points={{30,0},{90,0}}),
        Text(extent={{-150,90},{150,50}}, textString="%name", textColor={0,0,255}),
        Text(extent={{-150,-50},{150,-80}}, textString="d=%d")}),
    Documentation(info="<html>
<p>Massless linear torsional damper, as
Modelica.Mechanics.Rotational.Components.Damper:</p>
<pre>
  tau = d w_rel
</pre>
<p>with w_rel = der(flange_b.phi - flange_a.phi). With flange_b connected
to the housing (<code>Fixed</code>) it is the external viscous damping
c_i of body i, a diagonal term of C in Eq. (2).</p>
</html>"));
end Damper;
