within;
package Judder "Torsional driveline with a wet clutch under hydraulic dither (parametric clutch judder)"
  annotation (
    version="0.1.0",
    Documentation(info="<html>
<p>Acausal models of the 3-DOF and 4-DOF transmission of Tentarelli et al.,
<em>Parametric excitation as a cause of clutch judder</em>, and of the test
bench of its section 2.2. The structure follows
Modelica.Mechanics.Rotational: flanges with a potential angle and a flow
torque (flange_a, flange_b), partial models that write the balance once,
and components that add only their own law. Units are SI.</p>
<ul>
<li><b>Units</b>: the SI types of the library.</li>
<li><b>Icons</b>: icons drawn once (the wet clutch).</li>
<li><b>Data</b>: parameter records of the paper's Appendix A and of the
set fitted to the bench (section 4.2).</li>
<li><b>Interfaces</b>: flanges, signal connectors and partial models.</li>
<li><b>Components</b>: inertia, spring-damper, damper, housing and the
wet clutch of Eq. (3)-(5).</li>
<li><b>Sources</b>: the dither pressure of Eq. (4), a constant torque and a
speed-controlled motor.</li>
<li><b>Sensors</b>: speed, relative speed and torque sensors as in
Modelica.Mechanics.Rotational.Sensors.</li>
<li><b>Examples</b>: the 4-DOF model of Fig. 13 and Eq. (1)-(5), the
3-DOF model of Fig. 12 and the bench engagement of section 2.2.</li>
</ul>
</html>"));
end Judder;
