within Judder.Components;
model WetClutch "Wet clutch whose friction changes direction smoothly through zero slip (engagements)"
  extends Interfaces.PartialWetClutch;
  parameter Units.AngularVelocity w_small(min=0)=0.01
    "Slip speed over which the friction torque changes sign smoothly";
equation
  direction = noEvent(tanh(slip/w_small));
end WetClutch;
