-- The stability suite's cases and checks (issue 3), shared by scripts/stability.lua (each
-- case to its end, `make stability`) and tests/lua/test_stability.lua (the reduced
-- versions). A case passes when it finishes with no NaN and no particle through a plate
-- (the engine stops with a message on either), a max density error under 1 % at every
-- step, and, under a constant load, a plate that never moves back up by more than a
-- particle spacing. The free surface is checked too (surface_check): no particle inside the
-- sample taken for free surface, none on its outer edge missed.
local squeeze = require "sph.squeeze"

local S = {}

S.cases = {
  -- the paper's load relative to the yield stress (F = -2 tau0, as F = -10 at Bn = 5):
  -- the ideal Bingham sample stops at h = (tau0 / 2F)^(1/3) = 0.63 whatever Bn
  { name = "Bn=100 load", mode = "load", Re = 1, Bn = 100, M = 800, F = -200, t_end = 1 },
  { name = "M=1e4 Bn=5", mode = "velocity", Re = 1, Bn = 5, M = 1e4, t_end = 0.4 },
  { name = "Re=0.01", mode = "velocity", Re = 0.01, Bn = 0, t_end = 0.4 },
  { name = "Re=1000", mode = "velocity", Re = 1000, Bn = 0, t_end = 0.4 },
  { name = "thin film h=0.15", mode = "velocity", Re = 1, Bn = 0, t_end = 0.86, h_stop = 0.15, h_min = 0.15 },
  { name = "paper Bn=5 F*=-10", mode = "load", Re = 1, Bn = 5, M = 800, F = -10, t_end = 2 },
}

function S.find(name)
  for _, c in ipairs(S.cases) do
    if c.name == name then return c end
  end
  error("no stability case named '" .. tostring(name) .. "'")
end

-- Free-surface flags against the sample's outline (its body's: droplets thrown off do not
-- count), in rows of height dx. A surface particle more than 3 dx inside the outermost
-- particle of its row and the two rows beside it is false ("inside") when it is also
-- enclosed: no opening of 60 degrees or more around it, among the particles within 1.6 dx
-- and a plate's wall row within 1.5 dx (a Re = 1000 start throws a sheet off the upper
-- contact line whose underside, 3 dx and more inside the sheet's tip, is rightly free
-- surface, and not enclosed). The engine flags a particle off the bulk when the 60-degree
-- cone around its normal holds no fluid particle within 2 dx and no wall within 1.7 dx
-- (src/surface.c): the check's radii are below the engine's, so that round-off does not
-- decide between them. The opening is measured as the largest angle between neighbours
-- (sectors of 45 degrees would call enclosed an opening of up to 90 degrees), and the wall
-- row within 1.5 dx only, so that it fills no direction the engine's wall particles (dx
-- apart) leave open. Within dx of a plate's face
-- the outline is the contact line, the outermost body particle touching that face (within
-- 0.75 dx of it: a first row sits at 0.5 dx), not the rows beside it. The front of a
-- squeezed film is a fountain flow: ahead of the contact line its underside runs 0.8-1.3 dx
-- off the plate over a wedge of void thinner than a particle for 3-4 dx, and the rows
-- beside reach 2-4 dx further out; the particles bordering that wedge are rightly free
-- surface, and the 1.6 dx enclosure test does not resolve the wedge.
-- The outermost particle of a row not flagged is "missing" when it
-- is exposed, i.e. no fluid particle lies in the 90-degree cone facing outwards (+x) within
-- 2.1 dx of it (a particle with a surface particle diagonally in front of it, 0.8 dx away,
-- is the second layer, not the edge). The radius is beyond the engine's cone (2 dx), as
-- the enclosure's is inside it, for the same reason;
-- rows that touch a plate (within dx of its face: the contact line, whose particles have
-- the wall in their support and are held by it, not at p = 0) are not checked. The half
-- sample's other sides are the symmetry plane and the plates, with no free surface.
-- Returns the counts inside and missing and the lists of the inside particles' and of the
-- missing ones' indices.
-- The sample's outline in rows of height dx: the fields x, y, surface, the particles by
-- cell (cells, key) and outer[r], the outermost x of row r. The outline is the body's, not
-- the spray's: a particle with fewer than 3 others within 1.5 dx (a droplet thrown off the
-- contact line, as at Re = 1000) does not set it.
local function outline(w, dx)
  local x, y, s = w:field("x"), w:field("y"), w:field("surface")
  local cells = {}
  local function key(i, j) return i * 1000003 + j end
  for k = 1, #x do
    local c = key(math.floor(x[k] / dx), math.floor(y[k] / dx))
    local l = cells[c]
    if not l then l = {}; cells[c] = l end
    l[#l + 1] = k
  end
  local r2 = (1.5 * dx) ^ 2
  local function body(k)
    local ci, cj, n = math.floor(x[k] / dx), math.floor(y[k] / dx), 0
    for i = ci - 2, ci + 2 do
      for j = cj - 2, cj + 2 do
        for _, q in ipairs(cells[key(i, j)] or {}) do
          if q ~= k and (x[q] - x[k]) ^ 2 + (y[q] - y[k]) ^ 2 < r2 then n = n + 1 end
        end
      end
    end
    return n >= 3
  end
  local outer = {}
  for k = 1, #x do
    local r = math.floor(y[k] / dx)
    if (not outer[r] or x[k] > outer[r]) and body(k) then outer[r] = x[k] end
  end
  return x, y, s, cells, key, outer, body
end

-- x of the outermost particle of row r and the rows beside it
local function far_of(outer, r)
  return math.max(outer[r - 1] or -math.huge, outer[r] or -math.huge, outer[r + 1] or -math.huge)
end

function S.surface_check(w, dx, y_lo, y_hi)
  local x, y, s, cells, key, outer, body = outline(w, dx)
  -- a surface particle is "inside" when it is enclosed: no opening of 60 degrees or more
  -- around it, among the other particles within 1.6 dx and the plates (each as its wall row,
  -- 0.5 dx beyond its face, sampled every 0.25 dx) within 1.5 dx
  local R2, RW = (1.6 * dx) ^ 2, 1.5 * dx
  local function enclosed(k)
    local ang = {}
    local function see(ax, ay, r2max)
      local r2 = ax * ax + ay * ay
      if r2 < r2max and r2 > 0 then ang[#ang + 1] = math.atan(ay, ax) end
    end
    local ci, cj = math.floor(x[k] / dx), math.floor(y[k] / dx)
    for i = ci - 2, ci + 2 do
      for j = cj - 2, cj + 2 do
        for _, q in ipairs(cells[key(i, j)] or {}) do
          if q ~= k then see(x[q] - x[k], y[q] - y[k], R2) end
        end
      end
    end
    for _, yw in ipairs{ y_lo - 0.5 * dx, y_hi + 0.5 * dx } do
      if math.abs(yw - y[k]) < RW then
        for j = -8, 8 do see(j * 0.25 * dx, yw - y[k], RW * RW) end
      end
    end
    if #ang < 2 then return false end
    table.sort(ang)
    local gap = ang[1] + 2 * math.pi - ang[#ang]
    for m = 2, #ang do gap = math.max(gap, ang[m] - ang[m - 1]) end
    return gap < math.pi / 3
  end
  -- next to a plate (within dx of its face) the outline is the contact line: the outermost
  -- body particle touching that face (within 0.75 dx of it; none: the rows' outline)
  local contact = { -math.huge, -math.huge }
  for k = 1, #x do
    local side = (y[k] < y_lo + 0.75 * dx and 1) or (y[k] > y_hi - 0.75 * dx and 2)
    if side and x[k] > contact[side] and body(k) then contact[side] = x[k] end
  end
  local inside, missing, list, mlist = 0, 0, {}, {}
  for k = 1, #x do
    local r = math.floor(y[k] / dx)
    local far = far_of(outer, r)
    if y[k] < y_lo + dx and contact[1] > -math.huge then far = contact[1]
    elseif y[k] > y_hi - dx and contact[2] > -math.huge then far = contact[2] end
    if s[k] == 1 and x[k] < far - 3 * dx and enclosed(k) then inside = inside + 1; list[#list + 1] = k end
    if s[k] == 0 and outer[r] and x[k] >= outer[r] and y[k] > y_lo + dx and y[k] < y_hi - dx then
      local exposed = true
      for q = 1, #x do
        local ax, ay = x[q] - x[k], math.abs(y[q] - y[k])
        if q ~= k and ax > ay and ax * ax + ay * ay < (2.1 * dx) ^ 2 then exposed = false break end
      end
      if exposed then missing = missing + 1; mlist[#mlist + 1] = k end
    end
  end
  return inside, missing, list, mlist
end

-- Free-surface flags deep inside the sample, enclosed or not: more than 3 dx inside the
-- outline (surface_check's) and more than 3 dx from the plates at y_lo and y_hi. Returns
-- their count.
function S.flags_inside(w, dx, y_lo, y_hi)
  local x, y, s, _, _, outer = outline(w, dx)
  local deep = 0
  for k = 1, #x do
    if s[k] == 1 and x[k] < far_of(outer, math.floor(y[k] / dx)) - 3 * dx and y[k] > y_lo + 3 * dx and
       y[k] < y_hi - 3 * dx then
      deep = deep + 1
    end
  end
  return deep
end

-- Runs case c to t_end (default c.t_end); opts: dx (default 1/40), threads, world (more
-- sph.world options), check_every (steps between surface checks, default 5). Returns a
-- table: ok, err (the engine's message), t, steps, wall, p_iter and v_iter (per step),
-- emax (largest max density error of any step), h, backup (largest rise of a loaded plate
-- above its lowest position), inside and missing (the surface checks' worst counts), why
-- (the list of failed criteria) and pass.
function S.run(c, t_end, opts)
  opts = opts or {}
  t_end = t_end or c.t_end
  local dx = opts.dx or 1 / 40
  local wopts = { threads = opts.threads }
  for k, v in pairs(opts.world or {}) do wopts[k] = v end
  local w, top = squeeze.build{ dx = dx, Re = c.Re, Bn = c.Bn, M = c.M, mode = c.mode, F = c.F,
                                h_min = c.h_min or 0.3, world = wopts }
  local every = opts.check_every or 5
  local hmin, backup, inside, missing = top.position, 0, 0, 0
  local ok, err = pcall(function()
    while w.t < t_end - 1e-12 do
      w:step()
      local h = top.position
      hmin = math.min(hmin, h)
      backup = math.max(backup, h - hmin)
      if w.steps % every == 0 then
        local a, b = S.surface_check(w, dx, 0, h)
        inside, missing = math.max(inside, a), math.max(missing, b)
      end
      if c.h_stop and h <= c.h_stop then break end
    end
  end)
  local s = w:stats()
  local r = { ok = ok, err = not ok and tostring(err) or nil, t = w.t, steps = w.steps, wall = s.wall_time,
              p_iter = w.steps > 0 and s.solver_iterations_total / w.steps or 0,
              v_iter = w.steps > 0 and s.visc_iterations_total / w.steps or 0,
              emax = s.peak_density_error, h = top.position, backup = backup,
              inside = inside, missing = missing, why = {} }
  if not ok then r.why[#r.why + 1] = r.err end
  if r.emax >= 0.01 then r.why[#r.why + 1] = string.format("density error %.4f >= 1 %%", r.emax) end
  if c.mode == "load" and backup > dx then
    r.why[#r.why + 1] = string.format("plate moved back up %.4f > dx", backup)
  end
  if c.h_stop and ok and t_end >= c.t_end and top.position > c.h_stop + 1e-9 then
    r.why[#r.why + 1] = string.format("did not reach h = %g", c.h_stop)
  end
  if inside > 0 then r.why[#r.why + 1] = string.format("%d particles inside taken for free surface", inside) end
  if missing > 0 then r.why[#r.why + 1] = string.format("%d edge particles not taken for free surface", missing) end
  r.pass = #r.why == 0
  return r
end

return S
