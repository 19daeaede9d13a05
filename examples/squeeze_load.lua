-- squeeze_load.lua: a Bingham square squeezed under a constant load.
--
-- What it shows: the upper plate carries a constant force instead of a constant speed
-- (top:load(F), F < 0 presses down), so it moves as fast as the sample lets it: quickly
-- at first, then creeping as the gap thins and the yield stress holds the load. The half
-- sample is simulated (x = 0 is a mirror; loads and forces are the whole sample's), the
-- lower plate is fixed. Rows t, h (the gap), F (the fluid's force on the upper plate) and v
-- (the plate's velocity) go to series.csv every `every`; at the end yield.png (yielded
-- light, unyielded dark).
--
--   build/sph examples/squeeze_load.lua [name=value ...]
--
-- Parameters, in the paper's scaling (H = U = mu = 1, so rho = Re, tau0 = Bn, m = M):
--   Re=1 Bn=2 M=100      the Reynolds and Bingham numbers, the Papanastasiou exponent
--   F=-10                the load on the whole sample per unit depth (negative compresses;
--                        the paper's F* = F Bn)
--   dx=0.025             the particle spacing (800 particles in the half sample)
--   t_end=1 every=0.05   the end time and the rows
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/squeeze_load   threads (0: all cores) and the output folder
--
-- What you should see (about 4 s): the gap falls fast (h = 0.76 at t = 0.3, the plate at
-- v = -0.97), then slower and slower (h = 0.556 at t = 1, v = -0.06; with t_end=2, 0.518);
-- the fluid's force F settles on the load's size, 10, after the start. yield.png shows a few
-- unyielded (dark) patches near the free sides.
-- The last line gives the thin-gap plastic estimate of where a Bingham sample stops,
-- h = (Bn / (2 |F|))^(1/3) = 0.46 here (a long sample's, so only a guide for a square; and
-- the Bingham forces are low today, docs/limitations.md).
local sph = require "sph"
local params = require "sph.params"

local o = params.args("squeeze_load", {
  { "Re", "number", 1, "Reynolds number (the density)" },
  { "Bn", "number", 2, "Bingham number (the yield stress)" },
  { "M", "number", 100, "Papanastasiou exponent" },
  { "F", "number", -10, "load on the whole sample (negative compresses)" },
  { "dx", "number", 0.025, "particle spacing" },
  { "t_end", "number", 1, "end time" },
  { "every", "number", 0.05, "output interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/squeeze_load", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

-- shifting = 20 keeps the particles evenly spread as the sample is stretched sideways
-- (docs/limitations.md says why it is needed)
local w = sph.world{ dx = o.dx, rho = o.Re, symmetry = { x = 0 }, shifting = 20, threads = o.threads }
w:fill{ rect = { 0, 0, 0.5, 1 }, material = sph.bingham{ mu = 1, tau0 = o.Bn, m = o.M } }
local T = 3 * o.dx                                         -- plates 3 dx thick: the kernel's reach
w:plate{ rect = { -2, -T, 2, 0 } }                         -- lower plate, fixed
local top = w:plate{ rect = { -2, 1, 2, 1 + T }, axis = "y" }
top:load(o.F)                                             -- a constant force; top.mass is settable

local csv = assert(io.open(o.out .. "/series.csv", "w"))
csv:write("t,h,F,v\n")
local function row(w)
  csv:write(string.format("%.6g,%.6g,%.6g,%.6g\n", w.t, top.position, top.force, top:velocity()))
  print(string.format("t = %.3f  h = %.4f  F = %8.3f  v = %8.4f", w.t, top.position, top.force, top:velocity()))
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
                 label = string.format("Bingham, Bn = %g, load %g: h = %.3f", o.Bn, o.F, top.position) })
print(string.format("%d steps; h = %.4f; the thin-gap plastic estimate of the final gap (Bn / (2 |F|))^(1/3) = %.3f",
  w.steps, top.position, (o.Bn / (2 * math.abs(o.F))) ^ (1 / 3)))
print(string.format("wrote %s/series.csv and %s/yield.png", o.out, o.out))
