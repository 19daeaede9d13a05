-- Plane Poiseuille flows (lua/sph/flows.lua): a channel between fixed plates, periodic in
-- x, driven by a body force g along x, started from rest.
--
-- Newtonian start-up (channel 0 < y < 1, mu = rho = 1, g = 8) against the series solution
--   u(y, t) = (g / 2 nu) y (1 - y) - sum_{n odd} 4 g / (nu n^3 pi^3) sin(n pi y) exp(-n^2 pi^2 nu t)
-- at t = 0.1, dt <= 0.125 dx^2 (the time error then shrinks like dx^2).
--
-- Bingham (PHYSICS.md), channel |y| < L = 0.5, tau0 = 1, g = 5, M = 1000, at steady state
-- (t = 2, implicit viscosity) against the exact plug solution:
--   plug |y| < y0 = tau0 / (rho g), u_plug = (rho g / 2 mu) (L - y0)^2
--   u(y) = (rho g / 2 mu)(L^2 - y^2) - (tau0 / mu)(L - |y|) outside the plug
local T = require "sph.test"
local flows = require "sph.flows"
local o = ... or {}

T.case("Newtonian Poiseuille start-up", function()
  local c = flows.find("Poiseuille start-up")
  local r, order = flows.quick_study(c, { threads = o.threads },
    function(x) return string.format("max |v| = %.1e", x.vmax[1]) end)
  -- measured relative L2 at t = 0.1: 0.00513 (dx = 1/20), 0.00310 (1/40), order 0.72;
  -- 0.00271 at 1/80 (order 0.19: the error levels off; not the time step: dt 4 x shorter
  -- at 1/20 gives 0.00565). The SPH flow is ahead of the series by the same +0.0014 at
  -- the centre at dx = 1/20 and 1/40 (+0.0078 at t = 0.3, steady speed 0.8 % high): the
  -- Morris operator's epsilon^2 = 0.01 h^2 makes its Laplacian of y^2 on the lattice 0.60 %
  -- low whatever dx (h = dx; 0.08 % with epsilon = 0), a viscosity 0.6 % low that no
  -- refinement removes. Tolerances: 1.25 x the error, order above 0.5.
  T.below(r[2].error, 0.0039, "Newtonian Poiseuille start-up within 0.39 % (relative L2) of the series at dx = 1/40, t = 0.1")
  T.check(order > 0.5, "Newtonian Poiseuille start-up converges (observed order > 0.5)", string.format("order %.2f", order))
  -- measured max |v| below 1e-4 U
  T.below(r[2].vmax[1], 1e-3, "Newtonian Poiseuille stays parallel (|v| < 1e-3)")
end)

T.case("Bingham plane Poiseuille", function()
  local c = flows.find("Bingham Poiseuille")
  local r, order = flows.quick_study(c, { threads = o.threads, M = o.M, viscosity = o.viscosity },
    function(x) return string.format("plug spread %.5f  plug mean %.4f (exact %.4f)  max |v| %.1e", x.spread, x.plug, x.plug_exact, x.vmax) end)
  local f = r[2]
  -- issue 3: within 3 % (relative L2) of the exact solution, the plug uniform to 1 %
  -- (measured at dx = 1/40: 2.3 %, plug uniform to 0.03 %, plug 2.8 % slow)
  T.below(f.error, 0.03, "Bingham Poiseuille within 3 % (relative L2) of the exact solution")
  T.below(f.spread, 0.01, "Bingham Poiseuille plug uniform to 1 %")
  T.close(f.plug, f.plug_exact, 0.03 * f.plug_exact, "plug velocity within 3 % of (rho g / 2 mu)(L - y0)^2")
  -- measured 0.0900 (dx = 1/20), 0.0231 (1/40): order 1.96 (the regularised yield surface
  -- and the Morris mean of eta across it, resolved as dx shrinks). Order above 1.5.
  T.check(order > 1.5, "Bingham Poiseuille converges at second order (observed order > 1.5)", string.format("order %.2f", order))
end)

T.done()
