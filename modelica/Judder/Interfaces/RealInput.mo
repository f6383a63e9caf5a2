within Judder.Interfaces;
connector RealInput = input Real "Real input signal";
