-- The square at t = 0+ against the finite-element fields of ../shared/reference-fields/
-- (REFERENCES.md section 1): u, v, p, gammadot and the yield state at the FE grid points,
-- by region, so that one can see where a field goes wrong, not only the plate force.
--   build/sph scripts/compare_fields.lua [Bn=10] [n=40] [t=0.005] [threads=1] [lines=1] [plate=1] [dt_max=]
--     [ref=../shared/reference-fields]
-- lines=1 also prints the fields along x = 0 and y = 0.5 (or liney=, every 0.05), SPH / FE; plate=1 the
-- traction along the top plate (at its end).
-- An SPH value at a grid point is the linear moving-least-squares fit of the fluid
-- particles within 3 h (sph.flows.mls); grid points within dx / 2 of a plate or of the free side are left
-- out (no particle is there). The SPH sample has moved by t (plate speed 1): the grid is
-- compared as it is, at h = 1 - t; keep t small.
local flows = require "sph.flows"
local opt = ... or {}
local Bn, n, T = opt.Bn or 10, opt.n or 40, opt.t or 0.005
local refdir = opt.ref or "../shared/reference-fields"
local file = refdir .. (Bn == 0 and "/square_newtonian_grid.csv" or "/square_bn10_grid.csv")
if Bn ~= 0 and Bn ~= 10 then error("compare_fields: FE fields exist for Bn = 0 and 10 only") end

-- The rows of a reference CSV: `#` comment lines, a header line, numbers; each row a table
-- keyed by the header's names.
local function read_csv(path)
  local rows, header = {}, nil
  local f = assert(io.open(path))
  for line in f:lines() do
    if not line:match("^#") then
      if not header then
        header = {}
        for name in line:gmatch("[^,]+") do header[#header + 1] = name end
      else
        local r, k = {}, 0
        for v in line:gmatch("[^,]+") do k = k + 1; r[header[k]] = tonumber(v) end
        rows[#rows + 1] = r
      end
    end
  end
  f:close()
  return rows
end
local ref = read_csv(file)

local dx = 1 / n
local w, top = require("sph.squeeze_validation").square_world(n, Bn, { threads = opt.threads, dt_max = opt.dt_max })
w:run{ until_t = T }

local F = {}
for _, name in ipairs({ "x", "y", "u", "v", "p", "gammadot", "stress", "yielded" }) do F[name] = w:field(name) end
-- the particles and their mirror images across x = 0 within the fit's reach (u odd, the
-- rest even), so that points near the symmetry plane are fitted from both sides
local r = 3 * w.h
local M = {}
for _, f in ipairs({ "x", "y", "u", "v", "p", "gammadot", "stress" }) do
  M[f] = {}
  for k = 1, #F.x do M[f][k] = F[f][k] end
end
for k = 1, #F.x do
  if F.x[k] < r then
    local j = #M.x + 1
    for _, f in ipairs({ "y", "v", "p", "gammadot", "stress" }) do M[f][j] = F[f][k] end
    M.x[j], M.u[j] = -F.x[k], -F.u[k]
  end
end
-- the fields at (x, y) by the linear moving-least-squares fit of sph.flows (the one the
-- cavity's profiles use: first-order consistent next to the plates and the free side)
local function sample(x, y)
  local s = {}
  for _, f in ipairs({ "u", "v", "p", "gammadot", "stress" }) do s[f] = flows.mls(M.x, M.y, M[f], x, y, r) end
  return s
end

local hnow = top.position
local regions = { "interior", "free side", "plates" }
local stats = {}
for _, r in ipairs(regions) do stats[r] = { n = 0, u = 0, v = 0, p = 0, g = 0, pmax = 0, gmax = 0 } end
local un_sph, un_fe, agree, total = 0, 0, 0, 0
for _, r in ipairs(ref) do
  local y = r.y * hnow -- the FE square mapped onto the SPH gap
  if r.x <= 0.5 - dx / 2 and y >= dx / 2 and y <= hnow - dx / 2 then
    local s = sample(r.x, y)
    do
      local reg = (r.x > 0.5 - 3 * dx) and "free side" or ((y < 3 * dx or y > hnow - 3 * dx) and "plates" or "interior")
      local st = stats[reg]
      st.n = st.n + 1
      st.u = st.u + (s.u - r.u) ^ 2
      st.v = st.v + (s.v - r.v) ^ 2
      st.p = st.p + (s.p - r.p) ^ 2
      st.g = st.g + (s.gammadot - r.gammadot) ^ 2
      st.pmax = math.max(st.pmax, math.abs(s.p - r.p))
      st.gmax = math.max(st.gmax, math.abs(s.gammadot - r.gammadot))
      if Bn > 0 then
        local ys = s.stress > Bn and 1 or 0
        total = total + 1
        un_sph = un_sph + (1 - ys)
        un_fe = un_fe + (1 - r.yielded)
        if ys == r.yielded then agree = agree + 1 end
      end
    end
  end
end
print(("square Bn = %g, dx = 1/%d, t = %g (h = %.4f), plate force %.4f"):format(Bn, n, w.t, hnow, -top.force))
print("region      points  rms u    rms v    rms p    max p    rms gd   max gd")
for _, reg in ipairs(regions) do
  local st = stats[reg]
  local m = math.max(st.n, 1)
  print(("%-10s %6d  %.4f   %.4f   %.4f   %.4f   %.4f   %.4f"):format(reg, st.n, math.sqrt(st.u / m), math.sqrt(st.v / m),
    math.sqrt(st.p / m), st.pmax, math.sqrt(st.g / m), st.gmax))
end
if Bn > 0 then
  print(("unyielded share of the grid points: SPH (fitted stress) %.3f, FE %.3f; yield flags agree at %.1f %%"):format(
    un_sph / total, un_fe / total, 100 * agree / total))
  local y = F.yielded
  local u = 0
  for k = 1, #y do if y[k] < 0.5 then u = u + 1 end end
  print(("unyielded particles (the engine's yielded field): %d of %d (%.3f)"):format(u, #y, u / #y))
end
if opt.lines then
  for _, r in ipairs(ref) do
    local y = r.y * hnow
    if (math.abs(r.x - 0) < 1e-9 or math.abs(r.y - (opt.liney or 0.5)) < 1e-9) and (math.floor(r.x * 80 + 0.5) % 4 == 0) and (math.floor(r.y * 80 + 0.5) % 4 == 0) and y >= dx / 2 and y <= hnow - dx / 2 and r.x <= 0.5 - dx/2 then
      local s = sample(r.x, y)
      do print(("x %.3f y %.3f  u %.4f/%.4f v %.4f/%.4f p %.3f/%.3f gd %.3f/%.3f tau %.2f/%.2f"):format(r.x, r.y, s.u, r.u, s.v, r.v, s.p, r.p, s.gammadot, r.gammadot, s.stress, r.tau)) end
    end
  end
end
-- plate=1: the traction on the top plate along x, SPH / FE. On a no-slip plate du/dx = 0, so
-- dv/dy = 0 and -sigma_yy = p: the SPH value is the fluid pressure's linear MLS fit
-- extrapolated to the plate face. 2 * the trapezoid integral over x <= 0.5 - dx / 2 of each
-- says where along the plate the force is carried (the FE file is graded toward the corner).
if opt.plate then
  local plate = read_csv(refdir .. (Bn == 0 and "/square_newtonian_plate.csv" or "/square_bn10_plate.csv"))
  local xmax = 0.5 - dx / 2
  local isph, ife, ife_all, prev = 0, 0, 0, nil
  print("top plate: x, -sigma_yy SPH (fluid p extrapolated to the face) / FE")
  for k, row in ipairs(plate) do
    local x = row.x
    local cur = { x = x, fe = row["-sigma_yy"], sph = x <= xmax and flows.mls(M.x, M.y, M.p, x, hnow, r) or nil }
    if prev then
      local dxk = cur.x - prev.x
      ife_all = ife_all + dxk * (cur.fe + prev.fe)
      if cur.sph then
        isph, ife = isph + dxk * (cur.sph + prev.sph), ife + dxk * (cur.fe + prev.fe)
      end
    end
    if cur.sph and k % 10 == 1 then print(("x %.4f  %.3f / %.3f"):format(x, cur.sph, cur.fe)) end
    prev = cur
  end
  print(("force over x <= %.4f: SPH %.4f, FE %.4f (FE over the whole plate %.4f); engine's plate force %.4f"):format(
    xmax, isph, ife, ife_all, -top.force))
end
