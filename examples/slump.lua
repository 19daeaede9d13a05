-- slump.lua: a slump test: a Bingham column collapses under gravity on a plate.
--
-- What it shows: gravity (sph.world{gravity = {0, -g}}), a free surface all round the
-- sample, and a Bingham material that stops flowing once its weight no longer overcomes the
-- yield stress: the column sinks and spreads, then comes to rest at a height and spread
-- set by tau0 / (rho g H). The column (width x height) stands on a fixed plate; only its
-- right half is simulated (x = 0 is a mirror). Rows t, H (the top's height), spread (the
-- whole base's width), slump (height - H) and the kinetic energy go to series.csv every
-- `every`; at the end yield.png (yielded light, unyielded dark).
--
--   build/sph examples/slump.lua [name=value ...]
--
-- Parameters (units of your choice, used consistently):
--   rho=1 g=1            density and gravity
--   mu=0.1 tau0=0.1 m=100   plastic viscosity, yield stress, Papanastasiou exponent
--   width=1 height=1     the column
--   dx=0.025             the particle spacing (800 particles in the half column)
--   t_end=3 every=0.25   the end time and the rows
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/slump   threads (0: all cores) and the output folder
--
-- What you should see (about 3 s): the top sinks and the base spreads, fastest near t = 1
-- (the kinetic energy peaks), then the flow dies away: at t = 3 the kinetic energy is
-- about 1/400 of its peak, H = 0.506 (a slump of about 0.49) and the spread about 2.3
-- (from 1). The last line prints them. A stiffer material slumps less: tau0=0.2 stops near
-- H = 0.61 (spread 1.8). yield.png shows unyielded (dark) patches in the middle of the resting heap.
local sph = require "sph"
local params = require "sph.params"

local o = params.args("slump", {
  { "rho", "number", 1, "density" },
  { "g", "number", 1, "gravity" },
  { "mu", "number", 0.1, "plastic viscosity" },
  { "tau0", "number", 0.1, "yield stress" },
  { "m", "number", 100, "Papanastasiou exponent" },
  { "width", "number", 1, "the column's width" },
  { "height", "number", 1, "the column's height" },
  { "dx", "number", 0.025, "particle spacing" },
  { "t_end", "number", 3, "end time" },
  { "every", "number", 0.25, "output interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/slump", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

-- shifting = 20: the spreading stretches the particle lattice as a squeeze does
-- (docs/limitations.md)
local w = sph.world{ dx = o.dx, rho = o.rho, gravity = { 0, -o.g }, symmetry = { x = 0 }, shifting = 20,
                     threads = o.threads }
w:fill{ rect = { 0, 0, o.width / 2, o.height }, material = sph.bingham{ mu = o.mu, tau0 = o.tau0, m = o.m } }
local T = 3 * o.dx                                         -- 3 dx thick: the kernel's reach
local L = 1.5 * o.width + 2 * o.height                     -- wider than the heap gets
w:plate{ rect = { -L, -T, L, 0 } }                         -- the base plate, fixed

local csv = assert(io.open(o.out .. "/series.csv", "w"))
csv:write("t,H,spread,slump,kinetic_energy\n")
local H, spread, peak = o.height, o.width, 0
local function row(w)
  H = largest(w:field("y"))                  -- the top of the heap
  spread = 2 * largest(w:field("x"))         -- the whole base (mirrored)
  local ke = w:stats().kinetic_energy
  peak = math.max(peak, ke)
  csv:write(string.format("%.6g,%.6g,%.6g,%.6g,%.6g\n", w.t, H, spread, o.height - H, ke))
  print(string.format("t = %.3f  H = %.4f  spread = %.4f  slump = %.4f  kinetic energy = %.3g", w.t, H, spread,
    o.height - H, ke))
end

if o.steps > 0 then                      -- a quick look: N steps, a row each
  row(w)
  for _ = 1, o.steps do w:step(); row(w) end
else                                     -- the run: a row at the start and every `every` (w:run calls row then too)
  w:run{ until_t = o.t_end, every = o.every, each = row }
end
csv:close()

local a = spread / 2 + 0.1
local view = { -a, -T, a, o.height + 0.05 }
assert(w:render{ file = o.out .. "/yield.png", color = "yield", view = view, width = 800,
                 height = math.floor(800 * (view[4] - view[2]) / (view[3] - view[1])) + 40,
                 label = string.format("slump, tau0 / (rho g H) = %.3g", o.tau0 / (o.rho * o.g * o.height)) })
print(string.format("final (t = %g, %d steps): height %.4f, slump %.4f, spread %.4f (from %g); kinetic energy %.2g of its peak",
  w.t, w.steps, H, o.height - H, spread, o.width, peak > 0 and w:stats().kinetic_energy / peak or 0))
print(string.format("wrote %s/series.csv and %s/yield.png", o.out, o.out))
