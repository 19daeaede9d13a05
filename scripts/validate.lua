-- make validate: the engine against the independent references of ../shared/REFERENCES.md.
-- Section 1, the square at t = 0+ (creeping flow, V = -1, Re = 0.05): the plate force over
-- the finite-element (FE) force at the current gap, at three resolutions, with the observed
-- order of the error, and the unyielded area fraction. Writes docs/validation.md and
-- docs/validation_square.png.
--   build/sph scripts/validate.lua [n=20,40,80] [out=docs]
local sph = require "sph"
local opt = ... or {}
local out = opt.out or "docs"
local ns = {}
for v in tostring(opt.n or "20,40,80"):gmatch("[^,]+") do ns[#ns + 1] = tonumber(v) end

-- REFERENCES.md section 1: F_v at h = 1 and of the rectangle of the same area at h = 0.8
-- (ln F close to linear in ln h between them: the reference at the current gap), and the
-- unyielded area fraction at h = 1 (FE, not mesh-converged at Bn = 10: 0.11-0.13).
local REF = {
  { Bn = 0, f1 = 5.2493, f8 = 10.2585, unyielded = 0 },
  { Bn = 10, f1 = 26.806, f8 = 40.556, unyielded = 0.12 },
  { Bn = 1000, f1 = 2023, f8 = 2796.0, unyielded = 0.50 },
}

-- mean F / F_FE(h) over t in (0.005, 0.02), after the impulsive start's transient
local function square(c, n)
  local dx = 1 / n
  local w = sph.world{ dx = dx, rho = 0.05, symmetry = { x = 0 } }
  local mat = c.Bn == 0 and sph.newtonian{ mu = 1 } or sph.bingham{ mu = 1, tau0 = c.Bn, m = 800 }
  w:fill{ rect = {0, 0, 0.5, 1}, material = mat }
  w:plate{ rect = {-3, -5 * dx, 3, 0} }
  local top = w:plate{ rect = {-3, 1, 3, 1 + 5 * dx}, axis = "y" }
  top:velocity(-1)
  local k = math.log(c.f8 / c.f1) / -math.log(0.8)
  local s, m = 0, 0
  while w.t < 0.02 do
    w:step()
    if w.t > 0.005 then s = s + math.abs(top.force) / (c.f1 * top.position ^ -k); m = m + 1 end
  end
  local y, un = w:field("yielded"), 0
  for i = 1, #y do if y[i] < 0.5 then un = un + 1 end end
  return { ratio = s / m, unyielded = un / #y, steps = w.steps, cpu = w:stats().wall_time, particles = #y }
end

local rows, series = {}, {}
for _, c in ipairs(REF) do
  local xs, es = {}, {}
  for _, n in ipairs(ns) do
    local ok, r = pcall(square, c, n)
    local row = { Bn = c.Bn, n = n, ok = ok, r = r, ref_un = c.unyielded }
    if ok then
      row.err = math.abs(r.ratio - 1)
      xs[#xs + 1], es[#es + 1] = 1 / n, row.err
      io.write(("square Bn = %g, dx = 1/%d: F / F_FE = %.4f (error %.4f), unyielded %.3f (FE %.2f), %d steps, %.1f s\n")
        :format(c.Bn, n, r.ratio, row.err, r.unyielded, c.unyielded, r.steps, r.cpu))
    else
      io.write(("square Bn = %g, dx = 1/%d: failed: %s\n"):format(c.Bn, n, tostring(r)))
    end
    rows[#rows + 1] = row
  end
  for i = 2, #xs do
    local p = math.log(es[i - 1] / es[i]) / math.log(xs[i - 1] / xs[i])
    io.write(("  observed order 1/%d -> 1/%d: %.2f\n"):format(math.floor(1 / xs[i - 1] + 0.5), math.floor(1 / xs[i] + 0.5), p))
    rows[#rows].orders = (rows[#rows].orders or "") .. ("%.2f "):format(p)
  end
  if #xs > 0 then series[#series + 1] = { x = xs, y = es, label = ("Bn = %g"):format(c.Bn) } end
end

local md = assert(io.open(out .. "/validation.md.tmp", "w"))
md:write("# Validation against independent references\n\n",
  "Made by `make validate` (`scripts/validate.lua`); references in `../shared/REFERENCES.md`.\n\n",
  "## The square at t = 0+ (section 1)\n\n",
  "Half square 2a = H = 1, symmetry plane x = 0, V = -1, Re = 0.05, M = 800, default options; ",
  "F / F_FE is the mean over t in (0.005, 0.02) of the plate force over the FE force at the current gap.\n\n",
  "| Bn | dx | F / F_FE | error | observed order | unyielded fraction (FE) | steps | s |\n|---|---|---|---|---|---|---|---|\n")
for _, r in ipairs(rows) do
  if r.ok then
    md:write(("| %g | 1/%d | %.4f | %.4f | %s | %.3f (%.2f) | %d | %.1f |\n"):format(r.Bn, r.n, r.r.ratio, r.err,
      r.orders or "", r.r.unyielded, r.ref_un, r.r.steps, r.r.cpu))
  else
    md:write(("| %g | 1/%d | failed | | | | | |\n"):format(r.Bn, r.n))
  end
end
md:write("\n![error against dx](validation_square.png)\n")
md:close()
assert(os.rename(out .. "/validation.md.tmp", out .. "/validation.md"))
if #series > 0 then
  sph.plot{ file = out .. "/validation_square.png", xlabel = "dx", ylabel = "|F / F_FE - 1|", log = "xy", series = series }
end
print("wrote " .. out .. "/validation.md")
