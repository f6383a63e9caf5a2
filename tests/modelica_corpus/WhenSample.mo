model WhenSample "A when-clause on a sampled clock"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  when sample(0, 0.1) then
    reinit(x, 1);
  end when;
end WhenSample;
