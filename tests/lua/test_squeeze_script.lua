-- The headline script, scripts/squeeze.lua, run as a user runs it (the sph host that runs
-- this test, on a short case): it writes its series, says when the gap is a thin film, and
-- exits 0. (Its failure path, an engine error that stops the run, writes what was computed,
-- prints the message and exits 1: checked by hand on the thin film with the defaults,
-- which stops at step 970 of width=1.6 height=0.2 dx=0.025; too long for this suite.)
local T = require "sph.test"
local sph_bin = arg[-1]
local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
local dir = os.tmpname()
os.remove(dir)

local function run(args)
  local cmd = string.format("%s %s/scripts/squeeze.lua %s out=%s threads=1 2>&1; echo \"exit=$?\"", sph_bin, top, args, dir)
  local p = assert(io.popen(cmd))
  local text = p:read("a")
  p:close()
  return text, tonumber(text:match("exit=(%d+)"))
end

local function lines(file)
  local n = 0
  local f = io.open(file)
  if not f then return 0 end
  for _ in f:lines() do n = n + 1 end
  f:close()
  return n
end

T.case("headline squeeze script, a short run", function()
  local text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.02")
  T.check(code == 0, "squeeze.lua exits 0", text)
  T.check(text:find("done: t=0.02", 1, true) ~= nil, "squeeze.lua reports the end of the run", text)
  -- every = 0.005: rows at t = 0, 0.005, ..., 0.02 and the header
  T.check(lines(dir .. "/series.csv") == 6, "series.csv has the header and five rows", tostring(lines(dir .. "/series.csv")))
  T.check(not text:find("warning", 1, true), "no density-error warning on the headline case", text)
  T.check(not text:find("note:", 1, true), "no thin-film note on a square sample", text)
end)

T.case("headline squeeze script, a thin gap", function()
  local text, code = run("mode=velocity Re=1 Bn=0 width=1.6 height=0.2 dx=0.05 t_end=0.001")
  T.check(code == 0, "squeeze.lua exits 0 on a short thin-film run", text)
  T.check(text:find("is 4.0 particles across", 1, true) ~= nil, "squeeze.lua notes a gap a few particles across", text)
end)

T.case("headline squeeze script, the solver options reach the engine", function()
  local text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 tol=1e-7 visc_tol=1e-7")
  T.check(code == 0, "squeeze.lua runs with tol=1e-7 visc_tol=1e-7", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 visc_tol=2")
  T.check(code == 1 and text:find("visc_tol must be in (0, 1)", 1, true) ~= nil,
          "squeeze.lua with visc_tol=2 exits 1 naming visc_tol", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 dt_growth=eased")
  T.check(code == 0, "squeeze.lua runs with dt_growth=eased", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 dt_growth=slow")
  T.check(code == 1 and text:find("dt_growth", 1, true) ~= nil, "squeeze.lua with dt_growth=slow exits 1 naming dt_growth", text)
end)

os.execute("rm -rf '" .. dir .. "'")
T.done()
