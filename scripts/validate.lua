-- make validate: the engine against the independent references of ../shared/REFERENCES.md,
-- each case at up to three resolutions, with the error against the reference and the
-- observed order between successive resolutions. Writes docs/validation.md (whole) and one
-- error-against-dx plot per section (docs/validation_*.png).
--   1. the square at t = 0+ (creeping flow, V = -1, Re = 0.05): the plate force extrapolated
--      to t = 0 over the finite-element (FE) force (Bn = 0, 10; at Bn = 1000 the window mean
--      over the FE force at the current gap), and the unyielded area fraction;
--   2. thin films (Newtonian, V = -1, Re = 0.05): rectangles at a/h = 2, 5, 10, the plate
--      force against the FE / lubrication force at the current gap and aspect ratio;
--   3. yield: a Bingham square (Bn = 10, M = 800, Re = 1) under 0.75 and 1.5 times its
--      rigid-plastic limit load, the gap at t = 1; and the shape reached under 1.5 times it
--      against limit analysis' lower bound (the load it must carry without flowing), with the
--      creep under 0.8 of that bound;
--   4. exact and 1D flows: Bingham Couette start-up (Bn = 1) and Bingham Poiseuille
--      start-up (Bn = 0.8) at the tabulated times, and the creeping Bingham lid-driven
--      cavity (Bn = 0, 5): vortex centre and unyielded fraction.
-- A case whose run raises an engine error is reported as "failed: <message>" and the script
-- goes on. Every world runs on `threads` threads (default 1), and `jobs` sections run at once,
-- each in a process of its own (default 2: make validate takes about 17 minutes on two cores).
--   build/sph scripts/validate.lua [threads=1] [jobs=2] [out=docs] [only=1,2,3,4]
--     [n=20,40,80] (section 1) [rows=16,32,64] [ar=2,5,10] (section 2)
--     [yield_n=20,40,80] (section 3) [flow_n=20,40,80] [cavity_n=20,40,80] (section 4)
local sph = require "sph"
local squeeze = require "sph.squeeze"
local flows = require "sph.flows"
local squeeze_validation = require "sph.squeeze_validation"
local params = require "sph.params"
local SPEC = {
  { "threads", "integer", 1, "threads of every world (1..256)" },
  { "jobs", "integer", 2, "sections run at once, each in a process of its own (1..4)" },
  { "out", "string", "docs", "folder of validation.md and its plots" },
  { "only", "string", "1,2,3,4", "the sections to run, comma-separated, from 1..4" },
  { "n", "string", "20,40,80", "section 1: resolutions 1/dx, comma-separated" },
  { "rows", "string", "16,32,64", "section 2: particle rows across the film" },
  { "ar", "string", nil, "section 2: aspect ratios a/h (2,5,10; given, the thin-film scheme's row is left out)" },
  { "yield_n", "string", "20,40,80", "section 3: resolutions 1/dx" },
  { "flow_n", "string", "20,40,80", "section 4, Couette and Poiseuille: resolutions 1/dx" },
  { "cavity_n", "string", "20,40,80", "section 4, cavity: resolutions 1/dx" },
  { "part", "flag", 0, "1: run as one of the processes of a jobs > 1 run (writes OUT/validation.part<k>.md)" },
  { "check", "flag", 0, "1: check the parameters, print the plan, run nothing" },
}
local opt = params.args("validate", SPEC, ...)
local function refuse(msg) params.refuse("validate", msg) end
-- the lists, checked and read once (ar: the default's 2,5,10 when not given)
local lists = {}
for _, c in ipairs{ { "n", 4, 320 }, { "rows", 4, 256 }, { "ar", 0.5, 50, true }, { "yield_n", 4, 320 },
                    { "flow_n", 4, 320 }, { "cavity_n", 4, 320 }, { "only", 1, 4 } } do
  lists[c[1]] = params.list("validate", c[1], opt[c[1]] or "2,5,10", c[2], c[3], c[4])
end
if opt.threads < 1 or opt.threads > 256 then refuse(("threads must be 1..256, got %d"):format(opt.threads)) end
if opt.jobs < 1 or opt.jobs > 4 then refuse(("jobs must be 1..4, got %d"):format(opt.jobs)) end
local out = opt.out
-- the folder made and written to before the runs, not after them: a missing or read-only
-- folder stops the script at once rather than at its end
assert(sph.mkdir(out))
do
  local probe = assert(io.open(out .. "/validation.md.tmp", "w"))
  probe:close()
  os.remove(out .. "/validation.md.tmp")
end
local threads = opt.threads

local ns = lists.n
local only = {}
for _, k in ipairs(lists.only) do only[k] = true end
local clock0 = os.time()

-- An engine error as one line of a Markdown table.
local function clean(e)
  return (tostring(e):gsub("\n.*", ""):gsub("^[^:]*%.lua:%d+: ", ""):gsub("|", "/"))
end

-- Runs f(rec, ...) under pcall; f puts its world in rec.w as soon as it has one, so that a
-- failed run still reports its steps and seconds. Returns f's result table with ok = true,
-- or { ok = false, msg, steps, cpu, t }.
local function attempt(f, ...)
  local rec = {}
  local ok, r = pcall(f, rec, ...)
  if ok then
    r.ok = true
    return r
  end
  local w = rec.w
  local okw, s = pcall(function() return w:stats() end)
  return { ok = false, msg = clean(r), steps = okw and s.steps or 0, cpu = okw and s.wall_time or 0,
           t = okw and s.t or 0 }
end

-- Observed order between two errors at spacings dx1 > dx2 (nil when not defined).
local function order(e1, e2, dx1, dx2)
  if not (e1 and e2) or e1 <= 0 or e2 <= 0 or e1 ~= e1 or e2 ~= e2 then return nil end
  return math.log(e1 / e2) / math.log(dx1 / dx2)
end
local function ofmt(p) return p and ("%.2f"):format(p) or "" end

-- A failed run's table row under the header line head: cells[k] in column k (a sparse list:
-- the case, dx, "failed: ...", any reference), blanks elsewhere, its steps and seconds in the
-- last two columns, so that a column added to head needs no change here.
local function failed_row(head, cells, steps, cpu)
  local ncols, out = select(2, head:gsub("|", "")) - 1, {}
  for k = 1, ncols - 2 do out[k] = cells[k] or "" end
  out[ncols - 1], out[ncols] = ("%d"):format(steps), ("%.1f"):format(cpu)
  return "| " .. table.concat(out, " | ") .. " |\n"
end

-- orders[k] between resolution k - 1 and k of a list of { dx, err } (err nil: failed)
local function orders_of(list)
  local o = {}
  for k = 2, #list do o[k] = order(list[k - 1].err, list[k].err, list[k - 1].dx, list[k].dx) end
  return o
end

local function say(fmt, ...)
  io.write(fmt:format(...), "\n")
  io.stdout:flush()
end

local md = {} -- the sections of docs/validation.md, in order
local function w_md(...)
  for _, s in ipairs({ ... }) do md[#md + 1] = s end
end
local plots = {} -- { file, xlabel, ylabel, series }
local timing = {} -- { section, seconds }

---------------------------------------------------------------------------------------
-- 1. The square at t = 0+.
-- REFERENCES.md section 1: F_v at h = 1 and of the rectangle of the same area at h = 0.8
-- (ln F close to linear in ln h between them: the reference at the current gap), and the
-- unyielded area fraction at h = 1 (FE, not mesh-converged at Bn = 10: 0.11-0.13).
local refs = require "sph.references"
local REF = {
  { Bn = 0, unyielded = 0, at0 = true },
  { Bn = 10, unyielded = 0.12, at0 = true },
  { Bn = 1000, unyielded = 0.50 },
}

-- F / F_FE at t = 0+ (sph.squeeze_validation.square_t0), the world kept in rec
local function square(rec, c, n)
  return squeeze_validation.square_t0(n, c.Bn, { threads = threads, on_world = function(w) rec.w = w end })
end

local HEAD1 = "| Bn | dx | F(0+) / F_FE | window mean | error | observed order | unyielded fraction (FE) | correction share | steps | s |\n"
local function section1()
  local rows, series = {}, {}
  for _, c in ipairs(REF) do
    local xs, es = {}, {}
    for _, n in ipairs(ns) do
      local r = attempt(square, c, n)
      local row = { Bn = c.Bn, n = n, ok = r.ok, r = r, ref_un = c.unyielded, at0 = c.at0 }
      if r.ok then
        row.val = c.at0 and r.ratio0 or r.ratio
        row.err = math.abs(row.val - 1)
        xs[#xs + 1], es[#es + 1] = 1 / n, row.err
        say("square Bn = %g, dx = 1/%d: F / F_FE = %.4f (%s; error %.4f; window mean at the gap %.4f), unyielded %.3f (FE %.2f), correction share %.4f, %d steps, %.1f s",
          c.Bn, n, row.val, c.at0 and "t = 0+" or "window mean", row.err, r.ratio, r.unyielded, c.unyielded, r.correction_share, r.steps, r.cpu)
      else
        say("square Bn = %g, dx = 1/%d: failed: %s", c.Bn, n, r.msg)
      end
      rows[#rows + 1] = row
    end
    for i = 2, #xs do
      local p = math.log(es[i - 1] / es[i]) / math.log(xs[i - 1] / xs[i])
      say("  observed order 1/%d -> 1/%d: %.2f", math.floor(1 / xs[i - 1] + 0.5), math.floor(1 / xs[i] + 0.5), p)
      rows[#rows].orders = (rows[#rows].orders or "") .. ("%.2f "):format(p)
    end
    if #xs > 0 then series[#series + 1] = { x = xs, y = es, label = ("Bn = %g"):format(c.Bn) } end
  end
  w_md("## The square at t = 0+ (section 1)\n\n",
    "Half square 2a = H = 1, symmetry plane x = 0, V = -1, Re = 0.05, M = 800, default options; ",
    "F(0+) / F_FE: the plate force's least-squares line over t in (0.01, 0.02) at t = 0, over the square's FE force ",
    "(Bn = 0, 10; the error and the order are of this). Window mean: the mean over t in (0.005, 0.02) of the force ",
    "over the FE rectangle at the current gap, which the barrelling sample's pinned contact width biases by about ",
    "-1.4 %; at Bn = 1000 the force builds up over the first 0.005 and falls nonlinearly, so the error is the window ",
    "mean's. Correction share: the share of the particles' motion over the window that the density correction made, ",
    "not their velocity (stats.correction_share; 0 in the continuum).\n\n",
    HEAD1, "|---|---|---|---|---|---|---|---|---|---|\n")
  for _, r in ipairs(rows) do
    if r.ok then
      w_md(("| %g | 1/%d | %s | %.4f | %.4f | %s | %.3f (%.2f) | %.4f | %d | %.1f |\n"):format(r.Bn, r.n,
        r.at0 and ("%.4f"):format(r.r.ratio0) or "", r.r.ratio, r.err,
        r.orders or "", r.r.unyielded, r.ref_un, r.r.correction_share, r.r.steps, r.r.cpu))
    else
      w_md(failed_row(HEAD1, { ("%g"):format(r.Bn), ("1/%d"):format(r.n), "failed: " .. r.r.msg }, r.r.steps, r.r.cpu))
    end
  end
  w_md("\n![error against dx](validation_square.png)\n\n")
  if #series > 0 then
    plots[#plots + 1] = { file = "validation_square.png", xlabel = "dx", ylabel = "|F / F_FE - 1|", series = series }
  end
end

---------------------------------------------------------------------------------------
-- 2. Thin films: a Newtonian rectangle of height h0 = 1 and half-width a0 = (a/h) h0
-- (sph.squeeze.build: half sample, symmetry plane x = 0, shifting 20, the engine's
-- defaults otherwise), the upper plate at V = -1, Re = rho V h0 / mu = 0.05. The plate
-- force (the whole sample's) over the reference at the current gap h and half-width
-- a = A / (2 h) (A the sample's area from its particle count): REFERENCES.md section 2's
-- fit for a/h >= 2, F_FE = 8 mu V (a/h)^3 [1 - 0.151 (h/a) + 1.17 (h/a)^2], times the
-- inertia factor 1 + (17/70) Re h (1.012 here). The mean of the ratio over every step with
-- t in (FILM.t0, FILM.t1): after the impulsive start's transient (at 32 rows the force is
-- within 2 % of its later course by t = 0.004, 0.08 Re h0^2), while the gap has closed by
-- 0.5-2 %. The force moves by about 1 % as particles of the bulging sides reach the rows
-- next to the plates, every 0.003-0.005: the window spans several such events, so that its
-- mean does not hang on their phase (over (0.005, 0.01) two starts of the a/h = 10 film
-- differed by 0.9 % at 16 rows and 0.7 % at 32, over (0.005, 0.02) by 0.2 %).
-- Resolutions by rows across the gap (dx = h0 / rows).
local FILM = { Re = 0.05, t0 = 0.005, t1 = 0.02 }
local THIN = { thin_film = true } -- README, Thin films
local function film(rec, ar, rows, world)
  local wo = { threads = threads }
  for k, v in pairs(world or {}) do wo[k] = v end
  return squeeze_validation.film(ar, rows, { Re = FILM.Re, t0 = FILM.t0, t1 = FILM.t1, world = wo, on_world = function(w) rec.w = w end })
end

local HEAD2 = "| case | rows (dx) | F | F_FE | F / F_FE | F / F_FE, contact width | contact half-width at t1 (area's) | error | " ..
  "observed order | F / F_FE at t = 0+ | peak density error | correction share | steps | s |\n"
local function section2()
  local rowsl, ars = lists.rows, lists.ar
  local cases = {}
  for _, ar in ipairs(ars) do cases[#cases + 1] = { ar = ar, label = ("a/h = %g"):format(ar) } end
  if not opt.ar then
    cases[#cases + 1] = { ar = 10, label = "a/h = 10, thin_film = true", world = THIN }
  end
  local series = {}
  w_md("## Thin films (section 2)\n\n",
    "Newtonian rectangle, height h0 = 1, half-width a0 = (a/h) h0, half sample (symmetry plane x = 0, ",
    "`sph.squeeze.build`: shifting 20, the engine's defaults otherwise), V = -1, Re = rho V h0 / mu = ",
    ("%g. F / F_FE is the mean over every step with t in (%g, %g) (the gap closes by %g-%g %%) of the plate force "):format(FILM.Re,
      FILM.t0, FILM.t1, 100 * FILM.t0, 100 * FILM.t1),
    "over the reference at the current gap h and half-width a = A / (2h) (A: the sample's area): the fit of ",
    "REFERENCES.md section 2, F_FE = 8 mu V (a/h)^3 [1 - 0.151 h/a + 1.17 (h/a)^2] (F_FE / F_lub = 1.216, 1.017, 0.997 ",
    ("at a/h = 2, 5, 10), times the inertia factor 1 + (17/70) Re h = %.4f. "):format(1 + 17 / 70 * FILM.Re),
    "F and F_FE are the window means of the force and of the reference (whole sample). Over the window the ratio ",
    "drifts down (the force rises more slowly than the rectangle's at the current gap: the sample barrels, its contact ",
    "with the plates does not widen as a rectangle's would), and that drift is in the window mean; \"F / F_FE at t = 0+\" ",
    "is the least-squares line of the ratio against t over the window taken at t = 0, the rectangle at the start, ",
    "without the drift (where the force alternates from step to step, as at a/h = 10, it is mostly noise). ",
    "The contact with the no-slip plates stays where it was while the free sides bulge (a/h = 10, 32 rows: the ",
    "outermost particle at the plates moves from 9.984 to 10.001 by t = 0.01, the mid-height side to 10.12, A / (2h) ",
    "to 10.10), so the error is taken against the rectangle of the sample's gap and contact half-width instead ",
    "(\"F / F_FE, contact width\": the reference at a = the outermost particle of the rows within dx of either plate plus ",
    "dx / 2, the mean over the window; the contact half-width at the window's end and the area's a = A / (2h) are given). ",
    "Resolutions ",
    "by particle rows across the gap: 16, 32, 64 (8 rows is under the 12 below which the README calls the defaults ",
    "unreliable in a film, and leaves 5-16 steps in the window). The last case is the README's thin-film scheme ",
    "(`thin_film = true`; the free surface then holds p = 0, which REFERENCES.md puts at ",
    "h^2 / (2 a^2) = 0.5 % of the force at a/h = 10).\n\n",
    HEAD2, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
  for _, c in ipairs(cases) do
    local list = {}
    for k, rows in ipairs(rowsl) do
      local r = attempt(film, c.ar, rows, c.world)
      r.dx = 1 / rows
      if r.ok then r.err = math.abs(r.ratio_c - 1) end
      list[k] = r
    end
    local o = orders_of(list)
    local xs, es = {}, {}
    for k, r in ipairs(list) do
      if r.ok then
        say("film %s, %d rows: F = %.4g, F_FE = %.4g, F / F_FE = %.4f (%.4f at the contact width %.4f, the area's %.4f: error %.4f, order %s; %.4f at t = 0+ by the window's line), %d samples, h = %.4f, peak density error %.4f, correction share %.4f, %d steps, %.1f s",
          c.label, rowsl[k], r.F, r.Fref, r.ratio, r.ratio_c, r.a_c, r.a_area, r.err, ofmt(o[k]), r.ratio0, r.samples, r.h, r.peak, r.correction_share, r.steps, r.cpu)
        w_md(("| %s | %d (1/%d) | %.5g | %.5g | %.4f | %.4f | %.4f (%.4f) | %.4f | %s | %.4f | %.4f | %.4f | %d | %.1f |\n"):format(c.label, rowsl[k], rowsl[k],
          r.F, r.Fref, r.ratio, r.ratio_c, r.a_c, r.a_area, r.err, ofmt(o[k]), r.ratio0, r.peak, r.correction_share, r.steps, r.cpu))
        xs[#xs + 1], es[#es + 1] = r.dx, r.err
      else
        say("film %s, %d rows: failed: %s", c.label, rowsl[k], r.msg)
        w_md(failed_row(HEAD2, { c.label, ("%d (1/%d)"):format(rowsl[k], rowsl[k]), "failed: " .. r.msg }, r.steps, r.cpu))
      end
    end
    if #xs > 0 then series[#series + 1] = { x = xs, y = es, label = c.label, style = "both" } end
  end
  w_md("\n![error against dx](validation_film.png)\n\n")
  if #series > 0 then
    plots[#plots + 1] = { file = "validation_film.png", xlabel = "dx / h0 (1 / rows across the gap)", ylabel = "|F / F_FE - 1|",
                          series = series, title = "thin films, a/h = 2, 5, 10 (section 2)" }
  end
end

---------------------------------------------------------------------------------------
-- 3. Yield: the Bingham square (2a = H = 1, Bn = tau0 = 10, M = 800, mu = 1, rho = Re = 1;
-- sph.squeeze.build: half sample, lower plate fixed) under a constant load on the upper
-- plate, 0.75 and 1.5 times the limit load F_y = Bn F_tau,y(1) = 10 x 2.015 (negative:
-- compressing), from t = 0 to t = 1. References: under 0.75 F_y the sample only creeps,
-- h(1) > 0.98 (V of order 1e-3 or less); under 1.5 F_y it slows down near h*, where
-- Bn F_tau,y(h*) = load with F_tau,y(h) ~ 1/(2 h^3) + 1.5/h (within 3 %; barrelling ignored).
local YIELD = { Bn = 10, M = 800, Re = 1, Fty1 = refs.FTY[1], t_end = 1, probe_t = 0.2 }
YIELD.Fy = YIELD.Bn * YIELD.Fty1
local function yield_height(F) return refs.plastic_height(YIELD.Bn, F) end

local function yield_run(rec, frac, n)
  local dx = 1 / n
  local F = frac * YIELD.Fy
  local w, top = squeeze.build{ dx = dx, Re = YIELD.Re, Bn = YIELD.Bn, M = YIELD.M, mode = "load", F = -F, h_min = 0.25,
                                world = { threads = threads } }
  rec.w = w
  local ts, hs = { 0 }, { top.position }
  local h_lb -- the first gap at which the shape's lower bound (below) carries the load
  w:run{ until_t = YIELD.t_end, every = 0.01, each = function()
    ts[#ts + 1], hs[#hs + 1] = w.t, top.position
    if frac > 1 and not h_lb and w.t > 0 and YIELD.Bn * refs.shape_lower_bound(w:field("x"), w:field("y"), top.position, dx) >= F then
      h_lb = top.position
    end
  end }
  local s = w:stats()
  local r = { h = top.position, V = top:velocity(), force = top.force, yielded = s.yielded / s.fluid, steps = w.steps,
              correction_share = s.correction_share,
              cpu = s.wall_time, peak = s.peak_density_error, ts = ts, hs = hs }
  if frac > 1 then
    -- the shape reached: a lower bound on the load it carries without flowing (the largest
    -- rectangle inside it, refs.shape_lower_bound); then 0.8 of that bound for probe_t more,
    -- under which a Bingham sample can only creep
    local fty, a = refs.shape_lower_bound(w:field("x"), w:field("y"), r.h, dx)
    r.a_lb, r.F_lb, r.h_lb, r.load = a, YIELD.Bn * fty, h_lb, F
    top:load(-0.8 * r.F_lb)
    -- a probe that fails keeps the run's h(1): its cell says why
    local ok, err = pcall(w.run, w, { until_t = YIELD.t_end + YIELD.probe_t })
    if ok then r.creep = (r.h - top.position) / YIELD.probe_t else r.probe_failed = clean(err) end
    r.cpu = w:stats().wall_time
  end
  return r
end

local HEAD3 = "| load | dx | h(1) | reference | error | observed order | V(1) | yielded | correction share | steps | s |\n"
local function section3()
  local nl = lists.yield_n
  local hstar = yield_height(1.5 * YIELD.Fy)
  -- the table's F_tau,y(h) interpolated log-log between h = 0.8 and 0.6
  local H, T = refs.HS, refs.FTY
  local slope = math.log(T[3] / T[2]) / math.log(H[3] / H[2])
  local htab = H[2] * (1.5 * YIELD.Fty1 / T[2]) ^ (1 / slope)
  local cases = {
    { frac = 0.75, label = "0.75 F_y", ref = "> 0.98 (creep only)", err_name = "1 - h(1)",
      err = function(h) return 1 - h end },
    { frac = 1.5, label = "1.5 F_y", ref = ("%.4f (h*)"):format(hstar), err_name = "|h(1) / h* - 1|",
      err = function(h) return math.abs(h / hstar - 1) end },
  }
  w_md("## Yield: the load a Bingham square carries (section 3)\n\n",
    ("Bingham square 2a = H = 1, Bn = tau0 = %g, M = %g, mu = 1, rho = Re = %g, half sample (`sph.squeeze.build`: "):format(YIELD.Bn, YIELD.M, YIELD.Re),
    "symmetry plane x = 0, shifting 20, the engine's defaults otherwise), lower plate fixed, upper plate under a ",
    ("constant load `top:load(-F)` from t = 0, F = 0.75 and 1.5 F_y with F_y = Bn F_tau,y(1) = %g x %g = %g. "):format(YIELD.Bn,
      YIELD.Fty1, YIELD.Fy),
    "References (REFERENCES.md section 3): under 0.75 F_y the square must only creep (M = 800: plate speed of order ",
    "10^-3 or less), so h(1) > 0.98; the error given is 1 - h(1). Under 1.5 F_y it flows and slows down near h*, where ",
    ("Bn F_tau,y(h*) = F with F_tau,y(h) = 1/(2h^3) + 1.5/h: h* = %.4f (%.4f from the table's F_tau,y interpolated "):format(hstar, htab),
    "log-log; the estimate ignores barrelling, and with M = 800 the plate never stops exactly); the error given is ",
    "|h(1) / h* - 1|. V(1) is the plate velocity at t = 1, yielded the fraction of particles with |tau| > tau0 at t = 1, ",
    "correction share the share of the particles' motion over the run that the density correction made, not their ",
    "velocity (stats.correction_share).\n\n",
    HEAD3, "|---|---|---|---|---|---|---|---|---|---|---|\n")
  local series, hseries, probes, rows75 = {}, {}, {}, {}
  for _, c in ipairs(cases) do
    local list = {}
    for k, n in ipairs(nl) do
      local r = attempt(yield_run, c.frac, n)
      r.dx = 1 / n
      if r.ok then r.err = c.err(r.h) end
      list[k] = r
    end
    local o = orders_of(list)
    local xs, es = {}, {}
    for k, r in ipairs(list) do
      if r.ok then
        say("yield %s (F = %.4f), dx = 1/%d: h(1) = %.4f, reference %s, %s = %.4f (order %s), V(1) = %.4g, yielded %.3f, peak density error %.4f, correction share %.4f, %d steps, %.1f s",
          c.label, c.frac * YIELD.Fy, nl[k], r.h, c.ref, c.err_name, r.err, ofmt(o[k]), r.V, r.yielded, r.peak, r.correction_share, r.steps, r.cpu)
        local verdict = c.frac < 1 and (r.h > 0.98 and " (creeps only)" or " (flows: not > 0.98)") or ""
        w_md(("| %s | 1/%d | %.4f%s | %s | %.4f | %s | %.3g | %.3f | %.4f | %d | %.1f |\n"):format(c.label, nl[k], r.h, verdict, c.ref, r.err,
          ofmt(o[k]), r.V, r.yielded, r.correction_share, r.steps, r.cpu))
        xs[#xs + 1], es[#es + 1] = r.dx, r.err
        if r.F_lb then probes[#probes + 1] = { n = nl[k], r = r } end
        if c.frac < 1 then rows75[#rows75 + 1] = { n = nl[k], V = r.V } end
        hseries[#hseries + 1] = { x = r.ts, y = r.hs, label = ("%s, dx = 1/%d"):format(c.label, nl[k]) }
      else
        say("yield %s, dx = 1/%d: failed: %s", c.label, nl[k], r.msg)
        w_md(failed_row(HEAD3, { c.label, ("1/%d"):format(nl[k]), "failed: " .. r.msg, c.ref }, r.steps, r.cpu))
      end
    end
    if #xs > 0 then series[#series + 1] = { x = xs, y = es, label = ("%s: %s"):format(c.label, c.err_name), style = "both" } end
  end
  if #probes > 0 then
    w_md("\nThe shape the sample under 1.5 F_y has reached at t = 1 carries, without flowing, at least the rigid-plastic ",
      "limit load F_lb of the largest rectangle inside it (limit analysis' lower-bound theorem: a stress field the ",
      "rectangle carries, continued by zero outside it, is admissible for the whole sample; `sph.references.shape_lower_bound`: ",
      "the rectangle through the outermost particle centres of the narrowest row, a_lb its half-width, its limit load ",
      "from section 3's FE table). Where the load is below F_lb a Bingham sample with M = 800 can only creep (V of ",
      "order 10^-3, as under 0.75 F_y above); a sample still moving faster is too soft, whatever its height. From t = 1 ",
      ("the load is then lowered to 0.8 F_lb for %g of time; creep is the plate's mean speed over it (the 1.5 F_y rows' s above includes it). "):format(YIELD.probe_t),
      "h_lb is the gap at the first output (every 0.01 of time) where F_lb of the shape then reached was at least the ",
      "load: a Bingham sample going through the same shapes would have stopped there or before, above h_lb (the ",
      "shapes are the engine's, so h_lb is not independent of it, but its use of them is: a stopping height below ",
      "h_lb contradicts the theorem).\n\n",
      "| dx | h(1) | a_lb | F_lb | load / F_lb | V(1) | creep under 0.8 F_lb | creep under 0.75 F_y (fresh square, V(1)) | h_lb | h_lb / h* - 1 |\n",
      "|---|---|---|---|---|---|---|---|---|---|\n")
    local fresh = {}
    for _, row in ipairs(rows75) do fresh[row.n] = row.V end
    for _, p in ipairs(probes) do
      local r = p.r
      say("yield 1.5 F_y, dx = 1/%d: shape at t = 1: a_lb = %.4f, F_lb = %.3f, load / F_lb = %.3f, V(1) = %.4g; creep under 0.8 F_lb %.4g; h_lb %s",
        p.n, r.a_lb, r.F_lb, r.load / r.F_lb, r.V, r.creep or 0 / 0, r.h_lb and ("%.4f"):format(r.h_lb) or "not reached")
      w_md(("| 1/%d | %.4f | %.4f | %.2f | %.3f | %.3g | %s | %s | %s | %s |\n"):format(p.n, r.h, r.a_lb, r.F_lb, r.load / r.F_lb,
        r.V, r.creep and ("%.3g"):format(r.creep) or ("failed: " .. r.probe_failed), fresh[p.n] and ("%.3g"):format(-fresh[p.n]) or "", r.h_lb and ("%.4f"):format(r.h_lb) or "not reached",
        r.h_lb and ("%.3f"):format(r.h_lb / hstar - 1) or ""))
    end
  end
  hseries[#hseries + 1] = { x = { 0, YIELD.t_end }, y = { 0.98, 0.98 }, label = "0.98 (0.75 F_y must stay above)" }
  hseries[#hseries + 1] = { x = { 0, YIELD.t_end }, y = { hstar, hstar }, label = ("h* = %.3f (1.5 F_y)"):format(hstar) }
  w_md("\n![error against dx](validation_yield.png)\n\n![h(t)](validation_yield_h.png)\n\n")
  if #series > 0 then
    plots[#plots + 1] = { file = "validation_yield.png", xlabel = "dx", ylabel = "error of h(1)", series = series,
                          title = "Bingham square under 0.75 and 1.5 F_y (section 3)" }
    plots[#plots + 1] = { file = "validation_yield_h.png", xlabel = "t", ylabel = "h", series = hseries, log = "", yrange = { 0.2, 1.02 },
                          title = "gap under a constant load, Bn = 10, M = 800 (section 3)" }
  end
end

---------------------------------------------------------------------------------------
-- 4. Exact and 1D flows.
-- Channels as in sph.flows: 0 < y < 1 between plates 3 dx thick, periodic in x over
-- Lx = 10 dx, rho = mu = 1, dt <= 0.125 rho dx^2 / mu (sph.flows' start-up step: the
-- backward-Euler error of the impulsive start then shrinks like dx^2). u(0.5) is the mean
-- u of the two particle rows next to y = 0.5; Q = sum of u dx^2 / Lx; the wall stress is
-- the x-force on the lower plate (made movable along x at velocity 0 so that the engine
-- reports its force) over Lx.
local COUETTE = { Bn = 1, M = 800, times = { 0.05, 0.1, 0.2, 0.3, 0.5, 1.0 },
                  u = { 0.1154, 0.2637, 0.4119, 0.4672, 0.4954, 0.49997 },
                  tau = { 1.039, 1.296, 1.724, 1.897, 1.986, 1.99990 } }
local POIS = { Bn = 0.8, M = 800, g = 8, times = { 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0 },
               u = { 0.05901, 0.11203, 0.24494, 0.39839, 0.55069, 0.60716, 0.63566, 0.64010 },
               Q = { 0.05279, 0.09642, 0.19758, 0.30623, 0.40971, 0.44744, 0.46639, 0.46933 } }

local function centre_and_flux(w, dx, Lx)
  local ys, us = w:field("y"), w:field("u")
  local s, m, q = 0, 0, 0
  for i = 1, #ys do
    q = q + us[i]
    if math.abs(ys[i] - 0.5) < dx then s, m = s + us[i], m + 1 end
  end
  return s / m, q * dx * dx / Lx
end

local function channel(rec, n, mat, gravity, lid)
  local dx = 1 / n
  local Lx = 10 * dx
  local w = sph.world{ dx = dx, rho = 1, gravity = gravity, periodic = { x = { 0, Lx } }, threads = threads,
                       dt_max = 0.125 * dx * dx }
  rec.w = w
  w:fill{ rect = { 0, 0, Lx, 1 }, material = mat }
  local bot = w:plate{ rect = { 0, -3 * dx, Lx, 0 }, axis = lid and "x" or nil }
  if lid then bot:velocity(0) end
  local top = w:plate{ rect = { 0, 1, Lx, 1 + 3 * dx }, axis = lid and "x" or nil }
  if lid then top:velocity(lid) end
  return w, bot, dx, Lx
end

local function couette_run(rec, n)
  local w, bot, dx, Lx = channel(rec, n, sph.bingham{ mu = 1, tau0 = COUETTE.Bn, m = COUETTE.M }, nil, 1)
  local u, tau = {}, {}
  for k, t in ipairs(COUETTE.times) do
    w:run{ until_t = t }
    u[k] = centre_and_flux(w, dx, Lx)
    tau[k] = bot.force / Lx
  end
  return { a = u, b = tau, steps = w.steps, cpu = w:stats().wall_time }
end

local function poiseuille_run(rec, n)
  local w, _, dx, Lx = channel(rec, n, sph.bingham{ mu = 1, tau0 = POIS.Bn, m = POIS.M }, { POIS.g, 0 })
  local u, Q = {}, {}
  for k, t in ipairs(POIS.times) do
    w:run{ until_t = t }
    u[k], Q[k] = centre_and_flux(w, dx, Lx)
  end
  return { a = u, b = Q, steps = w.steps, cpu = w:stats().wall_time }
end

-- The creeping Bingham lid-driven cavity: the unit square, the walls and lid of sph.flows'
-- cavity (the lid a plate slide at U = 1; shifting 20, density_tol 0.04, surface = 0), mu = 1,
-- tau0 = Bn, M = 800, rho = Re = 0.01, from rest to t = 0.2 Re (the slowest Stokes mode of
-- the box decays like exp(-52 t / Re)); y_c at 0.1 Re is kept as a check that the flow is
-- steady. dt <= 0.25 rho dx^2 / mu: the steady state depends on dt (measured at dx = 1/20,
-- Newtonian: y_c = 0.7542 / 0.7490 / 0.7405 / 0.7250 at dt = 0.5 / 1 / 2 / 4 rho dx^2 / mu,
-- and 0.50 / 0.30 with the adaptive dt alone; Bn = 5: 0.8748 / 0.8728 / 0.8526 at 0.125 /
-- 0.25 / 0.5). y_c: the zero of u on x = 0.5 below the lid (u from a linear MLS fit over
-- 3 dx, flows.mls, scanned down from y = 1 - 1.5 dx in steps of 0.01, then bisection); the
-- unyielded fraction: the share of particles with |tau| <= tau0 (equal areas).
local CAV = { Re = 0.01, c = 0.25, t_end = 0.2, t_check = 0.1,
              cases = { { Bn = 0, yc = 0.7650, un = 0 }, { Bn = 5, yc = 0.8480, un = 0.40 }, { Bn = 50, yc = 0.9285, un = 0.70 } } }

local function vortex_centre(w, dx)
  local xs, ys, us = w:field("x"), w:field("y"), w:field("u")
  local function U(y) return flows.mls(xs, ys, us, 0.5, y, 3 * dx) end
  local y = 1 - 1.5 * dx
  local ua = U(y)
  while y > 0.1 do
    local y2 = y - 0.01
    local ub = U(y2)
    if ua > 0 and ub <= 0 then
      local lo, hi = y2, y
      for _ = 1, 40 do
        local m = 0.5 * (lo + hi)
        if U(m) > 0 then hi = m else lo = m end
      end
      return 0.5 * (lo + hi)
    end
    y, ua = y2, ub
  end
  return 0 / 0
end

local function cavity_run(rec, c, n)
  local dx = 1 / n
  local T3 = 3 * dx
  local w = sph.world{ dx = dx, rho = CAV.Re, threads = threads, shifting = 20, density_tol = 0.04, surface = 0,
                       dt_max = CAV.c * CAV.Re * dx * dx }
  rec.w = w
  local mat = c.Bn > 0 and sph.bingham{ mu = 1, tau0 = c.Bn, m = 800 } or sph.newtonian{ mu = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = mat }
  w:plate{ rect = { -T3, -T3, 1 + T3, 0 } }
  w:plate{ rect = { -T3, 0, 0, 1 + T3 } }
  w:plate{ rect = { 1, 0, 1 + T3, 1 + T3 } }
  w:plate{ rect = { 0, 1, 1, 1 + T3 }, slide = { 1, 0 } }
  w:run{ until_t = CAV.t_check * CAV.Re }
  local y1 = vortex_centre(w, dx)
  w:run{ until_t = CAV.t_end * CAV.Re }
  local yc = vortex_centre(w, dx)
  local yl, un = w:field("yielded"), 0
  for i = 1, #yl do if yl[i] < 0.5 then un = un + 1 end end
  local s = w:stats()
  return { yc = yc, drift = yc - y1, un = un / #yl, steps = w.steps, cpu = s.wall_time, peak = s.peak_density_error }
end

-- A start-up case's tables: per tabulated time the value at each resolution with its error,
-- and per resolution the largest error over the times, its order, steps and seconds.
local function startup_section(name, run, ref, qa, qb, la, lb, nl, series)
  local list = {}
  for k, n in ipairs(nl) do
    local r = attempt(run, n)
    r.dx = 1 / n
    if r.ok then
      r.ea, r.eb = 0, 0
      for j = 1, #ref.times do
        r.ea = math.max(r.ea, math.abs(r.a[j] - ref[qa][j]))
        r.eb = math.max(r.eb, math.abs(r.b[j] - ref[qb][j]))
      end
    end
    list[k] = r
  end
  local oa, ob = {}, {}
  for k = 2, #list do
    oa[k] = order(list[k - 1].ea, list[k].ea, list[k - 1].dx, list[k].dx)
    ob[k] = order(list[k - 1].eb, list[k].eb, list[k - 1].dx, list[k].dx)
  end
  local head = "| t | " .. la .. " reference"
  local sep = "|---|---"
  for _, n in ipairs(nl) do head, sep = head .. (" | 1/%d (error)"):format(n), sep .. "|---" end
  head = head .. " | " .. lb .. " reference"
  sep = sep .. "|---"
  for _, n in ipairs(nl) do head, sep = head .. (" | 1/%d (error)"):format(n), sep .. "|---" end
  w_md(head, " |\n", sep, "|\n")
  for j, t in ipairs(ref.times) do
    local line = ("| %g | %.5g"):format(t, ref[qa][j])
    for _, r in ipairs(list) do
      line = line .. (r.ok and (" | %.5f (%+.5f)"):format(r.a[j], r.a[j] - ref[qa][j]) or " | failed")
    end
    line = line .. (" | %.5g"):format(ref[qb][j])
    for _, r in ipairs(list) do
      line = line .. (r.ok and (" | %.5f (%+.5f)"):format(r.b[j], r.b[j] - ref[qb][j]) or " | failed")
    end
    w_md(line, " |\n")
  end
  local head = ("| dx | max error of %s | observed order | max error of %s | observed order | steps | s |\n"):format(la, lb)
  w_md("\n", head, "|---|---|---|---|---|---|---|\n")
  local xs, ea, eb = {}, {}, {}
  for k, r in ipairs(list) do
    if r.ok then
      say("%s, dx = 1/%d: max |%s - ref| = %.5f (order %s), max |%s - ref| = %.5f (order %s), %d steps, %.1f s",
        name, nl[k], la, r.ea, ofmt(oa[k]), lb, r.eb, ofmt(ob[k]), r.steps, r.cpu)
      for j, t in ipairs(ref.times) do
        say("  t = %-5g %s = %.5f (ref %.5g)  %s = %.5f (ref %.5g)", t, la, r.a[j], ref[qa][j], lb, r.b[j], ref[qb][j])
      end
      w_md(("| 1/%d | %.5f | %s | %.5f | %s | %d | %.1f |\n"):format(nl[k], r.ea, ofmt(oa[k]), r.eb, ofmt(ob[k]), r.steps, r.cpu))
      xs[#xs + 1], ea[#ea + 1], eb[#eb + 1] = r.dx, r.ea, r.eb
    else
      say("%s, dx = 1/%d: failed: %s", name, nl[k], r.msg)
      w_md(failed_row(head, { ("1/%d"):format(nl[k]), "failed: " .. r.msg }, r.steps, r.cpu))
    end
  end
  w_md("\n")
  if #xs > 0 then
    series[#series + 1] = { x = xs, y = ea, label = name .. ": max |" .. la .. " - ref|", style = "both" }
    series[#series + 1] = { x = xs, y = eb, label = name .. ": max |" .. lb .. " - ref|", style = "both" }
  end
end

local HEAD_CAVITY = "| Bn | dx | y_c | reference | error | observed order | change since 0.1 Re | unyielded | reference | " ..
  "error | observed order | steps | s |\n"
local function section4()
  local nl = lists.flow_n
  local cl = lists.cavity_n
  local series = {}
  w_md("## Exact and 1D flows (section 4)\n\n",
    "Channels 0 < y < 1 between plates 3 dx thick, periodic in x over 10 dx (the channels of `sph.flows`), rho = mu = 1, ",
    "M = 800, dt <= 0.125 rho dx^2 / mu (`sph.flows`' start-up step), from rest. u(0.5) is the mean u of the two particle ",
    "rows next to y = 0.5, Q the flux per unit depth (sum of u dx^2 over the channel length), tau_w the x-force on the ",
    "lower, fixed plate over the channel length (the plate is made movable along x at velocity 0 so that the engine ",
    "reports its force). Errors are absolute (in U, mu U / L, U L); the error of a resolution is the largest over the ",
    "tabulated times.\n\n",
    ("### Bingham Couette start-up (Bn = %g)\n\nThe upper plate slides at U = 1 from t = 0; the references are the "):format(COUETTE.Bn),
    "regularised (M = 800) values of REFERENCES.md section 4.\n\n")
  startup_section("Couette Bn = 1", couette_run, COUETTE, "u", "tau", "u(0.5)", "tau_w", nl, series)
  w_md(("### Bingham Poiseuille start-up (Bn = %g)\n\nBody force g = %g along x, plug half-width y0 = tau0 / g = %g; "):format(POIS.Bn,
    POIS.g, POIS.Bn / POIS.g), "references: 1D finite volumes, converged to 5e-5 (steady, M = 800: u(0.5) = 0.64013, Q = 0.46935).\n\n")
  startup_section("Poiseuille Bn = 0.8", poiseuille_run, POIS, "u", "Q", "u(0.5)", "Q", nl, series)
  w_md("### Creeping Bingham lid-driven cavity\n\n",
    ("The unit square, no-slip walls, the lid a plate slide at U = 1 (the walls of `sph.flows`' cavity; shifting 20, "):format(),
    ("density_tol 0.04, surface = 0), mu = 1, tau0 = Bn, M = 800, rho = Re = %g, from rest to t = %g Re (steady: the "):format(CAV.Re,
      CAV.t_end),
    ("change of y_c since t = %g Re is given), dt <= %g rho dx^2 / mu (the steady state depends on dt: at dx = 1/20, "):format(CAV.t_check,
      CAV.c),
    "Newtonian, y_c = 0.7542 / 0.7490 / 0.7405 / 0.7250 at dt = 0.5 / 1 / 2 / 4 rho dx^2 / mu, and 0.4-0.5 with the adaptive ",
    "dt alone; Bn = 5: 0.8748 / 0.8728 / 0.8526 at 0.125 / 0.25 / 0.5). y_c is the zero of u on x = 0.5 below the lid ",
    "(linear MLS fit of u over 3 dx); unyielded: the share of particles with |tau| <= tau0. References: FE, M = 800 ",
    "(REFERENCES.md section 4).\n\n",
    HEAD_CAVITY, "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
  for _, c in ipairs(CAV.cases) do
    local list = {}
    for k, n in ipairs(cl) do
      local r = attempt(cavity_run, c, n)
      r.dx = 1 / n
      if r.ok then r.ey, r.eu = math.abs(r.yc - c.yc), math.abs(r.un - c.un) end
      list[k] = r
    end
    local oy, ou = {}, {}
    for k = 2, #list do
      oy[k] = order(list[k - 1].ey, list[k].ey, list[k - 1].dx, list[k].dx)
      ou[k] = order(list[k - 1].eu, list[k].eu, list[k - 1].dx, list[k].dx)
    end
    local xs, ey, eu = {}, {}, {}
    for k, r in ipairs(list) do
      if r.ok then
        say("cavity Bn = %g, dx = 1/%d: y_c = %.4f (FE %.4f, error %.4f, order %s, change since 0.1 Re %+.5f), unyielded %.3f (FE %.2f, error %.3f, order %s), peak density error %.4f, %d steps, %.1f s",
          c.Bn, cl[k], r.yc, c.yc, r.ey, ofmt(oy[k]), r.drift, r.un, c.un, r.eu, ofmt(ou[k]), r.peak, r.steps, r.cpu)
        w_md(("| %g | 1/%d | %.4f | %.4f | %.4f | %s | %+.5f | %.3f | %.2f | %.3f | %s | %d | %.1f |\n"):format(c.Bn, cl[k], r.yc, c.yc,
          r.ey, ofmt(oy[k]), r.drift, r.un, c.un, r.eu, ofmt(ou[k]), r.steps, r.cpu))
        xs[#xs + 1], ey[#ey + 1], eu[#eu + 1] = r.dx, r.ey, r.eu
      else
        say("cavity Bn = %g, dx = 1/%d: failed: %s", c.Bn, cl[k], r.msg)
        w_md(failed_row(HEAD_CAVITY, { ("%g"):format(c.Bn), ("1/%d"):format(cl[k]), "failed: " .. r.msg, ("%.4f"):format(c.yc),
                                       [9] = ("%.2f"):format(c.un) }, r.steps, r.cpu))
      end
    end
    if #xs > 0 then
      series[#series + 1] = { x = xs, y = ey, label = ("cavity Bn = %g: |y_c - FE|"):format(c.Bn), style = "both" }
      if c.Bn > 0 then
        series[#series + 1] = { x = xs, y = eu, label = ("cavity Bn = %g: |unyielded - FE|"):format(c.Bn), style = "both" }
      end
    end
  end
  w_md("\n![error against dx](validation_flows.png)\n\n")
  if #series > 0 then
    plots[#plots + 1] = { file = "validation_flows.png", xlabel = "dx", ylabel = "error", series = series, yrange = { 1e-4, 1e4 }, height = 640,
                          title = "Couette, Poiseuille, cavity (section 4)" }
  end
end

---------------------------------------------------------------------------------------
-- The sections run in `jobs` processes at once (default 2: each case is one thread, and the
-- four sections take about the same time), each a copy of this script on a share of the
-- sections (part=1) that writes its sections' Markdown to out/validation.part<k>.md and its
-- plots; this process then puts validation.md together in section order.
local sections = { section1, section2, section3, section4 }
local chosen = {}
for k = 1, #sections do if only[k] then chosen[#chosen + 1] = k end end
local jobs = opt.jobs
if opt.check == 1 then
  print(("validate: sections %s, %d at a time, %d thread%s a world, into %s/"):format(table.concat(chosen, ","),
    math.min(jobs, #chosen), threads, threads == 1 and "" or "s", out))
  os.exit(0)
end

local function part_file(k) return ("%s/validation.part%d.md"):format(out, k) end
local function quote(s) return "'" .. tostring(s):gsub("'", "'\\''") .. "'" end

local function run_here()
  for _, k in ipairs(chosen) do
    local t0, m0 = os.time(), #md + 1
    sections[k]()
    local dt = os.time() - t0
    timing[#timing + 1] = { k, dt }
    say("section %d: %d s", k, dt)
    if opt.part == 1 then -- this section's Markdown, for the parent process
      local f = assert(io.open(part_file(k) .. ".tmp", "w"))
      f:write(("%d\n"):format(dt), table.concat(md, "", m0, #md))
      assert(f:close())
      assert(os.rename(part_file(k) .. ".tmp", part_file(k)))
    end
  end
end

local function run_jobs()
  local groups = {}
  for i, k in ipairs(chosen) do
    local g = (i - 1) % jobs + 1
    groups[g] = groups[g] or {}
    table.insert(groups[g], k)
  end
  local pass = {}
  for key, v in pairs(opt) do
    if key ~= "only" and key ~= "jobs" and key ~= "part" and key ~= "check" then pass[#pass + 1] = quote(key .. "=" .. tostring(v)) end
  end
  local cmds = {}
  for g, list in ipairs(groups) do
    for _, k in ipairs(list) do os.remove(part_file(k)) end
    cmds[g] = ("( %s %s only=%s part=1 %s ) &"):format(quote(arg[-1]), quote(arg[0]), table.concat(list, ","),
      table.concat(pass, " "))
    say(#list > 1 and "sections %s in a process of their own" or "section %s in a process of its own", table.concat(list, ", "))
  end
  os.execute(table.concat(cmds, " ") .. " wait")
  local missing = {}
  for _, k in ipairs(chosen) do
    local f = io.open(part_file(k))
    if f then
      local dt = tonumber(f:read("l"))
      md[#md + 1] = f:read("a")
      f:close()
      os.remove(part_file(k))
      timing[#timing + 1] = { k, dt or 0 }
    else
      missing[#missing + 1] = k
    end
  end
  if #missing > 0 then
    refuse(("section%s %s stopped before writing its results (see the messages above); %s/validation.md is left as it was"):format(
      #missing > 1 and "s" or "", table.concat(missing, ", "), out))
  end
end

if opt.part == 1 or jobs == 1 or #chosen < 2 then run_here() else run_jobs() end
-- plots of the sections run in this process (in jobs mode, each process wrote its own)
for _, p in ipairs(plots) do
  local ok, e = sph.plot{ file = out .. "/" .. p.file, xlabel = p.xlabel, ylabel = p.ylabel, log = p.log or "xy",
                          series = p.series, title = p.title, yrange = p.yrange, height = p.height }
  if not ok then say("plot %s: %s", p.file, tostring(e)) end
end
if opt.part == 1 then return end

local f = assert(io.open(out .. "/validation.md.tmp", "w"))
f:write("# Validation against independent references\n\n",
  "Made by `make validate` (`scripts/validate.lua`); references in `../shared/REFERENCES.md`.\n\n")
f:write(table.concat(md))
local inpar = jobs > 1 and #chosen > 1
f:write(("## Cost\n\nEvery world on %d thread%s%s; \"s\" in the tables is the engine's stepping time (`w:stats().wall_time`). "):format(threads,
  threads == 1 and "" or "s", inpar and (", %d sections at a time"):format(math.min(jobs, #chosen)) or ""),
  "Wall-clock seconds of each section of this run:")
for _, t in ipairs(timing) do f:write((" section %d, %d s;"):format(t[1], t[2])) end
f:write((" in all %d s.\n"):format(os.time() - clock0))
assert(f:close())
assert(os.rename(out .. "/validation.md.tmp", out .. "/validation.md"))
print("wrote " .. out .. "/validation.md")
