within Judder;
package Sources "Pressure and torque sources, speed-controlled drive"
end Sources;
