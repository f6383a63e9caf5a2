within Judder.Examples;
model TestBenchEngagement "Held-slip bench run of Fig. 5 and section 2.2: EVEN clutch held slipping steadily at 1000 rpm with a bounded friction curve, REV clutch as the load"
  extends PartialTestBench(redeclare replaceable model Clutch = Components.CurveWetClutch
      constrainedby Interfaces.PartialCurveWetClutch,
    clutch(mu_g=mu_g, delta_mu=delta_mu, w_op=w_op),
    S_load=load_share*(N_c*S*p_m - c3*w_gearbox/(mu0*R_m))/(N_c_load*p_load));
  extends Data.BoundedCurveData;
  annotation (
    experiment(StopTime=4, Interval=1e-3),
    Documentation(info="<html>
<p>A held-slip bench run on the test bench of section 2.2 (Fig. 5b):
the start of an engagement, held at its slip (it never engages). The 4-DOF
driveline of Fig. 13 driven by the 81 kW DC motor under speed control
at w_motor (SpeedDrive on body 1). The EVEN clutch (CurveWetClutch)
between body 4 and body 3 is pressed: its pressure ramps from 0 at t_engage
to p_m in t_ramp, with the dither p_f cos(2 pi f_dither t) of Eq. (4) on
top. Its friction coefficient is a bounded rising curve of the slip
whose value and slope at the slip w_op are mu0 and mu_g. As on the
modified gearbox, the REV clutch, whose gear is fixed to the frame,
slips against the housing (flat friction, mu0) and is the load on body
3; its pressure ramps with the EVEN pressure to p_load, and its default
piston area S_load makes its torque equal to the EVEN clutch's mean
torque mu0 N_c R_m S p_m less the drag c3 w_gearbox of the gearbox side
(2 N m, which would otherwise slow it by 2 rad/s in 4 s and move the
slip along the curve's steep part). The gearbox side then keeps its
initial speed w_gearbox and the EVEN clutch slips steadily at w_motor -
w_gearbox, the operating point of the stability model: the judder seen at the start of
an engagement (Fig. 7b), held long enough to measure its growth.
TestBenchCurveLockUp redeclares the clutch as LockingCurveWetClutch (the
same curve and parameters) and engages to lock-up.</p>
<p>Linearised about that operating point, the bench is the driveline of
Eq. (6) with mu0 and mu_g the curve's value and slope at the slip, and
two additions: the motor's speed control, a damping d_control of body 1
to ground, and the REV clutch, whose flat friction adds no damping (its
direction term tanh(w_gearbox/w_small) is saturated).</p>
<p>Outputs, from the sensors: w_upstream and w_downstream, the speeds of
the EVEN clutch plates on the engine side (body 4) and on the gearbox
side (body 3), the two speeds the bench acquires; slip = w4 - w3
(relative speed sensor across the EVEN clutch, whose w_rel is w3 - w4);
clutch_torque, the friction torque the EVEN clutch transmits to body 3
(torque sensor between the clutch and body 3); and actuation_pressure,
the EVEN pressure.</p>
</html>"));
end TestBenchEngagement;
