-- The analytic and reference flows, shared by the regression tests (tests/lua/
-- test_poiseuille.lua, test_couette.lua, test_taylor_green.lua, test_cavity.lua: quick
-- resolutions) and the convergence study (scripts/bench_validation.lua, every resolution).
-- Units: H = U = 1 throughout.
--
-- Each case: name, error_name (what `error` measures), resolutions (the full study),
-- quick (what a test affords) and run(dx, opts) -> { particles, steps, wall, p_iter, v_iter,
-- error, t, ... } with p_iter and v_iter the mean solver iterations per step (pressure with
-- the density correction; viscous u and v) and wall the engine's wall time in seconds.
-- opts: threads, and per case the knobs listed next to it (every knob has the default the
-- study uses).
--
-- The study's errors (threads = 1; at dx = 1/20, 1/40, 1/80, the cavity at 1/20, 1/30,
-- 1/40), the observed orders between successive resolutions, and the steps:
--   Poiseuille start-up  0.00513  0.00310  0.00271   orders 0.72 0.19   330 1290 5130 steps
--   Bingham Poiseuille   0.0900   0.0231   0.00624   orders 1.96 1.89    90  123  170
--   Couette start-up     0.00296  0.00182  0.00155   orders 0.70 0.23   330 1290 5130
--   Taylor-Green Re=100  0.0340   0.0167   0.0110    orders 1.02 0.60   846  624 1071
--     (kinetic energy decay rate 1.526 1.558 1.563, exact 1.579)
--   cavity Re=100        0.0143   0.00572  0.00354   orders 2.25 1.67  5064 5251 3214
--     (max deviation from Ghia 0.039 at 1/20)
-- The start-ups level off at the Morris operator's epsilon error (see startup_dt).
local sph = require "sph"

local F = {}

local pi = math.pi

-- The result table of a run, with any extra fields.
local function result(w, err, extra)
  local s = w:stats()
  local steps = math.max(w.steps, 1)
  local r = { particles = s.particles, steps = w.steps, wall = s.wall_time,
              p_iter = s.solver_iterations_total / steps, v_iter = s.visc_iterations_total / steps,
              error = err, t = w.t }
  for k, v in pairs(extra or {}) do r[k] = v end
  return r
end

-- Relative L2 norm of (a - b) over b, the sums over particles (equal masses): the test
-- helpers' (sph.test has no side effect until a check is made).
local rel_l2 = require("sph.test").rel_l2
F.rel_l2 = rel_l2

-- Observed order between two runs: log(e1 / e2) / log(dx1 / dx2).
function F.order(e1, e2, dx1, dx2) return math.log(e1 / e2) / math.log(dx1 / dx2) end

-- Runs case c at its quick resolutions with run options opts, prints one comment line per
-- resolution (the error, extra(r) when given, the cost) and the observed order between the
-- first two; returns the results and that order. The tests' convergence loop.
function F.quick_study(c, opts, extra)
  local r = {}
  for k, dx in ipairs(c.quick) do
    r[k] = c.run(dx, opts)
    print(string.format("# dx = 1/%d  %s = %.5g  %s%d particles  %d steps  %.1f pressure / %.1f viscous iterations per step  %.2f s",
      math.floor(1 / dx + 0.5), c.error_name, r[k].error, extra and extra(r[k]) .. "  " or "", r[k].particles,
      r[k].steps, r[k].p_iter, r[k].v_iter, r[k].wall))
  end
  local order = F.order(r[1].error, r[2].error, c.quick[1], c.quick[2])
  print(string.format("# observed order %.2f", order))
  return r, order
end

-- A channel 0 < y < Hc between fixed plates (3 dx thick), periodic in x over Lx = 10 dx,
-- unless lid is set: then the upper plate moves along x at velocity lid.
local function channel(dx, opts, mat, gravity, Hc, lid)
  local Lx = 10 * dx
  local w = sph.world{ dx = dx, rho = opts.rho or 1, gravity = gravity, periodic = { x = { 0, Lx } },
                       threads = opts.threads, viscosity = opts.viscosity, dt_max = opts.dt_max }
  w:fill{ rect = { 0, 0, Lx, Hc }, material = mat }
  w:plate{ rect = { 0, -3 * dx, Lx, 0 } }
  local top = w:plate{ rect = { 0, Hc, Lx, Hc + 3 * dx }, axis = lid and "x" or nil }
  if lid then top:velocity(lid) end
  return w
end

-- Runs w to each time of `times` and evaluates f(w, t) there; returns the list of values.
local function at_times(w, times, f)
  local out = {}
  for k, t in ipairs(times) do
    w:run{ until_t = t }
    out[k] = f(w, t)
  end
  return out
end

-- The start-ups' errors level off near 0.15-0.3 % as dx shrinks (Poiseuille: the SPH
-- profile runs ahead of the series by the same 0.0014 at the centre at dx = 1/20 and 1/40):
-- the Morris operator's epsilon = 0.1 h makes its Laplacian 0.6 % low on the lattice
-- whatever dx (h = dx).
-- The start-ups' time step: dt <= 0.125 rho dx^2 / mu (the explicit scheme's limit), so
-- that the backward-Euler error of the impulsive start (first order in dt) shrinks like
-- dx^2 and the error measured is the spatial one (with dt from the velocity limit alone the
-- implicit Couette start-up is 0.0137 U off at t = 0.1, dx = 1/20, against 0.0029 U here).
local function startup_dt(dx, nu) return 0.125 * dx * dx / nu end

---------------------------------------------------------------------------------------
-- Newtonian plane Poiseuille start-up: channel 0 < y < 1, mu = rho = 1, body force g = 8
-- along x (steady centre speed g / 8 = 1), from rest. Series solution (nu = mu / rho):
--   u(y, t) = (g / 2 nu) y (1 - y) - sum_{n odd} 4 g / (nu n^3 pi^3) sin(n pi y) exp(-n^2 pi^2 nu t)
local POIS_G = 8
function F.poiseuille_exact(y, t)
  local nu, g = 1, POIS_G
  local s = 0
  for n = 1, 399, 2 do
    s = s + 4 * g / (nu * n ^ 3 * pi ^ 3) * math.sin(n * pi * y) * math.exp(-n * n * pi * pi * nu * t)
  end
  return g / (2 * nu) * y * (1 - y) - s
end

local poiseuille = {
  name = "Poiseuille start-up",
  error_name = "relative L2 of u at t = 0.1 (series solution)",
  resolutions = { 1 / 20, 1 / 40, 1 / 80 },
  quick = { 1 / 20, 1 / 40 },
  -- opts: times (default {0.1}; errors[k], vmax[k] for each), viscosity, dt_max
  run = function(dx, opts)
    opts = opts or {}
    local o = { threads = opts.threads, viscosity = opts.viscosity,
                dt_max = opts.dt_max or startup_dt(dx, 1) }
    local w = channel(dx, o, sph.newtonian{ mu = 1 }, { POIS_G, 0 }, 1)
    local times = opts.times or { 0.1 }
    local errs, vmax = {}, {}
    at_times(w, times, function(w, t)
      local ys, us, vs = w:field("y"), w:field("u"), w:field("v")
      local ex, vm = {}, 0
      for i = 1, #ys do
        ex[i] = F.poiseuille_exact(ys[i], t)
        vm = math.max(vm, math.abs(vs[i]))
      end
      errs[#errs + 1], vmax[#vmax + 1] = rel_l2(us, ex), vm
    end)
    return result(w, errs[1], { errors = errs, vmax = vmax })
  end,
}

---------------------------------------------------------------------------------------
-- Bingham plane Poiseuille (PHYSICS.md): channel |y| < L = 1/2 (here 0 < y < 1 shifted),
-- rho = mu = 1, tau0 = 1, g = 5: plug |y| < y0 = tau0 / (rho g) = 0.2 at
-- u_plug = (rho g / 2 mu)(L - y0)^2 = 0.225, Bn = tau0 L / (mu u_plug) = 2.2; run to steady
-- state (t = 2) with the Papanastasiou law at M = 1000.
local BP = { L = 0.5, g = 5, tau0 = 1 }
function F.bingham_exact(y) -- y measured from the centreline
  local a, y0 = math.abs(y), BP.tau0 / BP.g
  if a <= y0 then return BP.g / 2 * (BP.L - y0) ^ 2 end
  return BP.g / 2 * (BP.L * BP.L - y * y) - BP.tau0 * (BP.L - a)
end

local bingham = {
  name = "Bingham Poiseuille",
  error_name = "relative L2 of u at steady state (t = 2, M = 1000)",
  resolutions = { 1 / 20, 1 / 40, 1 / 80 },
  quick = { 1 / 20, 1 / 40 },
  -- opts: M (1000), t_end (2), viscosity; extra results: spread (plug max - min over the
  -- plug speed, |y| < y0 - 2 dx), plug (its mean), vmax
  run = function(dx, opts)
    opts = opts or {}
    local M = opts.M or 1000
    local w = channel(dx, opts, sph.bingham{ mu = 1, tau0 = BP.tau0, m = M }, { BP.g, 0 }, 1)
    w:run{ until_t = opts.t_end or 2 }
    local ys, us, vs = w:field("y"), w:field("u"), w:field("v")
    local ex, pmin, pmax, vmax, y0 = {}, math.huge, -math.huge, 0, BP.tau0 / BP.g
    for i = 1, #ys do
      local yc = ys[i] - BP.L
      ex[i] = F.bingham_exact(yc)
      if math.abs(yc) < y0 - 2 * dx then pmin, pmax = math.min(pmin, us[i]), math.max(pmax, us[i]) end
      vmax = math.max(vmax, math.abs(vs[i]))
    end
    local uplug = F.bingham_exact(0)
    return result(w, rel_l2(us, ex), { spread = (pmax - pmin) / uplug, plug = 0.5 * (pmin + pmax),
                                       plug_exact = uplug, vmax = vmax })
  end,
}

---------------------------------------------------------------------------------------
-- Plane Couette start-up: 0 < y < 1, mu = rho = 1, the upper plate slides at U = 1 from
-- t = 0 (it moves along x with its particles, periodic in x):
--   u(y, t) = y - (2 / pi) sum_n (-1)^(n+1) / n sin(n pi y) exp(-n^2 pi^2 t)
function F.couette_exact(y, t)
  local s = 0
  for n = 1, 400 do
    s = s + (-1) ^ (n + 1) / n * math.sin(n * pi * y) * math.exp(-n * n * pi * pi * t)
  end
  return y - 2 / pi * s
end

local couette = {
  name = "Couette start-up",
  error_name = "max |u - series| / U at t = 0.1",
  resolutions = { 1 / 20, 1 / 40, 1 / 80 },
  quick = { 1 / 20, 1 / 40 },
  -- opts: times (default {0.1}; errors[k] max |u - series|, l2[k] relative L2, vmax[k],
  -- step_counts[k] at each),
  -- viscosity, dt_max (default 0.125 dx^2; 0 for the velocity limit alone)
  run = function(dx, opts)
    opts = opts or {}
    local dt_max = opts.dt_max or startup_dt(dx, 1)
    local o = { threads = opts.threads, viscosity = opts.viscosity, dt_max = dt_max > 0 and dt_max or nil }
    local w = channel(dx, o, sph.newtonian{ mu = 1 }, nil, 1, 1)
    local times = opts.times or { 0.1 }
    local errs, l2, vmax, nsteps = {}, {}, {}, {}
    at_times(w, times, function(w, t)
      local ys, us, vs = w:field("y"), w:field("u"), w:field("v")
      local ex, em, vm = {}, 0, 0
      for i = 1, #ys do
        ex[i] = F.couette_exact(ys[i], t)
        em = math.max(em, math.abs(us[i] - ex[i]))
        vm = math.max(vm, math.abs(vs[i]))
      end
      errs[#errs + 1], l2[#l2 + 1], vmax[#vmax + 1], nsteps[#nsteps + 1] = em, rel_l2(us, ex), vm, w.steps
    end)
    return result(w, errs[1], { errors = errs, l2 = l2, vmax = vmax, step_counts = nsteps })
  end,
}

---------------------------------------------------------------------------------------
-- Taylor-Green vortex, Re = U L / nu = 100 on the doubly periodic unit square (L = 1,
-- U = 1, rho = 1, mu = 0.01):
--   u = U sin(2 pi x) cos(2 pi y) e^(-b t),  v = -U cos(2 pi x) sin(2 pi y) e^(-b t),
--   b = 8 pi^2 nu; the kinetic energy decays as e^(-2 b t).
local TG = { nu = 0.01 }
TG.b = 8 * pi * pi * TG.nu
function F.taylor_green_exact(x, y, t)
  local e = math.exp(-TG.b * t)
  return math.sin(2 * pi * x) * math.cos(2 * pi * y) * e, -math.cos(2 * pi * x) * math.sin(2 * pi * y) * e
end
F.taylor_green_decay = 2 * TG.b -- of the kinetic energy

local taylor_green = {
  name = "Taylor-Green Re=100",
  error_name = "relative L2 of (u, v) at t = 1",
  resolutions = { 1 / 20, 1 / 40, 1 / 80 },
  quick = { 1 / 20, 1 / 40 },
  -- opts: t_end (1), shifting (5), dt_max (0.08 dx), every (output interval for the
  -- decay fit, 0.1); extra results: decay (least-squares rate of the kinetic energy,
  -- exact 2 b = 1.579), decay_exact, ke_ratio (kinetic energy at t_end over the exact one).
  -- Particles follow the flow into the stagnation lines (x, y = 0, 1/2: compressed across
  -- them at the strain rate 2 pi U, stretched along them), and only shifting restores an
  -- isotropic arrangement. The shifting is capped at h^2/4 per step, so a long step shifts
  -- less per unit time: with dt from the velocity limit the closest pairs come within half
  -- a dx and the run blows up before t = 0.2 (dx = 1/40); with dt <= 2e-3 they stay above
  -- 0.8 dx. Hence dt_max = 0.08 dx. The domain has no free surface (surface = 0: otherwise
  -- particles of the stretched lattice are taken for free surface).
  run = function(dx, opts)
    opts = opts or {}
    local w = sph.world{ dx = dx, rho = 1, periodic = { x = { 0, 1 }, y = { 0, 1 } }, threads = opts.threads,
                         shifting = opts.shifting or 5, viscosity = opts.viscosity, surface = 0,
                         dt_max = opts.dt_max or 0.08 * dx }
    w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = TG.nu } }
    local xs, ys = w:field("x"), w:field("y")
    local u0, v0 = {}, {}
    for i = 1, #xs do u0[i], v0[i] = F.taylor_green_exact(xs[i], ys[i], 0) end
    w:set_velocity(u0, v0)
    local ke0 = w:stats().kinetic_energy
    local ts, lk = {}, {} -- w:run's each gives the t = 0 point (log 1 = 0) too
    local t_end = opts.t_end or 1
    w:run{ until_t = t_end, every = opts.every or 0.1, each = function(w)
      ts[#ts + 1], lk[#lk + 1] = w.t, math.log(w:stats().kinetic_energy / ke0)
    end }
    -- least-squares slope of log KE through the outputs
    local n, sx, sy, sxx, sxy = #ts, 0, 0, 0, 0
    for i = 1, n do
      sx, sy, sxx, sxy = sx + ts[i], sy + lk[i], sxx + ts[i] ^ 2, sxy + ts[i] * lk[i]
    end
    local decay = -(n * sxy - sx * sy) / (n * sxx - sx * sx)
    xs, ys = w:field("x"), w:field("y")
    local us, vs = w:field("u"), w:field("v")
    local num, den = 0, 0
    for i = 1, #xs do
      local ue, ve = F.taylor_green_exact(xs[i], ys[i], w.t)
      num = num + (us[i] - ue) ^ 2 + (vs[i] - ve) ^ 2
      den = den + ue * ue + ve * ve
    end
    return result(w, math.sqrt(num / den), { decay = decay, decay_exact = F.taylor_green_decay,
      ke_ratio = w:stats().kinetic_energy / ke0 / math.exp(-F.taylor_green_decay * w.t) })
  end,
}

---------------------------------------------------------------------------------------
-- Lid-driven cavity at Re = U L / nu = 100: the unit square, no-slip walls, the lid
-- (y = 1) sliding at U = 1 along x (its particles stay: a plate slide), run to steady
-- state. Reference: Ghia, Ghia & Shin (1982), "High-Re solutions for incompressible flow
-- using the Navier-Stokes equations and a multigrid method", J. Comput. Phys. 48, 387-411,
-- Table I (u along the vertical centreline x = 0.5) and Table II (v along the horizontal
-- centreline y = 0.5), Re = 100 column, 129 x 129 grid; the wall points (u = 1 and 0 at
-- y = 1 and 0, v = 0 at x = 0 and 1) are left out.
F.ghia_u = { -- y, u at x = 0.5
  { 0.9766, 0.84123 }, { 0.9688, 0.78871 }, { 0.9609, 0.73722 }, { 0.9531, 0.68717 },
  { 0.8516, 0.23151 }, { 0.7344, 0.00332 }, { 0.6172, -0.13641 }, { 0.5000, -0.20581 },
  { 0.4531, -0.21090 }, { 0.2813, -0.15662 }, { 0.1719, -0.10150 }, { 0.1016, -0.06434 },
  { 0.0703, -0.04775 }, { 0.0625, -0.04192 }, { 0.0547, -0.03717 },
}
F.ghia_v = { -- x, v at y = 0.5
  { 0.9688, -0.05906 }, { 0.9609, -0.07391 }, { 0.9531, -0.08864 }, { 0.9453, -0.10313 },
  { 0.9063, -0.16914 }, { 0.8594, -0.22445 }, { 0.8047, -0.24533 }, { 0.5000, 0.05454 },
  { 0.2344, 0.17527 }, { 0.2266, 0.17507 }, { 0.1563, 0.16077 }, { 0.0938, 0.12317 },
  { 0.0781, 0.10890 }, { 0.0703, 0.10091 }, { 0.0625, 0.09233 },
}

-- Linear moving-least-squares fit of f at (px, py) from the particles within r: the value
-- of the weighted plane a + b (x - px) + c (y - py), weights (1 - d/r)^4 (1 + 4 d/r).
-- First-order consistent, so a point between the last particle row and a wall is
-- extrapolated, not pulled towards the interior.
function F.mls(xs, ys, f, px, py, r)
  local m = { 0, 0, 0, 0, 0, 0 } -- sww, swx, swy, swxx, swxy, swyy
  local bx = { 0, 0, 0 }
  for i = 1, #xs do
    local dx, dy = xs[i] - px, ys[i] - py
    local d = math.sqrt(dx * dx + dy * dy) / r
    if d < 1 then
      local wt = (1 - d) ^ 4 * (1 + 4 * d)
      m[1], m[2], m[3] = m[1] + wt, m[2] + wt * dx, m[3] + wt * dy
      m[4], m[5], m[6] = m[4] + wt * dx * dx, m[5] + wt * dx * dy, m[6] + wt * dy * dy
      bx[1], bx[2], bx[3] = bx[1] + wt * f[i], bx[2] + wt * dx * f[i], bx[3] + wt * dy * f[i]
    end
  end
  -- solve the symmetric 3 x 3 system [[m1 m2 m3][m2 m4 m5][m3 m5 m6]] (a b c) = bx for a
  local a11, a12, a13, a22, a23, a33 = m[1], m[2], m[3], m[4], m[5], m[6]
  local c11 = a22 * a33 - a23 * a23
  local c12 = a13 * a23 - a12 * a33
  local c13 = a12 * a23 - a13 * a22
  local det = a11 * c11 + a12 * c12 + a13 * c13
  assert(det ~= 0 and det == det, string.format("MLS fit at (%g, %g): no particles within %g", px, py, r))
  return (c11 * bx[1] + c12 * bx[2] + c13 * bx[3]) / det
end

-- The SPH centreline profiles at Ghia's points: {pos, sph, ghia} lists for u and v.
function F.cavity_profiles(w, dx)
  local xs, ys, us, vs = w:field("x"), w:field("y"), w:field("u"), w:field("v")
  local r = 3 * dx
  local pu, pv = {}, {}
  for k, g in ipairs(F.ghia_u) do pu[k] = { g[1], F.mls(xs, ys, us, 0.5, g[1], r), g[2] } end
  for k, g in ipairs(F.ghia_v) do pv[k] = { g[1], F.mls(xs, ys, vs, g[1], 0.5, r), g[2] } end
  return pu, pv
end

local cavity = {
  name = "lid-driven cavity Re=100",
  error_name = "RMS of centreline u(y), v(x) minus Ghia et al. (1982), in U",
  resolutions = { 1 / 20, 1 / 30, 1 / 40 },
  quick = { 1 / 20 },
  -- opts: t_end (default 10: steady, see the test), shifting (20), density_tol (0.04),
  -- surface (0: the box is closed, so there is no free surface to detect);
  -- extra results: u, v (the profiles, see cavity_profiles), umax_err (max abs deviation),
  -- ke (kinetic energy at the end).
  -- The density error left after the correction sits in the fluid rows that slide along
  -- the lid (continuity sees the lid's particles still: a fluid particle passing over the
  -- wall lattice sees a kernel sum that is not symmetric) and grows with dt, so the
  -- engine's density-error step control sets dt here: density_tol = 0.04 takes 2.5 times
  -- fewer steps than 0.02 for nearly the same error, and without the control the density
  -- error reaches 10 % and a particle goes through the bottom wall.
  -- surface = 0: with free-surface detection on, a particle next to a corner of the closed
  -- box sometimes passes the surface test; held at p = 0 it makes the pressure level of the
  -- whole box wrong (the pin is unused once a surface exists), and at dx = 1/40 the run
  -- fails (a particle through a wall). Declared closed, every resolution runs to t = 10.
  run = function(dx, opts)
    opts = opts or {}
    local T3 = 3 * dx
    local w = sph.world{ dx = dx, rho = 1, threads = opts.threads, shifting = opts.shifting or 20,
                         density_tol = opts.density_tol or 0.04, surface = opts.surface or 0 }
    w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 0.01 } }
    w:plate{ rect = { -T3, -T3, 1 + T3, 0 } }
    w:plate{ rect = { -T3, 0, 0, 1 + T3 } }
    w:plate{ rect = { 1, 0, 1 + T3, 1 + T3 } }
    w:plate{ rect = { 0, 1, 1, 1 + T3 }, slide = { 1, 0 } }
    w:run{ until_t = opts.t_end or 10 }
    local pu, pv = F.cavity_profiles(w, dx)
    local s2, n, emax = 0, 0, 0
    for _, prof in ipairs({ pu, pv }) do
      for _, q in ipairs(prof) do
        local d = q[2] - q[3]
        s2, n, emax = s2 + d * d, n + 1, math.max(emax, math.abs(d))
      end
    end
    return result(w, math.sqrt(s2 / n), { u = pu, v = pv, umax_err = emax, ke = w:stats().kinetic_energy })
  end,
}

F.cases = { poiseuille, bingham, couette, taylor_green, cavity }

function F.find(name)
  for _, c in ipairs(F.cases) do
    if c.name == name then return c end
  end
  error("no flow named '" .. tostring(name) .. "'")
end

return F
