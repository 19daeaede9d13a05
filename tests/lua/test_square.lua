-- The square at t = 0+ (Newtonian, and Bingham below) against finite elements (../shared/REFERENCES.md section 1):
-- the half square 2a = H = 1, V = -1, Re = 0.05, run to t = 0.02 (sph.squeeze_validation.square_t0).
-- Newtonian and Bn = 10: the force's least-squares line over t in (0.01, 0.02) at t = 0, over
-- the square's FE force (ratio0). The window mean against the FE rectangle at the current gap
-- (ratio) carries a bias of about -1.4 % at every dx: the sample's contact width stays pinned
-- at the no-slip plates while the rectangles' grows (square_t0 says more). The free surface is
-- traction-free (p = n . tau . n): with p = 0 the force was 0.55 / 0.59 / 0.61 of FE and did
-- not converge.
local T = require "sph.test"
local square_t0 = require("sph.squeeze_validation").square_t0

T.case("Newtonian square at t = 0+ against FE, converging", function()
  -- measured (one thread): F(0+) / F_FE 0.9860 / 0.9946 / 1.0002 at dx = 1/20, 1/40, 1/80
  -- (errors 0.0140, 0.0054, 0.0002: order 3.1), the window mean's spread 0.006-0.007,
  -- 629 / 2550 / 10230 steps. Bounds: 0.03 at 1/20 and 1/40 (REFERENCES.md's 3 %), 0.015 at
  -- 1/80; the observed order from 1/20 to 1/80 at least 1; the spread under 0.02.
  -- The velocity carries the flow: the share of the particles' motion that the density
  -- correction made over the window (stats correction_share; 0 in the continuum) measured
  -- 0.0092 / 0.0034 / 0.0012 (order 1.5). Bounds: 0.02 / 0.01 / 0.005, an order of at least 1.
  local errs, bounds, shares, sbounds = {}, { 0.03, 0.03, 0.015 }, {}, { 0.02, 0.01, 0.005 }
  for k, n in ipairs{ 20, 40, 80 } do
    local r = square_t0(n, 0)
    shares[k] = r.correction_share
    print(string.format("# square, dx = 1/%d: the density correction made %.4f of the motion", n, shares[k]))
    T.below(shares[k], sbounds[k], string.format("square, dx = 1/%d: the velocity carries the flow (correction share under %g)", n, sbounds[k]))
    errs[k] = math.abs(r.ratio0 - 1)
    print(string.format("# square, dx = 1/%d: F(0+) / F_FE %.4f (window mean at the gap %.4f, spread %.4f), %d steps",
                        n, r.ratio0, r.ratio, r.spread, r.steps))
    T.below(errs[k], bounds[k], string.format("square, dx = 1/%d: the t = 0+ plate force within %g of FE", n, bounds[k]))
    T.below(r.spread, 0.02, string.format("square, dx = 1/%d: the force's spread over the window under 0.02", n))
  end
  local order = math.log(errs[1] / errs[3]) / math.log(4)
  print(string.format("# square: observed order %.2f from dx = 1/20 to 1/80", order))
  T.check(order >= 1, "square: observed order at least 1 from dx = 1/20 to 1/80", string.format("order %.2f", order))
  local sorder = math.log(shares[1] / shares[3]) / math.log(4)
  print(string.format("# square: the correction share's observed order %.2f from dx = 1/20 to 1/80", sorder))
  T.check(sorder >= 1, "square: the correction share falls at first order or faster", string.format("order %.2f", sorder))
end)

T.case("Bingham square at t = 0+ against FE (Bn = 10, 1000), converging", function()
  -- The Bingham free surface at p = n . tau . n (tau0 + mu gammadot on the stretching side;
  -- with p = 0 the force was 0.52 / 0.57 of FE at Bn = 10 and 0.39 / 0.50 at Bn = 1000).
  -- Measured (one thread) at dx = 1/20, 1/40 (1/80 in make validate):
  --   Bn = 10, F(0+) / F_FE: 0.9872 / 1.0005, errors 0.013 / 0.0005.
  --   Bn = 1000, the window mean against the gap's FE (its force falls nonlinearly, so it has
  --   no t = 0+ line): 0.9916 / 0.9970, order 1.5 (1.0000 at 1/80), in 9,104 / 21,418 steps
  --   (the time step on the plastic stress's lag, timestep.c).
  -- Bounds: Bn = 10 0.05 at 1/20, REFERENCES.md's 3 % at 1/40, an order of at least 1;
  -- Bn = 1000 0.05 at 1/20, 3 % at 1/40, an order of at least 1; the spread under 0.02 / 0.05.
  -- The unyielded share at t = 0.02 (the kernel-averaged multiplier under tau0): FE 0.11-0.13
  -- at Bn = 10 (not mesh-converged, REFERENCES.md), 0.45-0.55 at Bn = 1000; measured 0.080 /
  -- 0.100 and 0.570 / 0.526. Bounds: within 0.04 of 0.12 and 0.08 of 0.50; at Bn = 10 at least
  -- 0.9 of the unyielded particles within 0.25 of a plate and at x < 0.45 (FE's wedges: 0.18
  -- deep at x = 0, reaching x = 0.405). At Bn = 1000 the share is bounded at 1/40 only, and
  -- asked to come closer to FE's from 1/20 to 1/40 (at 1/20 the plugs are a few particles
  -- across).
  -- The share of the motion the density correction made (see the Newtonian case): Bn = 10
  -- 0.046 / 0.017 (order 1.4), bounds 0.1 / 0.035 and an order of at least 1; Bn = 1000
  -- 0.238 / 0.170, bound 0.25 at 1/40 (not yet converging at first order:
  -- docs/limitations.md).
  for _, c in ipairs{ { Bn = 10, bounds = { 0.05, 0.03 }, order = 1, sd = 0.02, at0 = true, un = 0.12, un_bound = 0.04, at_plates = 0.9,
                        sbounds = { 0.1, 0.035 }, sorder = 1 },
                      { Bn = 1000, bounds = { 0.05, 0.03 }, order = 1, sd = 0.05, un = 0.50, un_bound = 0.08, un_from = 2,
                        sbounds = { [2] = 0.25 } } } do
    local errs, shares, uns = {}, {}, {}
    for k, n in ipairs{ 20, 40 } do
      local r = square_t0(n, c.Bn)
      shares[k] = r.correction_share
      print(string.format("# square Bn = %g, dx = 1/%d: the density correction made %.4f of the motion", c.Bn, n, shares[k]))
      if c.sbounds[k] then
        T.below(shares[k], c.sbounds[k], string.format("square Bn = %g, dx = 1/%d: the velocity carries the flow (correction share under %g)",
                                                       c.Bn, n, c.sbounds[k]))
      end
      local v = c.at0 and r.ratio0 or r.ratio
      errs[k] = math.abs(v - 1)
      print(string.format("# square Bn = %g, dx = 1/%d: F / F_FE %.4f (%s; window mean at the gap %.4f, spread %.4f), %d steps",
                          c.Bn, n, v, c.at0 and "t = 0+" or "window mean", r.ratio, r.spread, r.steps))
      T.below(errs[k], c.bounds[k], string.format("square Bn = %g, dx = 1/%d: the plate force within %g of FE", c.Bn, n, c.bounds[k]))
      T.below(r.spread, c.sd, string.format("square Bn = %g, dx = 1/%d: the force's spread over the window under %g", c.Bn, n, c.sd))
      print(string.format("# square Bn = %g, dx = 1/%d: unyielded share %.3f (FE %.2f), %.3f of it at the plate centres",
                          c.Bn, n, r.unyielded, c.un, r.at_plates))
      uns[k] = math.abs(r.unyielded - c.un)
      if k >= (c.un_from or 1) then
        T.below(uns[k], c.un_bound, string.format("square Bn = %g, dx = 1/%d: the unyielded share within %g of FE's %g",
                                                  c.Bn, n, c.un_bound, c.un))
      end
      if c.at_plates then
        T.check(r.at_plates >= c.at_plates, string.format("square Bn = %g, dx = 1/%d: at least %g of the unyielded particles at the plate centres",
                                                          c.Bn, n, c.at_plates), string.format("%.3f", r.at_plates))
      end
    end
    local sorder = math.log(shares[1] / shares[2]) / math.log(2)
    print(string.format("# square Bn = %g: the correction share's observed order %.2f", c.Bn, sorder))
    if c.sorder then
      T.check(sorder >= c.sorder, string.format("square Bn = %g: the correction share falls at first order or faster", c.Bn), string.format("order %.2f", sorder))
    end
    if c.un_from then
      T.below(uns[2], uns[1], string.format("square Bn = %g: the unyielded share comes closer to FE's from dx = 1/20 to 1/40", c.Bn))
    end
    local order = math.log(errs[1] / errs[2]) / math.log(2)
    print(string.format("# square Bn = %g: observed order %.2f from dx = 1/20 to 1/40", c.Bn, order))
    T.check(order >= c.order, string.format("square Bn = %g: observed order at least %g from dx = 1/20 to 1/40", c.Bn, c.order),
            string.format("order %.2f", order))
  end
end)

T.case("Bingham square, Bn = 1000: the force does not hang on the time step", function()
  -- The part of the plastic stress above the ALM's r is explicit (docs/limitations.md), so the
  -- force could carry an error in dt tau0 / (rho V H). At dx = 1/20 the mean of F / F_FE(h) over
  -- t in (0.002, 0.003) (the gap's FE, ln F linear in ln h) measured 0.9989 / 0.9998 / 1.0003 at
  -- dt = 2e-6 / 1e-6 / 4e-7 (errors 0.0011 / 0.0002 / 0.0003, 11 s in all): within FE's own
  -- 0.3 % (REFERENCES.md) at every step, where an order in dt says nothing. Bound: 0.003 at
  -- each dt.
  for _, dt in ipairs{ 2e-6, 1e-6, 4e-7 } do
    local r = square_t0(20, 1000, { dt_max = dt, t0 = 0.002, t1 = 0.003 })
    print(string.format("# square Bn = 1000, dx = 1/20, dt = %g: F / F_FE %.4f over t in (0.002, 0.003), %d steps", dt, r.ratio, r.steps))
    T.below(math.abs(r.ratio - 1), 0.003, string.format("square Bn = 1000, dx = 1/20, dt = %g: the plate force within FE's 0.3 %%", dt))
  end
end)

T.case("the square at Re = 1e-3 and 1e-4 starts and settles to FE's force", function()
  -- Before the first step no particle is marked as surface, so the first step is bounded by
  -- the surface's stability limit over all particles (timestep.c): a twentieth of the speed
  -- limit alone, 250 / 2,500 times rho h^2 / mu here, put a particle through a plate at step 1.
  -- Measured (dx = 0.05, Newtonian, V = -1): peak density error 4.2e-5 / 4.2e-6, F / F_FE
  -- 0.9846 after 300 steps at both (0.9861 at Re = 0.05, dx = 1/20: Stokes flow either way).
  -- Bounds: no engine error; peak density error under 1e-3 (density_tol's tenth); the force
  -- within REFERENCES.md's 3 % of FE's 5.2493.
  local sph = require "sph"
  for _, Re in ipairs{ 1e-3, 1e-4 } do
    local dx = 0.05
    local w = sph.world{ dx = dx, rho = Re, symmetry = { x = 0 }, threads = 1 }
    w:fill{ rect = {0, 0, 0.5, 1}, material = sph.newtonian{ mu = 1 } }
    w:plate{ rect = {-3, -5 * dx, 3, 0} }
    local top = w:plate{ rect = {-3, 1, 3, 1 + 5 * dx}, axis = "y" }
    top:velocity(-1)
    local ok, err = pcall(function() for _ = 1, 300 do w:step() end end)
    local s = w:stats()
    print(string.format("# square Re = %g, dx = 0.05, 300 steps: t = %.3g, F / F_FE %.4f, peak density error %.2g", Re, w.t,
                        math.abs(top.force) / 5.2493, s.peak_density_error))
    T.check(ok, string.format("square Re = %g: 300 steps without an engine error", Re), tostring(err))
    T.below(s.peak_density_error, 1e-3, string.format("square Re = %g: peak density error under 1e-3", Re))
    T.below(math.abs(math.abs(top.force) / 5.2493 - 1), 0.03, string.format("square Re = %g, dx = 0.05: the plate force within 3 %% of FE after 300 steps", Re))
  end
end)

T.done()
