within Judder;
package Interfaces "Connectors and partial models"
end Interfaces;
