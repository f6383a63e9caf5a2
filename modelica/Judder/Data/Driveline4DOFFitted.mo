within Judder.Data;
record Driveline4DOFFitted "4-DOF driveline fitted to the bench (section 4.2): c12 = 10, mu_g = 0.022, k24 + 6 %"
  extends Driveline4DOFData(c12=10, mu_g=0.022, k24=32885*1.06);
  annotation (Documentation(info="<html>
<p>The 4-DOF model of Driveline4DOFData as the paper fits it to the bench
measurements in section 4.2 (the solid line of Fig. 16): the clutch
damper damped at c12 = 10 N m s/rad, the friction gradient mu_g = 0.022
s/rad and the stiffness k24 raised by 6 %. The tool's preset
<code>paper-4dof-fitted</code> is read from it.</p>
</html>"));
end Driveline4DOFFitted;
