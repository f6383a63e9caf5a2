model WhenAnd "A when-condition combining two relations"
  Real h(start = 1, fixed = true);
  Real v(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = -9.81;
  when h < 0 and v < 0 then
    reinit(v, -0.8*pre(v));
  end when;
end WhenAnd;
