-- Thread independence: the headline Bingham squeeze (Re = 10, Bn = 0.5, M = 100, plate at
-- V = -1) at dx = 1/20, 40 steps of a fixed dt, with threads = 1 and threads = 2. The two
-- runs do the same arithmetic except for the order of the OpenMP sums (dot products in the
-- pressure solver, plate forces), so they may differ by round-off and by nothing else:
-- a larger difference means a race or a thread-count-dependent branch in the engine.
-- Fluid particles are matched by id (the engine sorts particles by cell every step).
local squeeze = require "sph.squeeze"
local T = require "sph.test"

-- 6e-5 is just below the adaptive step of this case at dx = 1/20 (6.13e-5, the viscous limit
-- with eta(0) = mu + tau0 m = 51); fixed, so both runs take the very same steps.
local DX, DT, STEPS = 1 / 20, 6e-5, 40

local function run(threads)
  local w, top = squeeze.build{ dx = DX, Re = 10, Bn = 0.5, M = 100, mode = "velocity", V = 1,
                                h_min = 0.25, world = { threads = threads } }
  local forces = {}
  for k = 1, STEPS do
    w:step(DT)
    forces[k] = top.force
  end
  local r = { forces = forces, h = top.position, t = w.t, stats = w:stats() }
  for _, f in ipairs{ "id", "x", "y", "u", "v" } do r[f] = w:field(f) end
  w:close()
  return r
end

T.case("threads = 1 and threads = 2 agree to round-off", function()
  local a, b = run(1), run(2)
  T.check(#a.id == #b.id and #a.id > 0, "same fluid particle count with 1 and 2 threads",
    string.format("%d vs %d", #a.id, #b.id))
  local where = {}
  for i = 1, #a.id do where[a.id[i]] = i end
  local matched = true
  local d = { x = 0, y = 0, u = 0, v = 0 }
  for i = 1, #b.id do
    local j = where[b.id[i]]
    if not j then
      matched = false
    else
      for f in pairs(d) do d[f] = math.max(d[f], math.abs(a[f][j] - b[f][i])) end
    end
  end
  T.check(matched, "every fluid particle id of the 2-thread run is in the 1-thread run")
  -- plate force: the largest difference over the 40 steps, absolute and relative to that
  -- step's force (the force falls from 4e4 at the impulsive start to 50 at step 40)
  local dF, dF_rel = 0, 0
  for k = 1, STEPS do
    local e = math.abs(a.forces[k] - b.forces[k])
    dF = math.max(dF, e)
    dF_rel = math.max(dF_rel, e / math.abs(a.forces[k]))
  end
  local dRho = math.abs(a.stats.max_density_error - b.stats.max_density_error)
  print(string.format("# %d fluid particles, %d steps of dt = %g (t = %g, h = %.6f)", #a.id, STEPS, DT, a.t, a.h))
  print(string.format("# max |x1 - x2| = %.3g  max |y1 - y2| = %.3g  max |u1 - u2| = %.3g  max |v1 - v2| = %.3g",
    d.x, d.y, d.u, d.v))
  print(string.format("# plate force: max over steps |F1 - F2| = %.3g, max over steps |F1 - F2| / |F1| = %.3g; "
    .. "at the end %.17g vs %.17g", dF, dF_rel, a.forces[STEPS], b.forces[STEPS]))
  print(string.format("# max density error %.17g vs %.17g (|diff| %.3g)", a.stats.max_density_error,
    b.stats.max_density_error, dRho))
  print(string.format("# pressure-solver iterations %d vs %d", a.stats.solver_iterations_total,
    b.stats.solver_iterations_total))

  -- Measured (gcc -O2 -march=x86-64-v2, this 2-core machine; bitwise repeatable run to run at
  -- a given thread count). Tolerances are round-off only, about 100-1000 x the measurement.
  -- positions: measured 5.6e-17 (x), 1.1e-16 (y), one ulp; tolerance 1e-13: round-off only
  T.below(d.x, 1e-13, "max |x1 - x2| over fluid particles below 1e-13 (round-off)")
  T.below(d.y, 1e-13, "max |y1 - y2| over fluid particles below 1e-13 (round-off)")
  -- velocities (U = 1): measured 2.5e-14 (u), 2.5e-14 (v); tolerance 1e-11: round-off only
  T.below(d.u, 1e-11, "max |u1 - u2| over fluid particles below 1e-11 U (round-off)")
  T.below(d.v, 1e-11, "max |v1 - v2| over fluid particles below 1e-11 U (round-off)")
  -- plate force: measured 5.8e-12 relative at worst over the steps (3.5e-10 on F = 61 at
  -- step 28); tolerance 1e-9 relative: round-off only (as amplified by the pressure solve)
  T.below(dF_rel, 1e-9, "plate force with 1 and 2 threads within 1e-9 relative at every step (round-off)")
  -- max density error (a relative figure, 5.1e-4 here): measured 2.2e-16; tolerance 1e-12
  T.below(dRho, 1e-12, "max density error with 1 and 2 threads within 1e-12 (round-off)")
  T.check(a.h == b.h, "plate position identical with 1 and 2 threads",
    string.format("%.17g vs %.17g", a.h, b.h))
end)

-- The sph host makes OpenMP threads spin briefly, then sleep, unless the environment says
-- how they wait (src/main.c, sph.h "Threads"): libgomp's long default spin on a busy machine
-- took the headline case from 1 s to 25-70 s, sleeping at once (passive) cost it 5x on an
-- idle one.
T.case("the host's default OpenMP wait is a bounded spin", function()
  local f = os.tmpname()
  local g = assert(io.open(f, "w"))
  g:write('print("policy=" .. tostring(os.getenv("OMP_WAIT_POLICY")) .. " spin=" .. tostring(os.getenv("GOMP_SPINCOUNT")))\n')
  g:close()
  local function policy(env)
    local p = assert(io.popen(string.format("%s %s %s 2>&1", env, arg[-1], f)))
    local out = p:read("a")
    p:close()
    return out:match("policy=(%S+) spin=(%S+)")
  end
  local pol, spin = policy("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT")
  T.check(pol == "nil" and spin == "10000", "unset: the host runs with GOMP_SPINCOUNT=10000", tostring(pol) .. " " .. tostring(spin))
  pol, spin = policy("env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active")
  T.check(pol == "active" and spin == "nil", "a policy given in the environment is kept", tostring(pol) .. " " .. tostring(spin))
  pol, spin = policy("env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=500")
  T.check(pol == "nil" and spin == "500", "a spin count given in the environment is kept", tostring(pol) .. " " .. tostring(spin))
  os.remove(f)
end)

T.done()
