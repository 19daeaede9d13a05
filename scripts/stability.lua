-- The stability suite (issue 3): the hard squeeze cases of lua/sph/stability.lua, each run
-- to its end. Each must finish with no NaN, no particle through a plate (the engine stops
-- with a message on either), a max density error under 1 % at every step, under a constant
-- load a plate that never moves back up by more than a particle spacing, and free-surface
-- flags that match the sample's outline. Prints one table row per case and a last line
-- `N passed, N failed`.
--   build/sph scripts/stability.lua [quick=1] [only=name] [threads=N] [dx=0.025]
--                                   [shifting=A] [thin_film=1]
-- quick=1 runs each case to a tenth of its end time (the reduced versions of make test).
local stability = require "sph.stability"
local o = ... or {}
local quick = (o.quick or 0) ~= 0

local failures, ran = 0, 0
print(string.format("%-20s %7s %8s %8s %8s %8s %8s %7s %7s %7s %s", "case", "t_end", "wall s", "steps",
  "p-iter", "v-iter", "max err", "h end", "inside", "missing", "result"))
for _, c in ipairs(stability.cases) do
  if not o.only or o.only == c.name then
    local r = stability.run(c, quick and c.t_end / 10 or c.t_end,
                            { dx = o.dx, threads = o.threads, world = { shifting = o.shifting,
                                       thin_film = o.thin_film == 1 or nil } })
    ran = ran + 1
    if not r.pass then failures = failures + 1 end
    print(string.format("%-20s %7.3g %8.1f %8d %8.1f %8.1f %8.4f %7.4f %7d %7d %s", c.name, r.t, r.wall, r.steps,
      r.p_iter, r.v_iter, r.emax, r.h, r.inside, r.missing, r.pass and "pass" or ("FAIL: " .. table.concat(r.why, "; "))))
    io.stdout:flush()
  end
end
print(string.format("%d passed, %d failed", ran - failures, failures))
if failures > 0 then os.exit(1) end
