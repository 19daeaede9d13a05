-- The Lua surface: argument checks name the argument, closed handles and failed writes
-- behave as in Lua's own libraries, a raising plate law stops the run with its message.
local sph = require "sph"
local T = require "sph.test"

T.case("module", function()
  T.check(type(sph.version) == "string", "sph.version is a string")
  T.check(sph.world and sph.bingham and sph.newtonian and sph.herschel_bulkley, "constructors exist")
end)

-- DESIGN.md: nothing in sph changes the metatables of Lua's own types
T.case("Lua's own types", function()
  T.check(getmetatable(1) == nil and getmetatable(1.5) == nil, "numbers have no metatable after require \"sph\"")
  T.check(getmetatable(true) == nil and getmetatable(print) == nil and getmetatable(nil) == nil,
          "nor booleans, functions or nil")
  T.check(getmetatable("").__index == string and getmetatable("").__call == nil, "strings keep theirs, unchanged")
  T.checkerror("attempt to call a number value", "(1)() is Lua's usual error", function() return (1)() end)
  T.checkerror("attempt to call a number value (local 'x')", "and names the value as Lua does",
               function() local x = 2; return x() end)
  -- the same in a stock lua5.4 loading sph.so (next to the host), also where the script gave
  -- numbers a metatable before require "sph" (the module used to add a __call to it)
  local so = arg[-1]:gsub("[^/]*$", "") .. "sph.so"
  local lua = io.popen("command -v lua5.4 2>/dev/null"):read("l")
  if not (lua and io.open(so)) then
    print("# no lua5.4 on PATH or no " .. so .. ": the stock-Lua checks are skipped")
    return
  end
  local script = os.tmpname()
  local f = assert(io.open(script, "w"))
  f:write(string.format("package.cpath = %q\n", (so:gsub("sph%.so$", "?.so"))), [[
local preset = ...
local mt = { __index = function(n, k) if k == "twice" then return 2 * n end end }
if preset == "preset" then debug.setmetatable(0, mt) end
local sph = require "sph"
local w = sph.world{ dx = 0.1, threads = 1 }
w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
local top = w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }
local v = top:velocity(-1):velocity()
local nmt = getmetatable(1)
local ok, err = pcall(function() return (1)() end)
print(string.format("velocity=%g metatable=%s fields=%d call=%s twice=%s",
  v, nmt == nil and "none" or nmt == mt and "kept" or "other", nmt and #(function() local t = {}
  for k in pairs(nmt) do t[#t + 1] = k end return t end)() or 0, ok and "ok" or err:match("attempt to call a number value") or err,
  tostring(nmt and (3).twice)))
]])
  f:close()
  -- a sanitizer build's module needs its runtime loaded first (tests/run.sh says how)
  local pre = (os.getenv("SPH_LUA_PRELOAD") or "") .. " "
  local function stock(a)
    local p = io.popen(string.format("%sOMP_WAIT_POLICY=passive '%s' '%s' %s 2>&1", pre, lua, script, a))
    local out = p:read("a")
    p:close()
    return out
  end
  local plain, preset = stock(""), stock("preset")
  os.remove(script)
  T.check(plain:find("velocity=-1 metatable=none fields=0 call=attempt to call a number value twice=nil", 1, true),
          "stock lua5.4: require \"sph\" gives numbers no metatable; plate:velocity() reads", plain)
  T.check(preset:find("velocity=-1 metatable=kept fields=1 call=attempt to call a number value twice=6", 1, true),
          "stock lua5.4: a number metatable set before require \"sph\" is kept as it was", preset)
end)

T.case("world arguments", function()
  T.checkerror("dx", "world without dx names dx", sph.world, {})
  T.checkerror("dx", "world with dx = 0 names dx", sph.world, { dx = 0 })
  T.checkerror("dx: number expected", "world with a string dx", sph.world, { dx = "a" })
  T.checkerror("unknown option 'dxx'", "misspelt option is an error", sph.world, { dx = 0.1, dxx = 1 })
  T.checkerror("viscosity", "bad viscosity", sph.world, { dx = 0.1, viscosity = "magic" })
  T.checkerror("thin_film: boolean expected, got string", "bad thin_film", sph.world, { dx = 0.1, thin_film = "yes" })
  T.check(pcall(sph.world, { dx = 0.1, thin_film = true }) and pcall(sph.world, { dx = 0.1, thin_film = false }),
          "thin_film = true / false are accepted")
  T.checkerror("'density_correction' was removed", "the old thin-film option names say where they went", sph.world,
               { dx = 0.1, density_correction = "gmres" })
  T.checkerror("thin_film = true", "the removed pressure_gradient names thin_film", sph.world,
               { dx = 0.1, pressure_gradient = "difference" })
  T.checkerror("gravity", "bad gravity", sph.world, { dx = 0.1, gravity = 3 })
  T.checkerror("periodic", "bad periodic", sph.world, { dx = 0.1, periodic = { x = { 1 } } })
  T.checkerror("periodic range", "periodic lo >= hi", sph.world, { dx = 0.1, periodic = { x = { 1, 0 } } })
  T.checkerror("symmetry plane", "periodic and symmetric axis", sph.world,
    { dx = 0.1, periodic = { x = { 0, 1 } }, symmetry = { x = 0 } })
  T.checkerror("rho", "negative rho", sph.world, { dx = 0.1, rho = -1 })
  T.checkerror("density_tol", "density_tol = 1", sph.world, { dx = 0.1, density_tol = 1 })
  T.checkerror("tol must be in (0, 1)", "tol = 0", sph.world, { dx = 0.1, tol = 0 })
  T.checkerror("tol must be in (0, 1)", "tol = 1", sph.world, { dx = 0.1, tol = 1 })
  T.check(pcall(sph.world, { dx = 0.1, tol = 1e-8 }), "tol = 1e-8 is accepted")
  -- the numerical options of earlier versions are errors that say what the engine does now
  for _, k in ipairs{ "cvisc", "cforce", "max_iter", "solver", "pressure_predictor", "wall", "projection_passes",
                      "dt_growth", "density_relax", "density_passes", "density_limit", "density_descent",
                      "density_solve_tol", "density_diffusion", "density_wait", "density_probe", "density_gradient",
                      "visc_tol" } do
    T.checkerror("'" .. k .. "' was removed: the engine now always ", "removed option " .. k, sph.world,
                 { dx = 0.1, [k] = 1 })
  end
  T.checkerror("'solver' was removed: the engine now always preconditions its solves with algebraic multigrid",
               "the removed option's message says what the engine does", sph.world, { dx = 0.1, solver = "jacobi" })
  T.checkerror("'visc_tol' was removed: the engine now always solves the implicit viscous step to tol",
               "visc_tol's message names the one tolerance", sph.world, { dx = 0.1, visc_tol = 1e-6 })
  local wh = sph.world{ dx = 0.1 }
  T.check(wh.h == 0.1, "w.h reads the smoothing length, dx by default", wh.h)
  -- h and cfl, as ../shared/DESIGN.md's sample script passes them (a stable name each)
  T.check(sph.world{ dx = 0.1, h = 0.15 }.h == 0.15, "h = 1.5 dx is the smoothing length")
  T.check(sph.world{ dx = 0.1, h = nil, cfl = 0.25 }.h == 0.1, "h = nil and cfl = 0.25 are the defaults")
  T.checkerror("h must be 0 (dx) or between dx and 2 dx", "h below dx", sph.world, { dx = 0.1, h = 0.05 })
  T.checkerror("h must be 0 (dx) or between dx and 2 dx", "h above 2 dx", sph.world, { dx = 0.1, h = 0.3 })
  T.checkerror("cfl must be 0 (0.25) or in (0, 1]", "cfl above 1", sph.world, { dx = 0.1, cfl = 2 })
  T.checkerror("cfl must be 0 (0.25) or in (0, 1]", "cfl negative", sph.world, { dx = 0.1, cfl = -0.1 })
  T.checkerror("h: number expected", "h of the wrong type", sph.world, { dx = 0.1, h = "big" })
  do -- cfl sets the speed limit of dt: a plate at speed 1 from rest, half the cfl, half the step
    local function dt_after_30(cfl)
      local w = sph.world{ dx = 0.05, cfl = cfl, density_tol = 0, threads = 1 }
      w:fill{ rect = { 0, 0, 0.5, 0.5 }, material = sph.newtonian{ mu = 0.01 } }
      w:plate{ rect = { -0.5, -0.2, 1, 0 } }
      w:plate{ rect = { -0.5, 0.5, 1, 0.7 }, axis = "y" }:velocity(-1)
      for _ = 1, 30 do w:step() end
      return w.dt
    end
    local a, b = dt_after_30(0.25), dt_after_30(0.125)
    T.check(math.abs(b / a - 0.5) < 0.05, "cfl = 0.125 takes half the step of 0.25 once the speed limit rules",
            ("%g / %g"):format(b, a))
  end
  -- threads are capped (SPH_MAX_THREADS): 100000 overflowed the OpenMP runtime's stack
  T.checkerror("threads must be 1..256 (0: all cores), got 100000", "threads = 100000", sph.world,
               { dx = 0.1, threads = 100000 })
  T.checkerror("threads must be 1..256 (0: all cores), got 257", "threads = 257", sph.world, { dx = 0.1, threads = 257 })
  T.checkerror("got -1", "threads = -1", sph.world, { dx = 0.1, threads = -1 })
  T.checkerror("got 2.5", "threads = 2.5", sph.world, { dx = 0.1, threads = 2.5 })
  T.checkerror("got 1e+20", "threads = 1e20 (beyond int)", sph.world, { dx = 0.1, threads = 1e20 })
  T.check(pcall(sph.world, { dx = 0.1, threads = 256 }), "threads = 256 is accepted")
  T.checkerror("table expected", "world needs a table", sph.world, 3)
end)

T.case("materials", function()
  T.checkerror("tau0", "bingham without tau0", sph.bingham, { mu = 1, m = 10 })
  T.checkerror("m: number expected", "bingham without m", sph.bingham, { mu = 1, tau0 = 1 })
  T.checkerror("mu must be a positive", "negative mu", sph.newtonian, { mu = -1 })
  T.checkerror("unknown option 'tau'", "newtonian with a stray option", sph.newtonian, { mu = 1, tau = 2 })
  T.checkerror("n must be", "herschel_bulkley n = 0", sph.herschel_bulkley, { K = 1, n = 0, tau0 = 1, m = 10 })
  local b = sph.bingham{ mu = 1, tau0 = 2, m = 800 }
  T.close(b:eta(0), 1 + 2 * 800, 1e-9, "material:eta(0) = mu + tau0 m")
  T.check(b.model == "bingham" and b.tau0 == 2, "material fields readable")
  T.checkerror("shear rate", "eta of a negative rate", b.eta, b, -1)
end)

T.case("fill and plate", function()
  local w = sph.world{ dx = 0.1 }
  local water = sph.newtonian{ mu = 1 }
  T.checkerror("rect", "fill without rect", w.fill, w, { material = water })
  T.checkerror("rect[4]", "fill with a short rect", w.fill, w, { rect = { 0, 0, 1 }, material = water })
  T.checkerror("x0 < x1", "fill with an inverted rect", w.fill, w, { rect = { 1, 0, 0, 1 }, material = water })
  T.checkerror("material", "fill without material", w.fill, w, { rect = { 0, 0, 1, 1 } })
  T.checkerror("material", "fill with a table as material", w.fill, w, { rect = { 0, 0, 1, 1 }, material = {} })
  T.check(w:fill{ rect = { 0, 0, 1, 1 }, material = water } == 100, "fill returns the particle count")
  T.checkerror("axis", "plate with a bad axis", w.plate, w, { rect = { 0, -0.3, 1, 0 }, axis = "z" })
  T.checkerror("kernel support", "plate thinner than 3h", w.plate, w, { rect = { 0, -0.1, 1, 0 } })
  T.checkerror("overlaps fluid", "plate over fluid", w.plate, w, { rect = { 0, 0.5, 1, 0.9 } })
  local bottom = w:plate{ rect = { -1, -0.3, 2, 0 } }
  local top = w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }
  T.checkerror("fixed", "a fixed plate cannot take a velocity", bottom.load, bottom, 1)
  T.checkerror("fixed", "a fixed plate cannot take a velocity law", bottom.velocity, bottom, 1)
  T.checkerror("bad argument #1 to 'load' (number or function of (t, plate) expected, got string)",
               "load law of the wrong type names the method", top.load, top, "fast")
  T.checkerror("bad argument #1 to 'velocity' (number or function of (t, plate) expected, got table)",
               "velocity law of the wrong type names the method", function() top:velocity{ -1 } end)
  T.checkerror("bad argument #1 to 'velocity' (number or function of (t, plate) expected, got nil; "
               .. "plate:velocity() with no argument reads it)", "an explicit nil is not a read", top.velocity, top, nil)
  T.checkerror("bad argument #1 to 'load' (finite number expected, got inf)", "a load must be finite",
               function() top:load(1 / 0) end)
  T.checkerror("calling 'velocity' on bad self (sph.plate expected, got number: call it as plate:velocity(...))",
               "plate.velocity(v), the colon forgotten, says how to call it", function() top.velocity(-1) end)
  T.check(top:velocity() == 0 and top.axial_velocity == 0, "a plate starts at rest")
  T.check(top:velocity(-1) == top, "plate:velocity(v) returns the plate")
  T.close(top:velocity(), -1, 0, "plate:velocity() reads the law's value")
  T.close(top.axial_velocity, -1, 0, "plate.axial_velocity reads it too")
  T.check(top.mode == "velocity" and top:load() == nil, "plate:load() is nil for a plate driven at a velocity")
  T.check(type(top.velocity) == "function" and top.velocity ~= top.load, "plate.velocity is the method")
  T.checkerror("cannot be set", "plate.axial_velocity is read-only", function() top.axial_velocity = 1 end)
  T.checkerror("cannot be set", "plate.velocity cannot be assigned", function() top.velocity = 1 end)
  T.close(top.position, 1, 1e-12, "plate.position is the face touching the fluid")
  T.close(bottom.position, 0, 1e-12, "bottom plate's face is its upper edge")
  T.check(top.mass > 0, "plate.mass defaults to its particles' mass")
  top.mass = 3
  T.close(top.mass, 3, 0, "plate.mass is settable")
  T.checkerror("cannot be set", "plate.force is read-only", function() top.force = 1 end)
  T.checkerror("positive", "plate mass must be positive", function() top.mass = -1 end)
  -- the value fields are numbers, and calling one is Lua's own error, naming it: a call of
  -- a value field never sets the plate's velocity
  T.checkerror("attempt to call a number value (method 'mass')", "plate:mass(m) is an error",
               function() top:mass(50) end)
  T.checkerror("attempt to call a number value (method 'force')", "plate:force(f) is an error",
               function() top:force(5) end)
  T.checkerror("attempt to call a number value (method 'axial_velocity')", "plate:axial_velocity(v) is an error",
               function() top:axial_velocity(5) end)
  T.checkerror("attempt to call a number value", "calling another number with a plate is an error",
               function() local x = 7; return x(top, 1) end)
  T.close(top:velocity(), -1, 0, "none of those calls changed the plate's velocity")
  top:load(-10)
  T.check(top.mode == "load" and top:load() == -10, "plate:load() reads a constant load")
  T.check(top:velocity(-1) == top and top.mode == "velocity" and top:load() == nil, "and a velocity law replaces it")
  T.checkerror("unknown field 'bogus'", "field with an unknown name", w.field, w, "bogus")
  local xs = w:field("x")
  T.check(#xs == 100, "field returns one value per fluid particle")
  -- rho_sum reads the last step's neighbour list: before any step it is an error, not a
  -- read of unset memory (a crash), and so is a render coloured by it
  T.checkerror("no neighbour list for the current particles yet", "rho_sum before a step", w.field, w, "rho_sum")
  T.checkerror("needs the neighbour list of a step", "render by rho_sum before a step", w.render, w,
               { file = os.tmpname(), color = "rho_sum" })
  local st = w:stats()
  T.check(st.fluid == 100 and st.particles > 100, "stats counts particles")
end)

T.case("plate slide and set_velocity", function()
  local dx = 0.1
  local w = sph.world{ dx = dx, periodic = { x = { 0, 1 } }, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  T.checkerror("slide", "plate with a slide that is not a table", w.plate, w, { rect = { 0, -0.3, 1, 0 }, slide = 1 })
  T.checkerror("slide", "plate with a short slide", w.plate, w, { rect = { 0, -0.3, 1, 0 }, slide = { 1 } })
  T.checkerror("slide", "plate with a non-finite slide", w.plate, w, { rect = { 0, -0.3, 1, 0 }, slide = { 0 / 0, 0 } })
  local bottom = w:plate{ rect = { 0, -0.3, 1, 0 } }
  local lid = w:plate{ rect = { 0, 1, 1, 1.3 }, slide = { 0.5, 0 } }
  local sx, sy = lid:slide()
  T.check(sx == 0.5 and sy == 0, "plate:slide() reads the slide given to plate{}", sx .. ", " .. sy)
  T.check(select(1, bottom:slide()) == 0, "a plate slides at 0 by default")
  T.checkerror("number expected", "slide with a string", lid.slide, lid, "fast", 0)
  T.checkerror("finite", "slide with an infinite component", lid.slide, lid, 1 / 0, 0)
  T.check(lid:slide(1, 0) == lid, "plate:slide(ux, uy) returns the plate")
  T.check(lid.mode == "fixed" and lid.axis == nil, "a sliding plate stays a fixed plate")
  local n = #w:field("x")
  T.checkerror("one per fluid particle", "set_velocity with the wrong length", w.set_velocity, w, { 1 })
  local bad = {}
  for i = 1, n do bad[i] = 0 end
  bad[3] = "x"
  T.checkerror("number expected", "set_velocity with a string", w.set_velocity, w, bad)
  bad[3] = 0 / 0
  T.checkerror("not finite", "set_velocity with a NaN", w.set_velocity, w, nil, bad)
  local us = {}
  for i = 1, n do us[i] = 0.01 * i end
  w:set_velocity(us)
  local back, vs = w:field("u"), w:field("v")
  T.check(back[7] == us[7] and vs[7] == 0, "set_velocity sets u in field order and keeps v")
  w:set_velocity(nil, us)
  back, vs = w:field("u"), w:field("v")
  T.check(back[7] == us[7] and vs[9] == us[9], "set_velocity(nil, vs) sets v only")
  local zero = {}
  for i = 1, n do zero[i] = 0 end
  w:set_velocity(zero, zero)
  for _ = 1, 20 do w:step(2e-3) end
  local ys, u = w:field("y"), w:field("u")
  local top, low = 0, 0
  for i = 1, #ys do
    if ys[i] > 0.9 then top = math.max(top, u[i]) end
    if ys[i] < 0.1 then low = math.max(low, math.abs(u[i])) end
  end
  local r = lid.rect
  T.check(r[1] == 0 and r[2] == 1 and r[3] == 1 and r[4] == 1.3, "a sliding plate's particles stay in place")
  -- the row under the lid follows it: after 0.04 (= 4 dx^2 / nu) it moves at over a
  -- third of the lid speed, the row on the still bottom plate at under a tenth of that
  T.check(top > 0.33 and low < 0.1 * top, "the fluid under a sliding lid follows it",
    string.format("top row %.3f, bottom row %.3f", top, low))
end)

T.case("laws", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -1, -0.3, 2, 0 } }
  local top = w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }
  local seen
  top:velocity(function(t, plate) seen = plate; return -0.5 end)
  w:step()
  T.check(seen == top, "a law receives the plate handle")
  T.close(top:velocity(), -0.5, 0, "a velocity law sets the plate's velocity")
  top:load(function(t, plate) return -5 end)
  T.check(top:load() == 0, "a load law is applied at the next step (plate:load() reads 0 until then)")
  w:step()
  T.check(top:load() == -5 and top:velocity() == top.axial_velocity and top:velocity() < 0,
          "plate:load() reads the load a law applied; plate:velocity() the plate's velocity under it")
  top:velocity(function(t) error("law exploded at " .. t) end)
  T.checkerror("law exploded", "an error in a law stops step with its message", w.step, w)
  T.checkerror("law exploded", "an error in a law stops run with its message", w.run, w, { until_t = 1 })
  top:load(function() return "heavy" end)
  T.checkerror("a finite number expected", "a law returning a string", w.step, w)
  T.checkerror("until_t", "run without until_t", w.run, w, {})
  T.checkerror("each", "run with a non-function each", w.run, w, { until_t = 1, each = 3 })
end)

-- plate.impulse is the sum of force * dt over the steps (its change over a time span, over
-- the span, the mean force: squeeze.lua's series), 0 before the first, read-only
T.case("plate impulse", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local bottom = w:plate{ rect = { -1, -0.3, 2, 0 } }
  local top = w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }
  top:velocity(-0.5)
  T.check(top.impulse == 0 and bottom.impulse == 0, "plate.impulse is 0 before the first step")
  local sum, sumb = 0, 0
  for _ = 1, 20 do
    w:step()
    sum, sumb = sum + top.force * w.dt, sumb + bottom.force * w.dt
  end
  T.close(top.impulse, sum, 1e-12, "plate.impulse: the sum of force * dt over the steps", top.impulse)
  T.close(bottom.impulse, sumb, 1e-12, "a fixed plate's too", bottom.impulse)
  T.check(top.impulse > 0, "the fluid pushes back on a plate pressed down into it: a positive impulse", top.impulse)
  T.checkerror("cannot be set", "plate.impulse is read-only", function() top.impulse = 1 end)
  T.checkerror("attempt to call a number value (method 'impulse')", "plate:impulse() is an error",
               function() top:impulse() end)
end)

-- A step that fails on a non-finite or non-positive value leaves it in the particles; a
-- next step run on from there would have the neighbour build, meeting a particle its cell
-- grid does not hold (a NaN), write before its arrays (a heap-buffer-overflow that
-- tests/lua/test_fuzz.lua can reach).
T.case("step: a world a failed step left non-finite is not stepped on", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -0.5, -0.3, 1.5, 0 } }
  local u = {}
  for i = 1, w:stats().fluid do u[i] = 0 end
  u[5] = 1e20
  w:set_velocity(u)
  T.checkerror("non-positive density at fluid particle", "the step that goes wrong fails", w.step, w, 1e-3)
  T.checkerror("cannot step: non-positive density at fluid particle", "the next step refuses, naming the particle",
               w.step, w, 1e-3)
  T.checkerror("left by a failed step: load a saved state", "and says what to do", w.run, w, { until_t = 1, progress = false })
end)

T.case("run: the engine's own steps are not held to the bound of a given dt", function()
  -- a Bingham square at Bn = 1000, M = 800: at rest its viscosity tau0 m = 8e5 makes the
  -- bound 1e6 rho h^2 / max eta = 3.9e-5, below the first adaptive step (3.1e-4), which
  -- w:run passes on to land on until_t (it stopped there at step 0)
  local w = sph.world{ dx = 1 / 40, rho = 0.05, symmetry = { x = 0 }, threads = 1 }
  w:fill{ rect = { 0, 0, 0.5, 1 }, material = sph.bingham{ mu = 1, tau0 = 1000, m = 800 } }
  w:plate{ rect = { -3, -0.125, 3, 0 } }
  local top = w:plate{ rect = { -3, 1, 3, 1.125 }, axis = "y" }
  top:velocity(-1)
  local ok, err = pcall(w.run, w, { until_t = 0.001, progress = false })
  T.check(ok and math.abs(w.t - 0.001) < 1e-12, "w:run{until_t = 0.001} of a Bn = 1000 square runs", tostring(err))
  T.checkerror("exceeds the bound", "while a dt given beyond the bound is refused", w.step, w, 1e300)
end)

T.case("step: the dt given must be finite and within bounds", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  -- the viscous time rho h^2 / max eta is 0.01 here: the bound is 10^6 times that
  T.checkerror("dt = 1e+300 exceeds the bound 10000", "w:step(1e300) is refused, naming dt and the bound", w.step, w, 1e300)
  T.checkerror("dt must be a finite positive number (or <= 0: adaptive), got inf", "w:step(math.huge)", w.step, w,
               math.huge)
  T.checkerror("dt must be a finite positive number", "w:step(NaN)", w.step, w, 0 / 0)
  T.checkerror("dt must be a finite positive number", "w:step(-math.huge)", w.step, w, -math.huge)
  T.checkerror("dt must be a finite positive number", "w:run with dt = math.huge", w.run, w,
               { until_t = 1, dt = math.huge })
  T.check(w.t == 0 and w.steps == 0, "the refused steps left the clock alone", w.t)
  w:step(1e-3)
  T.check(w.t == 1e-3 and w.steps == 1, "a dt within the bound steps", w.t)
end)

T.case("a callback that closes its world", function()
  -- a plate law or run's each may close the world it is called from: the step or run then
  -- raises (its engine world is gone), it does not go on with freed memory
  local function world()
    local w = sph.world{ dx = 0.1, threads = 1 }
    w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
    w:plate{ rect = { -1, -0.3, 2, 0 } }
    return w, w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }
  end
  local w, top = world()
  top:velocity(function() w:close(); return -1 end)
  T.checkerror("world closed during w:step", "a velocity law closing the world stops step", w.step, w)
  T.checkerror("closed sph.world", "the world stays closed after that", function() w:step() end)
  w, top = world()
  top:load(function() w:close(); return 1 end)
  T.checkerror("world closed during w:run", "a load law closing the world stops run", w.run, w, { until_t = 1 })
  w = world()
  T.checkerror("world closed during w:run (in its each function)", "each closing the world stops run", w.run, w,
               { until_t = 1, every = 1e-9, each = function(ww) ww:close() end })
  w = world()
  T.checkerror("world closed during w:run (in its each function)", "each closing the world and returning false",
               w.run, w, { until_t = 1, every = 1e-9, each = function(ww) ww:close(); return false end })
end)

T.case("fill: bounds and all or nothing", function()
  local water = sph.newtonian{ mu = 1 }
  local w = sph.world{ dx = 0.1, threads = 1 }
  T.check(w:fill{ rect = { 0, 0, 1, 1 }, material = water } == 100, "a first fill of 100 particles")
  local function consistent(what)
    local n = w:stats().fluid
    T.check(n == 100 and #w:field("x") == 100 and #w:field("u") == 100,
            "after " .. what .. " the world still holds its 100 particles", n)
  end
  T.checkerror("asks for 1e+14 particles", "a rect of 1e14 lattice points is refused up front", w.fill, w,
               { rect = { 0, 0, 1e6, 1e6 }, material = water })
  consistent("a refused huge fill")
  local fine = sph.world{ dx = 1e-5 }
  T.checkerror("at dx = 1e-05 asks for 1e+22 particles", "rect {0, 0, 1e6, 1e6} at dx = 1e-5 names the count",
               fine.fill, fine, { rect = { 0, 0, 1e6, 1e6 }, material = water })
  T.check(fine:stats().fluid == 0, "that world stays empty")
  T.checkerror("must be finite", "an infinite rect", w.fill, w, { rect = { 0, 0, math.huge, 1 }, material = water })
  T.checkerror("must be finite", "a rect from -inf", w.fill, w, { rect = { -math.huge, 0, 1, 1 }, material = water })
  T.checkerror("x0 < x1", "a NaN in the rect", w.fill, w, { rect = { 0, 0, 0 / 0, 1 }, material = water })
  T.checkerror("asks for inf particles", "a rect whose width overflows", w.fill, w,
               { rect = { -1e308, 0, 1e308, 1 }, material = water })
  T.checkerror("holds no lattice point at dx = 0.1", "a rect narrower than dx", w.fill, w,
               { rect = { 2, 0, 2.04, 1 }, material = water })
  T.checkerror("must be finite", "a plate with an infinite rect", w.plate, w, { rect = { 0, -1, math.huge, 0 } })
  T.checkerror("asks for", "a plate of too many particles", w.plate, w, { rect = { -1e9, -1e9, 1e9, -1 } })
  consistent("refused rects")
  w:plate{ rect = { -1, -0.3, 2, 0 } }
  T.checkerror("overlaps plate 1: 10 of its lattice points", "a fill into a plate names the overlap", w.fill, w,
               { rect = { 1.5, -0.2, 2.5, 0.8 }, material = water })
  consistent("a fill into a plate")
  local half = sph.world{ dx = 0.1, symmetry = { x = 0 } }
  T.checkerror("no lattice point inside the simulated domain", "a fill wholly behind the symmetry plane",
               half.fill, half, { rect = { -1, 0, -0.5, 1 }, material = water })
  T.checkerror("dx = 1e-300 is out of range", "dx = 1e-300", sph.world, { dx = 1e-300 })
  T.checkerror("dx = 1e+300 is out of range", "dx = 1e300", sph.world, { dx = 1e300 })
  T.checkerror("particle mass", "a particle mass that underflows", sph.world, { dx = 1e-20, rho = 1e-300 })
end)

-- a 10 x 10 Bingham box between two plates, the upper one at V = -1, after three steps
local function squeezed_box()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.bingham{ mu = 1, tau0 = 1, m = 100 } }
  w:plate{ rect = { -1, -0.3, 2, 0 } }
  w:plate{ rect = { -1, 1, 2, 1.3 }, axis = "y" }:velocity(-1)
  for _ = 1, 3 do w:step() end
  return w
end

T.case("rho_sum", function()
  local w = squeezed_box()
  -- rho_sum after steps: the bulk's kernel sum within 1 % of rho (a 10 x 10 lattice at
  -- dx = 0.1; the middle particle has its full support), and an error again after a fill
  local rs, xs, ys = w:field("rho_sum"), w:field("x"), w:field("y")
  local mid
  for j = 1, #xs do if math.abs(xs[j] - 0.55) < 0.06 and math.abs(ys[j] - 0.45) < 0.06 then mid = rs[j] end end
  T.check(mid and math.abs(mid - 1) < 0.01, "rho_sum in the bulk after a step is the kernel sum, near 1", mid)
  w:fill{ rect = { 3, 0, 3.5, 0.5 }, material = sph.newtonian{ mu = 1 } }
  T.checkerror("no neighbour list", "rho_sum after a fill, before the next step", w.field, w, "rho_sum")
  w:step()
  T.check(#w:field("rho_sum") == 125, "rho_sum again after the next step")
end)

T.case("phase timers", function()
  local w = squeezed_box()
  local st = w:stats()
  local names = { "sort", "neighbours", "rheology", "viscous_assembly", "viscous_solve",
                  "pressure_assembly", "pressure_solve", "correction", "shifting", "other" }
  local sum, ok, count = 0, true, 0
  for _, k in ipairs(names) do
    local v = st.phases[k]
    if type(v) ~= "number" or v < 0 then ok = false end
    sum = sum + (v or 0)
  end
  for _ in pairs(st.phases) do count = count + 1 end
  T.check(ok and count == #names, "stats().phases has the ten phases, each a time >= 0",
    string.format("%d entries", count))
  T.check(st.phases.pressure_solve > 0 and st.phases.neighbours > 0, "the solve and the neighbour phases took time")
  -- the phases tile the step: their sum is wall_time up to the rounding of the sums
  T.close(sum, st.wall_time, 1e-9 * (1 + st.wall_time), "the phases add up to wall_time")
  T.check(st.steps == 3, "stats().steps counts the steps")
  T.check(type(st.density_alpha) == "number" and st.density_alpha >= 0 and st.density_alpha <= 1,
    "stats().density_alpha (the density passes' step length) is in [0, 1]", tostring(st.density_alpha))
  T.check(math.type(st.density_passes) == "integer" and st.density_passes >= 0 and st.density_passes <= 10,
    "stats().density_passes (the last step's density corrections) is an integer in [0, 10]", tostring(st.density_passes))
end)

T.case("run schedule", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -1, -0.3, 2, 0 } }
  local times, steps = {}, {}
  w:run{ until_t = 0.05, every = 0.01, each = function(ww) times[#times + 1], steps[#steps + 1] = ww.t, ww.steps end }
  T.check(#times == 6, "run calls each at the start and at every output time", #times .. " calls")
  T.check(times[1] == 0 and steps[1] == 0, "the first call is at the start, before the first step",
    tostring(times[1]) .. " " .. tostring(steps[1]))
  T.close(times[6] or 0, 0.05, 1e-12, "run lands on the output times")
  T.close(w.t, 0.05, 1e-12, "run ends at until_t")
  local n = 0
  local s0 = w.steps
  w:run{ until_t = 1, every = 0.01, each = function() n = n + 1; return false end }
  T.check(n == 1 and w.steps == s0, "each returning false at the start stops the run before a step",
    n .. " calls, " .. (w.steps - s0) .. " steps")
  -- a run continued on an earlier grid (t0 before now) had its start output already
  times = {}
  w:run{ until_t = 0.07, every = 0.01, t0 = 0, each = function(ww) times[#times + 1] = ww.t end }
  T.check(#times == 2 and math.abs(times[1] - 0.06) < 1e-12, "a run continued with t0 = 0 from t = 0.05 calls each at 0.06 and 0.07",
    table.concat(times, " "))
  n = 0
  w:run{ until_t = 0.1, each = function() n = n + 1 end }
  T.check(n == 0, "without every there are no outputs: each is not called, not even at the start")
  -- every output time is landed on: a grid finer than the clock's round-off is refused
  T.checkerror("every = 1e-300 is below the run's time resolution", "run with every = 1e-300", w.run, w,
               { until_t = 0.2, every = 1e-300, progress = false })
  T.checkerror("output times from t0 = -1e+300 to now", "run with t0 = -1e300", w.run, w,
               { until_t = 0.2, every = 0.01, t0 = -1e300, progress = false })
  T.check(w.t == 0.1, "the refused runs took no step", w.t)
end)


-- The fuzz (seed 1796185637, call 27049): at t = 0.02, t0 + k every with every = 1e-300
-- rounds to t0 for every k, so each step's output time was already behind it; the step
-- went adaptive (dt ignored) and each ran at every step, for millions of tiny steps here.
T.case("run refuses an output interval below its time resolution", function()
  local w = sph.world{ dx = 0.1, threads = 1, dt_max = 1e-8 } -- adaptive steps of 1e-8
  w:fill{ rect = { 0, 0, 0.5, 0.5 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -0.5, -0.3, 1, 0 } }
  w:run{ until_t = 0.02, dt = 1e-3 }
  local steps, n, c0 = w.steps, 0, os.clock()
  T.checkerror("every = 1e-300 is below the run's time resolution", "every = 1e-300 at t = 0.02 is refused", w.run, w,
               { until_t = w.t + 3e-5, dt = 1e-5, every = 1e-300, each = function() n = n + 1 end })
  T.check(w.steps == steps and n == 0, "... before a step or an output", (w.steps - steps) .. " steps, " .. n .. " outputs")
  T.below(os.clock() - c0, 0.1, "... at once (seconds)")
  -- (each stops it after a few outputs, where the run would otherwise make 1e12 steps)
  T.checkerror("below the run's time resolution", "every = 1e-12 with until_t = 1 is refused", w.run, w,
               { until_t = 1, every = 1e-12, each = function() n = n + 1; if n > 10 then return false end end })
  n, steps = 0, w.steps
  -- an interval the run can tell apart: the fixed dt kept, each at the start and every step
  w:run{ until_t = w.t + 3e-5, dt = 1e-5, every = 1e-5, each = function() n = n + 1 end }
  T.check(w.steps == steps + 3 and n == 4, "every = dt = 1e-5 for 3e-5: 3 steps, 4 outputs",
          (w.steps - steps) .. " steps, " .. n .. " outputs")
end)
T.case("files and closing", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local ok, msg = w:write_csv("/nonexistent-dir/p.csv")
  T.check(ok == nil and msg:find("nonexistent", 1, true), "write_csv to a bad path gives nil and a message")
  ok, msg = w:write_vtk("/nonexistent-dir/p.vtk")
  T.check(ok == nil and msg:find("nonexistent", 1, true), "write_vtk to a bad path gives nil and a message")
  local tmp = os.tmpname()
  T.check(w:write_vtk(tmp) == true, "write_vtk returns true")
  local f = io.open(tmp)
  local head = f:read("l")
  f:close()
  T.check(head == "# vtk DataFile Version 3.0", "VTK header")
  T.check(w:write_csv(tmp) == true, "write_csv returns true")
  local lines = 0
  for _ in io.lines(tmp) do lines = lines + 1 end
  T.check(lines == 101, "CSV has a header and one row per particle")
  os.remove(tmp)
  w:close()
  T.checkerror("closed sph.world", "a closed world raises", function() w:step() end)
  T.checkerror("closed sph.world", "closing twice raises, as for a closed file", function() w:close() end)
end)

-- Every writer replaces its file whole (src/atomic.c): a write that fails leaves the file
-- that was there byte for byte, and no temporary file. The failure is real: a child sph
-- under a file size limit of 1 KB (ulimit -f 2, SIGXFSZ ignored) whose writes stop with
-- "File too large" (a writer that truncates the old file first would lose it).
T.case("a failed write leaves the old file", function()
  local base = os.tmpname()
  local names = { csv = base .. ".csv", vtk = base .. ".vtk", save = base .. ".state" }
  local old = "old bytes\n"
  for _, f in pairs(names) do
    local g = assert(io.open(f, "wb")); g:write(old); g:close()
  end
  local script = base .. ".lua"
  local g = assert(io.open(script, "w"))
  g:write([[
local sph = require "sph"
local o = ...
local w = sph.world{ dx = 0.1, threads = 1 }
w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
print("csv", w:write_csv(o.base .. ".csv"))
print("vtk", w:write_vtk(o.base .. ".vtk"))
print("save", pcall(w.save, w, o.base .. ".state"))
]])
  g:close()
  local p = io.popen("sh -c \"trap '' XFSZ; ulimit -f 2; exec '" .. arg[-1] .. "' '" .. script .. "' base='" .. base ..
                     "'\" 2>&1")
  local out = p:read("a")
  p:close()
  for what, f in pairs(names) do
    local line = out:match(what .. "\t([^\n]*)") or "(no line)"
    T.check(line:find("File too large", 1, true) and line:find(f, 1, true),
            what .. " under a 1 KB file limit fails, naming the file and why", line)
    local h = io.open(f, "rb")
    local now = h and h:read("a")
    if h then h:close() end
    T.check(now == old, what .. ": the old file keeps its bytes after the failed write", now and #now .. " bytes")
    os.remove(f)
  end
  local left = io.popen("ls '" .. base .. "'.*.tmp.* 2>/dev/null | wc -l"):read("a")
  T.check(tonumber(left) == 0, "no temporary file left behind", left)
  os.remove(script)
  os.remove(base)
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  T.checkerror("cannot open '/nonexistent-sph-dir/s.state' for writing: No such file or directory",
               "w:save into a missing directory names the file and why", w.save, w, "/nonexistent-sph-dir/s.state")
  local ok, msg = w:write_csv("/nonexistent-sph-dir/p.csv")
  T.check(ok == nil and msg == "cannot open '/nonexistent-sph-dir/p.csv' for writing: No such file or directory",
          "write_csv into a missing directory names the file and why", msg)
end)

T.case("dt grows at most 25 % a step", function()
  -- the paper's squeeze (Bn = 5, M = 800, Re = 1, V = -1) at dx = 1/40, 150 adaptive steps:
  -- no step more than 25 % longer than the one before, and dt grows after steps whose
  -- density error was at 95 % of density_tol (0.5 %) or more (measured: 27 of them)
  local squeeze = require "sph.squeeze"
  local w = squeeze.build{ dx = 1 / 40, Re = 1, Bn = 5, M = 800, mode = "velocity", V = 1, world = { threads = 1 } }
  local tol = 0.005
  local grew_near, over25 = 0, 0
  local t0, dt0, e0 = 0, nil, nil
  for _ = 1, 150 do
    w:step()
    local s = w:stats()
    local dt = s.t - t0
    if dt0 then
      if dt > 1.25 * dt0 * (1 + 1e-9) then over25 = over25 + 1 end
      if e0 >= 0.95 * tol and dt > dt0 * (1 + 1e-9) then grew_near = grew_near + 1 end
    end
    t0, dt0, e0 = s.t, dt, s.max_density_error
  end
  w:close()
  print(string.format("# dt: steps that grew after a step near density_tol: %d", grew_near))
  T.check(over25 == 0, "dt never grew more than 25 % a step", over25)
end)

T.case("errors in the engine", function()
  local w = sph.world{ dx = 0.1 }
  T.checkerror("no fluid", "stepping an empty world", w.step, w)
end)

T.case("a time step below the minimum says what set it", function()
  -- gravity 1e30 makes the force limit 0.25 sqrt(h / g) ~ 3e-18, below dt_min = 1e-12 h
  local w = sph.world{ dx = 0.05, gravity = { 0, -1e30 }, threads = 1 }
  w:fill{ rect = { 0, 0, 0.5, 0.5 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -0.2, -0.2, 0.7, 0 } }
  T.checkerror("below the minimum", "dt collapse is an error", w.step, w)
  T.checkerror("largest density error", "dt collapse names the density error", w.step, w)
  T.checkerror("gravity 1e+30", "dt collapse names gravity when it sets the force limit", w.step, w)
end)

T.case("DESIGN.md's squeeze runs with the defaults; unshifted, it fails and says why", function()
  -- DESIGN.md's squeeze at dx = 1/20: without shifting the stretched lattice closes up
  -- (measured: fluid particles within dx / 2 from step 608, t = 0.34) and the time step
  -- collapses at t = 0.49; with the default, shifting = "auto", shifting starts when a pair
  -- comes within 0.7 dx (t = 0.198) and the run reaches t = 0.7, as with shifting = 20 from
  -- the start (about 3 s each)
  local function squeeze(shifting)
    local w = sph.world{ dx = 1 / 20, rho = 1, symmetry = { x = 0 }, threads = 1, shifting = shifting }
    w:fill{ rect = { 0, 0, 0.5, 1 }, material = sph.bingham{ mu = 1, tau0 = 2, m = 800 } }
    w:plate{ rect = { -2, -0.15, 2, 0 } }
    w:plate{ rect = { -2, 1, 2, 1.15 }, axis = "y" }:velocity(-1)
    return w, pcall(w.run, w, { until_t = 0.7, progress = false })
  end
  local w, ok, err = squeeze(0)
  T.check(not ok, "the unshifted squeeze (shifting = 0) fails before t = 0.7", ("t = %g"):format(w.t))
  T.check(not ok and tostring(err):find("needs particle shifting, sph.world{shifting = 20}", 1, true) ~= nil,
          "its message names the cause and the option", tostring(err))
  w, ok, err = squeeze(nil)
  T.check(ok and w.t >= 0.7, "with the defaults the squeeze reaches t = 0.7 (h = 0.3)", tostring(err))
  local since = w:stats().shifting_since
  T.check(since and since > 0.05 and since < 0.45, "its shifting started once the lattice clustered (before t = 0.45, where the unshifted run fails)",
          tostring(since))
  w, ok, err = squeeze(20)
  T.check(ok and w.t >= 0.7, "the shifted squeeze reaches t = 0.7 (h = 0.3)", tostring(err))
  T.check(w:stats().shifting_since == nil, "shifting = 20: no shifting_since")
end)

T.case("sph.mkdir makes a folder and its parents, and says why when it cannot", function()
  local base = os.tmpname()
  os.remove(base)
  local deep = base .. "/a'b c/d//e/"
  T.check(sph.mkdir(deep) == true, "sph.mkdir makes nested folders (a quote and a space in a name)")
  T.check(sph.mkdir(deep) == true, "an existing folder is success")
  local f = assert(io.open(deep .. "f.txt", "w"))
  f:write("x")
  f:close()
  local ok, why = sph.mkdir(deep .. "f.txt/g")
  T.check(ok == nil and tostring(why):find("f.txt", 1, true) ~= nil and tostring(why):find("Not a directory", 1, true) ~= nil,
          "a file in the way: nil and a message naming it", tostring(why))
  T.checkerror("empty path", "sph.mkdir('')", sph.mkdir, "")
  os.remove(deep .. "f.txt")
  os.remove(base .. "/a'b c/d/e")
  os.remove(base .. "/a'b c/d")
  os.remove(base .. "/a'b c")
  os.remove(base)
end)

T.case("sph.params: case parameters checked by name and type", function()
  local params = require "sph.params"
  local SPEC = { { "n", "integer", 3 }, { "x", "number", 0.5 }, { "mode", { "a", "b" }, "a" }, { "name", "string", nil } }
  local o = params.parse("case", SPEC, { n = 4 })
  T.check(o.n == 4 and o.x == 0.5 and o.mode == "a" and o.name == nil, "defaults fill in, given values stay")
  o = params.parse("case", SPEC, "n=5", "x=1e-3", "mode=b", "name=it's")
  T.check(o.n == 5 and o.x == 1e-3 and o.mode == "b" and o.name == "it's", "name=value strings (a stock lua5.4's arguments)")
  T.checkerror("case: unknown parameter 'mdoe' (did you mean mode?)", "a misspelt name", params.parse, "case", SPEC, { mdoe = "a" })
  T.checkerror('case: x must be a number, got "abc"', "x = abc", params.parse, "case", SPEC, { x = "abc" })
  T.checkerror("case: n must be an integer, got 2.5", "n = 2.5", params.parse, "case", SPEC, { n = 2.5 })
  T.checkerror("case: mode must be one of a, b", "mode = c", params.parse, "case", SPEC, { mode = "c" })
  T.checkerror("x must be a number", "x = inf", params.parse, "case", SPEC, { x = "inf" })
  T.checkerror("name=value expected", "a bare word", params.parse, "case", SPEC, "n")
end)


T.case("sph.units: the groups and scales of a case in physical units", function()
  local units = require "sph.units"
  local s = units.scales{ H = 0.01, U = 0.01, rho = 1000, mu = 0.1, tau0 = 0.2, m = 100 }
  T.close(s.Re, 1, 1e-12, "Re = rho U H / mu")
  T.close(s.Bn, 2, 1e-12, "Bn = tau0 H / (mu U)")
  T.close(s.M, 100, 1e-12, "M = m U / H")
  T.close(s.force(1), 1e-3, 1e-15, "force scale mu U per unit depth")
  T.close(s.to_time(s.time(0.3)), 0.3, 1e-15, "time there and back")
  -- Herschel-Bulkley: mu_ref = K (U/H)^(n-1)
  local hb = units.scales{ H = 0.02, U = 0.04, rho = 1, K = 3, n = 0.5, tau0 = 6, m = 1 }
  T.close(hb.mu_ref, 3 * 2 ^ -0.5, 1e-12, "Herschel-Bulkley reference viscosity K (U/H)^(n-1)")
  T.close(hb.Bn, 6 * 0.02 / (hb.mu_ref * 0.04), 1e-12, "and its Bn")
  -- under a load: U is the load's viscous speed, so the engine's load is -1
  local ld = units.scales{ H = 0.01, F = -0.01, rho = 1000, mu = 0.1 }
  T.close(ld.U, 0.1, 1e-15, "load scaling: U = |F| / mu")
  T.close(ld.to_force(-0.01), -1, 1e-12, "the load is -1 in the engine's units")
  local lh = units.scales{ H = 0.02, F = 5, rho = 1, K = 3, n = 0.5 }
  T.close(lh.mu_ref * lh.U, 5, 1e-12, "Herschel-Bulkley under a load: K (U/H)^(n-1) U = |F|")
  T.checkerror("give the plate speed U or the load F", "neither U nor F", units.scales, { H = 1, rho = 1, mu = 1 })
  T.checkerror("mu must be a positive number", "mu = 0", units.scales, { H = 1, U = 1, rho = 1, mu = 0 })
  T.checkerror("not both", "mu and K", units.scales, { H = 1, U = 1, rho = 1, mu = 1, K = 1, n = 1 })
end)

-- docs/api.md documents sph.world's options as they are: each key the engine takes in a
-- row of the options' tables (and their count in the heading), each removed one in the
-- table of removed options, and no other.
T.case("docs/api.md lists sph.world's options", function()
  local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
  local f = assert(io.open(top .. "/docs/api.md"))
  local doc = f:read("a")
  f:close()
  local _, err = pcall(sph.world, { dx = 0.1, not_an_option = 1 })
  local list = tostring(err):match("options are ([^)]*)")
  T.check(list ~= nil, "the unknown-option error lists the options", tostring(err))
  local keys = {}
  for k in (list or ""):gmatch("[%w_]+") do keys[#keys + 1] = k end
  local a = doc:find("## `sph.world{...}`", 1, true) or 1
  local r = doc:find("### Removed options", a, true) or #doc
  local e = doc:find("\n## ", r, true) or #doc
  local opts, removed = doc:sub(a, r), doc:sub(r, e)
  local rows = {}
  for k in opts:gmatch("\n| `([%w_]+)` |") do rows[k] = true end
  local missing = {}
  for _, k in ipairs(keys) do
    if not rows[k] then missing[#missing + 1] = k end
    rows[k] = nil
  end
  local extra = {}
  for k in pairs(rows) do extra[#extra + 1] = k end
  T.check(#missing == 0 and #extra == 0, "every option has its row and every row is an option",
    "missing: " .. table.concat(missing, ", ") .. "; not options: " .. table.concat(extra, ", "))
  T.check(opts:find(("the %d options"):format(#keys), 1, true) ~= nil,
    ("the heading gives the count, %d"):format(#keys))
  local gone, undocumented = 0, {}
  for k in removed:gmatch("\n| `([%w_]+)` |") do
    gone = gone + 1
    local ok, msg = pcall(sph.world, { dx = 0.1, [k] = 1 })
    if ok or not tostring(msg):find("was removed", 1, true) then undocumented[#undocumented + 1] = k end
  end
  T.check(gone > 0 and #undocumented == 0, "every removed option of the table is refused as removed",
    table.concat(undocumented, ", "))
  T.check(tonumber(removed:match("took (%d+) more options")) == gone, ("the removed options' count is the table's, %d"):format(gone))
end)

T.done()
