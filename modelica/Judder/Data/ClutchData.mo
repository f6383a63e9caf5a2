within Judder.Data;
record ClutchData "EVEN clutch of Eq. (3)-(5): friction of Appendix A, calibrated plate pack, bench pressure"
  parameter Units.FrictionCoefficient mu0=0.09 "Friction coefficient at zero slip";
  parameter Units.FrictionGradient mu_g=0.017 "Friction gradient with slip speed";
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter Units.Length R_m=0.075 "Mean radius of the friction surfaces";
  parameter Units.Area S=0.01 "Area the actuation pressure acts on";
  parameter Units.Pressure p_m=1e6 "Mean actuation pressure";
  parameter Units.Fraction mean_pressure_damping=0 "Share of p_m in the slip damping";
  annotation (Documentation(info="<html>
<p>The wet clutch of Eq. (3)-(5): mu0 and mu_g of Appendix A; the number
of plate pairs N_c, the mean radius R_m and the piston area S, which the
paper keeps confidential, calibrated so that N_c R_m S = 6e-3 m^3 (the
clutch then transmits mu0 N_c R_m S p_m = 540 N m at the bench pressure
p_m of about 10 bar, section 2.2, and the tongue tips of Fig. 14 lie in
the bench's dither range); and the share of the mean pressure in the
slip damping (0: the paper's maps).</p>
</html>"));
end ClutchData;
