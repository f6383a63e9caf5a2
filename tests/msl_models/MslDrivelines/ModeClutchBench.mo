within MslDrivelines;
model ModeClutchBench "ModeClutchDriveline with the outputs a run records (w_upstream, w_downstream, slip, clutch_torque, actuation_pressure), for simulate and crosscheck"
  extends ModeClutchDriveline;
  import Judder.Sources.DitherPressure "the dither source ModeClutchDriveline uses (rumoca loads the packages a class names)";
  Modelica.Blocks.Interfaces.RealOutput w_upstream = inertia4.w "Speed of the clutch's engine side";
  Modelica.Blocks.Interfaces.RealOutput w_downstream = inertia3.w "Speed of the clutch's gearbox side";
  Modelica.Blocks.Interfaces.RealOutput slip = inertia4.w - inertia3.w "Slip speed";
  Modelica.Blocks.Interfaces.RealOutput clutch_torque = clutch.tau "Friction torque";
  Modelica.Blocks.Interfaces.RealOutput actuation_pressure = pressure.p "Actuation pressure";
end ModeClutchBench;
