within Judder.Interfaces;
partial model PartialOneFlange "Component with one rotational flange"
  Flange_b flange "Flange";
end PartialOneFlange;
