-- The plane-strain references of REFERENCES.md that the scripts compare with (make
-- validate, make paper): whole-sample forces on the square 2a = H = 1 squeezed at V = -1,
-- mu = 1, in mu V units per unit depth.
local R = {}

-- The gaps h of the tables: the rectangle of the same area (1) at gap h.
R.HS = { 1, 0.8, 0.6, 0.5, 0.4, 0.3 }
-- Section 1: FE creeping force F_v(h) by Bn (Bn = 1000: h = 1 and 0.8 only).
R.FV = { [0] = { 5.2493, 10.2585, 32.013, 77.721, 261.59, 1386.6 },
         [10] = { 26.806, 40.556, 84.006, 156.13, 398.24, 1684.6 },
         [1000] = { 2023, 2796.0 } }
-- Section 3: the rigid-plastic limit load F_tau,y(h) over tau0 H (FE, +-0.5 %).
R.FTY = { 2.015, 2.762, 4.82, 7.06, 11.70, 23.7 }

-- Piecewise log-log interpolation of a table over R.HS (nil outside it or past its end).
function R.interp(tab, h)
  local HS = R.HS
  if h > HS[1] + 1e-9 or h < HS[#HS] - 1e-9 then return nil end
  for k = 1, #HS - 1 do
    if h <= HS[k] + 1e-9 and h >= HS[k + 1] - 1e-9 then
      if not tab[k + 1] then return nil end
      local s = math.log(tab[k + 1] / tab[k]) / math.log(HS[k + 1] / HS[k])
      return tab[k] * (h / HS[k]) ^ s
    end
  end
end

-- Section 2: FE over lubrication (8 mu V a^3 / h^3) for a rectangle of half-width a and gap h,
-- by aspect ratio a / h.
R.AR = { 0.5, 0.78, 1.39, 2, 3.13, 5, 5.56, 10 }
R.FE_LUB = { 5.25, 2.69, 1.49, 1.216, 1.071, 1.017, 1.011, 0.997 }

-- Section 2's fit to that table for a / h >= 2: 1 - 0.151 (h/a) + 1.17 (h/a)^2.
function R.film_fit(h, a)
  local r = h / a
  return 1 - 0.151 * r + 1.17 * r * r
end

-- Section 2's quasi-steady inertia factor, first order in Re h: 1 + (17/70) Re h.
function R.inertia(Re, h) return 1 + 17 / 70 * Re * h end

-- The creeping Newtonian force of a rectangle of half-width a and gap h at V = 1 (whole sample,
-- mu = 1): lubrication times FE's ratio, log-log between the table's aspect ratios, the fit
-- past a / h = 10; nil below a / h = 0.5. Exact for a rectangle whatever its aspect: the
-- Stokes force per unit depth depends on a / h alone.
function R.rect_force(h, a)
  local r, AR, T = a / h, R.AR, R.FE_LUB
  local c
  if r < AR[1] - 1e-9 then return nil end
  if r > AR[#AR] then
    c = R.film_fit(h, a)
  else
    for k = 1, #AR - 1 do
      if r <= AR[k + 1] then
        c = T[k] * (r / AR[k]) ^ (math.log(T[k + 1] / T[k]) / math.log(AR[k + 1] / AR[k]))
        break
      end
    end
  end
  return 8 * r ^ 3 * c
end

-- The rigid-plastic limit load of that rectangle over tau0: 2 a^2 / h + 3 a, section 3's fit
-- 1 / (2 h^3) + 1.5 / h written for a = 1 / (2 h) (within 3 % of FE's F_tau,y).
function R.rect_plastic(h, a) return 2 * a * a / h + 3 * a end

-- The same limit load from FE's table (section 3, +-0.5 %): the limit load of a rectangle is
-- tau0 h g(a / h) whatever its size, and the table gives g at the aspect ratios 1 / (2 h^2)
-- of its gaps; FE over the fit, interpolated linearly in a / h between them (held at the
-- end values outside, where the fit is within 3 %), times the fit.
function R.rect_plastic_fe(h, a)
  local r, HS, T = a / h, R.HS, R.FTY
  local function q(k) return T[k] / R.rect_plastic(HS[k], 1 / (2 * HS[k])) end
  local function ar(k) return 1 / (2 * HS[k] ^ 2) end
  local c = r <= ar(1) and q(1) or q(#HS)
  for k = 1, #HS - 1 do
    if r > ar(k) and r <= ar(k + 1) then c = q(k) + (q(k + 1) - q(k)) * (r - ar(k)) / (ar(k + 1) - ar(k)) end
  end
  return c * R.rect_plastic(h, a)
end

-- A lower bound on the load over tau0 that a sample of any shape between two no-slip plates
-- at gap h carries without flowing, from the particles of its half x >= 0 (fluid x, y; rows
-- dx apart from the lower plate at y = 0): the limit load of the largest rectangle inside
-- it, of half-width the least over the rows of the outermost particle's x. A stress field
-- the rectangle can carry, continued by zero outside it, is admissible for the whole sample
-- (its sides are traction-free), so the sample's limit load is at least the rectangle's
-- (limit analysis' lower-bound theorem). The particles' centres keep the rectangle inside.
function R.shape_lower_bound(xs, ys, h, dx)
  local rows = math.max(1, math.floor(h / dx + 0.5))
  local far = {}
  for i = 1, #xs do
    local k = math.min(rows, math.max(1, math.floor(ys[i] / h * rows) + 1))
    far[k] = math.max(far[k] or 0, xs[i])
  end
  local a = math.huge
  for k = 1, rows do a = math.min(a, far[k] or 0) end
  return R.rect_plastic_fe(h, a), a
end

-- The gap where a load |F| meets the plastic limit load, Bn (1/(2h^3) + 1.5/h) = |F| (the
-- fit to F_tau,y within 3 %, barrelling ignored): the stopping-height estimate. By
-- bisection over (0.05, 2), where the left side falls with h.
function R.plastic_height(Bn, F)
  local lo, hi = 0.05, 2
  for _ = 1, 100 do
    local h = 0.5 * (lo + hi)
    if Bn * R.rect_plastic(h, 1 / (2 * h)) > math.abs(F) then lo = h else hi = h end
  end
  return 0.5 * (lo + hi)
end

return R
