-- Squeeze-flow regressions (paper's scaling, half sample with a symmetry plane, dx = 1/40).
-- 1. Bingham Bn = 0.5, M = 100, Re = 10 at constant velocity, explicit and implicit
--    viscosity: each reaches h = 0.6 with no NaN and a max density error under 1 %, and
--    their plate forces agree (means over windows of 0.1 in t: the force has a few %
--    of step-to-step noise, and single-step spikes up to 2x with explicit viscosity).
-- 2. Newtonian, Re = 1, V = 1 (implicit viscosity) against lubrication theory F = mu V / h^6.
local squeeze = require "sph.squeeze"
local T = require "sph.test"
local sv = require "sph.squeeze_validation"
local o = ... or {}

local function bingham(viscosity)
  local w, top = squeeze.build{ dx = 1 / 40, Re = 10, Bn = 0.5, M = 100, mode = "velocity",
                                world = { threads = o.threads, viscosity = viscosity } }
  -- the mean of every step's force weighted by its dt: with the force's step-to-step
  -- noise, 20 samples a window would move a window's mean by up to 8 %
  local win = {}
  while w.t < 0.41 - 1e-12 do
    local t0 = w.t
    w:step()
    local k = math.floor(w.t / 0.1 - 1e-9) + 1 -- window (0, 0.1], (0.1, 0.2], ...
    win[k] = win[k] or { s = 0, n = 0 }
    win[k].s, win[k].n = win[k].s + top.force * (w.t - t0), win[k].n + (w.t - t0)
  end
  local s = w:stats()
  local emax = s.peak_density_error -- the largest of any step
  print(string.format("# Bingham %s: h = %.3f after %d steps (%.1f s), max density error %.4f, mean pressure iterations %.1f",
    viscosity, top.position, w.steps, s.wall_time, emax, s.solver_iterations_total / w.steps))
  T.below(top.position, 0.6 + 1e-9, "Bingham squeeze (" .. viscosity .. ") reaches h = 0.6")
  T.below(emax, 0.01, "Bingham squeeze (" .. viscosity .. ") max density error under 1 %")
  local means = {}
  for k = 1, 4 do means[k] = win[k].s / win[k].n end
  return means
end

T.case("Bingham squeeze, explicit against implicit viscosity", function()
  local e = bingham("explicit")
  local i = bingham("implicit")
  for k = 2, 4 do
    local d = math.abs(i[k] - e[k]) / e[k]
    print(string.format("# mean force over t in (%.1f, %.1f]: explicit %.3f implicit %.3f (%.1f %%)", (k - 1) / 10, k / 10, e[k], i[k], 100 * d))
    -- measured differences 2.2, 0.6, 3.8 % (two threads); the runs are chaotic at the
    -- percent level: a change of round-off alone moves a window's difference by several %,
    -- up to 9 %. Tolerance 6 %.
    T.below(d, 0.06, string.format("explicit and implicit mean plate force agree within 6 %% over t in (%.1f, %.1f]", (k - 1) / 10, k / 10))
  end
end)

T.case("Newtonian squeeze against lubrication theory", function()
  local dx = 1 / 40
  local w, top = squeeze.build{ dx = dx, Re = 1, Bn = 0, mode = "velocity", world = { threads = o.threads } }
  local lx, ly, lr = {}, {}, {} -- ln h, ln F and ln F_FE (the film at the contact width) for h <= 0.5
  -- F over the FE film at the current gap and contact half-width, in three windows of h
  local wins = { { lo = 0.5, hi = 0.6 }, { lo = 0.45, hi = 0.5 }, { lo = 0.37, hi = 0.45 } }
  for _, b in ipairs(wins) do b.s, b.n = 0, 0 end
  w:run{ until_t = 0.66, every = 0.005, each = function()
    local h = top.position
    if h <= 0.5 then
      lx[#lx + 1], ly[#ly + 1] = math.log(h), math.log(top.force)
      lr[#lr + 1] = math.log(sv.film_force(h, sv.contact_half_width(w, h, dx), 1))
    end
    for _, b in ipairs(wins) do
      if h >= b.lo and h <= b.hi then
        b.s, b.n = b.s + top.force / sv.film_force(h, sv.contact_half_width(w, h, dx), 1), b.n + 1
      end
    end
  end }
  local function slope_of(ys) -- least-squares slope of ys against ln h
    local n, sx, sy, sxx, sxy = #lx, 0, 0, 0, 0
    for k = 1, n do sx, sy, sxx, sxy = sx + lx[k], sy + ys[k], sxx + lx[k] ^ 2, sxy + lx[k] * ys[k] end
    return (n * sxy - sx * sy) / (n * sxx - sx * sx), sx, sy
  end
  local n = #lx
  local slope, sx, sy = slope_of(ly)
  local rslope = slope_of(lr)
  local ratio = math.exp((sy - slope * sx) / n + slope * math.log(0.35)) / squeeze.newtonian_force(0.35)
  print(string.format("# Newtonian: %d samples in h in [%.3f, 0.5], log-log slope %.3f (FE's film at the contact width: %.3f), fitted F(0.35) / lubrication %.4f, %d steps",
    n, top.position, slope, rslope, ratio, w.steps))
  -- The slope against FE's film at the run's own gap and contact half-width, over the same
  -- outputs (the FE rectangles' -5.56 is not the barrelled sample's: its contact width grows
  -- slower than a / h). Measured -6.019 / -5.925 and -6.003 / -5.934 (-O2, one / two threads),
  -- -6.093 / -5.943 and -5.816 / -5.911 (make check's build): differences 0.07-0.15. Bound 0.5,
  -- as against the rectangles (the run's own slope moves by up to 0.28 with round-off).
  T.below(math.abs(slope - rslope), 0.5, "Newtonian squeeze: log-log slope of F against h within 0.5 of FE's film at the contact width")
  -- With the traction-free free surface (p = n . tau . n) the ratio is 0.994 (one thread).
  -- The reference is the FE rectangle at a/h = 1 / (2 h^2) = 4.08, 1.033 x lubrication
  -- (REFERENCES.md section 2's fit); the sample's barrelling and inertia (Re h = 0.35) are
  -- not in it. Measured 0.038 from it (0.18 with p = 0 at the surface); bound 0.10.
  T.below(math.abs(ratio / 1.033 - 1), 0.10, "Newtonian squeeze: F(0.35) within 10 % of the FE rectangle's (1.033 x lubrication)")
  T.below(top.position, 0.35, "Newtonian squeeze reaches h = 0.35")
  -- The squeezed square barrels: its contact with the no-slip plates (the outermost particle
  -- of the rows within dx of a plate, plus dx / 2) is 0.84-1.26 where the rectangle of its area
  -- has 0.95-1.33 (h = 0.525-0.375), so the rectangles' log-log slope (-5.56 over h in
  -- [0.35, 0.5]) is not the sample's: the run's was -6.00 to -6.09 and moved by up to 0.28 with
  -- round-off alone. The reference is REFERENCES.md section 2's FE fit at the current gap and
  -- contact half-width (within 0.3 % of FE's table down to a/h = 0.78), with the inertia factor
  -- 1 + (17/70) Re h, over three windows of h, so that the force's dependence on h is checked
  -- along with its level. Means of the outputs (every 0.005) measured, h in [0.5, 0.6] /
  -- [0.45, 0.5] / [0.37, 0.45]: 0.9933 / 0.9983 / 1.0012 (-O2, one thread), 0.9935 / 0.9985 /
  -- 1.0000 (two threads), 0.9937 / 0.9987 / 0.9888 (make check's build); the force's
  -- step-to-step spread is 0.026 / 0.058 / 0.07, so a mean's own is 0.006 / 0.018 / 0.018.
  -- Bound 0.04 (at least two of those standard errors).
  for _, b in ipairs(wins) do
    local mc = b.s / b.n
    print(string.format("# Newtonian: F / F_FE at the contact half-width, mean of %d outputs with h in [%.2f, %.2f]: %.4f", b.n, b.lo, b.hi, mc))
    T.below(math.abs(mc - 1), 0.04, string.format("Newtonian squeeze: F within 4 %% of FE's film at the current gap and contact width (h %.2f-%.2f)", b.lo, b.hi))
  end
end)

T.done()
