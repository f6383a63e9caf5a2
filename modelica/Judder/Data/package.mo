within Judder;
package Data "Parameter records: the paper's Appendix A and the set fitted to the bench"
  annotation (Documentation(info="<html>
<p>The values of the paper's Appendix A, written once, as records in the
manner of the parameter records of the Modelica Standard Library. The
examples extend them, so every value is a parameter of the example of
the same name (J1, k12, mu_g, ...), and the tool's presets
(<code>judder params --preset paper-4dof</code>) are read from these
files (drivelines/records.py).</p>
<ul>
<li><code>ClutchData</code>: the EVEN clutch of Eq. (3)-(5): friction of
Appendix A, the plate pack N_c R_m S calibrated as the registry's
docstring explains, and the bench pressure p_m.</li>
<li><code>Driveline4DOFData</code>: the 4-DOF model of Fig. 13
(Appendix A, 4 DOFs), with the clutch.</li>
<li><code>Driveline4DOFFitted</code>: the same, fitted to the bench in
section 4.2 (solid line of Fig. 16).</li>
<li><code>Driveline3DOFData</code>: the 3-DOF model of Fig. 12
(Appendix A, 3 DOFs), with the clutch.</li>
</ul>
</html>"));
end Data;
