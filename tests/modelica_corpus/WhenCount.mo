model WhenCount "Integer and Boolean variables assigned in when-clauses (when, elsewhen) and by edge() and change(), on x = sin(time)"
  Real x(start = 0, fixed = true);
  Boolean high "x > 0.5";
  Integer rises(start = 0, fixed = true) "Times x has risen above 0.5";
  Integer returns(start = 0, fixed = true) "Times x has risen above -0.5 (not at the start, where it already is)";
  Integer changes(start = 0, fixed = true) "Changes of high";
  Boolean latched(start = false, fixed = true) "Set at the first rising edge of high";
  Integer level(start = 0, fixed = true) "1 once high, -1 once x is below -0.5";
equation
  der(x) = cos(time);
  high = x > 0.5;
  when x > 0.5 then
    rises = pre(rises) + 1;
  end when;
  when x > -0.5 then
    returns = pre(returns) + 1;
  end when;
  changes = if change(high) then pre(changes) + 1 else pre(changes);
  latched = pre(latched) or edge(high);
  when high then
    level = 1;
  elsewhen x < -0.5 then
    level = -1;
  end when;
end WhenCount;
