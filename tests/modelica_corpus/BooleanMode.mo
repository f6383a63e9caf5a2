model BooleanMode "A Boolean mode and an Integer counter with pre() and initial(): x decays until 0.5, then holds"
  Boolean on "Decaying";
  Integer stops(start = 0, fixed = true) "Times the decay has stopped";
  Real x(start = 1, fixed = true);
equation
  on = initial() or x > 0.5;
  stops = if pre(on) and not on then pre(stops) + 1 else pre(stops);
  der(x) = if on then -x else 0;
end BooleanMode;
