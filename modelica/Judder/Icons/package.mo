within Judder;
package Icons "Icons drawn once and extended by the classes that look alike"
  annotation (Documentation(info="<html>
<p>Partial classes that hold only an icon, as Modelica.Icons and the
icon classes of Modelica.Mechanics.Rotational: a class extends one of
them and draws on top only what is its own.</p>
<ul>
<li><code>Clutch</code>: the wet clutch of Eq. (3)-(5), shafts, plates
and the actuation pressure.</li>
</ul>
</html>"));
end Icons;
