-- w:save / sph.load (src/state.c): the loaded world holds exactly the saved state, and a run
-- continued from it is the uninterrupted run bit for bit (one thread): the state holds the
-- solves' first guesses and the multigrid hierarchies kept for reuse with their counters.
-- Without them, a run saved at step 100 and continued 50 steps is off by about 5e-8 in t
-- and the plate position, and a loaded one by 4e-5 relative in the force.
local sph = require "sph"
local squeeze = require "sph.squeeze"
local T = require "sph.test"
local o = ... or {}

-- every field compared with ==, the plate's position, force and impulse, t and dt
local function same_run(w, w2, name)
  local diff = {}
  if w.t ~= w2.t then diff[#diff + 1] = string.format("t %.17g vs %.17g", w.t, w2.t) end
  if w.dt ~= w2.dt then diff[#diff + 1] = string.format("dt %.17g vs %.17g", w.dt, w2.dt) end
  if w.steps ~= w2.steps then diff[#diff + 1] = "steps" end
  for k = 1, 2 do
    local a, b = w:plate(k), w2:plate(k)
    if a.position ~= b.position then diff[#diff + 1] = "plate " .. k .. " position" end
    if a.force ~= b.force then diff[#diff + 1] = string.format("plate %d force %.17g vs %.17g", k, a.force, b.force) end
    if a.impulse ~= b.impulse then diff[#diff + 1] = string.format("plate %d impulse %.17g vs %.17g", k, a.impulse, b.impulse) end
    if a:velocity() ~= b:velocity() then diff[#diff + 1] = "plate " .. k .. " velocity" end
    if a:load() ~= b:load() or a.mode ~= b.mode then diff[#diff + 1] = "plate " .. k .. " law" end
  end
  for _, f in ipairs{ "x", "y", "u", "v", "p", "rho", "eta", "gammadot", "stress", "yielded", "speed", "surface",
                      "material", "id", "rho_sum", "divr" } do
    local a, b = w:field(f), w2:field(f)
    local worst = #a == #b and 0 or math.huge
    for i = 1, #a do if a[i] ~= b[i] then worst = math.max(worst, math.abs(a[i] - b[i])) end end
    if worst > 0 then diff[#diff + 1] = string.format("%s (%.3g)", f, worst) end
  end
  T.check(#diff == 0, name, table.concat(diff, ", "))
end

for _, mode in ipairs{ "velocity", "load" } do
  T.case("save at step 100, load, 50 steps on: bit for bit (" .. mode .. ")", function()
    local file = os.tmpname()
    local w = squeeze.build{ dx = 1 / 20, Re = 1, Bn = 5, M = 100, mode = mode, F = -40, world = { threads = 1 } }
    for _ = 1, 100 do w:step() end
    w:save(file)
    for _ = 1, 50 do w:step() end
    local w2 = sph.load(file)
    os.remove(file)
    for _ = 1, 50 do w2:step() end
    T.check(w:stats().pressure_solves > 0, "the run solves")
    same_run(w, w2, "the continued run is the uninterrupted one bit for bit (" .. mode .. ", Bingham, shifting)")
  end)
end

T.case("save, load and continue", function()
  local file = os.tmpname()
  local w, top = squeeze.build{ dx = 1 / 20, Re = 1, Bn = 5, M = 100, mode = "velocity", world = { threads = o.threads or 1 } }
  for _ = 1, 50 do w:step() end
  T.check(w:save(file) == w, "w:save returns the world")
  local xs, rhos, t, steps = w:field("x"), w:field("rho"), w.t, w.steps
  for _ = 1, 30 do w:step() end
  local w2 = sph.load(file)
  T.check(w2.t == t and w2.steps == steps, "the loaded world's clock is the saved one (t and steps exactly)")
  local same = true
  local xs2, rhos2 = w2:field("x"), w2:field("rho")
  for i = 1, #xs do same = same and xs[i] == xs2[i] and rhos[i] == rhos2[i] end
  T.check(same and #xs == #xs2, "the loaded particles are the saved ones, bit for bit (x and rho)")
  local top2 = w2:plate(2)
  T.check(top2:velocity() == -1 and top2.mode == "velocity", "the loaded plate keeps its law's value")
  for _ = 1, 30 do w2:step() end
  same_run(w, w2, "continued 30 steps: bit for bit")
  os.remove(file)
  T.checkerror("cannot open", "sph.load of a missing file", sph.load, file .. ".none")
  local g = assert(io.open(file, "w")); g:write("not a state"); g:close()
  T.checkerror("not a state saved by this build", "sph.load of another file", sph.load, file)
  os.remove(file)
  T.checkerror("no plate 3", "w:plate(k) beyond the plates", w2.plate, w2, 3)
end)

-- The density correction's GMRES fallback (density.c) waits after a useless one (10, 20,
-- ... 640 steps); the wait is part of the state. The lid-driven cavity (closed, dx = 1/20)
-- stepped at dt = 0.0175, 1.4 times the adaptive step's limit 0.25 h / U (the descent then
-- does not always bring the error under the density limit), takes a fallback before step
-- 40 and 2 in 190 steps (one thread); saved at step 40 and continued 150 steps, the loaded
-- world must take as many as the uninterrupted one. (At 1.6 times the limit and more a
-- particle in the lid's corner crosses the side wall: nothing but the pressure holds the
-- velocity normal to a wall, as in the continuum, viscous.c.)
T.case("save, load and continue: the density fallback's wait", function()
  local file = os.tmpname()
  local dx, T3, DT = 1 / 20, 3 / 20, 0.0175
  local w = sph.world{ dx = dx, rho = 1, threads = o.threads or 1, shifting = 20, density_tol = 0.04, surface = 0 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 0.01 } }
  w:plate{ rect = { -T3, -T3, 1 + T3, 0 } }
  w:plate{ rect = { -T3, 0, 0, 1 + T3 } }
  w:plate{ rect = { 1, 0, 1 + T3, 1 + T3 } }
  w:plate{ rect = { 0, 1, 1, 1 + T3 }, slide = { 1, 0 } }
  for _ = 1, 40 do w:step(DT) end
  local f0 = w:stats().density_fallbacks
  w:save(file)
  local w2 = sph.load(file)
  os.remove(file)
  for _ = 1, 150 do w:step(DT); w2:step(DT) end
  local a, b = w:stats().density_fallbacks - f0, w2:stats().density_fallbacks - f0
  print(string.format("# cavity: %d fallbacks in 40 steps; then %d in the run, %d in the loaded one", f0, a, b))
  T.check(f0 > 0, "the cavity takes GMRES fallbacks", f0)
  T.check(a == b, "the loaded world takes the fallbacks the uninterrupted one takes", a .. " against " .. b)
end)

-- The form the last first density pass moved along is where the
-- next one starts (density.c), and it is part of the state. The film started thin
-- (tests/lua/test_thin_film.lua) moves its first passes along the difference form from
-- early on; saved at step 100 and continued 20 steps, the loaded world must move as many
-- first passes along it as the uninterrupted one.
T.case("save, load and continue: the density passes' starting form", function()
  local file = os.tmpname()
  local w = squeeze.build{ dx = 1 / 40, Re = 1, Bn = 0, mode = "velocity", width = 1.6, height = 0.2, h_min = 0.17,
                           world = { threads = o.threads or 1 } }
  for _ = 1, 100 do w:step() end
  local s0 = w:stats().density_switches
  w:save(file)
  for _ = 1, 20 do w:step() end
  local w2 = sph.load(file)
  for _ = 1, 20 do w2:step() end
  local a, b = w:stats().density_switches - s0, w2:stats().density_switches - s0
  print(string.format("# first passes along the difference form in the 20 steps after the save: %d (uninterrupted), %d (loaded)", a, b))
  T.check(a > 0, "the film's first passes move along the difference form after step 100", a)
  T.check(a == b, "the loaded world starts its first passes from the saved form", b)
  os.remove(file)
end)

-- sph.load checks every field it reads (src/state.c): a damaged file is an error naming
-- the field, never a world that crashes or computes with garbage later. The files are
-- w:save's with bytes patched; the offsets come from the header's sizes and the layout of
-- state.c, and a field inside a struct is found as the first byte where two saves that
-- differ only in it differ.
T.case("sph.load checks what it reads", function()
  local function build(opts)
    opts = opts or {}
    local w = sph.world{ dx = 0.1, threads = opts.threads or 1 }
    w:fill{ rect = { 0, 0, 1, 1 }, material = opts.mat or sph.newtonian{ mu = 1 } }
    w:plate{ rect = { -1, -0.3, 2, 0 } }
    local top = w:plate{ rect = { -1, 1, 2, 1.3 }, axis = opts.axis or "y" }
    if opts.velocity then top:velocity(0) end
    if opts.mass then top.mass = opts.mass end
    return w
  end
  local function saved(w)
    local f = os.tmpname()
    w:save(f)
    local g = assert(io.open(f, "rb"))
    local d = g:read("a")
    g:close()
    os.remove(f)
    return d
  end
  local function first_diff(a, b)
    for i = 1, math.min(#a, #b) do if a:byte(i) ~= b:byte(i) then return i end end
  end
  local base = saved(build())
  local w = build()
  local n = w:stats().particles
  -- header: magic, then the sizes of sph_params, sph_material, sph_plate, sph_stats
  local _, P, M, PL, S = string.unpack("<c8I4I4I4I4", base)
  local nmats_at = 28 + P + 1                       -- 1-based positions from here on
  local nplates_at = nmats_at + 4 + 64 * M
  local ints_at = nplates_at + 4 + 64 * PL          -- n, nfluid, next_id
  local clock_at = ints_at + 12                     -- t, dt, dt_prev, wall_time
  -- after the particles (SPHSTAT8): the plates' preparation flag, three first guesses
  -- (2 doubles, 2 ints, 2 doubles a particle), the reuse count, two hierarchy tags and
  -- two hierarchies (none before a step: 6 ints and a long each)
  local solver_len = 4 + 3 * (24 + 16 * n) + 8 + 8 + 2 * 32
  local parts_at = #base - solver_len - n * (19 * 8 + 3 * 4 + 1) + 1 -- 15 doubles, 4 sensitivities, 3 ints, a flag per particle
  local solver_at = #base - solver_len + 1
  local guess_at = solver_at + 4
  local kind_at, mat_at = parts_at + 19 * 8 * n, parts_at + 19 * 8 * n + 4 * n
  local mats_at, plates_at = nmats_at + 4, nplates_at + 4
  local function check(at, bytes, msg, name, data)
    data = data or base
    local f = os.tmpname()
    local g = assert(io.open(f, "wb"))
    g:write(data)
    g:close()
    g = assert(io.open(f, "r+b")) -- patched in place, as a damaged disk would leave it
    g:seek("set", at - 1)
    g:write(bytes)
    g:close()
    T.checkerror(msg, "sph.load: " .. name, sph.load, f)
    os.remove(f)
  end
  T.check(string.unpack("<i4", base, ints_at) == n, "the layout is understood (n read back at its offset)")
  check(ints_at, string.pack("<i4", -5), "particle count -5 not in [0, 200000000]", "a negative particle count")
  check(ints_at, string.pack("<i4", 0x7fffffff), "particle count 2147483647", "a huge particle count")
  check(ints_at + 4, string.pack("<i4", n + 1), "fluid count " .. (n + 1), "a fluid count above n")
  check(ints_at + 4, string.pack("<i4", 50), "fluid count 50 disagrees with the 100 fluid particles",
        "a fluid count that disagrees with the kinds")
  check(nmats_at, string.pack("<i4", 65), "material count 65", "too many materials")
  check(nplates_at, string.pack("<i4", -1), "plate count -1", "a negative plate count")
  check(kind_at, string.pack("<i4", 2), "particle 1: kind 2 is neither fluid (-1) nor a plate", "a plate index out of range")
  check(mat_at, string.pack("<i4", 7), "particle 1: material 8", "a fluid material out of range")
  check(parts_at, string.pack("<d", 0 / 0), "particle 1: x = ", "a NaN position")
  check(parts_at + 2 * 8 * n + 8 * 3, string.pack("<d", math.huge), "particle 4: u = inf is not finite",
        "an infinite velocity")
  check(parts_at + 6 * 8 * n, string.pack("<d", 0 / 0), "particle 1: p = ", "a NaN pressure")
  check(parts_at + 7 * 8 * n, string.pack("<d", -1), "particle 1: rho = -1", "a negative density")
  check(parts_at + 7 * 8 * n, string.pack("<d", 0 / 0), "particle 1: rho = ", "a NaN density")
  check(clock_at, string.pack("<d", 0 / 0), "t = ", "a NaN time")
  check(clock_at, string.pack("<d", -1), "t = -1 must be finite and >= 0", "a negative time")
  check(clock_at + 8, string.pack("<d", math.huge), "dt = inf must be finite and >= 0", "an infinite dt")
  check(clock_at + 8, string.pack("<d", -1e-3), "dt = -0.001", "a negative dt")
  -- fields inside the structs, found by difference
  local at = first_diff(base, saved(build{ axis = "x" }))
  T.check(at and at > plates_at + PL and at < plates_at + 2 * PL, "the second plate's axis found by difference", at)
  check(at, string.pack("<i4", 3), "plate 2: axis 3 is not -1, 0 or 1", "a plate axis out of range")
  at = first_diff(base, saved(build{ velocity = true }))
  check(at, string.pack("<i4", 7), "plate 2: mode 7 is not fixed", "a plate mode out of range")
  check(plates_at + (at - plates_at - PL), string.pack("<i4", 1), "plate 1: mode 1 on a fixed plate",
        "a fixed plate in velocity mode")
  at = first_diff(saved(build{ mass = 3 }), saved(build{ mass = 3 + 2 ^ -51 })) -- the lowest byte: the double's start
  check(at, string.pack("<d", 0), "plate 2: mass 0 is not a positive finite number", "a plate mass of 0")
  check(at, string.pack("<d", 0 / 0), "plate 2: mass", "a NaN plate mass")
  at = first_diff(base, saved(build{ mat = sph.bingham{ mu = 1, tau0 = 1, m = 10 } }))
  T.check(at == mats_at, "the material model found by difference at the first material", at)
  check(mats_at, string.pack("<i4", 9), "material 1: model 9 is not newtonian", "a material model out of range")
  check(mats_at + 8, string.pack("<d", -1), "material 1: mu must be a positive number", "a material's bad mu")
  check(29, string.pack("<d", -0.1), "parameters: dx must be a positive number", "a negative dx")
  at = first_diff(base, saved(build{ threads = 2 }))
  T.check(at and at > 28 and at <= 28 + P, "threads found by difference in the parameters", at)
  check(at, string.pack("<i4", 100000), "parameters: threads = 100000: must be 1..256", "threads = 100000")
  check(at, string.pack("<i4", -3), "parameters: threads = -3", "threads = -3")
  check(solver_at, string.pack("<i4", 5), "plate preparation flag 5 is not 0 or 1", "a bad preparation flag")
  check(guess_at + 24 + 8 * 2, string.pack("<d", 0 / 0), "viscous u first guess: particle 3's change is not finite",
        "a NaN first guess")
  check(guess_at + 16, string.pack("<i4", -2), "viscous u first guess: dt 0, 0 or counts -2", "a negative guess count")
  check(solver_at + 4 + 3 * (24 + 16 * n) + 8, string.pack("<i4", 7), "hierarchy matrices {7, 0} out of range",
        "a bad hierarchy tag")
  check(#base - 31, string.pack("<i4", 99), "multigrid hierarchy 2: 99 levels", "a bad level count")
  -- a stepped world's hierarchies (the viscous and the pressure one), damaged: a world
  -- of more rows than the coarsest level takes (100)
  local ws = sph.world{ dx = 1 / 25, threads = 1 }
  ws:fill{ rect = { 0, 0, 1, 1 }, material = sph.bingham{ mu = 1, tau0 = 1, m = 10 } }
  ws:plate{ rect = { -1, -0.3, 2, 0 } }
  ws:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }:velocity(-1)
  for _ = 1, 3 do ws:step() end
  local sb = saved(ws)
  local h1 = parts_at + ws:stats().particles * (19 * 8 + 3 * 4 + 1) + 4 + 3 * (24 + 16 * ws:stats().particles) + 16
  local lev1 = string.unpack("<i4", sb, h1)
  T.check(lev1 >= 2, "a stepped world saves a multigrid hierarchy", lev1)
  local sizes_at = h1 + 32
  check(sizes_at + 4, string.pack("<i4", 10 ^ 6), "multigrid hierarchy 1: level 2: 1000000 rows", "a coarse level too large", sb)
  local p_at = sizes_at + 4 * lev1 -- level 1's prolongation: entries, starts, columns, values
  local fine = string.unpack("<i4", sb, sizes_at)
  check(p_at + 4 + 4 * (fine + 1), string.pack("<i4", -1), "level 1's prolongation: column -1 not in", "a bad prolongation column", sb)
  check(p_at + 4 + 4, string.pack("<i4", -1), "level 1's prolongation: row", "bad prolongation row starts", sb)
  T.checkerror("is truncated (reading multigrid hierarchy", "sph.load: a hierarchy cut short", function()
    local f2 = os.tmpname()
    local g2 = assert(io.open(f2, "wb")); g2:write(sb:sub(1, #sb - 10)); g2:close()
    local ok, err = pcall(sph.load, f2)
    os.remove(f2)
    if not ok then error(err, 0) end
  end)
  T.checkerror("data after the end of the state", "sph.load: a file with data after the state", function()
    local f2 = os.tmpname()
    local g2 = assert(io.open(f2, "wb")); g2:write(sb .. "x"); g2:close()
    local ok, err = pcall(sph.load, f2)
    os.remove(f2)
    if not ok then error(err, 0) end
  end)
  -- SPHSTAT: files lack the plates' impulse: refused by name
  check(1, "SPHSTAT:", "was written by an older sph (SPHSTAT:; this build reads SPHSTAT;): load it with the build that saved it",
        "an older state file")
  check(1, "SPHSTAT<", "was written by a newer sph (SPHSTAT<; this build reads SPHSTAT;)", "a newer state file")
  local cut = base:sub(1, parts_at + 100)
  local f = os.tmpname()
  local g = assert(io.open(f, "wb")); g:write(cut); g:close()
  T.checkerror("is truncated (reading the particles' doubles)", "sph.load: a file cut short", sph.load, f)
  os.remove(f)
  T.check(sph.load and pcall(function()
    local f2 = os.tmpname()
    local g2 = assert(io.open(f2, "wb")); g2:write(base); g2:close()
    local w2 = sph.load(f2)
    os.remove(f2)
    w2:step()
  end), "the undamaged file loads and steps")
end)

T.done()
