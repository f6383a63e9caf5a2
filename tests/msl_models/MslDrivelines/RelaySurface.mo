within MslDrivelines;
model RelaySurface "A torsional oscillator whose stiffness a relay doubles past a switching angle, started at rest exactly on that angle (the relay's mode is ambiguous there)"
  import Modelica.Constants.pi;
  parameter Real J(unit="kg.m2") = 0.1 "Inertia";
  parameter Real k(unit="N.m/rad") = 1000 "Stiffness below the switching angle (twice as much past it)";
  parameter Real d(unit="N.m.s/rad") = 0.5 "Damping";
  parameter Real phi_switch(unit="rad") = 0 "Switching angle of the relay";
  parameter Real phi0(unit="rad") = 0 "Start angle";
  parameter Real p_f(unit="Pa") = 1e4 "Dither amplitude";
  parameter Real f_dither(unit="Hz") = 50 "Dither frequency";
  parameter Real g(unit="N.m/(rad.Pa)") = 0.01 "Stiffness modulated per pascal of dither";
  Boolean past "The relay: past the switching angle";
  Real phi(unit="rad", start = phi0, fixed = true);
  Real w(unit="rad/s", start = 0, fixed = true);
equation
  past = phi > phi_switch;
  der(phi) = w;
  J*der(w) = -(if past then 2*k else k)*phi - d*w - g*p_f*cos(2*pi*f_dither*time)*phi;
end RelaySurface;
