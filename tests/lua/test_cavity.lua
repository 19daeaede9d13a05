-- Lid-driven cavity at Re = U L / nu = 100 (lua/sph/flows.lua, case "lid-driven cavity
-- Re=100"): the unit square, no-slip walls, the lid sliding at U = 1 (a plate slide: its
-- particles stay), from rest to steady state. Reference: Ghia, Ghia & Shin (1982),
-- "High-Re solutions for incompressible flow using the Navier-Stokes equations and a
-- multigrid method", J. Comput. Phys. 48, 387-411: Table I, u(y) on the vertical
-- centreline x = 0.5, and Table II, v(x) on the horizontal centreline y = 0.5, Re = 100,
-- 129 x 129 grid (the numbers are in flows.ghia_u and flows.ghia_v; the interior points
-- only, the wall values being the boundary conditions):
--   y      u          x      v
--   0.9766  0.84123   0.9688 -0.05906
--   0.9688  0.78871   0.9609 -0.07391
--   0.9609  0.73722   0.9531 -0.08864
--   0.9531  0.68717   0.9453 -0.10313
--   0.8516  0.23151   0.9063 -0.16914
--   0.7344  0.00332   0.8594 -0.22445
--   0.6172 -0.13641   0.8047 -0.24533
--   0.5000 -0.20581   0.5000  0.05454
--   0.4531 -0.21090   0.2344  0.17527
--   0.2813 -0.15662   0.2266  0.17507
--   0.1719 -0.10150   0.1563  0.16077
--   0.1016 -0.06434   0.0938  0.12317
--   0.0703 -0.04775   0.0781  0.10890
--   0.0625 -0.04192   0.0703  0.10091
--   0.0547 -0.03717   0.0625  0.09233
-- The SPH velocity at each point is a linear moving-least-squares fit over the particles
-- within 3 dx (flows.mls).
local T = require "sph.test"
local flows = require "sph.flows"
local o = ... or {}

T.case("lid-driven cavity, Re = 100, against Ghia, Ghia & Shin (1982)", function()
  local c = flows.find("lid-driven cavity Re=100")
  local dx = o.dx or c.quick[1]
  local r = c.run(dx, { threads = o.threads, t_end = o.t_end })
  for _, q in ipairs(r.u) do print(string.format("# u(x = 0.5, y = %.4f) = %8.5f  Ghia %8.5f", q[1], q[2], q[3])) end
  for _, q in ipairs(r.v) do print(string.format("# v(x = %.4f, y = 0.5) = %8.5f  Ghia %8.5f", q[1], q[2], q[3])) end
  print(string.format("# dx = 1/%d  t = %g  %s = %.4f, max %.4f  kinetic energy %.5f  %d particles  %d steps  %.1f pressure / %.1f viscous iterations per step  %.2f s",
    math.floor(1 / dx + 0.5), r.t, c.error_name, r.error, r.umax_err, r.ke, r.particles, r.steps, r.p_iter, r.v_iter, r.wall))
  -- measured at dx = 1/20, t = 10 (810 steps, two threads): RMS 0.0148 U over the 30
  -- points, max 0.035 U. The "steady" SPH state fluctuates: with another step sequence the
  -- RMS moves between 0.012 and 0.015 over t = 10-15, the max up to 0.042, the kinetic
  -- energy within 1.5 %. Bounds 1.25 x the largest seen: RMS 0.0184, max 0.053.
  T.below(r.error, 0.0184, "cavity centreline velocities within 0.0184 U (RMS) of Ghia et al. at dx = 1/20")
  T.below(r.umax_err, 0.053, "cavity centreline velocities within 0.053 U (max) of Ghia et al. at dx = 1/20")
end)

T.done()
