-- Benchmark (not a test): engine speed on the headline Bingham squeeze (Re = 10, Bn = 0.5,
-- M = 100, upper plate at V = -1, half sample with a symmetry plane), a fixed number of
-- adaptive steps from t = 0. Run by scripts/bench.sh (`make bench`); by hand:
--   build/sph scripts/bench_squeeze.lua [runs=3] [warmup=20] [dx=0.025 threads=2 steps=300]
-- Without dx, the default cases: dx = 1/40 (300 steps) and 1/80 (100 steps), threads = 1
-- and 2. Each run builds a fresh world, takes `warmup` steps untimed (the impulsive start),
-- then times the next `steps` steps with the engine's own clock, w:stats().wall_time (wall
-- clock inside w:step, all threads; os.clock would sum the CPU time of every thread).
-- The runs are interleaved (run 1 of every case, then run 2, ...) so that a burst of load
-- from another program falls on several cases rather than on every run of one.
-- One row per case: particles (fluid + wall, ghosts not counted), median steps/s, median
-- microseconds per particle-step, pressure-solver iterations per timed step (the mean over
-- the timed steps of all runs), and the spread of steps/s over the runs, (max - min) /
-- median: a large spread means the machine was busy. A run stops timing after max_s seconds
-- (default 20) of stepping, so that a busy machine cannot stretch `make bench` past a few
-- minutes; such a row says how many steps were timed.
local squeeze = require "sph.squeeze"
local o = ... or {}

local runs = math.floor(o.runs or 3)
local warmup = math.floor(o.warmup or 20)
local max_s = o.max_s or 20 -- seconds of stepping per timed run at most (see below)
local cases
if o.dx then
  cases = { { dx = o.dx, threads = math.floor(o.threads or 1), steps = math.floor(o.steps or 100) } }
else
  cases = { { dx = 1 / 40, threads = 1, steps = 300 }, { dx = 1 / 40, threads = 2, steps = 300 },
            { dx = 1 / 80, threads = 1, steps = 100 }, { dx = 1 / 80, threads = 2, steps = 100 } }
end
if not (runs > 0 and warmup >= 0) then error("runs > 0 and warmup >= 0 expected") end
for _, c in ipairs(cases) do
  if not (c.dx > 0 and c.threads > 0 and c.steps > 0) then error("dx, threads and steps > 0 expected") end
  c.rate, c.cost, c.iters = {}, {}, 0
end

local median = require("sph.bench").median

local function one_run(c)
  local w = squeeze.build{ dx = c.dx, Re = 10, Bn = 0.5, M = 100, mode = "velocity", V = 1,
                           h_min = 0.25, world = { threads = c.threads } }
  for _ = 1, warmup do w:step() end
  local s0 = w:stats()
  local n = 0
  while n < c.steps do
    w:step()
    n = n + 1
    -- a busy machine can make threads = 2 fifty times slower: stop timing after max_s
    -- seconds rather than take minutes (the row is marked); w:stats() is outside the clock
    if n % 10 == 0 and w:stats().wall_time - s0.wall_time > max_s then break end
  end
  local s1 = w:stats()
  local wall = s1.wall_time - s0.wall_time
  if n < c.steps then c.capped = true end
  c.timed = (c.timed or 0) + n
  c.particles = s1.fluid + s1.wall -- constant in this scene (no inflow, no outflow)
  c.rate[#c.rate + 1] = n / wall
  c.cost[#c.cost + 1] = 1e6 * wall / (n * c.particles)
  c.iters = c.iters + (s1.solver_iterations_total - s0.solver_iterations_total)
  w:close()
end

for r = 1, runs do
  for _, c in ipairs(cases) do one_run(c) end
end

local fraction = require("sph.bench").fraction

print(string.format("%-8s %6s %7s %9s %6s %9s %12s %10s %7s", "case", "dx", "threads", "particles",
  "steps", "steps/s", "us/part-step", "CG it/step", "spread"))
for _, c in ipairs(cases) do
  local m = median(c.rate)
  local lo, hi = math.min(table.unpack(c.rate)), math.max(table.unpack(c.rate))
  print(string.format("%-8s %6s %7d %9d %6d %9.1f %12.3f %10.1f %6.0f%%", "squeeze", fraction(c.dx), c.threads,
    c.particles, c.steps, m, median(c.cost), c.iters / c.timed, 100 * (hi - lo) / m)
    .. (c.capped and string.format("  * %d of %d steps timed in %d runs: %g s cap", c.timed, runs * c.steps, runs, max_s) or ""))
end
