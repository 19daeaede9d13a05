-- squeeze_velocity.lua: a Bingham square squeezed between two plates at constant speed.
--
-- What it shows: a squeeze case built from scratch. Only the right half of the sample is
-- simulated: x = 0 is a mirror (symmetry = {x = 0}), and forces are the whole sample's.
-- The lower plate is fixed, the upper one moves down at the speed V. Every `every` the
-- script writes a row t, h (the gap), F (the fluid's force on the upper plate) to
-- series.csv; at the end a yield-state picture, yield.png (yielded light, unyielded dark,
-- drawn mirrored).
--
--   build/sph examples/squeeze_velocity.lua [name=value ...]
--
-- Parameters, in the paper's scaling (H = U = mu = 1, so rho = Re, tau0 = Bn, m = M):
--   Re=10 Bn=0.5 M=100   the Reynolds and Bingham numbers, the Papanastasiou exponent
--   V=1                  the plate speed
--   dx=0.025             the particle spacing (1/40: 800 particles in the half sample)
--   t_end=0.4 every=0.02 the end time (the gap goes from 1 to 1 - V t_end) and the rows
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/squeeze_velocity   threads (0: all cores) and the output folder
--
-- What you should see (about 1 s): one line a row, the gap falling by 0.02 a row; the
-- force jumps to about 22 at the start, eases to about 16 by h = 0.85, then grows as the
-- gap thins, to about 45 at h = 0.6 (a Bingham sample resists more the thinner it is).
-- The last line says how many particles are yielded: all of them, where the
-- finite-element reference has an unyielded core (docs/limitations.md: the Bingham force
-- is about 0.6 of the reference today).
local sph = require "sph"
local params = require "sph.params"

local o = params.args("squeeze_velocity", {
  { "Re", "number", 10, "Reynolds number (the density)" },
  { "Bn", "number", 0.5, "Bingham number (the yield stress)" },
  { "M", "number", 100, "Papanastasiou exponent" },
  { "V", "number", 1, "plate speed" },
  { "dx", "number", 0.025, "particle spacing" },
  { "t_end", "number", 0.4, "end time" },
  { "every", "number", 0.02, "output interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/squeeze_velocity", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

-- The world: shifting = 20 keeps the particles evenly spread as the sample is stretched
-- sideways (without it the run fails near h = 0.5: docs/limitations.md).
local w = sph.world{ dx = o.dx, rho = o.Re, symmetry = { x = 0 }, shifting = 20, threads = o.threads }
local dough = sph.bingham{ mu = 1, tau0 = o.Bn, m = o.M }
w:fill{ rect = { 0, 0, 0.5, 1 }, material = dough }      -- the right half of the unit square

-- Plates 3 dx thick (the kernel's reach), wide enough for the sample spread down to h = 0.25.
local T = 3 * o.dx
w:plate{ rect = { -2, -T, 2, 0 } }                         -- lower plate: no axis, fixed
local top = w:plate{ rect = { -2, 1, 2, 1 + T }, axis = "y" }
top:velocity(-o.V)                                        -- moves down at V

local csv = assert(io.open(o.out .. "/series.csv", "w"))
csv:write("t,h,F\n")
local function row(w)
  csv:write(string.format("%.6g,%.6g,%.6g\n", w.t, top.position, top.force))
  print(string.format("t = %.3f  h = %.4f  F = %8.3f", w.t, top.position, top.force))
end

if o.steps > 0 then                      -- a quick look: N steps, a row each
  row(w)
  for _ = 1, o.steps do w:step(); row(w) end
else                                     -- the run: a row at the start and every `every` (w:run calls row then too), landing on those times
  w:run{ until_t = o.t_end, every = o.every, each = row }
end
csv:close()

-- The picture: cropped to the sample and the plates' faces (drawn mirrored about x = 0).
local a = 0.1 + largest(w:field("x"))
local view = { -a, -T, a, top.position + T }
assert(w:render{ file = o.out .. "/yield.png", color = "yield", view = view, width = 800,
                 height = math.floor(800 * (view[4] - view[2]) / (view[3] - view[1])) + 40,
                 label = string.format("Bingham, Bn = %g, h = %.3f", o.Bn, top.position) })
local s = w:stats()
print(string.format("%d steps; %d of %d particles yielded; wrote %s/series.csv and %s/yield.png",
  w.steps, s.yielded, s.fluid, o.out, o.out))
