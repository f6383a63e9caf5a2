within Judder.Data;
record TestBenchData "Test bench of section 2.2 (Fig. 5b): motor under speed control, REV clutch as the load, pressure ramp"
  parameter Units.Time t_engage(min=0)=0.1 "Start of the EVEN pressure ramp";
  parameter Units.Time t_ramp(min=0)=0.5 "Duration of the EVEN and REV pressure ramps (clutch fill)";
  parameter Real N_c_load(min=1)=10 "Plate pairs of the REV clutch (two more than EVEN)";
  parameter Units.Pressure p_load(min=0)=0.98e6 "REV pressure (670 mA, about 9.8 bar)";
  parameter Real load_share(min=0)=1
    "REV torque over the EVEN clutch's mean torque mu0 N_c R_m S p_m (1: the slip stays steady; below 1 the gearbox side speeds up)";
  parameter Units.AngularVelocity w_motor(min=0)=104.71975511965977 "Motor speed (1000 rpm)";
  parameter Units.AngularVelocity w_gearbox(min=0)=20 "Initial speed of the gearbox side, at which the REV clutch slips";
  parameter Units.RotationalDampingConstant d_control=2000 "Gain of the motor speed controller";
  parameter Units.Torque tau_max(min=0)=680 "Largest torque the motor delivers (81 kW at about 1140 rpm)";
  annotation (Documentation(info="<html>
<p>The test bench of section 2.2 (Fig. 5b) around the driveline: the
81 kW DC motor holds body 1 at w_motor by a proportional speed control
of gain d_control, up to its torque limit tau_max; the REV clutch
(N_c_load plate pairs at the pressure p_load) slips against the
housing as the load of the gearbox side, which starts at w_gearbox;
both pressures ramp from t_engage over t_ramp. load_share sets the REV
clutch's torque against the EVEN clutch's mean torque. The tool reads
the bench's defaults, units and allowed ranges from this record
(<code>--bench NAME=VALUE</code>).</p>
</html>"));
end TestBenchData;
