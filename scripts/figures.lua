-- The README's figures (into docs/): the paper's constant-load squeezes of a Bingham sample
-- (its Figure 5), Bn = 2 and Bn = 5, Re = 1, F = -10 (mode=load F=-10 of squeeze.lua),
-- M = 800, dx = 1/40, to t = 2: yield-state stills (yielded light, unyielded dark; the
-- mirrored half drawn so the whole sample shows), an animated PNG of each, and h(t) of both
-- with the ideal Bingham stop heights (tau0 / 2F)^(1/3).
--   build/sph scripts/figures.lua [dx=0.025] [M=800] [t_end=2] [threads=2] [out=docs]
-- Other parameters: times (comma-separated still times, default 0,0.1,0.5,2; those after
-- t_end are dropped and t_end is added), nanim (animation frames, default 21), width and
-- awidth (still and animation widths in pixels), every (h(t) sampling). About three minutes at
-- the defaults on a 2-core machine.
local sph = require "sph"
local squeeze = require "sph.squeeze"
local o = ... or {}

local dx, M, t_end = o.dx or 1 / 40, o.M or 800, o.t_end or 2
local Re, F, every = 1, -10, o.every or 0.005
local out = o.out or "docs"
local width = math.floor(o.width or 640)
local nanim = math.floor(o.nanim or 21)
local awidth = math.floor(o.awidth or 400) -- animation frames: smaller, the file holds every frame whole
local threads = o.threads
local times = {}
for v in tostring(o.times or "0,0.1,0.5,2"):gmatch("[^,]+") do
  local t = assert(tonumber(v), "times: numbers separated by commas expected")
  if t <= t_end + 1e-12 then times[#times + 1] = t end
end
if times[#times] == nil or times[#times] < t_end - 1e-12 then times[#times + 1] = t_end end
if nanim < 2 then error("nanim: at least 2 frames expected") end

assert(sph.mkdir(out .. "/anim"))
print(string.format("figures: constant load F=%g, Re=%g, Bn=2 and 5, M=%g, dx=%g, t_end=%g -> %s/",
  F, Re, M, dx, t_end, out))

local series = {}
for _, Bn in ipairs{ 2, 5 } do
  local w, top, bottom = squeeze.build{ dx = dx, Re = Re, Bn = Bn, M = M, mode = "load", F = F, h_min = 0.4,
                                        world = { threads = threads } }
  -- one view for every frame: the whole sample (mirrored) at its widest, the first gap
  local b, t = bottom.rect, top.rect
  local half = math.min(b[3], 1.1)
  local pad = 0.02 * (t[4] - b[2])
  local view = { -half, b[2] - pad, half, t[4] + pad }
  local function opts(file, wd)
    return { file = file, width = wd, mirror = true, view = view, colorbar = true, -- the yield legend
             height = math.max(120, math.floor(wd * (view[4] - view[2]) / (view[3] - view[1])) + 40),
             label = string.format("Bn=%g  Re=%g  F=%g  M=%g  dx=%g", Bn, Re, F, M, dx) }
  end
  -- the gap at every output, t = 0 included (each runs at the start of the first run; the
  -- later ones continue the output grid t0 = 0, so no time comes twice)
  local ts, hs = {}, {}
  local stills, anim = {}, {}
  local targets = {} -- every time at which something is drawn, in order
  for _, tk in ipairs(times) do targets[#targets + 1] = { t = tk, still = true } end
  for k = 0, nanim - 1 do targets[#targets + 1] = { t = t_end * k / (nanim - 1), anim = true } end
  table.sort(targets, function(a, c) return a.t < c.t end)
  local wall0 = os.time()
  for _, g in ipairs(targets) do
    if g.t > w.t + 1e-12 then
      w:run{ until_t = g.t, every = every, t0 = 0, each = function(ww) ts[#ts + 1], hs[#hs + 1] = ww.t, top.position end }
    end
    if g.still then
      local f = string.format("%s/load_bn%g_t%04d.png", out, Bn, math.floor(g.t * 1000 + 0.5))
      assert(w:render(opts(f, width)))
      stills[#stills + 1] = f
    end
    if g.anim then
      local f = string.format("%s/anim/bn%g_%03d.png", out, Bn, #anim + 1)
      assert(w:render(opts(f, awidth)))
      anim[#anim + 1] = f
    end
  end
  local afile = string.format("%s/load_bn%g.png", out, Bn)
  assert(sph.animate{ frames = anim, file = afile, fps = 8 })
  for _, f in ipairs(anim) do os.remove(f) end
  local s = w:stats()
  print(string.format("  Bn=%g: %d fluid particles (half sample), %d steps in %.0f s (%d s wall); h(%g) = %.4f " ..
    "(ideal stop %.4f); %d of %d yielded; peak density error %.4f",
    Bn, s.fluid, w.steps, s.wall_time, os.time() - wall0, w.t, top.position, squeeze.stop_height(Bn, -F),
    s.yielded, s.fluid, s.peak_density_error))
  print("  wrote " .. table.concat(stills, " ") .. " " .. afile)
  series[#series + 1] = { x = ts, y = hs, label = string.format("Bn = %g", Bn) }
  local hs_ = squeeze.stop_height(Bn, -F)
  series[#series + 1] = { x = { 0, t_end }, y = { hs_, hs_ }, label = string.format("ideal stop, Bn = %g", Bn) }
end
os.remove(out .. "/anim")

local hfile = out .. "/load_h.png"
assert(sph.plot{ file = hfile, xlabel = "t", ylabel = "h", series = series,
                 title = string.format("constant load F=%g, Re=%g, M=%g, dx=%g", F, Re, M, dx) })
print("  wrote " .. hfile)
