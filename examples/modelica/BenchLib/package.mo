within;
package BenchLib "A user's own Modelica package: drivelines for the benchmarks (uses the Judder library)"
  annotation (Documentation(info="<html>
<p>Stands for an engineer's own package beside the project's library:
<code>judder map --modelica BenchLib.Driveline6DOF --library
benchmarks/modelica</code>.</p>
</html>"));
end BenchLib;
