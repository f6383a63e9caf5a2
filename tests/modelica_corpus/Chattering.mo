model Chattering "A Boolean that never settles: b = not pre(b) changes at every event iteration"
  Boolean b(start = false, fixed = true);
  Real x(start = 1, fixed = true);
equation
  b = not pre(b);
  der(x) = if b then -x else x;
end Chattering;
