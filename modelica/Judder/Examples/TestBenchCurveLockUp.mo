within Judder.Examples;
model TestBenchCurveLockUp "Full bench engagement to lock-up with the held-slip bench's friction curve: the gearbox side from rest until the EVEN clutch sticks, by events"
  extends TestBenchEngagement(S_load=0.006, w_gearbox=0, t_ramp=0.05,
    redeclare model Clutch = Components.LockingCurveWetClutch);
  annotation (
    experiment(StopTime=4, Interval=1e-3),
    Documentation(info="<html>
<p>An engagement on the test bench of section 2.2 that engages: the
gearbox side starts at rest, the pressures ramp in 0.05 s, the REV
clutch takes less torque than the EVEN clutch transmits (S_load =
0.006 m^2), and the gearbox side speeds up until the slip reaches zero,
where the EVEN clutch sticks (Components.LockingCurveWetClutch, by
events). The EVEN clutch has the friction law of the held-slip bench
run (TestBenchEngagement, whose parameters mu0, mu_g, delta_mu and w_op
it passes on unchanged): the bounded curve whose value and slope at the
slip w_op are mu0 and mu_g, so its torque at a slip and a pressure is
the held-slip bench's. The engagement sweeps the slip from w_motor down
to zero: the curve's slope is mu_g only within a few delta_mu/mu_g of
w_op, and the dither torque is mu(slip) N_c R_m S p_f cos(omega t)
throughout. TestBenchLockUp is the same engagement with the straight
line of Eq. 5 over the whole slip, another friction law.</p>
</html>"));
end TestBenchCurveLockUp;
