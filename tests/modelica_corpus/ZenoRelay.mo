model ZenoRelay "A relay on its own output: der(w) = -1 above zero, +1 below, so w chatters about zero from t = 1 (Zeno)"
  Real w(start = 1, fixed = true);
equation
  der(w) = if w > 0 then -1 else 1;
end ZenoRelay;
