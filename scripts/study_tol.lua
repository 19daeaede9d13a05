-- Study (not a test): what the pressure-solver tolerance buys in density error. The paper's
-- Bingham squeeze (Re = 1, Bn = 5, M = 800, upper plate at V = -1, half sample) to t_end
-- at each tolerance; per row the max density error of the last step, the peak over the
-- run, the pressure-solver iterations per step, the steps taken, the upper plate's force
-- (mean over 20 output times, and at the end):
--   build/sph scripts/study_tol.lua [dx=0.0125] [t_end=0.1] [tols=1e-4,1e-5,1e-6,1e-8]
local squeeze = require "sph.squeeze"
local o = ... or {}
local dx, t_end = o.dx or 1 / 80, o.t_end or 0.1
local tols = {}
for v in tostring(o.tols or "1e-4,1e-5,1e-6,1e-8"):gmatch("[^,]+") do tols[#tols + 1] = tonumber(v) end

print(string.format("%-8s %6s %10s %10s %10s %10s %8s %12s %12s", "tol", "steps", "rho err",
  "peak err", "p it/step", "v it/step", "h", "mean force", "end force"))
for _, tol in ipairs(tols) do
  local w, top = squeeze.build{ dx = dx, Re = o.Re or 1, Bn = o.Bn or 5, M = o.M or 800, mode = "velocity", V = 1,
                                world = { threads = math.floor(o.threads or 1), tol = tol } }
  local fsum, fn = 0, 0
  w:run{ until_t = t_end, every = t_end / 20, each = function(ww)
    if ww.steps > 0 then fsum, fn = fsum + top.force, fn + 1 end -- no force before the first step (t = 0)
  end }
  local s = w:stats()
  print(string.format("%-8.0e %6d %10.5f %10.5f %10.1f %10.1f %8.4f %12.6g %12.6g", tol, w.steps, s.max_density_error, s.peak_density_error, s.solver_iterations_total / w.steps,
    s.visc_iterations_total / w.steps, top.position, fsum / fn, top.force))
  io.stdout:flush()
  w:close()
end
