within Judder;
package Interfaces "Connectors and partial models"
  annotation (Documentation(info="<html>
<p>Connectors and partial models, as in
Modelica.Mechanics.Rotational.Interfaces:</p>
<ul>
<li><code>Flange_a</code>, <code>Flange_b</code>: rotational flanges
(angle phi, cut torque tau as a flow variable),</li>
<li><code>RealInput</code>, <code>RealOutput</code>: signal connectors
(the actuation pressure, the sensor outputs),</li>
<li>partial models that write the flange equations once: two flanges,
one flange, compliant connection, the wet clutches (a pressure clutch,
one fed by a dither pressure, the linear law of Eq. (3)-(5)), and the
absolute and relative sensors.</li>
</ul>
</html>"));
end Interfaces;
