-- Benchmark (not a test): cost of the step and the share of each of its phases from 10^3 to
-- 10^6 particles, on 1 and 2 threads. The paper's constant-velocity squeeze (Bn = 5,
-- M = 800, Re = 1, upper plate at V = -1, half sample with a symmetry plane) at a ladder of
-- resolutions dx = 1/40 .. 1/1400; for each, `warmup` untimed steps at the engine's adaptive
-- step (the impulsive start), then `steps` timed steps, timed by the engine's clock
-- (w:stats().wall_time and its per-phase split w:stats().phases). The timed steps' dt, one
-- rule for every size:
--   dt = 0.025 (default): a fixed dt = 0.025 dx (dx/40; w:step(dt): every run of a
--     resolution takes the same steps, and every size the same plate travel a step);
--   dt = adaptive: the engine's own step control (w:step()), what a run pays; each size
--     takes its own dt, printed as dt/dx (the plate's travel a step in dx, V = 1).
-- The column ns/dx is the cost of moving the plate by one dx: ns a particle-step over dt/dx.
-- Run by scripts/bench.sh (`make bench`); by hand:
--   build/sph scripts/bench_scaling.lua [max_n=120000] [runs=3] [steps=60] [warmup=20]
--                                       [dt=0.025|adaptive] [until_t=] [threads=1,2] [dx=0.0025]
--                                       [out=out/bench] [from_t=]
-- until_t: the timed steps run until the time t reaches it instead of `steps` of them (the
-- same span of the flow for every dt rule: docs/performance.md, t = 0.009 at dx = 1/450).
-- from_t: after the adaptive warm-up, untimed steps at the timed rule's dt until t reaches
-- from_t, then the timed steps: every size timed over the same span of the flow. Steps 21-80
-- at dx/40 are not that: they end at t = 2 dx, 0.0125 at 1/160 but 0.0013 at 1/1400, where
-- the impulsive start's viscous layer (depth sqrt(nu t), nu = 1) still moves 0.4 dx a step
-- (docs/performance.md).
-- max_n caps the particle count (fluid + wall) of the ladder (default 1.2e5; the 10^6 row is
-- opt-in: max_n=1e6, several minutes a run); dx= runs one
-- resolution only. Runs are interleaved (run 1 of every thread count, then run 2, ...) and
-- each row is the median over runs; above 3e4 particles one run (the steps are long).
-- Columns: particles (fluid + wall, ghosts not counted), ns per particle-step (the whole
-- step: sort, neighbours, sweeps and the solves), pressure-solver iterations per step
-- (pressure and density-correction solves), viscous iterations per step (u and v), the
-- share of each phase in % of the step, and for 2 threads the speed-up over 1 thread of the
-- whole step and of the sweeps alone (everything but the two solve phases).
-- Writes scaling.csv and scaling.png (log-log ns per particle-step against particles).
local sph = require "sph"
local squeeze = require "sph.squeeze"
local o = ... or {}

local max_n = o.max_n or 1.2e5
local warmup = math.floor(o.warmup or 20)
local adaptive = o.dt == "adaptive"
local dt_dx = tonumber(o.dt or 0.025) -- dt = dx / 40 (the adaptive step of this case saw-tooths around 0.02-0.075 dx at 10^5)
if not adaptive and not (dt_dx and dt_dx > 0) then
  error("bench_scaling: dt must be 'adaptive' or a positive number (dt / dx), got '" .. tostring(o.dt) .. "'")
end
if o.from_t ~= nil and not (tonumber(o.from_t) and tonumber(o.from_t) > 0) then
  error("bench_scaling: from_t must be a positive time, got '" .. tostring(o.from_t) .. "'")
end
local outdir = o.out or "out/bench"
local threads = {}
for t in tostring(o.threads or "1,2"):gmatch("%d+") do threads[#threads + 1] = math.floor(tonumber(t)) end
local ladder = { 40, 80, 160, 320, 450, 640, 1000, 1400 }
if o.dx then ladder = { 1 / o.dx } end

local PHASES = { "sort", "neighbours", "rheology", "viscous_assembly", "viscous_solve",
                 "pressure_assembly", "pressure_solve", "correction", "shifting", "other" }
local SHORT = { sort = "sort", neighbours = "nbrs", rheology = "rheo", viscous_assembly = "v-asm",
                viscous_solve = "v-sol", pressure_assembly = "p-asm", pressure_solve = "p-sol",
                correction = "corr", shifting = "shift", other = "other" }

local median = require("sph.bench").median

local function build(k, nthreads)
  return squeeze.build{ dx = 1 / k, Re = 1, Bn = 5, M = 800, mode = "velocity", V = 1,
                        world = { threads = nthreads } }
end

-- particles (fluid + wall) of each rung, from a world that is built and dropped
local rungs = {}
for _, k in ipairs(ladder) do
  local fluid = 0.5 * k * k -- the half sample 0.5 x 1
  if #rungs == 0 or fluid <= max_n or o.dx then
    local w = build(k, 1)
    local s = w:stats()
    w:close()
    if s.fluid + s.wall <= max_n or o.dx then
      rungs[#rungs + 1] = { k = k, dx = 1 / k, particles = s.fluid + s.wall }
    end
  end
end

local function one_run(r, nthreads, steps)
  local w, top = build(r.k, nthreads)
  -- the warm-up takes the adaptive step (the impulsive start: a fixed dx/40 from rest put a
  -- fluid particle through the upper plate at step 4 at dx = 1/1000), the timed steps the
  -- rule's (above)
  for _ = 1, warmup do w:step() end
  local dt = not adaptive and dt_dx * r.dx or nil
  local from_t = tonumber(o.from_t)
  while from_t and w.t < from_t do w:step(dt) end
  local s0 = w:stats()
  local maxerr = 0
  local until_t = tonumber(o.until_t)
  for _ = 1, until_t and math.huge or steps do
    if until_t and w.t >= until_t then break end
    w:step(dt)
    maxerr = math.max(maxerr, w:stats().max_density_error)
  end
  local s1 = w:stats()
  local n = s1.steps - s0.steps
  local wall = s1.wall_time - s0.wall_time
  local res = { n = n, ns = 1e9 * wall / (n * r.particles), wall = wall, dtdx = (s1.t - s0.t) / (n * r.dx), maxerr = maxerr,
                psolves = (s1.pressure_solves - s0.pressure_solves) / n,
                switches = (s1.density_switches - s0.density_switches) / n,
                piter = (s1.solver_iterations_total - s0.solver_iterations_total) / n,
                viter = (s1.visc_iterations_total - s0.visc_iterations_total) / n,
                phases = {}, neighbours = s1.neighbours }
  for _, p in ipairs(PHASES) do res.phases[p] = (s1.phases[p] - s0.phases[p]) / n end
  res.h = top.position
  w:close()
  return res
end

-- the table: printed row by row as the rungs finish (a long run shows its progress)
local head = string.format("%-7s %9s %3s %10s %6s %7s %7s %7s %5s %7s %6s %6s", "dx", "particles", "thr", "ns/pt-step",
  "dt/dx", "ns/dx", "p-it/st", "p-sol/st", "sw/st", "v-it/st", "rhoerr", "spread")
for _, p in ipairs(PHASES) do head = head .. string.format(" %6s", SHORT[p]) end
head = head .. string.format(" %7s %7s", "x step", "x sweep")
print(head)
io.stdout:flush()
local one = {} -- the 1-thread row of each rung, for the speed-ups
local function print_row(row)
  local line = string.format("1/%-5.5g %9d %3d %10.0f %6.4f %7.0f %7.1f %8.2f %5.2f %7.1f %5.2f%% %5.0f%%", row.k,
    row.particles, row.threads, row.ns, row.dtdx, row.ns / row.dtdx, row.piter, row.psolves, row.switches, row.viter,
    100 * row.maxerr, 100 * row.spread)
  for _, p in ipairs(PHASES) do line = line .. string.format(" %5.1f%%", 100 * row.phases[p] / row.step) end
  local b = one[row.k]
  if row.threads ~= 1 and b then
    line = line .. string.format(" %7.2f %7.2f", b.step / row.step, b.sweeps / row.sweeps)
  end
  print(line)
  io.stdout:flush()
end

local rows = {}
-- A rung whose run stops with an engine error (at a fixed dt above the free surface's
-- stability limit: dx/40 is 4 times it at dx = 1/320) is printed as FAILED with the engine's
-- message; the table, CSV and plot of the others are written and the script exits 1.
local failed = 0
for _, r in ipairs(rungs) do
  local runs = math.floor(o.runs or (r.particles > 3e4 and 1 or 3))
  local steps = math.floor(o.steps or 60)
  local byt = {}
  for _, t in ipairs(threads) do byt[t] = {} end
  local ok, err = pcall(function()
    for _ = 1, runs do
      for _, t in ipairs(threads) do byt[t][#byt[t] + 1] = one_run(r, t, steps) end
    end
  end)
  if not ok then
    failed = failed + 1
    print(string.format("1/%-5.5g %9d     FAILED: %s", r.k, r.particles, tostring(err)))
    io.stdout:flush()
  end
  for _, t in ipairs(ok and threads or {}) do
    local list = byt[t]
    local ns = {}
    for i, x in ipairs(list) do ns[i] = x.ns end
    local med = median(ns)
    local pick = list[1] -- the run whose cost is the median (its phases are reported)
    for _, x in ipairs(list) do if math.abs(x.ns - med) < math.abs(pick.ns - med) then pick = x end end
    local step = 0
    for _, p in ipairs(PHASES) do step = step + pick.phases[p] end
    local sweeps = step - pick.phases.viscous_solve - pick.phases.pressure_solve
    local lo, hi = math.huge, 0
    for _, x in ipairs(ns) do lo, hi = math.min(lo, x), math.max(hi, x) end
    local row = { k = r.k, dx = r.dx, particles = r.particles, threads = t, runs = runs, steps = pick.n,
                  ns = med, spread = (hi - lo) / med, piter = pick.piter, viter = pick.viter, dtdx = pick.dtdx,
                  maxerr = pick.maxerr, psolves = pick.psolves, switches = pick.switches,
                  phases = pick.phases, step = step, sweeps = sweeps, neighbours = pick.neighbours }
    rows[#rows + 1] = row
    if t == 1 then one[r.k] = row end
    print_row(row)
  end
end

print("phases in % of the step: sort (+ ghosts), nbrs (neighbour list, kernel gradients), rheo (shear rate,")
print("viscosity), v-asm / v-sol (implicit viscous assembly / solve), p-asm / p-sol (pressure assembly /")
print("pressure and density-correction solves), corr (projection, continuity, density correction), shift,")
print("other (plates, checks). x step, x sweep: speed-up over 1 thread of the step and of the sweeps (the")
print("step without the two solve phases). ns/pt-step: median over runs of the step's wall time per particle.")
print(adaptive and "dt: the engine's adaptive step; dt/dx: the plate's mean travel a timed step in dx; ns/dx: ns/pt-step over dt/dx"
  or string.format("dt = %g dx fixed after the warm-up; ns/dx: ns/pt-step over dt/dx (the cost of moving the plate by one dx)", dt_dx))
if o.from_t then print(string.format("timed from t = %g (untimed steps at the timed dt after the warm-up)", tonumber(o.from_t))) end
print("p-sol/st: pressure-type solves a step (the pressure, then one per density pass); sw/st: first density passes a step")
print("that moved along the difference form's direction; rhoerr: the largest max density")
print("error after a timed step (over density_tol, 0.5 %, a step takes a second density pass)")

assert(sph.mkdir(outdir))
local csv = assert(io.open(outdir .. "/scaling.csv", "w"))
local cols = "dx,particles,threads,runs,steps,dt_over_dx,max_density_error,pressure_solves_per_step,density_switches_per_step,ns_per_particle_step,spread,pressure_iterations_per_step," ..
  "viscous_iterations_per_step,neighbours_mean,step_s"
for _, p in ipairs(PHASES) do cols = cols .. "," .. p .. "_s" end
csv:write(cols, "\n")
for _, row in ipairs(rows) do
  local line = string.format("%.10g,%d,%d,%d,%d,%.6g,%.6g,%.4g,%.4g,%.6g,%.4g,%.6g,%.6g,%.4g,%.6g", row.dx, row.particles,
    row.threads, row.runs, row.steps, row.dtdx, row.maxerr, row.psolves, row.switches, row.ns, row.spread, row.piter, row.viter, row.neighbours, row.step)
  for _, p in ipairs(PHASES) do line = line .. string.format(",%.6g", row.phases[p]) end
  csv:write(line, "\n")
end
csv:close()

local series = {}
for _, t in ipairs(threads) do
  local xs, ys, sx, sy = {}, {}, {}, {}
  for _, row in ipairs(rows) do
    if row.threads == t then
      xs[#xs + 1], ys[#ys + 1] = row.particles, row.ns
      sx[#sx + 1], sy[#sy + 1] = row.particles, 1e9 * row.sweeps / row.particles
    end
  end
  if #xs > 0 then
    series[#series + 1] = { x = xs, y = ys, label = string.format("step, %d thread%s", t, t > 1 and "s" or ""),
                            style = "both" }
    series[#series + 1] = { x = sx, y = sy, label = string.format("sweeps only, %d thread%s", t, t > 1 and "s" or ""),
                            style = "markers" }
  end
end
if #rows > 1 then
  local ok, err = sph.plot{ file = outdir .. "/scaling.png", xlabel = "particles (fluid + wall)",
    ylabel = "ns per particle-step", log = "xy", series = series,
    title = "squeeze Bn = 5, M = 800, Re = 1, V = -1: cost of the step" }
  if not ok then error(err) end
end
print("wrote " .. outdir .. "/scaling.csv" .. (#rows > 1 and " and " .. outdir .. "/scaling.png" or ""))
if failed > 0 then
  io.stderr:write(string.format("bench_scaling: %d rung%s failed (above)\n", failed, failed > 1 and "s" or ""))
  os.exit(1)
end
