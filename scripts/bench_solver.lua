-- Benchmark (not a test): the linear solver, AMG-PCG (src/amg.c), on the squeeze scene. The
-- paper's Bingham case (Re = 1, Bn = 5, M = 800, upper plate at
-- V = -1, half sample), `warmup` untimed steps from rest, then `steps` timed ones; per
-- case the medians over `runs` runs of the solver's own clocks (w:stats() *_setup_time and
-- *_solve_time: wall clock inside the solver), and the iteration counts, which do not
-- depend on the machine's load:
--   build/sph scripts/bench_solver.lua [dx=0.0125] [steps=20]
--     [warmup=5] [runs=3] [threads=1] [tol=1e-6] [Bn=5] [M=800] [Re=1]
-- Columns: rows of the pressure and viscous systems; for each system: setup ms per step,
-- solves per step, CG iterations per solve, ms per solve (iterations only), ns per row and
-- solve (setup included, the cost that counts); the whole step in us per particle (wall
-- clock, and "cpu": the process's CPU time, os.clock, less disturbed by other programs on a
-- shared machine when threads = 1); the max density error at the end.
local squeeze = require "sph.squeeze"
local o = ... or {}
local dxs = o.dx and { o.dx } or { 1 / 40, 1 / 80, 1 / 160 }
local steps, warmup, runs = math.floor(o.steps or 20), math.floor(o.warmup or 5), math.floor(o.runs or 3)

local median = require("sph.bench").median

local fraction = require("sph.bench").fraction

print(string.format("%-6s %8s %8s | %7s %5s %6s %8s %8s | %7s %5s %6s %8s %8s | %8s %8s %8s",
  "dx", "p rows", "v rows", "p setup", "solv", "it", "ms/solve", "ns/row", "v setup", "solv", "it",
  "ms/solve", "ns/row", "us/p-st", "cpu", "rho err"))
for _, dx in ipairs(dxs) do
  local r = { psu = {}, pso = {}, vsu = {}, vso = {}, step = {}, cpu = {} }
  local last
  for _ = 1, runs do
    local w = squeeze.build{ dx = dx, Re = o.Re or 1, Bn = o.Bn or 5, M = o.M or 800, mode = "velocity",
                             V = 1, world = { threads = math.floor(o.threads or 1), tol = o.tol } }
    for _ = 1, warmup do w:step() end
    local s0 = w:stats()
    local c0 = os.clock()
    for _ = 1, steps do w:step() end
    local c1 = os.clock()
    local s1 = w:stats()
    r.cpu[#r.cpu + 1] = c1 - c0
    local function d(k) return s1[k] - s0[k] end
    r.psu[#r.psu + 1] = d "pressure_setup_time"
    r.pso[#r.pso + 1] = d "pressure_solve_time"
    r.vsu[#r.vsu + 1] = d "visc_setup_time"
    r.vso[#r.vso + 1] = d "visc_solve_time"
    r.step[#r.step + 1] = d "wall_time"
    last = { ps = d "pressure_solves", vs = d "visc_solves", pit = d "solver_iterations_total",
             vit = d "visc_iterations_total", prows = s1.unknowns, vrows = s1.fluid,
             part = s1.fluid + s1.wall, err = s1.max_density_error }
    w:close()
  end
  local ps, vs = last.ps, last.vs
  local psu, pso, vsu, vso = median(r.psu), median(r.pso), median(r.vsu), median(r.vso)
  print(string.format("%-6s %8d %8d | %7.2f %5.2f %6.1f %8.3f %8.1f | %7.2f %5.2f %6.1f %8.3f %8.1f | %8.2f %8.2f %8.2g",
    fraction(dx), last.prows, last.vrows,
    1e3 * psu / steps, ps / steps, last.pit / ps, 1e3 * pso / ps, 1e9 * (psu + pso) / (ps * last.prows),
    1e3 * vsu / steps, vs / steps, last.vit / vs, 1e3 * vso / vs, 1e9 * (vsu + vso) / (vs * last.vrows),
    1e6 * median(r.step) / (steps * last.part), 1e6 * median(r.cpu) / (steps * last.part), last.err))
  io.stdout:flush()
end
