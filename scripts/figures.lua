-- The README's figures (into docs/): the paper's Figure-5-style constant-load squeezes of a
-- Bingham sample, Bn = 2 and Bn = 5, Re = 1, F = -10 (mode=load F=-10 of squeeze.lua), as
-- yield-state frames (yielded light, unyielded dark) at a few times, and h(t) of both.
--   build/sph scripts/figures.lua [dx=0.05] [M=20] [t_end=0.5] [threads=1] [out=docs]
-- Parameters: dx, M (Papanastasiou exponent), t_end, times (comma-separated frame times,
-- default 0,0.05,0.15,0.5; those after t_end are dropped and t_end is added), every (h(t)
-- sampling), width (frame width in pixels), threads, out (folder).
-- The engine's viscosity is explicit for now: dt ~ rho h^2 / (tau0 M), so the cost grows
-- like Bn M / dx^4. The defaults finish in minutes; the paper's M = 800 at dx = 1/40 does not.
local sph = require "sph"
local squeeze = require "sph.squeeze"
local o = ... or {}

local dx, M, t_end = o.dx or 1 / 20, o.M or 20, o.t_end or 0.5
local Re, F, every = 1, -10, o.every or 0.005
local out = o.out or "docs"
local width = math.floor(o.width or 640)
local threads = o.threads or 1 -- small worlds: one thread beats waiting for a busy second
local times = {}
for v in tostring(o.times or "0,0.05,0.15,0.5"):gmatch("[^,]+") do
  local t = assert(tonumber(v), "times: numbers separated by commas expected")
  if t <= t_end + 1e-12 then times[#times + 1] = t end
end
if times[#times] == nil or times[#times] < t_end - 1e-12 then times[#times + 1] = t_end end

os.execute("mkdir -p '" .. out .. "'")
print(string.format("figures: constant load F=%g, Re=%g, Bn=2 and 5, M=%g, dx=%g, t_end=%g, threads=%d -> %s/",
  F, Re, M, dx, t_end, threads, out))

local series = {}
for _, Bn in ipairs{ 2, 5 } do
  local w, top, bottom = squeeze.build{ dx = dx, Re = Re, Bn = Bn, M = M, mode = "load", F = F, h_min = 0.4,
                                        world = { threads = threads } }
  local b, t = bottom.rect, top.rect -- one view for every frame: the plates' width, the first gap
  local pad = 0.02 * (t[4] - b[2])
  local view = { b[1], b[2] - pad, b[3], t[4] + pad }
  local ropts = { width = width, height = math.max(120, math.floor(width * (view[4] - view[2]) / (view[3] - view[1])) + 40),
                  view = view, label = string.format("Bn=%g  Re=%g  F=%g  M=%g  dx=%g", Bn, Re, F, M, dx) }
  local ts, hs = { 0 }, { top.position }
  local function record(w)
    ts[#ts + 1], hs[#hs + 1] = w.t, top.position
  end
  local files = {}
  for _, tk in ipairs(times) do
    if tk > w.t then w:run{ until_t = tk, every = every, each = record } end
    ropts.file = string.format("%s/load_bn%g_t%04d.png", out, Bn, math.floor(tk * 1000 + 0.5))
    assert(w:render(ropts))
    files[#files + 1] = ropts.file
  end
  local s = w:stats()
  print(string.format("  Bn=%g: %d fluid particles (half sample), %d steps (dt=%.3g) in %.1f s; h(%g)=%.4f; %d of %d yielded",
    Bn, s.fluid, w.steps, w.dt, s.wall_time, w.t, top.position, s.yielded, s.fluid))
  print("  wrote " .. table.concat(files, " "))
  series[#series + 1] = { x = ts, y = hs, label = string.format("Bn = %g", Bn) }
end

local hfile = out .. "/load_h.png"
assert(sph.plot{ file = hfile, xlabel = "t", ylabel = "h", series = series,
                 title = string.format("constant load F=%g, Re=%g, M=%g, dx=%g", F, Re, M, dx) })
print("  wrote " .. hfile)
