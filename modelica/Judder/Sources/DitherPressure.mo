within Judder.Sources;
block DitherPressure "Actuation pressure with dither, p = r(t)*(p_m + p_f*cos(2*pi*f*t)) (Eq. 4) with the engagement ramp r"
  parameter Units.Pressure p_m(min=0)=1e6 "Mean pressure after the engagement ramp";
  parameter Units.Pressure p_f(min=0)=0 "Dither amplitude after the engagement ramp";
  parameter Units.Frequency f(min=0)=100 "Dither frequency";
  parameter Units.Time t_start=-1 "Start of the engagement ramp (the valve is energised)";
  parameter Units.Time t_ramp(min=0)=0 "Duration of the engagement ramp (0: a step at t_start)";
  parameter Boolean use_p_in=false
    "= true: p is the input p_in (a valve model's pressure); p_mean stays r(t)*p_m"
    annotation (Evaluate=true);
  Interfaces.RealInput p_in(unit="Pa") if use_p_in "Actuation pressure given from outside (use_p_in = true)"
    annotation (Placement(transformation(extent={{-140,-20},{-100,20}})));
  Interfaces.RealOutput p(unit="Pa") "Actuation pressure"
    annotation (Placement(transformation(extent={{100,30},{120,50}})));
  Interfaces.RealOutput p_mean(unit="Pa") "Mean part of the actuation pressure"
    annotation (Placement(transformation(extent={{100,-50},{120,-30}})));
  Real ramp(unit="1") "Engagement command: 0 before t_start, 1 after the ramp";
equation
  ramp = noEvent(if time <= t_start then 0 else if time >= t_start + t_ramp then 1
    else (time - t_start)/t_ramp);
  p_mean = p_m*ramp;
  connect(p_in, p);
  if not use_p_in then
    p = ramp*(p_m + p_f*cos(2*3.141592653589793*f*time));
  end if;
  annotation (
    Icon(coordinateSystem(preserveAspectRatio=true, extent={{-100,-100},{100,100}}),
      graphics={
        Rectangle(extent={{-100,100},{100,-100}}, lineColor={0,0,127},
          fillColor={255,255,255}, fillPattern=FillPattern.Solid),
        Line(points={{-80,-80},{-80,80}}, color={192,192,192}),
        Line(points={{-90,-60},{90,-60}}, color={192,192,192}),
        Line(points={{-80,-60},{-40,-60},{-20,40},{-16.7,36.2},{-13.3,26.2},{-10,13.8},
          {-6.7,3.8},{-3.3,0},{0,3.8},{3.3,13.8},{6.7,26.2},{10,36.2},{13.3,40},
          {16.7,36.2},{20,26.2},{23.3,13.8},{26.7,3.8},{30,0},{33.3,3.8},{36.7,13.8},
          {40,26.2},{43.3,36.2},{46.7,40},{50,36.2},{53.3,26.2},{56.7,13.8},{60,3.8},
          {63.3,0},{66.7,3.8},{70,13.8},{73.3,26.2},{76.7,36.2},{80,40}}),
        Text(extent={{60,70},{98,50}}, textString="p"),
        Text(extent={{30,-70},{98,-90}}, textString="p_mean"),
        Text(extent={{-150,150},{150,110}}, textString="%name", textColor={0,0,255})}),
    Documentation(info="<html>
<p>Actuation pressure of the clutch: a constant part p_m plus the dither,
a cosine of amplitude p_f and frequency f, as Eq. (4) of the paper,
p(t) = p_m + p_f cos(omega_p t), omega_p = 2 pi f. Both parts are
multiplied by the engagement command r(t), which is 0 before t_start,
rises linearly during t_ramp and is 1 after (the default t_start = -1
gives r = 1 from t = 0, the steady slipping of the paper):</p>
<pre>
  p      = r(t) (p_m + p_f cos(2 pi f t))
  p_mean = r(t) p_m
</pre>
<p>p_mean, the mean part, goes to the clutch with p (see
mean_pressure_damping of Interfaces.PartialWetClutch). With use_p_in =
true the waveform is replaced by the input p_in (p = p_in, a valve
model's pressure through an FMU input) and p_mean stays r(t) p_m, as in
Examples.Driveline4DOFInputs.</p>
</html>"));
end DitherPressure;
