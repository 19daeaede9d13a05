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
