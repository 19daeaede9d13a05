-- Taylor-Green vortex at Re = U L / nu = 100 on the doubly periodic unit square
-- (lua/sph/flows.lua, case "Taylor-Green Re=100"), against the exact decaying solution
--   u = U sin(2 pi x) cos(2 pi y) e^(-b t),  v = -U cos(2 pi x) sin(2 pi y) e^(-b t),
--   b = 8 pi^2 nu, kinetic energy ~ e^(-2 b t), 2 b = 1.579;
-- shifting 5, dt <= 0.08 dx (see the case for why).
local T = require "sph.test"
local flows = require "sph.flows"
local o = ... or {}

T.case("Taylor-Green vortex, Re = 100", function()
  local c = flows.find("Taylor-Green Re=100")
  local r, order = flows.quick_study(c, { threads = o.threads }, function(x)
    return string.format("kinetic energy decay rate %.4f (exact %.4f), KE(t = 1) / exact %.4f", x.decay, x.decay_exact, x.ke_ratio)
  end)
  local f = r[2]
  -- measured relative L2 at t = 1: 0.0340 (dx = 1/20, 846 steps), 0.0167 (1/40, 624
  -- steps), order 1.02; kinetic energy decay rate 1.526 and 1.558 (exact 1.579: 3.4 % and
  -- 1.3 % slow), KE(t = 1) 6.4 % and 3.1 % high. Tolerances 1.25 x the dx = 1/40 figures,
  -- order above 0.8. (Since w:run's each gives the t = 0 point, the fit no longer holds it
  -- twice: decay rates 1.5326 and 1.5601 with the same run, 2.9 % and 1.2 % slow.)
  T.below(f.error, 0.021, "Taylor-Green (u, v) within 2.1 % (relative L2) of the exact solution at t = 1, dx = 1/40")
  T.close(f.decay, f.decay_exact, 0.017 * f.decay_exact, "Taylor-Green kinetic energy decays at 2 b = 16 pi^2 nu within 1.7 %")
  T.check(order > 0.8, "Taylor-Green converges (observed order > 0.8)", string.format("order %.2f", order))
end)

T.done()
