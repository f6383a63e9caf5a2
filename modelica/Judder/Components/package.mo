within Judder;
package Components "Inertias, couplings, ground and the wet clutch"
end Components;
