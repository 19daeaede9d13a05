-- Helpers shared by the benchmark scripts (scripts/bench_*.lua).
local B = {}

-- The median of an array of numbers (the array is left as it is).
function B.median(t)
  local s = table.move(t, 1, #t, 1, {})
  table.sort(s)
  local n = #s
  return n % 2 == 1 and s[(n + 1) // 2] or 0.5 * (s[n // 2] + s[n // 2 + 1])
end

-- dx as "1/k" when 1/dx is a whole number, else "%.4g".
function B.fraction(dx)
  local k = 1 / dx
  if math.abs(k - math.floor(k + 0.5)) < 1e-6 then return string.format("1/%d", math.floor(k + 0.5)) end
  return string.format("%.4g", dx)
end

return B
