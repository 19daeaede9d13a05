-- The square at t = 0+ (sph.squeeze_validation.square_t0) against its time step: F / F_FE
-- at the engine's own step and with dt capped at fractions of the free surface's viscous
-- time rho h^2 / mu, so that the time error of a figure can be told from its spatial error
-- (docs/limitations.md, "The default step's time error in the plate force").
--   build/sph scripts/square_dt.lua [Bn=0] [n=20,40] [c=1,0.5,0.25,0.1] [threads=1]
-- c: the caps, dt_max = c rho h^2 / mu (rho = 0.05, mu = 1, h = dx); the engine's step
-- limit on a Newtonian free surface is c = 2.
local sv = require "sph.squeeze_validation"
local o = ... or {}
local Bn = tonumber(o.Bn or 0)
local function list(s, what)
  local t = {}
  for x in tostring(s):gmatch("[^,]+") do
    local v = tonumber(x)
    if not v or v <= 0 then error("square_dt: " .. what .. " must be positive numbers, got '" .. x .. "'", 0) end
    t[#t + 1] = v
  end
  return t
end
local ns, cs = list(o.n or "20,40", "n"), list(o.c or "1,0.5,0.25,0.1", "c")
print(string.format("square Bn = %g: F / F_FE averaged over t in (0.005, 0.02), against the step", Bn))
print(string.format("%-6s %-22s %9s %8s %7s", "dx", "step", "F / F_FE", "spread", "steps"))
for _, n in ipairs(ns) do
  local dx = 1 / n
  local runs = { { label = "engine's own" } }
  for _, c in ipairs(cs) do
    runs[#runs + 1] = { label = string.format("c = %g (%.3g)", c, c * 0.05 * dx * dx), dt_max = c * 0.05 * dx * dx }
  end
  for _, r in ipairs(runs) do
    local ok, res = pcall(sv.square_t0, n, Bn, { dt_max = r.dt_max, threads = tonumber(o.threads or 1) })
    if ok then
      print(string.format("1/%-4d %-22s %9.4f %8.4f %7d", n, r.label, res.ratio, res.spread, res.steps))
    else
      print(string.format("1/%-4d %-22s failed: %s", n, r.label, tostring(res)))
    end
    io.stdout:flush()
  end
end
