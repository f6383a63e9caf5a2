within Judder;
package Examples "The paper's drivelines and the test bench, ready to simulate or export"
end Examples;
