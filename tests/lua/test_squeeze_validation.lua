-- Squeeze-flow validations (lua/sph/squeeze_validation.lua) at their quick resolutions
-- (dx = 1/20 and 1/30; Bingham at 1/20 only; the full study is `make bench`): the errors against
-- thin-film theory and their observed orders, with tolerances from the measured values
-- written next to each reference. threads = 1 unless the runner says otherwise: a run on
-- one thread is reproducible to the last digit, and the tolerances below are taken from
-- one-thread runs (two threads change the summation order; the squeeze is chaotic at the
-- percent level, see test_squeeze.lua). About 60 s of CPU in all (58 s user + 9 s system
-- measured on a machine loaded 10-fold by other programs).
local V = require "sph.squeeze_validation"
local T = require "sph.test"
local o = ... or {}
local threads = o.threads or 1

T.case("thin-film Bingham reference: Newtonian and plastic limits", function()
  for _, h in ipairs{ 0.5, 0.35 } do
    -- tau0 -> 0: lubrication F = mu V / h^6 (measured 9e-8 relative at tau0 = 1e-6)
    local n = V.bingham_force(h, 1, 1, 1e-6) / V.newtonian_force(h, 1, 1) - 1
    T.below(math.abs(n), 1e-6, string.format("Bingham film at tau0 = 1e-6 is Newtonian at h = %g", h))
    -- tau0 -> infinity: plastic limit tau0 / (2 h^3) times 1 + (4 sqrt 2 / 5) sqrt(mu V /
    -- (tau0 h^3)) (the first correction); the rest is of the order of the correction
    -- squared: measured 7e-6 (h = 0.5) and 2e-5 (h = 0.35) at tau0 = 1e6
    local tau0 = 1e6
    local r = V.bingham_force(h, 1, 1, tau0) / V.plastic_force(h, tau0)
    local c = 4 * math.sqrt(2) / 5 * math.sqrt(1 / (tau0 * h ^ 3))
    T.below(math.abs(r - 1 - c), 1e-4, string.format("Bingham film at tau0 = 1e6: plastic limit and its first correction at h = %g", h))
  end
  -- Bn = 100 in the window: the viscous part is not small, 1.40 (h = 0.5) to 1.81 (0.35)
  -- times the plastic limit
  local r = V.bingham_force(0.4, 1, 1, 100) / V.plastic_force(0.4, 100)
  print(string.format("# thin-film Bingham, Bn = 100, V = 1, h = 0.4: %.3f x the plastic limit tau0 / (2 h^3)", r))
  T.close(r, 1.615, 0.005, "Bingham film at Bn = 100, h = 0.4: 1.615 x the plastic limit")
end)

-- runs a case at resolutions res (default: its quick ones); returns the results and the
-- observed order between the first two
local function study(c, res)
  res = res or c.quick
  local rs = {}
  for k, dx in ipairs(res) do
    local r = c.run(dx, { threads = threads })
    rs[k] = r
    print(string.format("# %s, dx = 1/%d: error %.4f (force or speed ratio %.4f), %d particles, %d steps, %.1f s, %.0f + %.0f solver iterations per step, peak density error %.4f",
      c.name, math.floor(1 / dx + 0.5), r.error, r.mean_ratio, r.particles, r.steps, r.wall, r.p_iter, r.v_iter, r.peak_density_error))
  end
  if #res < 2 then return rs end
  local order = math.log(rs[1].error / rs[2].error) / math.log(res[1] / res[2])
  print(string.format("# %s: observed order %.2f (dx = 1/%d to 1/%d); error: %s", c.name, order,
    math.floor(1 / res[1] + 0.5), math.floor(1 / res[2] + 0.5), c.error_name))
  return rs, order
end

local cases = {}
for _, c in ipairs(V.cases) do cases[c.name] = c end

-- The comparisons are in the late squeeze of the paper's sample, h in [0.35, 0.45],
-- a / h = 2.5 to 4.1: thin-film theory leaves out corrections of relative order h / a
-- there (0.25 to 0.4), and none of the errors below is mostly discretisation error: they
-- barely change from dx = 1/20 to 1/30 (orders 0.2-0.4) or 1/40 (see make bench). The
-- tolerances are two-sided, so that a change of the engine that moves these figures
-- either way is noticed and the figures here (and in docs/limitations.md) are updated.

T.case("Newtonian squeeze at constant velocity against lubrication", function()
  local rs, order = study(cases["Newtonian squeeze V = 1"])
  -- measured (one thread, Re = 0.1): errors 0.2861 (dx = 1/20) and 0.2641 (1/30), the
  -- force 0.72 and 0.74 x lubrication mu V / h^6, order 0.20 (session 6, after
  -- density_limit, density_solve_tol, shifting's plain surface normal and the 1.5 dx
  -- free-surface cone; 0.3223 and 0.2779, order 0.37, before). (At Re = 1 the force is
  -- 0.84 x lubrication at dx = 1/20, the same in test_squeeze.lua at 1/40: inertia adds
  -- about 0.16; V = 0.1 at Re = 1 gives the same run as V = 1 at Re = 0.1, to the digit.)
  -- Tolerances: the squeeze is chaotic at the percent level (a change of round-off moves
  -- mean forces by up to 3 %, test_squeeze.lua): 0.03 on each error, 0.5 on the order.
  -- Session 7, the pressure predictor (pressure_predictor = 1: the viscous step carries
  -- -grad p^n, kernel-averaged): errors 0.2306 / 0.2186 (order 0.13) with -O2, 0.2304 /
  -- 0.2162 (0.16) under make check's -O1 sanitizer build; the references below are their
  -- middle. The predictor removes much of the force's time-step error: 0.231 in 1727
  -- steps, 0.218 at dt_max = 1e-4 (6723 steps), where without it 0.286 in 1741 and 0.243.
  -- Session 14 (the engine since: the surface cone, the density descent, the viscous
  -- first guess): re-measured over round-off variants (one and two threads, solver
  -- tolerance 1e-6 / 1e-7 / 1e-8, with and without the viscous guess): 0.242-0.253 at
  -- 1/20, 0.227-0.238 at 1/30; the references are their middles (the old ones, 0.230 and
  -- 0.217, had drifted to within 0.01 of their bands' edge).
  -- The traction-free free surface (p = n . tau . n, not 0): errors 0.1516 (1/20) and 0.1369
  -- (1/30), the force 0.874 / 0.870 x lubrication (0.757 / 0.774 with p = 0); the window's
  -- a/h 2.5-4.1 puts the FE rectangles 1.03-1.07 over lubrication (REFERENCES.md section 2),
  -- what is left of the error. Bounds: the measured errors plus the round-off spread above
  -- (0.011 at 1/20) and a margin of 0.015.
  T.below(rs[1].error, 0.18, "Newtonian squeeze V = 1, dx = 1/20: error under 0.18")
  T.below(rs[2].error, 0.165, "Newtonian squeeze V = 1, dx = 1/30: error under 0.165")
  T.close(order, 0.15, 0.5, "Newtonian squeeze V = 1: observed order within 0.5 of 0.15")
  T.below(rs[2].peak_density_error, 0.03, "Newtonian squeeze V = 1, dx = 1/30: peak density error under 3 %")
end)

T.case("Newtonian squeeze in the thin-film regime against lubrication", function()
  local rs, order = study(cases["Newtonian squeeze, thin film"])
  -- a film started thin (a/h 9.9-11 in the window), with the thin-film options
  -- (density_correction = gmres, pressure_gradient = difference). Measured (session 8, one
  -- thread): errors 0.1475 / 0.1217 (order 0.67; force 0.860 / 0.884 x lubrication) with
  -- -O2, 0.1593 / 0.1226 (order 0.91) under make check's -O1 sanitizer build; finer, 0.1102
  -- / 0.0861 / 0.088 at 1/60, 1/80, 1/100 (make bench). References: the two builds' middle;
  -- tolerances 0.02 and 0.015 (the builds differ by 0.012 and 0.001), 0.5 on the order.
  T.close(rs[1].error, 0.153, 0.02, "Newtonian thin film, dx = 1/30: error within 0.02 of 0.153")
  T.close(rs[2].error, 0.122, 0.015, "Newtonian thin film, dx = 1/40: error within 0.015 of 0.122")
  T.close(order, 0.79, 0.5, "Newtonian thin film: observed order within 0.5 of 0.79 (converging)")
  T.below(rs[2].peak_density_error, 0.01, "Newtonian thin film, dx = 1/40: peak density error under 1 %")
end)

T.case("Bingham squeeze in the thin-film regime against thin-film theory", function()
  local rs = study(cases["Bingham squeeze, thin film"])
  -- the Newtonian case's film, Bn = 100, M = 100 (thin-film options). Measured (session 8,
  -- one thread): force / theory 1.0116 and 0.9971 (errors 0.0567, 0.0138) with -O2,
  -- 1.0117 and 0.9960 (0.0582, 0.0239) with -O1. The mean ratio is the stable figure (the
  -- L2 error carries the force's step-to-step noise): within 0.03 of each build's middle;
  -- the errors under 0.08 (until session 15, below). With the defaults this film blows up (squeeze_validation.lua).
  -- Session 14: the L2 error's spread over round-off variants of one code (1 and 2
  -- threads, pressure tolerance 1e-6 / 1e-7 / 1e-8, dx = 1/30 and 1/30 +- 1e-10; 18 runs)
  -- at 1/30: 0.020-0.073 (mean 0.052) with session 13's code, 0.022-0.081 (mean 0.051)
  -- with session 14's solver guesses; 0.08 is at that distribution's tail, so a change of
  -- round-off alone can cross it (one variant in 18 did), while the mean ratio stays
  -- within 1.00-1.03.
  -- Session 15: the L2 error taken apart (squeeze_validation.lua: trend_error, the force's
  -- 11-step running mean against theory; noise, the force about that mean). 18 variants
  -- (as above) of session 15's code: at 1/30 error 0.023-0.076 (the old bound 0.08 0.005
  -- above the largest), trend 0.012-0.052, noise 0.019-0.047, mean ratio 1.005-1.020,
  -- 265-301 steps in the window (round-off moves the step count too); at 1/40 error
  -- 0.031-0.070, trend 0.017-0.039, noise 0.017-0.054, ratio 0.992-1.007. The bounds on the
  -- trend and the noise, 0.07, are over the largest measured by a third or more, and a
  -- trend off by 0.07 is a real departure from the theory, not noise.
  T.close(rs[1].mean_ratio, 1.012, 0.03, "Bingham thin film, dx = 1/30: force within 0.03 of 1.012 x thin-film theory")
  T.close(rs[2].mean_ratio, 0.997, 0.03, "Bingham thin film, dx = 1/40: force within 0.03 of 0.997 x thin-film theory")
  for k, name in ipairs{ "1/30", "1/40" } do
    print(string.format("# Bingham thin film, dx = %s: error %.4f = trend %.4f (+) noise %.4f", name, rs[k].error,
      rs[k].trend_error, rs[k].noise))
    T.below(rs[k].trend_error, 0.07, "Bingham thin film, dx = " .. name .. ": the force's running mean within 0.07 (L2) of theory")
    T.below(rs[k].noise, 0.07, "Bingham thin film, dx = " .. name .. ": the force's noise about its running mean under 0.07")
  end
  T.below(rs[2].peak_density_error, 0.01, "Bingham thin film, dx = 1/40: peak density error under 1 %")
end)

T.case("Newtonian squeeze under a constant load against lubrication", function()
  local rs, order = study(cases["Newtonian squeeze F = 20"])
  -- measured (one thread, Re = 1; late plate speeds 0.04-0.15, so close to Stokes flow):
  -- the slope of h^-5 against t is 1.639 (dx = 1/20) and 1.535 (1/30) x lubrication's 5 F /
  -- mu, errors 0.639 and 0.535, order 0.44: the plate closes 1.5-1.6 times faster than
  -- lubrication says, i.e. the sample carries about 0.65 x the lubrication force at its
  -- speed, as in the constant-velocity case at Re = 0.1 (0.68-0.72). dx = 1/40 fails near
  -- h = 0.43 (a fluid particle goes through the upper plate at t = 0.51). Tolerances 0.06
  -- on each error (a loaded run integrates the force's noise into h), 0.6 on the order.
  -- Session 6 (density_limit, density_solve_tol, shifting's plain surface normal, the
  -- 1.5 dx free-surface cone): errors 0.5934 / 0.4813 (order 0.52) with -O2, 0.5916 /
  -- 0.4736 (0.55) under make check's -O1 sanitizer build: the references below are those.
  -- Session 7, the pressure predictor: errors 0.4790 / 0.3882 (order 0.52) with -O2,
  -- 0.4790 / 0.3881 (0.52) with -O1: the plate now closes 1.39-1.48 times faster than
  -- lubrication says (1.48-1.59 before).
  -- The traction-free free surface: errors 0.2186 / 0.2057 (order 0.15; the plate closes
  -- 1.21-1.22 times faster than lubrication, 1.39-1.48 with p = 0 at the surface), which
  -- at a/h 2.5-4.1 is mostly the FE rectangles' 3-7 % over lubrication and the time error.
  -- Bounds: the measured errors plus 0.03 (a loaded run integrates the force's noise).
  T.below(rs[1].error, 0.25, "Newtonian squeeze F = 20, dx = 1/20: error under 0.25")
  T.below(rs[2].error, 0.24, "Newtonian squeeze F = 20, dx = 1/30: error under 0.24")
  T.close(order, 0.52, 0.6, "Newtonian squeeze F = 20: observed order within 0.6 of 0.52")
end)

T.case("Newtonian squeeze under a constant load in the thin-film regime against lubrication", function()
  local rs, order = study(cases["Newtonian squeeze under load, thin film"])
  -- the film started thin (h0 = 0.2, half-width 1.6, thin-film options) under F = 400 (the
  -- plate closes at 0.05-0.1, Re = 1: nearly Stokes flow); error |slope of h^-5 / (5 F /
  -- (mu A^3)) - 1| over h in [0.17, 0.18]. Measured (session 9, one thread): 0.3598 /
  -- 0.2843 (order 0.82) with -O2, 0.3547 / 0.2881 (0.72) with -O1; finer 0.2205 / 0.2060
  -- at 1/60, 1/80 (-O2). The plate closes 1.2-1.36 x faster than lubrication; part of it
  -- is a time-step error (0.253 at 1/30 with dt_max = 1e-4) that projection_passes = 1
  -- removes (0.241, either dt; pressure.c says why it is not the default). The peak density
  -- error reaches 1.3 % (-O2, 1/30) and 2.7 % (-O1, 1/40) in this film: not asserted here.
  -- Tolerances 0.015 on each error (the builds differ by 0.005 and 0.004), 0.5 on the order.
  -- Session 15: re-measured over 18 round-off variants (1 and 2 threads x pressure
  -- tolerance 1e-6 / 1e-7 / 1e-8 x dx and dx +- 1e-10): 0.360-0.382 at 1/30 (5 of the 18
  -- over the old band 0.357 +- 0.015), 0.279-0.300 at 1/40 (the default run at 0.3004, the
  -- old band's edge 0.301): the references had drifted over six sessions of engine changes
  -- and are now the measured middles, 0.371 and 0.289; tolerance 0.015 unchanged.
  T.close(rs[1].error, 0.371, 0.015, "Newtonian thin film under load, dx = 1/30: error within 0.015 of 0.371")
  T.close(rs[2].error, 0.289, 0.015, "Newtonian thin film under load, dx = 1/40: error within 0.015 of 0.289")
  T.close(order, 0.77, 0.5, "Newtonian thin film under load: observed order within 0.5 of 0.77")
  T.below(rs[2].error, rs[1].error, "Newtonian thin film under load: the error falls from dx = 1/30 to 1/40")
  -- the option projection_passes = 1 (pressure.c): measured 0.2410 (-O2) and 0.2402 (-O1)
  -- at 1/30, and the same at dt_max = 1e-4 (0.252): tolerance 0.015. Session 15, the 18
  -- variants above: 0.245-0.251; the reference is their middle, 0.248.
  local c = cases["Newtonian squeeze under load, thin film"]
  local r = c.run(1 / 30, { threads = threads, world = { projection_passes = 1 } })
  print(string.format("# %s, dx = 1/30, projection_passes = 1: error %.4f, %d steps, %.1f pressure-type iterations a step",
    c.name, r.error, r.steps, r.p_iter))
  T.close(r.error, 0.248, 0.015, "Newtonian thin film under load, dx = 1/30, projection_passes = 1: error within 0.015 of 0.248")
end)

T.case("Bingham squeeze, Bn = 100, at constant velocity against thin-film Bingham theory", function()
  -- dx = 1/20 only here (CPU budget); dx = 1/30 and 1/40 are in make bench
  local rs = study(cases["Bingham squeeze Bn = 100 V = 1"], { 1 / 20 })
  -- measured (one thread, M = 100, Re = 1): errors 0.0731 (dx = 1/20), 0.0686 (1/30) and
  -- 0.0588 (1/40), orders 0.16 and 0.53; the force 1.07 x the thin-film Bingham load
  -- (itself 1.40-1.81 x the plastic limit tau0 / (2 h^3) in the window: at Bn = 100 and
  -- V = 1 the viscous part is not small). M = 1000 gives 0.070 at 1/20 (the
  -- regularisation does not matter) but stops at 1/30 (the force explodes near h = 0.42:
  -- time step below its minimum), and M = 100 stops the same way at 1/25 (h = 0.37).
  -- Tolerance 0.02 on the error.
  -- Session 7: that 1.07 was a time-step error. Without the pressure predictor the mean
  -- force ratio was 1.079 / 1.146 / 1.176 at the adaptive dt / dt_max = 1e-4 / 3e-5; with
  -- it (pressure_predictor = 1, the default) 1.156 / 1.178 (and 1.180 / 1.191 / 1.190
  -- with p^n not kernel-averaged): what is left (1.16-1.19 x thin-film theory at a / h
  -- 2.5-4.1) is the resolution and the theory's own neglect of the edge. Measured: error
  -- 0.1505, ratio 1.1558 (-O2); 0.1512, 1.1567 (-O1 sanitizer build).
  T.close(rs[1].error, 0.151, 0.02, "Bingham squeeze V = 1, dx = 1/20: error within 0.02 of 0.151")
  T.close(rs[1].mean_ratio, 1.156, 0.03, "Bingham squeeze V = 1, dx = 1/20: mean force within 0.03 of 1.156 x thin-film theory")
  -- The force does not depend on dt (the pressure predictor's purpose): the same run with
  -- dt_max = 1e-4 (6521 steps against 2019) measured 1.1781 against 1.1558, 0.022 apart;
  -- without the predictor 1.146 against 1.079, 0.067 apart. Tolerance 0.035.
  local r2 = cases["Bingham squeeze Bn = 100 V = 1"].run(1 / 20, { threads = threads, world = { dt_max = 1e-4 } })
  print(string.format("# Bingham squeeze V = 1, dx = 1/20, dt_max = 1e-4: force ratio %.4f in %d steps (adaptive: %.4f in %d)",
    r2.mean_ratio, r2.steps, rs[1].mean_ratio, rs[1].steps))
  T.below(math.abs(r2.mean_ratio - rs[1].mean_ratio), 0.035,
    "Bingham squeeze V = 1, dx = 1/20: mean force ratio at dt_max = 1e-4 within 0.035 of the adaptive step's")
end)

T.case("Bingham squeeze, Bn = 100, under a constant load: the stop height", function()
  local c = cases["Bingham squeeze Bn = 100 F = 400"]
  -- the case runs to t = 1 (window t in [0.5, 1]); here to t = 0.7 (CPU budget)
  local r = c.run(1 / 20, { threads = threads, t_end = 0.7, t_win = 0.5 })
  print(string.format("# %s, dx = 1/20, t in [0.5, 0.7]: error %.4f (thin-film load at the current h and V: %.3f x F), h(0.7) = %.4f against the ideal stop height %.4f, %d steps, %.1f s",
    c.name, r.error, r.mean_ratio, r.h, r.h_stop, r.steps, r.wall))
  -- measured (one thread, M = 100, Re = 1, dx = 1/20): the sample goes through the ideal
  -- Bingham stop height (tau0 / (2 F))^(1/3) = 0.5: h(0.7) = 0.399, h(1) = 0.377, still
  -- closing at V = 0.06, where thin-film theory needs 2.1-2.3 x the load (error 1.12 over
  -- t in [0.5, 0.7]; over [0.5, 1] 1.34, 1.10 and 0.88 at dx = 1/20, 1/30 and 1/40, orders
  -- 0.48 and 0.77: it shrinks with dx, slowly): at slow closing speeds the
  -- sample carries far less than its yield stress says (the constant-velocity case at
  -- V = 0.1 falls to 0.2 x the thin-film load at h = 0.46, against 1.07 at V = 1). A wrong
  -- result, kept here so that a fix shows: tolerance 0.15 on the error, 0.02 on h(0.7).
  -- Session 7, the fix: most of it was the projection's splitting error (the no-slip
  -- walls did not see the pressure gradient within a step, so the slow film slipped);
  -- with the pressure predictor (the default) h(0.7) = 0.445 (ideal stop 0.5) and the
  -- error 0.495 (1.495 x F needed by thin-film theory at the run's h and V); 0.4416 and
  -- 0.532 under make check's -O1 build (0.456 and 0.375 with p^n not kernel-averaged,
  -- which the stability suite's stiff cases do not survive: pressure.c).
  T.close(r.error, 0.513, 0.15, "Bingham squeeze F = 400, dx = 1/20: error within 0.15 of 0.513")
  T.close(r.h, 0.443, 0.02, "Bingham squeeze F = 400, dx = 1/20: h(0.7) within 0.02 of 0.443 (ideal stop 0.5)")
end)

T.done()
