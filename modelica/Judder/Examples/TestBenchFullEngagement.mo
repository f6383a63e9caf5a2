within Judder.Examples;
model TestBenchFullEngagement "Bench engagement that ends: the EVEN clutch (WetClutch, Eq. 5) brings the gearbox side up to the motor speed"
  extends PartialTestBench(S_load=0.006, w_gearbox=0, t_ramp=0.05,
    redeclare model Clutch = Components.WetClutch, clutch(mu_g=mu_g));
  annotation (
    experiment(StopTime=4, Interval=1e-3),
    Documentation(info="<html>
<p>An engagement on the test bench of section 2.2 that ends: the EVEN
clutch is Components.WetClutch (the straight-line friction law of
Eq. (3)-(5), its direction following the sign of the slip smoothly), the
REV clutch takes less torque than the EVEN clutch transmits (S_load =
0.006 m^2), the gearbox side starts at rest and the pressures ramp in
0.05 s. The gearbox side then speeds up until the slip reaches zero,
where the steep slope of tanh(slip/w_small) holds the plates together
(they creep at a few mrad/s). TestBenchLockUp is the same engagement with
a clutch that sticks by events. The straight-line law gives a dither
torque mu_g slip N_c R_m S p_f that is large at high slip; the steady
slip bench with a bounded friction curve is TestBenchEngagement, its
engagement to lock-up TestBenchCurveLockUp.</p>
</html>"));
end TestBenchFullEngagement;
