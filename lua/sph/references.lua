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

-- The gap where a load |F| meets the plastic limit load, Bn (1/(2h^3) + 1.5/h) = |F| (the
-- fit to F_tau,y within 3 %, barrelling ignored): the stopping-height estimate. By
-- bisection over (0.05, 2), where the left side falls with h.
function R.plastic_height(Bn, F)
  local lo, hi = 0.05, 2
  for _ = 1, 100 do
    local h = 0.5 * (lo + hi)
    if Bn * (1 / (2 * h ^ 3) + 1.5 / h) > math.abs(F) then lo = h else hi = h end
  end
  return 0.5 * (lo + hi)
end

return R
