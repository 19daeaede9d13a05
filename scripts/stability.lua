-- The stability suite (issue 3): hard squeeze cases, each run to its end. Each must finish
-- with no NaN, no particle through a plate (the engine stops with a message on either), a
-- max density error under 1 %, and, under a constant load, a plate that never moves back
-- up by more than a particle spacing. Prints one table row per case.
--   build/sph scripts/stability.lua [quick=1] [only=name] [threads=N]
-- quick=1 runs each case to a tenth of its end time (the reduced versions).
local squeeze = require "sph.squeeze"
local o = ... or {}
local quick = (o.quick or 0) ~= 0

local cases = {
  -- the paper's load relative to the yield stress (F = -2 tau0, as F = -10 at Bn = 5):
  -- the ideal Bingham sample stops at h = (tau0 / 2F)^(1/3) = 0.63 whatever Bn
  { name = "Bn=100 load", mode = "load", Re = 1, Bn = 100, M = 800, F = -200, t_end = 1 },
  { name = "M=1e4 Bn=5", mode = "velocity", Re = 1, Bn = 5, M = 1e4, t_end = 0.4 },
  { name = "Re=0.01", mode = "velocity", Re = 0.01, Bn = 0, t_end = 0.4 },
  { name = "Re=1000", mode = "velocity", Re = 1000, Bn = 0, t_end = 0.4 },
  { name = "thin film h=0.15", mode = "velocity", Re = 1, Bn = 0, t_end = 0.86, h_stop = 0.15, h_min = 0.15 },
  { name = "paper Bn=5 F*=-10", mode = "load", Re = 1, Bn = 5, M = 800, F = -10, t_end = 2 },
}

local failures, ran = 0, 0
print(string.format("%-20s %7s %8s %8s %9s %9s %8s %8s %s", "case", "t_end", "wall s", "steps",
  "p-iter", "v-iter", "max err", "h end", "result"))
for _, c in ipairs(cases) do
  if not o.only or o.only == c.name then
    local t_end = quick and c.t_end / 10 or c.t_end
    local w, top = squeeze.build{ dx = o.dx or 1 / 40, Re = c.Re, Bn = c.Bn, M = c.M, mode = c.mode, F = c.F,
                                  h_min = c.h_min or 0.3, world = { threads = o.threads } }
    local dx = o.dx or 1 / 40
    local hmin, backup = top.position, 0
    -- checked after every step: the plate's travel back up, the target height
    local ok, err = pcall(function()
      while w.t < t_end - 1e-12 do
        w:step()
        local h = top.position
        hmin = math.min(hmin, h)
        backup = math.max(backup, h - hmin)
        if c.h_stop and h <= c.h_stop then break end
      end
    end)
    local s = w:stats()
    local emax = s.peak_density_error -- the largest of any step
    local why = {}
    if not ok then why[#why + 1] = tostring(err) end
    if emax >= 0.01 then why[#why + 1] = string.format("density error %.4f >= 1 %%", emax) end
    if c.mode == "load" and backup > dx then why[#why + 1] = string.format("plate moved back up %.4f > dx", backup) end
    if c.h_stop and ok and top.position > c.h_stop + 1e-9 and not quick then
      why[#why + 1] = string.format("did not reach h = %g", c.h_stop)
    end
    local pass = #why == 0
    ran = ran + 1
    if not pass then failures = failures + 1 end
    print(string.format("%-20s %7.3g %8.1f %8d %9.1f %9.1f %8.4f %8.4f %s", c.name, w.t, s.wall_time, w.steps,
      w.steps > 0 and s.solver_iterations_total / w.steps or 0, w.steps > 0 and s.visc_iterations_total / w.steps or 0, emax, top.position,
      pass and "pass" or ("FAIL: " .. table.concat(why, "; "))))
    io.stdout:flush()
  end
end
print(string.format("%d passed, %d failed", ran - failures, failures))
if failures > 0 then os.exit(1) end
