-- The analytic and reference flows of lua/sph/flows.lua, each at every resolution of its
-- convergence study: one row per run (error, observed order against the run before,
-- particles, steps, solver iterations per step, engine wall time) and the Taylor-Green
-- decay rate and the cavity's profiles. (make bench runs the same cases through
-- scripts/bench_validation.lua with repeats; this script is for one case by hand.)
--   build/sph scripts/flows.lua [only=N or name] [quick=1] [threads=1] [dx=0.025]
-- quick=1: the test resolutions only; dx: that resolution only.
local flows = require "sph.flows"
local o = ... or {}

for k, c in ipairs(flows.cases) do
  if not o.only or o.only == k or o.only == c.name then
    print(string.format("%s: %s", c.name, c.error_name))
    print(string.format("  %8s %10s %7s %9s %8s %8s %8s %9s", "dx", "error", "order", "particles", "steps",
      "p-iter", "v-iter", "wall s"))
    local list = o.dx and { o.dx } or ((o.quick or 0) ~= 0 and c.quick or c.resolutions)
    local prev
    for _, dx in ipairs(list) do
      local r = c.run(dx, { threads = o.threads })
      local order = prev and flows.order(prev.error, r.error, prev.dx, dx) or nil
      print(string.format("  1/%-6d %10.5f %7s %9d %8d %8.1f %8.1f %9.2f", math.floor(1 / dx + 0.5), r.error,
        order and string.format("%.2f", order) or "", r.particles, r.steps, r.p_iter, r.v_iter, r.wall))
      if r.decay then print(string.format("           kinetic energy decay rate %.4f (exact %.4f)", r.decay, r.decay_exact)) end
      if r.spread then print(string.format("           plug %.4f (exact %.4f), spread %.2e", r.plug, r.plug_exact, r.spread)) end
      if r.u then
        for _, q in ipairs(r.u) do print(string.format("           u(0.5, %.4f) = %8.5f  Ghia %8.5f", q[1], q[2], q[3])) end
        for _, q in ipairs(r.v) do print(string.format("           v(%.4f, 0.5) = %8.5f  Ghia %8.5f", q[1], q[2], q[3])) end
      end
      io.stdout:flush()
      prev = { error = r.error, dx = dx }
    end
  end
end
