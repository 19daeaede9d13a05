-- poiseuille.lua: plane Poiseuille flow, checked against the exact steady profile.
--
-- What it shows: a periodic channel (periodic = {x = {0, Lx}}: what leaves at x = Lx comes
-- back at x = 0) between two fixed plates, driven by a body force g along x (gravity =
-- {g, 0}). From rest the flow develops to the parabola
--   u(y) = g / (2 nu) y (H - y),   nu = mu / rho,   centre speed g H^2 / (8 nu),
-- in a few viscous times H^2 / nu. At the end the script prints the relative L2 error of
-- the particles' u against it and writes profile.csv (y, u, exact) and u.png.
--
--   build/sph examples/poiseuille.lua [name=value ...]
--
-- Parameters (channel height H = 1):
--   g=8 mu=1 rho=1       driving force per unit mass, viscosity, density (centre speed 1)
--   dx=0.05              the particle spacing (20 particles across; the channel is 10 dx long)
--   t_end=1 every=0.1    the end time (the start-up has decayed to 1e-4 of the centre speed
--                        by t = 1 at nu = 1) and the progress lines
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/poiseuille   threads (0: all cores) and the output folder
--
-- What you should see (under a second): the centre speed rising to 1 by t = 0.5 and settling
-- 0.7 % above it; then "relative L2 error ... 0.011" at dx = 0.05 (0.0078 at dx=0.025):
-- the no-slip walls' linear extrapolation is first order. u.png shows the bands of
-- the parabola, fastest in the middle.
local sph = require "sph"
local params = require "sph.params"

local o = params.args("poiseuille", {
  { "g", "number", 8, "body force per unit mass along x" },
  { "mu", "number", 1, "viscosity" },
  { "rho", "number", 1, "density" },
  { "dx", "number", 0.05, "particle spacing" },
  { "t_end", "number", 1, "end time" },
  { "every", "number", 0.1, "progress interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/poiseuille", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

-- the largest value of a field (table.unpack would hit Lua's limit on big runs)
local function largest(t)
  local m = -math.huge
  for _, v in ipairs(t) do m = math.max(m, v) end
  return m
end

local H, Lx = 1, 10 * o.dx
local nu = o.mu / o.rho
local function exact(y) return o.g / (2 * nu) * y * (H - y) end

local w = sph.world{ dx = o.dx, rho = o.rho, gravity = { o.g, 0 }, periodic = { x = { 0, Lx } },
                     threads = o.threads }
w:fill{ rect = { 0, 0, Lx, H }, material = sph.newtonian{ mu = o.mu } }
local T = 3 * o.dx                                         -- walls 3 dx thick: the kernel's reach
w:plate{ rect = { 0, -T, Lx, 0 } }                         -- fixed plates: no-slip walls
w:plate{ rect = { 0, H, Lx, H + T } }

local function progress(w)
  local us = w:field("u")
  print(string.format("t = %.3f  centre speed %.5f (exact steady %.5f)  %d steps", w.t, largest(us),
    exact(H / 2), w.steps))
end
if o.steps > 0 then                      -- a quick look: N steps
  for _ = 1, o.steps do w:step() end
  progress(w)
else
  w:run{ until_t = o.t_end, every = o.every, each = progress }
end

-- the error against the steady parabola, over every particle
local ys, us = w:field("y"), w:field("u")
local num, den = 0, 0
local rows = {}
for i = 1, #ys do
  local e = exact(ys[i])
  num, den = num + (us[i] - e) ^ 2, den + e * e
  rows[i] = { ys[i], us[i], e }
end
table.sort(rows, function(a, b) return a[1] < b[1] end)
local csv = assert(io.open(o.out .. "/profile.csv", "w"))
csv:write("y,u,exact\n")
for _, r in ipairs(rows) do csv:write(string.format("%.6g,%.6g,%.6g\n", r[1], r[2], r[3])) end
csv:close()
print(string.format("relative L2 error of u against the steady profile: %.5f  (dx = %g, t = %g)", math.sqrt(num / den),
  o.dx, w.t))
assert(w:render{ file = o.out .. "/u.png", color = "u", width = 300, height = 500, label = "u" })
print(string.format("wrote %s/profile.csv and %s/u.png", o.out, o.out))
