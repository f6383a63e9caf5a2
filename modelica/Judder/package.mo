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
</html>"));
end Judder;
