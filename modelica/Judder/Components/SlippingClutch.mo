within Judder.Components;
model SlippingClutch "Wet clutch slipping forwards, Eq. (3)-(5) as printed: linear in the slip speed"
  extends Interfaces.PartialWetClutch;
equation
  direction = 1;
end SlippingClutch;
