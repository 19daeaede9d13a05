-- Benchmark (not a test): speed against error for the validation cases. Run by
-- scripts/bench.sh (`make bench`); by hand:
--   build/sph scripts/bench_validation.lua [runs=3] [only=Newtonian,Bingham] [quick=1]
--                                          [threads=1] [modules=sph.flows,sph.squeeze_validation]
--                                          [out=out/bench]
-- Every module listed (default: sph.flows, sph.squeeze_validation) returns
-- { cases = { { name, error_name, resolutions, quick, run = function(dx, opts) } } } and
-- run returns { particles, steps, wall, p_iter, v_iter, error, t } (the validation
-- interface). A module that is not installed is skipped with a note. For every case (only=:
-- those whose name contains one of the comma-separated words, case-insensitive) and every
-- resolution (quick=1: the case's quick list), `runs` repeats (default BENCH_RUNS, else 3);
-- the wall time is the median over the repeats, the other columns come from the first run
-- (the error of every repeat is compared: a spread above 1e-9 relative is printed, since
-- threads > 1 changes the summation order and the runs are chaotic at that level).
-- Columns: case, dx, particles (fluid + wall), steps, wall s (median), ns per
-- particle-step = wall / (particles * steps) * 1e9, mean pressure and viscous solver
-- iterations per step, error, observed order against the previous resolution
-- (log(e1 / e2) / log(dx1 / dx2)). Writes the table to OUT/validation.txt (as printed),
-- OUT/validation.csv and the log-log plot
-- OUT/error_vs_time.png (error against wall time, one line per case). A run that fails
-- (an engine error: a particle through a plate, a NaN, a solver that diverges) is printed
-- as FAILED with its message, left out of the CSV and the plot, and makes the script end
-- with an error (exit status 1) once everything else is written.
local sph = require "sph"
local o = ... or {}

local runs = math.floor(o.runs or tonumber(os.getenv("BENCH_RUNS") or "") or 3)
if runs < 1 then error("runs must be a positive integer") end
local threads = math.floor(o.threads or 1)
local outdir = o.out or "out/bench"
local function split(s)
  local t = {}
  for w in tostring(s):gmatch("[^,]+") do t[#t + 1] = w end
  return t
end
local modules = split(o.modules or "sph.flows,sph.squeeze_validation")
local only = o.only and split(o.only) or nil

-- every line printed is kept for OUT/validation.txt
local lines = {}
local function say(fmt, ...)
  local line = select("#", ...) > 0 and string.format(fmt, ...) or fmt
  lines[#lines + 1] = line
  print(line)
  io.stdout:flush()
end

local function selected(name)
  if not only then return true end
  for _, w in ipairs(only) do
    if name:lower():find(w:lower(), 1, true) then return true end
  end
  return false
end

local median = require("sph.bench").median

local fraction = require("sph.bench").fraction

-- the cases, module by module
local cases = {}
for _, m in ipairs(modules) do
  local ok, mod = pcall(require, m)
  if not ok then
    if tostring(mod):find("module '" .. m .. "' not found", 1, true) then
      say(string.format("note: module %s is not installed: skipped", m))
    else
      error(string.format("module %s failed to load: %s", m, tostring(mod)))
    end
  else
    if type(mod) ~= "table" or type(mod.cases) ~= "table" then
      error(string.format("module %s: { cases = { ... } } expected", m))
    end
    for _, c in ipairs(mod.cases) do
      if type(c.name) ~= "string" or type(c.run) ~= "function" or type(c.resolutions) ~= "table" then
        error(string.format("module %s: a case without name, run or resolutions", m))
      end
      if selected(c.name) then
        local res = (o.quick and o.quick ~= 0 and c.quick) or c.resolutions
        cases[#cases + 1] = { module = m, name = c.name, error_name = c.error_name or "?", run = c.run,
                              resolutions = res, rows = {} }
      end
    end
  end
end
if #cases == 0 then
  say("no case selected" .. (only and (" (only = " .. o.only .. ")") or ""))
  return
end

-- the runs: resolution by resolution, repeats of one resolution interleaved across the
-- cases would mix a long 1/80 run into every comparison; here each (case, dx) runs its
-- repeats back to back, coarse to fine, and every case prints as soon as it is done
local failed = 0
local header = string.format("%-34s %6s %9s %7s %9s %11s %8s %8s %11s %7s", "case", "dx", "particles", "steps",
  "wall s", "ns/part-st", "p it/st", "v it/st", "error", "order")
say(string.format("validation bench: median wall time of %d run%s per row, threads = %d", runs,
  runs == 1 and "" or "s", threads))
say(header)
for _, c in ipairs(cases) do
  local prev
  for _, dx in ipairs(c.resolutions) do
    local walls, first, errs, msg = {}, nil, {}, nil
    for _ = 1, runs do
      local ok, r = pcall(c.run, dx, { threads = threads })
      if not ok then
        msg = tostring(r)
        break
      end
      for _, k in ipairs{ "particles", "steps", "wall", "p_iter", "v_iter", "error" } do
        if type(r[k]) ~= "number" then
          error(string.format("%s (%s), dx = %s: run returned no number '%s'", c.name, c.module, fraction(dx), k))
        end
      end
      walls[#walls + 1] = r.wall
      errs[#errs + 1] = r.error
      first = first or r
      collectgarbage()
    end
    if msg then
      failed = failed + 1
      say(string.format("%-34s %6s FAILED: %s", c.name, fraction(dx), msg:gsub("\n", " ")))
      prev = nil
    else
      local r = first
      local row = { dx = dx, particles = r.particles, steps = r.steps, wall = median(walls),
                    p_iter = r.p_iter, v_iter = r.v_iter, error = r.error, extra = r }
      row.ns = row.wall / (row.particles * row.steps) * 1e9
      if prev and prev.error > 0 and row.error > 0 then
        row.order = math.log(prev.error / row.error) / math.log(prev.dx / row.dx)
      end
      local lo, hi = math.min(table.unpack(errs)), math.max(table.unpack(errs))
      row.spread = hi - lo
      c.rows[#c.rows + 1] = row
      say(string.format("%-34s %6s %9d %7d %9.2f %11.0f %8.1f %8.1f %11.4g %7s", c.name, fraction(dx), row.particles,
        row.steps, row.wall, row.ns, row.p_iter, row.v_iter, row.error,
        row.order and string.format("%.2f", row.order) or "")
        .. (row.spread > 1e-9 * math.abs(row.error) and string.format("  (error spread over runs %.3g)", row.spread) or ""))
      prev = row
    end
  end
end
say("")
say("errors:")
for _, c in ipairs(cases) do say(string.format("  %s: %s (%s)", c.name, c.error_name, c.module)) end

-- CSV and plot
assert(sph.mkdir(outdir))
local csv = assert(io.open(outdir .. "/validation.csv", "w"))
csv:write("module,case,dx,particles,steps,wall_s,ns_per_particle_step,p_iter,v_iter,error,order,runs,threads\n")
local series = {}
for _, c in ipairs(cases) do
  local xs, ys = {}, {}
  for _, r in ipairs(c.rows) do
    csv:write(string.format("%s,\"%s\",%.10g,%d,%d,%.6g,%.6g,%.4g,%.4g,%.6g,%s,%d,%d\n", c.module, c.name, r.dx,
      r.particles, r.steps, r.wall, r.ns, r.p_iter, r.v_iter, r.error, r.order and string.format("%.4f", r.order) or "",
      runs, threads))
    if r.error > 0 and r.wall > 0 then xs[#xs + 1], ys[#ys + 1] = r.wall, r.error end
  end
  if #xs > 0 then series[#series + 1] = { x = xs, y = ys, label = c.name, style = "both" } end
end
csv:close()
local txt = assert(io.open(outdir .. "/validation.txt", "w"))
txt:write(table.concat(lines, "\n"), "\n")
txt:close()
say("wrote " .. outdir .. "/validation.csv and validation.txt")
if #series > 0 then
  local ok, err = sph.plot{ file = outdir .. "/error_vs_time.png", title = "error against wall time",
    xlabel = string.format("wall time, s (median of %d, threads = %d)", runs, threads), ylabel = "error",
    log = "xy", series = series }
  if not ok then error("plot: " .. tostring(err)) end
  say("wrote " .. outdir .. "/error_vs_time.png")
end
if failed > 0 then
  -- an error, not os.exit: the host then closes the Lua state and frees cairo's and
  -- fontconfig's caches (os.exit skips that and the leak checker of make check complains)
  error(string.format("%d validation run%s FAILED (see the table above)", failed, failed == 1 and "" or "s"), 0)
end
