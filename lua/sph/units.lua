-- Cases in physical units (SI or any consistent set) and the engine's dimensionless inputs.
-- The engine runs in the squeeze's scaling: lengths in H (the sample's height), velocities
-- in U (the plate speed), viscosities in mu_ref, so mu = 1, rho = Re, tau0 = Bn, m = M:
--   Re = rho U H / mu_ref,  Bn = tau0 H / (mu_ref U),  M = m U / H,
-- with mu_ref = mu (Newtonian, Bingham) or K (U/H)^(n-1) (Herschel-Bulkley), and
-- time in H / U, stress in mu_ref U / H, force per unit depth in mu_ref U.
-- Under a load there is no plate speed to scale with: U is the viscous speed of the load,
-- U = |F| / mu_ref per unit depth (Newtonian, Bingham; for Herschel-Bulkley the speed at
-- which K (U/H)^(n-1) U = |F|), so the load is F = -1 or +1 in the engine's units.
--   local units = require "sph.units"
--   local s = units.scales{ H = 0.01, U = 1e-3, rho = 1200, mu = 10, tau0 = 50, m = 0.1 }
--   s.Re, s.Bn, s.M; s.time(t), s.length(h), s.force(F) (engine -> physical);
--   s.to_time(t), s.to_length(x), s.to_force(F) (physical -> engine)
local U = {}

local function positive(name, v)
  if type(v) ~= "number" or not (v > 0) or v == math.huge then
    error(string.format("units: %s must be a positive number, got %s", name, tostring(v)), 3)
  end
  return v
end

-- q: H, and U (plate speed) or F (load per unit depth on the whole sample, any sign), rho,
-- and either mu (with tau0 >= 0 and m for a Bingham material) or K and n (with tau0, m):
-- returns the scales and the dimensionless groups.
function U.scales(q)
  local H = positive("H", q.H)
  local rho = positive("rho", q.rho)
  local tau0 = q.tau0 or 0
  if type(tau0) ~= "number" or not (tau0 >= 0) then error("units: tau0 must be a number >= 0, got " .. tostring(tau0), 2) end
  local hb = q.K ~= nil
  if hb and q.mu ~= nil then error("units: give mu (Newtonian, Bingham) or K and n (Herschel-Bulkley), not both", 2) end
  local K, n = hb and positive("K", q.K) or nil, hb and positive("n", q.n) or nil
  local mu = not hb and positive("mu", q.mu) or nil
  if (q.U == nil) == (q.F == nil) then error("units: give the plate speed U or the load F, one of them", 2) end
  local V
  if q.U ~= nil then
    V = positive("U", q.U)
  else
    if type(q.F) ~= "number" or q.F == 0 or q.F ~= q.F then error("units: F must be a non-zero number, got " .. tostring(q.F), 2) end
    local F = math.abs(q.F)
    -- mu_ref(V) V = F: V = F / mu, or K (V/H)^(n-1) V = F
    V = hb and (F / K * H ^ (n - 1)) ^ (1 / n) or F / mu
  end
  local mu_ref = hb and K * (V / H) ^ (n - 1) or mu
  local s = { H = H, U = V, rho = rho, mu_ref = mu_ref, tau0 = tau0, K = K, n = n }
  s.Re = rho * V * H / mu_ref
  s.Bn = tau0 * H / (mu_ref * V)
  if tau0 > 0 or q.m ~= nil then s.M = positive("m", q.m) * V / H end
  s.T, s.P, s.Fs = H / V, mu_ref * V / H, mu_ref * V -- time, stress, force per unit depth
  function s.time(t) return t * s.T end
  function s.length(x) return x * H end
  function s.velocity(v) return v * V end
  function s.stress(p) return p * s.P end
  function s.force(f) return f * s.Fs end
  function s.to_time(t) return t / s.T end
  function s.to_length(x) return x / H end
  function s.to_velocity(v) return v / V end
  function s.to_force(f) return f / s.Fs end
  -- the engine's material in these units (mu_ref = 1)
  function s.material(sph)
    if hb then return sph.herschel_bulkley{ K = 1, n = n, tau0 = s.Bn, m = s.M or 800 } end
    if tau0 > 0 then return sph.bingham{ mu = 1, tau0 = s.Bn, m = s.M } end
    return sph.newtonian{ mu = 1 }
  end
  return s
end

return U
