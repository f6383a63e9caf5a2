within Judder.Interfaces;
partial model PartialTwoFlanges "Component with two rotational flanges"
  Flange_a flange_a "Left flange"
    annotation (Placement(transformation(extent={{-110,-10},{-90,10}})));
  Flange_b flange_b "Right flange"
    annotation (Placement(transformation(extent={{90,-10},{110,10}})));
  annotation (Documentation(info="<html>
<p>Base of a component with two flanges, as
Modelica.Mechanics.Rotational.Interfaces.PartialTwoFlanges: flange_a on
the left, flange_b on the right. It adds no equation.</p>
</html>"));
end PartialTwoFlanges;
