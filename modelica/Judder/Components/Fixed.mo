within Judder.Components;
model Fixed "Flange fixed in the housing at a given angle"
  parameter Units.Angle phi0=0 "Fixed angle of the housing";
  Interfaces.Flange_b flange "Flange fixed in the housing";
equation
  flange.phi = phi0;
end Fixed;
