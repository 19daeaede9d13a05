-- The headline case: the squeeze-flow test of a Bingham (or Newtonian) sample.
--   build/sph scripts/squeeze.lua mode=velocity Re=10 Bn=0.5 M=800 dx=0.025 t_end=0.5 out=out/sq
--   build/sph scripts/squeeze.lua mode=load F=-10 Re=1 Bn=5 t_end=2 out=out/load
-- Parameters (paper's scaling, H = U = mu = 1): mode (velocity | load), Re, Bn, M, dx,
-- t_end, F (load on the whole sample per unit depth, in units of mu U: the paper's
-- F* = F Bn; negative compresses), V (plate speed), every (output interval), h_stop (end
-- the run when the gap is thinner), viscosity, shifting, threads, out (folder).
-- Writes out/series.csv: t, h, plate velocity, plate force, solver iterations, max
-- density error, and the lubrication reference (Newtonian: mu V / h^6 or h(t) under load).
local sph = require "sph"
local squeeze = require "sph.squeeze"
local o = ... or {}

local mode = o.mode or "velocity"
if mode ~= "velocity" and mode ~= "load" then error("mode must be velocity or load, got " .. tostring(mode)) end
local Re, Bn, M, dx = o.Re or 10, o.Bn or 0.5, o.M or 800, o.dx or 1 / 40
local t_end, every = o.t_end or 0.5, o.every or 0.005
local out = o.out or "out/squeeze"
local h_stop = o.h_stop or 0.05

local world_opts = { threads = o.threads, viscosity = o.viscosity, shifting = o.shifting }
local w, top = squeeze.build{ dx = dx, Re = Re, Bn = Bn, M = M, mode = mode, F = o.F or -10,
                              V = o.V or 1, h_min = o.h_min or 0.25, world = world_opts }

os.execute("mkdir -p '" .. out .. "'")
local series = assert(io.open(out .. "/series.csv", "w"))
series:write("t,h,velocity,force,solver_iterations,max_density_error,reference\n")
local function ref(h, t)
  if Bn > 0 then return 0 / 0 end
  if mode == "velocity" then return squeeze.newtonian_force(h, o.V or 1) end
  return squeeze.newtonian_height(t, -(o.F or -10))
end
local function record(w)
  local s = w:stats()
  local h = top.position
  series:write(string.format("%.8g,%.8g,%.8g,%.8g,%d,%.4e,%.8g\n", w.t, h, top.velocity, top.force,
    s.solver_iterations, s.max_density_error, ref(h, w.t)))
  series:flush()
  if h < h_stop then return false end
end

print(string.format("squeeze: mode=%s Re=%g Bn=%g M=%g dx=%g: %d fluid particles (half sample), t_end=%g",
  mode, Re, Bn, M, dx, w:stats().fluid, t_end))
record(w)
w:run{ until_t = t_end, every = every, each = record }
series:close()
local s = w:stats()
print(string.format("done: t=%.4g h=%.4f force=%.5g  %d steps in %.1f s (%.0f steps/s, %.2f us per particle-step)  "
  .. "mean pressure iterations %.1f  max density error %.2e",
  w.t, top.position, top.force, w.steps, s.wall_time, w.steps / s.wall_time,
  1e6 * s.wall_time / (w.steps * s.particles), s.solver_iterations_total / w.steps, s.max_density_error))
print("wrote " .. out .. "/series.csv")
