within Judder.Interfaces;
connector RealOutput = output Real "Real output signal";
