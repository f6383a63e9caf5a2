within Judder.Interfaces;
connector Flange_b "Rotational flange (open icon in the MSL)"
  Units.Angle phi "Absolute rotation angle of the flange";
  flow Units.Torque tau "Cut torque in the flange";
end Flange_b;
