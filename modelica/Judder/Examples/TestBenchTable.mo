within Judder.Examples;
model TestBenchTable "Held-slip bench run of section 2.2 with the EVEN clutch's friction characteristic given as a table of up to 64 points (a friction rig's mu(slip))"
  extends PartialTestBench(redeclare replaceable model Clutch = Components.TableWetClutch
      constrainedby Interfaces.PartialDitheredClutch,
    clutch(mu_pos=friction_table),
    S_load=load_share*(N_c*S*p_m - c3*w_gearbox/(mu0*R_m))/(N_c_load*p_load));
  parameter Real friction_table[64, 2]={{0, 0.05}, {10, 0.05}, {20, 0.05}, {30, 0.05}, {40, 0.05}, {50, 0.05}, {60, 0.05}, {61.25, 0.05}, {62.5, 0.05}, {63.75, 0.05}, {65, 0.05}, {66.25, 0.05}, {67.5, 0.05}, {68.75, 0.0500001}, {70, 0.0500003}, {71.25, 0.0500009}, {72.5, 0.0500025}, {73.75, 0.0500071}, {75, 0.0500207}, {76.25, 0.0500597}, {77.5, 0.0501726}, {78.75, 0.0504973}, {80, 0.0514223}, {81.25, 0.0539816}, {82.5, 0.0605289}, {83.75, 0.0743883}, {85, 0.0947418}, {86.25, 0.112876}, {87.5, 0.123118}, {88.75, 0.12748}, {90, 0.129111}, {91.25, 0.12969}, {92.5, 0.129893}, {93.75, 0.129963}, {95, 0.129987}, {96.25, 0.129996}, {97.5, 0.129998}, {98.75, 0.129999}, {100, 0.13}, {101.25, 0.13}, {102.5, 0.13}, {103.75, 0.13}, {105, 0.13}, {106.25, 0.13}, {107.5, 0.13}, {108.75, 0.13}, {110, 0.13}, {121.176, 0.13}, {132.353, 0.13}, {143.529, 0.13}, {154.706, 0.13}, {165.882, 0.13}, {177.059, 0.13}, {188.235, 0.13}, {199.412, 0.13}, {210.588, 0.13}, {221.765, 0.13}, {232.941, 0.13}, {244.118, 0.13}, {255.294, 0.13}, {266.471, 0.13}, {277.647, 0.13}, {288.824, 0.13}, {300, 0.13}}
    "Friction characteristic of the EVEN clutch: absolute slip speed (rad/s, increasing), friction coefficient";
  annotation (
    experiment(StopTime=4, Interval=1e-3),
    Documentation(info="<html>
<p>TestBenchEngagement with the EVEN clutch's friction characteristic
as the clutch has it: a table of 64 points of the absolute slip speed
(Components.TableWetClutch, interpolated linearly), which a friction rig
gives. The tool fills it from <code>--friction FILE.csv</code>: a table
of fewer points is continued flat past its last slip, so that the
interpolation is the table's own. The default is the bounded curve of
TestBenchEngagement (mu0 = 0.09 and mu_g = 0.017 at w_op = 84.72 rad/s,
delta_mu = 0.04) at 64 slips. mu0 is the characteristic's value at the
held slip w_motor - w_gearbox: the mean torque the REV clutch balances
(S_load) and, with mean_pressure_damping = 0, the friction of the mean
clamping load.</p>
</html>"));
end TestBenchTable;
