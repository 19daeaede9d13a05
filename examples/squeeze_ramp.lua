-- squeeze_ramp.lua: a Bingham square squeezed under a load law written in Lua.
--
-- What it shows: a plate law is any Lua function of (t, plate), called once a step at the
-- step's start: here the load ramps linearly from 0 to F over t_ramp, then holds. The same
-- works for a velocity, top:velocity(function(t, plate) ... end), and the function may read
-- the plate (plate.position, plate.force, plate:velocity()): a law can stop at a gap, or
-- follow a measured curve. The half sample is simulated (x = 0 is a mirror), the lower
-- plate is fixed. Rows t, h, F (the fluid's force), load (the law's value) and v (the
-- plate's velocity) go to series.csv; at the end yield.png.
--
--   build/sph examples/squeeze_ramp.lua [name=value ...]
--
-- Parameters, in the paper's scaling (H = U = mu = 1, so rho = Re, tau0 = Bn, m = M):
--   Re=1 Bn=2 M=100      the Reynolds and Bingham numbers, the Papanastasiou exponent
--   F=-10 t_ramp=0.5     the final load (whole sample, negative compresses), the ramp's time
--   dx=0.025             the particle spacing
--   t_end=1 every=0.05   the end time and the rows
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/squeeze_ramp   threads (0: all cores) and the output folder
--
-- What you should see (about 4 s): the load column goes down by about 1 a row to -10 at
-- t = 0.5 (negative: it presses down) and the fluid's force F pushes back with nearly as
-- much (the difference accelerates the plate); the gap hardly moves while the load is small
-- (h = 0.995 at t = 0.2), then falls, fastest just after the ramp (v = -0.92 at t = 0.55),
-- to about 0.59 at t = 1: behind squeeze_load.lua, which pressed with 10 from the start
-- (0.556 at t = 1).
local sph = require "sph"
local params = require "sph.params"

local o = params.args("squeeze_ramp", {
  { "Re", "number", 1, "Reynolds number (the density)" },
  { "Bn", "number", 2, "Bingham number (the yield stress)" },
  { "M", "number", 100, "Papanastasiou exponent" },
  { "F", "number", -10, "final load on the whole sample (negative compresses)" },
  { "t_ramp", "number", 0.5, "time the load takes to reach F" },
  { "dx", "number", 0.025, "particle spacing" },
  { "t_end", "number", 1, "end time" },
  { "every", "number", 0.05, "output interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/squeeze_ramp", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

-- shifting = 20 keeps the particles evenly spread as the sample spreads (docs/limitations.md)
local w = sph.world{ dx = o.dx, rho = o.Re, symmetry = { x = 0 }, shifting = 20, threads = o.threads }
w:fill{ rect = { 0, 0, 0.5, 1 }, material = sph.bingham{ mu = 1, tau0 = o.Bn, m = o.M } }
local T = 3 * o.dx                                         -- plates 3 dx thick: the kernel's reach
w:plate{ rect = { -2, -T, 2, 0 } }                         -- lower plate, fixed
local top = w:plate{ rect = { -2, 1, 2, 1 + T }, axis = "y" }

-- The law: called once a step with the step's start time and the plate's handle.
top:load(function(t, plate)
  return o.F * math.min(1, t / o.t_ramp)
end)

local csv = assert(io.open(o.out .. "/series.csv", "w"))
csv:write("t,h,F,load,v\n")
local function row(w)
  local load = top:load()                                  -- the law's last value (0 before a step)
  csv:write(string.format("%.6g,%.6g,%.6g,%.6g,%.6g\n", w.t, top.position, top.force, load, top:velocity()))
  print(string.format("t = %.3f  h = %.4f  F = %8.3f  load = %8.3f  v = %8.4f", w.t, top.position, top.force,
    load, top:velocity()))
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
assert(w:render{ file = o.out .. "/yield.png", color = "yield", view = view, width = 800,
                 height = math.floor(800 * (view[4] - view[2]) / (view[3] - view[1])) + 40,
                 label = string.format("Bingham, Bn = %g, load ramped to %g: h = %.3f", o.Bn, o.F, top.position) })
print(string.format("%d steps; h = %.4f; wrote %s/series.csv and %s/yield.png", w.steps, top.position, o.out, o.out))
