within Judder.Sources;
block DitherPressure "Actuation pressure with dither, p = p_mean + p_f*cos(2*pi*f*t) (Eq. 4)"
  parameter Units.Pressure p_m(min=0)=1e6 "Mean pressure after the engagement ramp";
  parameter Units.Pressure p_f(min=0)=0 "Dither amplitude";
  parameter Units.Frequency f(min=0)=100 "Dither frequency";
  parameter Units.Time t_start=-1 "Start of the engagement ramp of the mean pressure";
  parameter Units.Time t_ramp(min=0)=0 "Duration of the engagement ramp (0: a step at t_start)";
  Interfaces.RealOutput p(unit="Pa") "Actuation pressure";
  Interfaces.RealOutput p_mean(unit="Pa") "Mean part of the actuation pressure";
equation
  p_mean = p_m*noEvent(if time <= t_start then 0 else if time >= t_start + t_ramp then 1
    else (time - t_start)/t_ramp);
  p = p_mean + p_f*cos(2*3.141592653589793*f*time);
end DitherPressure;
