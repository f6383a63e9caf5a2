within Judder.Examples;
model TestBenchLockUp "Bench engagement of TestBenchFullEngagement ending in lock-up with the straight line of Eq. 5 (another friction law than the bench's curve): the EVEN clutch sticks and breaks away by events"
  extends PartialTestBench(S_load=0.006, w_gearbox=0, t_ramp=0.05,
    redeclare model Clutch = Components.LockingWetClutch, clutch(mu_g=mu_g));
  annotation (
    experiment(StopTime=4, Interval=1e-3),
    Documentation(info="<html>
<p>The engagement of TestBenchFullEngagement (the same bench settings)
with the EVEN clutch as a Components.LockingWetClutch: it slips by Eq. (5) and sticks from the
instant the slip reaches zero, by events. Outside the tongues (f_dither = 60 Hz, p_f = 0.05 bar) the
engagement ends in lock-up at 3.23 s: the slip stays at zero and the
clutch transmits the torque the load takes. Inside tongue 2 (the default
102.9 Hz, 0.3 bar) the slip oscillates through zero; at each zero the
torque needed to stay stuck exceeds mu0 N_c R_m S p, so the clutch
breaks away in the same event and no lock holds. The mode is
clutch.lockups - clutch.breakaways (1 stuck, 0 slipping). The
straight line holds over the whole slip, so its dither torque is 9-19
times that of the held-slip bench's curve over the slip the engagement
sweeps (17 at w_op);
TestBenchCurveLockUp is the engagement with that curve.</p>
</html>"));
end TestBenchLockUp;
