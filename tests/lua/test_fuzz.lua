-- A fuzz test of the Lua API (issue 27 E): random calls on worlds, plates, materials,
-- fields, states, CSV / VTK / VTU / PVD, render, plot and animate, with random and bad arguments, each
-- in pcall. It passes when nothing crashes (the process ends: run.sh counts a crash as a
-- failure) and every error raised is a non-empty Lua string. A fixed seed in `make test`
-- (5,000 calls, a second or two); `make check` runs 30,000 calls under the sanitizers with
-- the seed from the environment (SPH_FUZZ_SEED, else the clock's; printed first):
-- SPH_FUZZ_CALLS=N, SPH_FUZZ_SEED=S (default 27 here); SPH_FUZZ_VERBOSE=1 prints each call
-- (and a step's world, a run's options) before it runs, to find the one that crashed.
-- Every file it writes is in a temporary folder (bad names included). The kind of bug it
-- finds: a step on a world a failed step left with a NaN (world.c checks for it), a log
-- plot of data at 5e-324 (plot.c keeps the decades finite).
local sph = require "sph"
local T = require "sph.test"

local CALLS = tonumber(os.getenv("SPH_FUZZ_CALLS") or "") or 5000
local SEED = tonumber(os.getenv("SPH_FUZZ_SEED") or "") or 27
local VERBOSE = os.getenv("SPH_FUZZ_VERBOSE") == "1"
math.randomseed(SEED)
print(string.format("# fuzz: %d calls, seed %d", CALLS, SEED))

local dir = os.tmpname()
os.remove(dir)
os.execute("mkdir -p '" .. dir .. "'")

local R = math.random
local function pick(t) return t[R(#t)] end

-- values, from the plausible to the absurd
local NUMBERS = { 0, 1, -1, 0.5, 2, 3, 0.1, 0.05, 1e-3, 1e-300, 5e-324, 1e300, -1e300, 1 / 0, -1 / 0, 0 / 0, 2 ^ 31,
                  -2 ^ 31, 2 ^ 53, 1e20, -0.0, 7, 100, 1e6, 0.25, 1.5, 12, 64, 257 }
local STRINGS = { "", "x", "y", "velocity", "load", "fixed", "p", "rho", "u", "v", "speed", "stress", "yield",
                  "eta", "id", "surface", "implicit", "explicit", "passes", "gmres", "symmetric",
                  "difference", "line", "markers", "both", "viridis", "\0", string.rep("a", 300), "%s%n%d",
                  "nan", "1e309", "../x", "/nonexistent/dir/file" }
local pool = { worlds = {}, plates = {}, mats = {}, files = {} }

local value -- forward
local function pcall_close(w) pcall(function() w:close() end) end
local function number()
  if R() < 0.6 then return pick(NUMBERS) end
  return (R() - 0.5) * 10 ^ R(-5, 5)
end
local function rect()
  if R() < 0.15 then return { number(), number(), number(), number() } end
  if R() < 0.05 then return { 1, 2 } end
  local x0, y0 = (R() - 0.5) * 2, (R() - 0.5) * 2
  return { x0, y0, x0 + R() * 1.2, y0 + R() * 1.2 }
end
local function table_of(depth)
  local t = {}
  for _ = 1, R(0, 4) do
    if R() < 0.5 then t[#t + 1] = value(depth + 1) else t[pick(STRINGS)] = value(depth + 1) end
  end
  return t
end
local function law()
  local kind = R(5)
  if kind == 1 then return function() return number() end end
  if kind == 2 then return function() error("law failed") end end
  if kind == 3 then return function() return "text" end end
  if kind == 4 then return function() local w = pick(pool.worlds); if w then pcall_close(w) end return 0 end end
  return function() return nil end
end
function value(depth)
  depth = depth or 0
  local k = R(12)
  if k <= 3 then return number() end
  if k <= 5 then return pick(STRINGS) end
  if k == 6 then return R() < 0.5 end
  if k == 7 then return nil end
  if k == 8 and depth < 2 then return table_of(depth) end
  if k == 9 then return law() end
  if k == 10 then return pick(pool.worlds) end
  if k == 11 then return pick(pool.plates) end
  return pick(pool.mats) or rect()
end
-- a table of options: the names the call takes with random values, sometimes an unknown one
local function options(keys, gen)
  local t = {}
  for _, key in ipairs(keys) do
    if R() < 0.3 then t[key] = (gen and gen[key] and R() < 0.9) and gen[key]() or value() end
  end
  if R() < 0.05 then t[pick(STRINGS)] = value() end
  return t
end

local function material()
  local k = R(4)
  if k == 1 then return sph.newtonian(R() < 0.8 and { mu = pick{ 1, 0.1, 10 } } or table_of(0)) end
  if k == 2 then return sph.bingham(R() < 0.8 and { mu = 1, tau0 = pick{ 0.5, 5 }, m = pick{ 10, 100 } } or table_of(0)) end
  if k == 3 then return sph.herschel_bulkley(R() < 0.8 and { K = 1, n = pick{ 0.5, 1.5 }, tau0 = 1, m = 100 } or table_of(0)) end
  return sph.newtonian{ mu = number() }
end

local WORLD_KEYS = { "rho", "gravity", "viscosity", "shifting", "dt_max", "periodic", "symmetry",
                     "threads", "tol", "surface", "density_tol", "thin_film" }
local WORLD_GEN = {
  gravity = function() return { 0, pick{ 0, -1, -10 } } end,
  threads = function() return pick{ 1, 1, 2, 0, -1, 257, 2.5 } end,
  periodic = function() return { x = { -0.5, 1.5 } } end,
  symmetry = function() return pick{ { x = 0 }, { y = 0 }, { x = 1e300 } } end,
  viscosity = function() return pick{ "implicit", "explicit", "other" } end,
  thin_film = function() return pick{ true, false, "yes" } end,
}

-- A lattice the engine would take but that is large (a real fill of millions of particles,
-- gigabytes: no defect, only slow) is shrunk; refused sizes (beyond 2e8 points, not
-- finite, inverted) stay.
local function small(w, r)
  local ok, dx = pcall(function() return w.dx end)
  if not ok or type(r) ~= "table" or type(r[1]) ~= "number" or type(r[4]) ~= "number" then return r end
  local nx, ny = (r[3] - r[1]) / dx + 1, (r[4] - r[2]) / dx + 1
  local n = nx * ny
  if n == n and nx > 0 and ny > 0 and n > 2e4 and n <= 4e8 then return { r[1], r[2], r[1] + 60 * dx, r[2] + 60 * dx } end
  return r
end

local function new_world()
  local o = R() < 0.7 and {} or options(WORLD_KEYS, WORLD_GEN)
  o.dx = R() < 0.9 and pick{ 0.1, 0.125, 0.2, 0.08 } or number()
  if o.threads == nil then o.threads = 1 end
  local w = sph.world(o)
  if R() < 0.7 then -- most worlds hold a sample on a plate: their steps run
    local dx = w.dx
    pcall(w.fill, w, { rect = small(w, { 0, 0, 0.5, 0.5 }), material = pick(pool.mats) or sph.newtonian{ mu = 1 } })
    local ok, p = pcall(w.plate, w, { rect = small(w, { -0.5, -3 * dx, 1, 0 }) })
    if ok then pool.plates[#pool.plates + 1] = p end
    if R() < 0.5 then
      ok, p = pcall(w.plate, w, { rect = small(w, { -0.5, 0.5 + dx, 1, 0.5 + 4 * dx }), axis = "y" })
      if ok then pool.plates[#pool.plates + 1] = p; pcall(p.velocity, p, -1) end
    end
  end
  pool.worlds[#pool.worlds + 1] = w
  if #pool.worlds > 6 then table.remove(pool.worlds, 1) end
  return w
end

local function a_world() return pick(pool.worlds) or new_world() end
-- a file to write: mostly a name in dir, else a bad one, but never a path outside dir (a
-- number or a string would be taken as a name in the working directory)
local function out_file(stem)
  local k = R(10)
  if k <= 8 then return dir .. "/" .. stem .. R(3) end
  return pick{ false, {}, "", dir, dir .. "/missing/sub/" .. stem, dir .. "/" .. (pick(STRINGS):gsub("[/.%z]", "_")) }
end


-- the calls: name, function (raises or returns)
local ops = {
  { "sph.world", new_world },
  { "sph.world(bad)", function() return sph.world(value()) end },
  { "material", function() pool.mats[#pool.mats + 1] = material() end },
  { "w:fill", function()
    local w = a_world()
    local o = { rect = small(w, rect()), material = pick(pool.mats) or material() }
    if R() < 0.1 then o = options({ "rect", "material" }) end
    return w:fill(o)
  end },
  { "w:plate", function()
    local w = a_world()
    local o = { rect = small(w, rect()), axis = R() < 0.5 and pick{ "x", "y", "z", 1 } or nil,
                mass = R() < 0.2 and number() or nil, slide = R() < 0.1 and { number(), number() } or nil }
    if R() < 0.1 then o = options({ "rect", "axis", "mass", "slide" }) end
    local p = w:plate(o)
    pool.plates[#pool.plates + 1] = p
    if #pool.plates > 12 then table.remove(pool.plates, 1) end
  end },
  { "plate law", function()
    local p = pick(pool.plates)
    if not p then return end
    local k = R(4)
    -- a law (a number, a function, or anything), or a read: no argument
    local function arg() local r = R() return r < 0.5 and number() or r < 0.8 and law() or value() end
    if k == 1 then if R() < 0.15 then return p:velocity() end return p:velocity(arg()) end
    if k == 2 then if R() < 0.15 then return p:load() end return p:load(arg()) end
    if k == 3 then p[pick{ "mass", "n", "velocity", "axial_velocity", "x" }] = value() return end
    return p[pick{ "position", "velocity", "axial_velocity", "force", "mass", "mode", "axis", "rect", "index", "fixed",
                   "slide", "x" }]
  end },
  { "w:plate(k)", function() return a_world():plate(value()) end },
  { "w:step", function()
    local w = a_world()
    if VERBOSE then
      pcall(function()
        local st = w:stats()
        print(string.format("#   step: dx=%.17g h=%.17g t=%.17g particles=%d fluid=%d", w.dx, w.h, w.t, st.particles, st.fluid))
      end)
    end
    if R() < 0.7 then return w:step() end
    return w:step(pick{ 1e-4, 1e-6, 0, -1, 1e300, 1 / 0, 0 / 0, "x", 1e-300 })
  end },
  { "w:run", function()
    -- bounded: a few steps whatever the world's time step (one of 1e-12 is legitimate)
    local w = a_world()
    local n = 0
    local o
    local mode = R(3)
    if mode == 1 then -- each step an output time, each stops after three
      o = { until_t = w.t + pick{ 1e-4, 1e-3, 0, -1, 0 / 0, 1e300 }, every = pick{ 1e-300, 1e-300, -1, 0 / 0 },
            each = function() n = n + 1; if n >= 3 then return false end end, progress = false }
      if R() < 0.3 then o.dt = pick{ 1e-5, 1 / 0, 0 / 0, -1, 0 } end
    elseif mode == 2 then -- a fixed dt, up to three of them
      local d = pick{ 1e-5, 1e-7 }
      o = { until_t = w.t + R(0, 3) * d, dt = d, every = pick{ 0, 1e-6, 1e-300, 2 * d },
            each = R() < 0.7 and function() n = n + 1 end or value(), progress = R() < 0.5 }
    else -- random options: an until_t after now is taken back to now
      o = options({ "until_t", "every", "each", "progress", "dt", "t0" })
      local ok, t = pcall(function() return w.t end)
      if ok and type(o.until_t) == "number" and o.until_t > t then o.until_t = t end
    end
    if mode ~= 3 and R() < 0.2 then o.t0 = pick{ 0, 1 / 0, -1e300, w.t } end
    if VERBOSE then
      local d = {}
      for k, v in pairs(o) do d[#d + 1] = k .. "=" .. tostring(v) end
      print(string.format("#   run at t=%.17g dt=%.17g: %s", w.t, w.dt, table.concat(d, " ")))
    end
    return w:run(o)
  end },
  { "w:field", function()
    local w = a_world()
    return w:field(R() < 0.8 and pick{ "x", "y", "u", "v", "p", "rho", "eta", "gammadot", "stress", "yielded", "speed",
                                       "surface", "material", "id", "rho_sum", "divr" } or value())
  end },
  { "w:set_velocity", function()
    local w = a_world()
    local n = w:stats().fluid
    local function arr()
      if R() < 0.3 then return value() end
      local t = {}
      for i = 1, n + pick{ 0, 0, 0, 1, -1 } do t[i] = R() < 0.98 and R() or value() end
      return t
    end
    return w:set_velocity(arr(), arr())
  end },
  { "w:stats", function() return a_world():stats() end },
  { "w index", function() local w = a_world(); return w[pick{ "t", "dt", "steps", "dx", "h", "rho", "nope", 1 }], tostring(w) end },
  { "w:write_csv", function()
    return a_world():write_csv(out_file("f.csv"))
  end },
  { "w:write_vtk", function()
    return a_world():write_vtk(out_file("f.vtk"))
  end },
  { "w:write_vtu", function()
    local o = R() < 0.5 and nil or options({ "encoding", "header_type", "mirror" }, {
      encoding = function() return pick{ "base64", "raw", "ascii" } end,
      header_type = function() return pick{ "UInt32", "UInt64", "Int8" } end,
      mirror = function() return R() < 0.5 end })
    return a_world():write_vtu(out_file("f.vtu"), o)
  end },
  { "sph.pvd_write", function()
    local list = {}
    for k = 1, R(0, 4) do
      list[k] = R() < 0.8 and { t = R() < 0.9 and number() or value(), file = R() < 0.9 and pick(STRINGS) or value() } or value()
    end
    return sph.pvd_write(out_file("s.pvd"), R() < 0.9 and list or value())
  end },
  { "w:save", function()
    local f = dir .. "/s" .. R(3) .. ".bin"
    a_world():save(R() < 0.9 and f or out_file("s.bin"))
    pool.files[#pool.files + 1] = f
  end },
  { "sph.load", function()
    local f = pick(pool.files)
    if f and R() < 0.5 then -- damage a saved state at a random byte
      local g = io.open(f, "rb")
      local d = g and g:read("a")
      if g then g:close() end
      if d and #d > 0 then
        local at = R(#d)
        local out = dir .. "/damaged.bin"
        g = assert(io.open(out, "wb"))
        local cut = R() < 0.2 and R(#d) or #d
        g:write((d:sub(1, at - 1) .. string.char(R(0, 255)) .. d:sub(at + 1)):sub(1, cut))
        g:close()
        f = out
      end
    end
    local w = sph.load(f or value())
    pool.worlds[#pool.worlds + 1] = w
    if #pool.worlds > 6 then table.remove(pool.worlds, 1) end
  end },
  { "w:close", function() local w = pick(pool.worlds); if w and R() < 0.3 then return w:close() end end },
  { "w:render", function()
    local w = a_world()
    local o = options({ "width", "height", "color", "view", "colorbar", "label", "range", "mirror", "radius",
                        "colormap" }, {
      width = function() return pick{ 8, 32, 100, 7, 16385, -1, 0 / 0, 2.5 } end,
      height = function() return pick{ 8, 40, 100, 0, 1e9 } end,
      color = function() return pick{ "p", "speed", "yield", "rho", "eta", "id", "none" } end,
      view = function() return rect() end,
      range = function() return pick{ { 0, 1 }, { 1, 0 }, { 0, 5e-324 }, { -1e308, 1e308 }, { 0 / 0, 1 } } end,
      radius = function() return pick{ 0.5, 0, -1, 1e300 } end,
      colorbar = function() return R() < 0.5 end,
      label = function() return pick(STRINGS) end,
      mirror = function() return pick{ true, false, "x", "y" } end,
      colormap = function() return pick{ "viridis", "gray", "jet", "cividis", 3 } end,
    })
    o.width = type(o.width) == "number" and o.width or 64
    o.height = type(o.height) == "number" and o.height or 48
    o.file = R() < 0.8 and dir .. "/r" .. R(3) .. ".png" or out_file("r.png")
    return w:render(o)
  end },
  { "sph.plot", function()
    local function series()
      local s = {}
      for _ = 1, R(0, 3) do
        local x, y = {}, {}
        for i = 1, R(0, 30) do x[i], y[i] = R() < 0.95 and i or number(), R() < 0.95 and R() or number() end
        if R() < 0.1 then y[#y + 1] = 1 end
        s[#s + 1] = R() < 0.9 and { x = x, y = y, label = pick(STRINGS), style = pick{ "line", "markers", "both", "line", "dots" } }
                    or value()
      end
      return s
    end
    local o = options({ "title", "xlabel", "ylabel", "log", "xrange", "yrange", "legend", "width", "height" }, {
      width = function() return pick{ 64, 200, 63, 16385, 0 / 0 } end,
      height = function() return pick{ 64, 150, 10 } end,
      xrange = function() return pick{ { 0, 1 }, { 1, 1 }, { 0, 5e-324 }, { -1e308, 1e308 } } end,
      yrange = function() return pick{ { 0, 1 }, { 0, 0 }, { 1 / 0, 1 } } end,
      log = function() return pick{ "x", "y", "xy", true, "z" } end,
      title = function() return pick(STRINGS) end,
      xlabel = function() return pick(STRINGS) end,
      ylabel = function() return pick(STRINGS) end,
      legend = function() return pick{ true, false, "upper left", "none" } end,
    })
    o.series = R() < 0.9 and series() or value()
    o.file = out_file("p.png")
    o.width = type(o.width) == "number" and o.width or 200
    o.height = type(o.height) == "number" and o.height or 150
    return sph.plot(o)
  end },
  { "sph.animate", function()
    local frames = {}
    for i = 1, R(0, 3) do frames[i] = R() < 0.8 and dir .. "/r" .. R(3) .. ".png" or value() end
    local o = { frames = R() < 0.9 and frames or value(), file = out_file("a.png"),
                fps = R() < 0.7 and pick{ 10, 25 } or number(), loop = R() < 0.2 and value() or nil }
    return sph.animate(o)
  end },
  { "gc", function() collectgarbage() end },
}

local bad, errors, t0 = 0, 0, os.clock()
local counts = {}
for call = 1, CALLS do
  local op = ops[R(#ops)]
  if VERBOSE then print(string.format("# %d %s", call, op[1])); io.stdout:flush() end
  local c0 = os.clock()
  local ok, err = pcall(op[2])
  local dt = os.clock() - c0
  if ok then counts[op[1]] = (counts[op[1]] or 0) + 1 end
  if VERBOSE and dt > 0.2 then print(string.format("# slow: call %d %s %.2f s: %s", call, op[1], dt, tostring(err))) end
  if not ok then
    errors = errors + 1
    if type(err) ~= "string" or #err == 0 then
      bad = bad + 1
      if bad <= 10 then print(string.format("# call %d (%s): error of type %s: %s", call, op[1], type(err), tostring(err))) end
    end
  end
  if #pool.mats > 8 then table.remove(pool.mats, 1) end
end
for _, w in ipairs(pool.worlds) do pcall(function() w:close() end) end
pool = nil
collectgarbage()
print(string.format("# fuzz: %d calls, %d raised (all Lua strings: %s), %.1f s", CALLS, errors, bad == 0 and "yes" or "no",
  os.clock() - t0))
local names = {}
for k in pairs(counts) do names[#names + 1] = k end
table.sort(names)
local parts = {}
for _, k in ipairs(names) do parts[#parts + 1] = k .. " " .. counts[k] end
print("# succeeded: " .. table.concat(parts, ", "))
T.check(true, "the fuzzed API did not crash (" .. CALLS .. " calls, seed " .. SEED .. ")")
T.check(bad == 0, "every error the fuzzed API raised is a Lua string", bad .. " were not")
T.check(errors > CALLS / 10 and errors < CALLS, "the fuzz raises errors and also succeeds", errors)
-- nothing sph did changed the types of Lua's own values (DESIGN.md)
T.check(getmetatable(1) == nil and getmetatable(true) == nil and getmetatable(print) == nil and getmetatable(nil) == nil,
        "after the fuzz, numbers, booleans, functions and nil still have no metatable")
T.check(getmetatable("").__index == string, "after the fuzz, strings still index the string library")
os.execute("rm -rf '" .. dir .. "'")
-- not T.done(): os.exit skips closing the Lua state, and the host's release of cairo's and
-- fontconfig's caches after it (the leak checker of make check counted them)
if T.failed() > 0 then error("fuzz: " .. T.failed() .. " checks failed", 0) end
