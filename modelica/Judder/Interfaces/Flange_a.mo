within Judder.Interfaces;
connector Flange_a "Rotational flange (filled icon in the MSL)"
  Units.Angle phi "Absolute rotation angle of the flange";
  flow Units.Torque tau "Cut torque in the flange";
end Flange_a;
