-- herschel_bulkley.lua: a Herschel-Bulkley sample squeezed at constant plate speed.
--
-- What it shows: the third material, sph.herschel_bulkley{K, n, tau0, m}: a yield stress
-- tau0 and, once yielded, a power law K gammadot^n (n < 1: shear-thinning, n > 1:
-- thickening); the yield term is regularised as for Bingham (exponent m). mat:eta(gammadot)
-- gives its apparent viscosity, printed at the start. The half sample is simulated
-- (x = 0 is a mirror), the lower plate fixed, the upper one moves down at V. Rows t, h, F go
-- to series.csv; at the end two pictures: yield.png (yielded light, unyielded dark) and
-- eta.png (the apparent viscosity, colour bar at the right).
--
--   build/sph examples/herschel_bulkley.lua [name=value ...]
--
-- Parameters (H = U = 1 scaling; rho = Re):
--   K=1 n=0.5 tau0=0.5 m=100   consistency, flow index, yield stress, regularisation exponent
--   Re=10 V=1 dx=0.025         density, plate speed, particle spacing
--   t_end=0.3 every=0.02       end time and rows
--   steps=0                    N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/herschel_bulkley   threads (0: all cores) and the output folder
--
-- What you should see (about 2 s): the viscosities eta(gammadot) at 0.1, 1 and 10 (falling:
-- shear-thinning), then the rows: the force stays near 15-20, lower than the Bingham one of
-- squeeze_velocity.lua at the same gap (20 against 28 at h = 0.7). eta.png is darkest
-- (lowest) along the plates away from the middle, where the sample shears most, and
-- yellow (highest) at the middle of each plate, where the flow parts and the shear rate
-- vanishes.
local sph = require "sph"
local params = require "sph.params"

local o = params.args("herschel_bulkley", {
  { "K", "number", 1, "consistency" },
  { "n", "number", 0.5, "flow index" },
  { "tau0", "number", 0.5, "yield stress" },
  { "m", "number", 100, "Papanastasiou exponent" },
  { "Re", "number", 10, "density" },
  { "V", "number", 1, "plate speed" },
  { "dx", "number", 0.025, "particle spacing" },
  { "t_end", "number", 0.3, "end time" },
  { "every", "number", 0.02, "output interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/herschel_bulkley", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

local paste = sph.herschel_bulkley{ K = o.K, n = o.n, tau0 = o.tau0, m = o.m }
print(string.format("eta(0.1) = %.3f  eta(1) = %.3f  eta(10) = %.3f", paste:eta(0.1), paste:eta(1), paste:eta(10)))

-- shifting = 20 keeps the particles evenly spread as the sample spreads (docs/limitations.md)
local w = sph.world{ dx = o.dx, rho = o.Re, symmetry = { x = 0 }, shifting = 20, threads = o.threads }
w:fill{ rect = { 0, 0, 0.5, 1 }, material = paste }
local T = 3 * o.dx                                         -- plates 3 dx thick: the kernel's reach
w:plate{ rect = { -2, -T, 2, 0 } }                         -- lower plate, fixed
local top = w:plate{ rect = { -2, 1, 2, 1 + T }, axis = "y" }
top:velocity(-o.V)

local csv = assert(io.open(o.out .. "/series.csv", "w"))
csv:write("t,h,F\n")
local function row(w)
  csv:write(string.format("%.6g,%.6g,%.6g\n", w.t, top.position, top.force))
  print(string.format("t = %.3f  h = %.4f  F = %8.3f", w.t, top.position, top.force))
end

if o.steps > 0 then                      -- a quick look: N steps, a row each
  row(w)
  for _ = 1, o.steps do w:step(); row(w) end
else                                     -- the run: a row at the start and every `every` (w:run calls row then too)
  w:run{ until_t = o.t_end, every = o.every, each = row }
end
csv:close()

local a = 0.1 + largest(w:field("x"))
local view = { -a, -T, a, top.position + T }
local pic = { view = view, width = 800, height = math.floor(800 * (view[4] - view[2]) / (view[3] - view[1])) + 40 }
pic.file, pic.color, pic.label = o.out .. "/yield.png", "yield", string.format("Herschel-Bulkley, n = %g: yield state", o.n)
assert(w:render(pic))
pic.file, pic.color, pic.label = o.out .. "/eta.png", "eta", "apparent viscosity eta"
pic.width = 900                                           -- room for the colour bar
assert(w:render(pic))
local s = w:stats()
print(string.format("%d steps; %d of %d particles yielded; wrote %s/series.csv, yield.png and eta.png",
  w.steps, s.yielded, s.fluid, o.out))
