within Judder;
package Examples "The paper's drivelines and the test bench, ready to simulate or export"
  annotation (Documentation(info="<html>
<p>Complete models with an experiment annotation and the same five
outputs, each taken from a sensor: w_upstream and w_downstream (speeds
on each side of the clutch), slip, clutch_torque and
actuation_pressure.</p>
<ul>
<li><code>PartialDriveline4DOF</code>: the 4-DOF chain of Fig. 13 with
the values of Appendix A (Data.Driveline4DOFData), a replaceable EVEN
clutch, its dither pressure and the sensors, wired once; the 4-DOF
examples and the bench extend it.</li>
<li><code>Driveline4DOF</code>: the minimal 4-DOF model of Fig. 13,
Eq. (1)-(5), slipping steadily with dither.</li>
<li><code>Driveline3DOF</code>: the essential 3-DOF model of Fig. 12.</li>
<li><code>Driveline5DOFGeared</code>: the 4-DOF chain with a gear,
an output shaft and a fifth inertia, and a friction-curve clutch whose
slip speed is a parameter.</li>
<li><code>Driveline4DOFTwoClutches</code>: the 4-DOF model with the REV
clutch as a second slipping clutch with dither (a rank-2
modulation).</li>
<li><code>TestBenchEngagement</code>: a held-slip bench run on the
bench of section 2.2 (Fig. 5b): the EVEN clutch held at a steady slip
with its bounded friction curve, the REV clutch as the load.</li>
<li><code>TestBenchCurveLockUp</code>: a full engagement on the same
bench with the same friction curve, the gearbox side from rest until
the EVEN clutch locks up by events.</li>
<li><code>TestBenchFullEngagement</code>, <code>TestBenchLockUp</code>:
full engagements with the straight line of Eq. 5 over the whole slip,
another friction law than the bench's curve (smooth through zero slip,
and locking by events).</li>
</ul>
</html>"));
end Examples;
