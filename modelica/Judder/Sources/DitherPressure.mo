within Judder.Sources;
block DitherPressure "Actuation pressure with dither, p = r(t)*(p_m + p_f*cos(2*pi*f*t)) (Eq. 4) with the engagement ramp r"
  parameter Units.Pressure p_m(min=0)=1e6 "Mean pressure after the engagement ramp";
  parameter Units.Pressure p_f(min=0)=0 "Dither amplitude after the engagement ramp";
  parameter Units.Frequency f(min=0)=100 "Dither frequency";
  parameter Units.Time t_start=-1 "Start of the engagement ramp (the valve is energised)";
  parameter Units.Time t_ramp(min=0)=0 "Duration of the engagement ramp (0: a step at t_start)";
  Interfaces.RealOutput p(unit="Pa") "Actuation pressure";
  Interfaces.RealOutput p_mean(unit="Pa") "Mean part of the actuation pressure";
  Real ramp(unit="1") "Engagement command: 0 before t_start, 1 after the ramp";
equation
  ramp = noEvent(if time <= t_start then 0 else if time >= t_start + t_ramp then 1
    else (time - t_start)/t_ramp);
  p_mean = p_m*ramp;
  p = ramp*(p_m + p_f*cos(2*3.141592653589793*f*time));
end DitherPressure;
