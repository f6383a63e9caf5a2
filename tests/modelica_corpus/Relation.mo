model Relation "A relation that generates events"
  Real x(start = 1, fixed = true);
equation
  der(x) = if x > 0.5 then -1 else -2;
end Relation;
