within;
package MslDrivelines "Drivelines written with the Modelica Standard Library, as an OEM engineer writes them (tests of the FMU compiler)"
  annotation(Documentation(info="<html><p>Models of tests/test_fmu_msl.py: MSL 4.x parts (Modelica.Mechanics.Rotational, Modelica.Blocks) and the Judder library's wet clutch.</p></html>"));
end MslDrivelines;
