within Judder.Data;
record BoundedCurveData "Bounded rising friction curve of the held-slip bench's EVEN clutch (Components.CurveWetClutch)"
  parameter Units.FrictionCoefficient delta_mu(min=1e-6)=0.04
    "Half the rise of the EVEN friction curve (mu within mu0 +- delta_mu)";
  parameter Units.AngularVelocity w_op(min=0)=84.71975511965977
    "Slip at which the EVEN curve has the value mu0 and the slope mu_g (w_motor - w_gearbox at 1000 rpm)";
  annotation (Documentation(info="<html>
<p>The friction curve of Components.CurveWetClutch,
mu = mu0 + delta_mu tanh(mu_g (|w| - w_op)/delta_mu), whose value and
slope at the slip w_op are mu0 and mu_g and which stays within
mu0 +- delta_mu.</p>
</html>"));
end BoundedCurveData;
