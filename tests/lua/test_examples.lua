-- The examples (examples/*.lua and the C one, build/examples/squeeze) as a user runs them,
-- a few steps each (steps=3, one thread): each exits 0 and writes its files, its series
-- has a row at the start and one a step; its top comment says what it shows, its
-- parameters and what to expect; examples/README.md names it; a misspelt parameter stops
-- it with status 1 and the parameter's name.
local T = require "sph.test"
local sph_bin = arg[-1]
local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
local build = sph_bin:match("^(.*)/[^/]+$") or "."
local dir = os.tmpname()
os.remove(dir)
assert(require("sph").mkdir(dir))

local STEPS = 3
-- name, files written, the series file whose rows follow the steps (nil: none)
local EXAMPLES = {
  { "squeeze_velocity", { "series.csv", "yield.png" }, "series.csv" },
  { "squeeze_load", { "series.csv", "yield.png" }, "series.csv" },
  { "squeeze_ramp", { "series.csv", "yield.png" }, "series.csv" },
  { "herschel_bulkley", { "series.csv", "yield.png", "eta.png" }, "series.csv" },
  { "slump", { "series.csv", "yield.png" }, "series.csv" },
  { "cavity", { "profiles.csv", "speed.png" } },
  { "poiseuille", { "profile.csv", "u.png" } },
}

local sh = T.sh

local function read(file)
  local f = io.open(file, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

local function lines(s)
  local n = 0
  for _ in (s or ""):gmatch("[^\n]+") do n = n + 1 end
  return n
end

local function is_png(file)
  local s = read(file)
  return s ~= nil and #s > 100 and s:sub(1, 8) == "\137PNG\r\n\26\n"
end

local readme = read(top .. "/examples/README.md") or ""

local function files_ok(name, out, files, series)
  for _, f in ipairs(files) do
    local path = out .. "/" .. f
    if f:match("%.png$") then
      T.check(is_png(path), name .. " writes " .. f .. " (a PNG)", path)
    else
      T.check(lines(read(path)) >= 2, name .. " writes " .. f .. " (a header and rows)", path)
    end
  end
  if series then
    local n = lines(read(out .. "/" .. series))
    T.check(n == STEPS + 2, string.format("%s: %s has the header, the start and a row a step", name, series),
      string.format("%d lines, expected %d", n, STEPS + 2))
  end
end

T.case("every example has a smoke test here", function()
  local listed = {}
  for _, e in ipairs(EXAMPLES) do listed[e[1]] = true end
  local p = assert(io.popen(string.format("ls '%s/examples'", top)))
  for f in p:lines() do
    local name = f:match("^(.*)%.lua$")
    if name then T.check(listed[name], name .. ".lua is run below", "add it to EXAMPLES") end
  end
  p:close()
end)

local t0 = os.time()
for _, e in ipairs(EXAMPLES) do
  local name, files, series = e[1], e[2], e[3]
  T.case(name, function()
    local script = string.format("%s/examples/%s.lua", top, name)
    local src = read(script) or ""
    T.check(src:match("^%-%- " .. name .. "%.lua: ") ~= nil and src:find("What it shows", 1, true) ~= nil and
            src:find("Parameters", 1, true) ~= nil and src:find("What you should see", 1, true) ~= nil,
            name .. ".lua's top comment says what it shows, its parameters and what to expect")
    T.check(readme:find("`" .. name .. ".lua`", 1, true) ~= nil, "examples/README.md lists " .. name .. ".lua")
    local out = dir .. "/" .. name
    local text, code = sh(string.format("%s %s steps=%d threads=1 out=%s", sph_bin, script, STEPS, out))
    T.check(code == 0, name .. ".lua steps=" .. STEPS .. " exits 0", text)
    files_ok(name, out, files, series)
  end)
end

T.case("a misspelt parameter", function()
  local text, code = sh(string.format("%s %s/examples/squeeze_velocity.lua Bnn=1 out=%s/bad", sph_bin, top, dir))
  T.check(code == 1 and text:find("unknown parameter 'Bnn' (did you mean Bn?)", 1, true) ~= nil
          and not text:find("traceback", 1, true),
          "squeeze_velocity.lua Bnn=1 exits 1 naming Bnn and Bn, without a traceback", text)
end)

T.case("squeeze.c", function()
  local src = read(top .. "/examples/squeeze.c") or ""
  T.check(src:find("pkg-config --cflags --libs sph", 1, true) ~= nil and src:find("What you should see", 1, true) ~= nil,
          "squeeze.c's top comment gives its build command and what to expect")
  T.check(readme:find("`squeeze.c`", 1, true) ~= nil, "examples/README.md lists squeeze.c")
  local bin = build .. "/examples/squeeze"
  if not io.open(bin) then
    T.check(false, "make builds " .. bin, "missing: run make")
    return
  end
  local out = dir .. "/squeeze_c"
  local text, code = sh(string.format("OMP_WAIT_POLICY=passive %s steps=%d threads=1 out=%s", bin, STEPS, out))
  T.check(code == 0, "build/examples/squeeze steps=" .. STEPS .. " exits 0", text)
  files_ok("squeeze.c", out, { "series.csv", "yield.png" }, "series.csv")
  text, code = sh(string.format("%s bogus=1", bin))
  T.check(code == 1 and text:find("unknown argument 'bogus=1'", 1, true) ~= nil, "and refuses an unknown argument", text)
end)

os.execute(string.format("rm -rf '%s'", dir))
print(string.format("# the examples took %d s", os.time() - t0))
T.done()
