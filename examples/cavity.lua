-- cavity.lua: the lid-driven cavity at Re = 100, against Ghia, Ghia & Shin (1982).
--
-- What it shows: a closed box of Newtonian fluid (a unit square, no-slip walls made of
-- plates) whose lid slides along itself: a plate with slide = {U, 0} carries that surface
-- velocity without moving. The settings that work for a closed box (lua/sph/flows.lua
-- says why): surface = 0 (no free surface to look for), shifting = 20, and
-- density_tol = 0.04 (the time step follows the density error, which sits in the rows
-- sliding along the lid). At the end the script compares the velocity on the centrelines,
-- u(y) at x = 1/2 and v(x) at y = 1/2, with the published Re = 100 profiles, writes them
-- to profiles.csv, and draws the speed, speed.png.
--
--   build/sph examples/cavity.lua [name=value ...]
--
-- Parameters (unit box, lid speed U = 1, rho = 1; Re = U / nu):
--   Re=100               the Reynolds number (mu = 1 / Re); Ghia's table is for Re = 100
--   dx=0.05              the particle spacing (400 particles)
--   t_end=10 every=1     the end time (steady by t = 10) and the progress lines
--   steps=0              N > 0: stop after N steps, whatever t_end (a quick look)
--   threads=0 out=out/cavity   threads (0: all cores) and the output folder
--
-- What you should see (about 2 s): the kinetic energy levelling off near 0.029 as the main
-- vortex spins up; then the two profiles, SPH against Ghia point by point (the largest gap
-- just under the lid), and their RMS difference: about 0.017 U at dx = 0.05, 0.005 U at
-- dx=0.025 (10 s). speed.png shows the fast layer under the lid and the slow centre of the
-- vortex near (0.62, 0.74), where Ghia has it.
local sph = require "sph"
local params = require "sph.params"
local flows = require "sph.flows" -- Ghia's tables and a moving-least-squares probe

local o = params.args("cavity", {
  { "Re", "number", 100, "Reynolds number U L / nu" },
  { "dx", "number", 0.05, "particle spacing" },
  { "t_end", "number", 10, "end time" },
  { "every", "number", 1, "progress interval" },
  { "steps", "integer", 0, "N > 0: stop after N steps" },
  { "threads", "integer", 0, "threads (0: all cores)" },
  { "out", "string", "out/cavity", "output folder" },
}, ...)
assert(sph.mkdir(o.out))

local w = sph.world{ dx = o.dx, rho = 1, shifting = 20, density_tol = 0.04, surface = 0, threads = o.threads }
w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 / o.Re } }
local T = 3 * o.dx                                         -- walls 3 dx thick: the kernel's reach
w:plate{ rect = { -T, -T, 1 + T, 0 } }                     -- bottom
w:plate{ rect = { -T, 0, 0, 1 + T } }                      -- left
w:plate{ rect = { 1, 0, 1 + T, 1 + T } }                   -- right
w:plate{ rect = { 0, 1, 1, 1 + T }, slide = { 1, 0 } }     -- the lid: slides at U = 1, stays put

local function progress(w)
  local s = w:stats()
  print(string.format("t = %5.2f  kinetic energy = %.5f  max density error = %.3g  %d steps", w.t,
    s.kinetic_energy, s.max_density_error, w.steps))
end
if o.steps > 0 then                      -- a quick look: N steps
  for _ = 1, o.steps do w:step() end
  progress(w)
else
  w:run{ until_t = o.t_end, every = o.every, each = progress }
end

-- the centreline profiles at Ghia's points: { position, SPH, Ghia }
local pu, pv = flows.cavity_profiles(w, o.dx)
local csv = assert(io.open(o.out .. "/profiles.csv", "w"))
csv:write("line,position,sph,ghia\n")
local s2, n = 0, 0
print("   u(y) on x = 1/2          v(x) on y = 1/2")
print("   y      SPH     Ghia       x      SPH     Ghia")
for k = 1, math.max(#pu, #pv) do
  local a, b = pu[k], pv[k]
  print(string.format("  %.4f %7.4f %7.4f    %.4f %7.4f %7.4f", a[1], a[2], a[3], b[1], b[2], b[3]))
  csv:write(string.format("u,%g,%.6g,%g\nv,%g,%.6g,%g\n", a[1], a[2], a[3], b[1], b[2], b[3]))
  s2, n = s2 + (a[2] - a[3]) ^ 2 + (b[2] - b[3]) ^ 2, n + 2
end
csv:close()
print(string.format("RMS difference from Ghia et al. (Re = 100): %.4f U  (t = %g, %d steps)%s", math.sqrt(s2 / n),
  w.t, w.steps, o.Re ~= 100 and "  [Re is not 100: the table does not apply]" or ""))
assert(w:render{ file = o.out .. "/speed.png", color = "speed", width = 560, height = 500, label = "speed |u|" })
print(string.format("wrote %s/profiles.csv and %s/speed.png", o.out, o.out))
