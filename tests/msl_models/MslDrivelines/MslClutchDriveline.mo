within MslDrivelines;
model MslClutchDriveline "ModeClutchDriveline with MSL's own Rotational.Components.Clutch (its ExternalCombiTable1D table object as the user has it), slipping forward"
  import Modelica.Mechanics.Rotational;
  import Modelica.Units.SI;
  parameter SI.Inertia J1=1.12 "Inertia of the engine-side body";
  parameter SI.Inertia J2=0.231 "Inertia of the clutch damper";
  parameter SI.Inertia J3=4.07 "Inertia of the gearbox-side body";
  parameter SI.Inertia J4=0.122 "Inertia between clutch damper and clutch discs";
  parameter SI.RotationalSpringConstant k12=3856 "Stiffness of the clutch damper";
  parameter SI.RotationalSpringConstant k24=32885 "Stiffness between damper and clutch pack";
  parameter SI.RotationalDampingConstant c12=0.5 "Damping of the clutch damper";
  parameter SI.RotationalDampingConstant c24=0.1 "Internal damping between 2 and 4";
  parameter SI.RotationalDampingConstant c1=0.1 "External damping of body 1";
  parameter SI.RotationalDampingConstant c2=0.1 "External damping of body 2";
  parameter SI.RotationalDampingConstant c3=0.1 "External damping of body 3";
  parameter SI.RotationalDampingConstant c4=0.1 "External damping of body 4";
  parameter Real N_c(min=1)=8 "Number of pairs of clutch plates";
  parameter SI.Length R_m=0.075 "Mean radius of the friction surfaces";
  parameter SI.Area S=0.01 "Area the actuation pressure acts on";
  parameter SI.Pressure p_max=2e6 "Pressure of the clutch's maximum normal force";
  parameter SI.Pressure p_m=1e6 "Mean actuation pressure";
  parameter SI.Pressure p_f=0.3e5 "Dither amplitude";
  parameter SI.Frequency f_dither=102.9 "Dither frequency";
  parameter SI.AngularVelocity w_in=104.71975511965977 "Initial speed of bodies 1, 2 and 4 (1000 rpm)";
  parameter SI.AngularVelocity w_out=0 "Initial speed of body 3";
  parameter Real mu_pos[4, 2]=[0, 0.09; 50, 0.1; 150, 0.11; 300, 0.115]
    "Friction coefficient against the slip speed (rad/s), as MSL Clutch's mu_pos";
  parameter SI.Torque T_c=(mu_pos[2, 2] + (mu_pos[3, 2] - mu_pos[2, 2])*(w_in - w_out - mu_pos[2, 1])
    /(mu_pos[3, 1] - mu_pos[2, 1]))*N_c*R_m*S*p_m
    "The clutch's torque at the start slip (in the second row's segment)";
  parameter SI.Torque T_e=T_c + (c1 + c2 + c4)*w_in "Engine torque on body 1: a steady slip";
  parameter SI.Torque T_r=T_c - c3*w_out "Resistant torque on body 3: a steady slip";
  Rotational.Components.Inertia inertia1(J=J1, phi(start=0, fixed=true), w(start=w_in, fixed=true));
  Rotational.Components.Inertia inertia2(J=J2, phi(start=-(T_e - c1*w_in)/k12, fixed=true), w(start=w_in, fixed=true));
  Rotational.Components.Inertia inertia4(J=J4, phi(start=-(T_e - c1*w_in)/k12 - (T_e - (c1 + c2)*w_in)/k24, fixed=true),
    w(start=w_in, fixed=true));
  Rotational.Components.Inertia inertia3(J=J3, phi(start=0, fixed=true), w(start=w_out, fixed=true));
  Rotational.Components.SpringDamper damper12(c=k12, d=c12) "Clutch damper";
  Rotational.Components.SpringDamper shaft24(c=k24, d=c24) "Shaft and gear mesh to the clutch pack";
  Rotational.Components.Clutch clutch(mu_pos=mu_pos, cgeo=N_c*R_m, fn_max=S*p_max)
    "flange_b on the engine side: w_rel = w4 - w3 > 0 is forward sliding";
  Rotational.Components.Damper external1(d=c1);
  Rotational.Components.Damper external2(d=c2);
  Rotational.Components.Damper external4(d=c4);
  Rotational.Components.Damper external3(d=c3);
  Rotational.Components.Fixed housing;
  Judder.Sources.DitherPressure pressure(p_m=p_m, p_f=p_f, f=f_dither);
  Rotational.Sources.ConstantTorque engine(tau_constant=T_e);
  Rotational.Sources.ConstantTorque load(tau_constant=-T_r);
equation
  connect(engine.flange, inertia1.flange_a);
  connect(inertia1.flange_b, damper12.flange_a);
  connect(damper12.flange_b, inertia2.flange_a);
  connect(inertia2.flange_b, shaft24.flange_a);
  connect(shaft24.flange_b, inertia4.flange_a);
  connect(inertia4.flange_b, clutch.flange_b);
  connect(clutch.flange_a, inertia3.flange_b);
  connect(inertia3.flange_a, load.flange);
  connect(external1.flange_a, inertia1.flange_a);
  connect(external2.flange_a, inertia2.flange_a);
  connect(external4.flange_a, inertia4.flange_a);
  connect(external3.flange_a, inertia3.flange_a);
  connect(external1.flange_b, housing.flange);
  connect(external2.flange_b, housing.flange);
  connect(external4.flange_b, housing.flange);
  connect(external3.flange_b, housing.flange);
  clutch.f_normalized = pressure.p/p_max;
  annotation(experiment(StopTime=2, Interval=1e-4));
end MslClutchDriveline;
