-- The headline script, scripts/squeeze.lua, run as a user runs it (the sph host that runs
-- this test, on a short case): it writes its series, says when the gap is a thin film, and
-- exits 0. (Its failure path, an engine error that stops the run, writes what was computed,
-- prints the message and exits 1: checked by hand on the thin film with the defaults,
-- which stops at step 970 of width=1.6 height=0.2 dx=0.025; too long for this suite.)
-- Interrupted by SIGINT / SIGTERM it writes its outputs and a state and exits 130 / 143;
-- restarted from the state it ends as the uninterrupted run.
local T = require "sph.test"
local sph_bin = arg[-1]
local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
local dir = os.tmpname()
os.remove(dir)

local function run(args) return T.script("squeeze.lua", ("%s out=%s threads=1"):format(args, dir)) end

-- series.csv's rows after the header, each a list of its numbers (nil for an empty cell)
local function series(file)
  local rows = {}
  local f = io.open(file)
  if not f then return rows end
  f:read("l")
  for line in f:lines() do
    local r, c = {}, 0
    for v in (line .. ","):gmatch("([^,]*),") do -- by position: an empty cell leaves a hole
      c = c + 1
      r[c] = tonumber(v)
    end
    rows[#rows + 1] = r
  end
  f:close()
  return rows
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

-- The force column is the mean since the last row (the plate's impulse over the interval),
-- so a Newtonian run's reference is the mean of mu V / h^6 over the same interval: Simpson's
-- rule on the rows' gaps (linear in t at constant V), to the print's 8 digits.
T.case("headline squeeze script, the reference is the interval's mean", function()
  local text, code = run("mode=velocity Re=1 Bn=0 dx=0.05 t_end=0.1 every=0.02 frames=0 plots=0")
  T.check(code == 0, "squeeze.lua exits 0 on a Newtonian run", text)
  local rows = series(dir .. "/series.csv") -- t, h, velocity, force, iterations, density error, reference
  T.check(#rows == 6 and rows[1][4] == nil, "six rows, the first without a force", #rows)
  local worst, forces = 0, true
  for k = 2, #rows do
    local a, b = rows[k - 1][2], rows[k][2]
    local mean = (a ^ -6 + 4 * (0.5 * (a + b)) ^ -6 + b ^ -6) / 6
    worst = math.max(worst, math.abs(rows[k][7] / mean - 1))
    forces = forces and rows[k][4] ~= nil and rows[k][4] > 0
  end
  T.below(worst, 1e-6, "each row's reference is the mean of mu V / h^6 since the last row")
  T.check(forces, "each row after the first has a positive mean force")
end)

T.case("headline squeeze script, a thin gap", function()
  local text, code = run("mode=velocity Re=1 Bn=0 width=1.6 height=0.2 dx=0.05 t_end=0.001")
  T.check(code == 0, "squeeze.lua exits 0 on a short thin-film run", text)
  T.check(text:find("is 4.0 particles across", 1, true) ~= nil, "squeeze.lua notes a gap a few particles across", text)
end)

T.case("headline squeeze script, the solver options reach the engine", function()
  local text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 tol=1e-7")
  T.check(code == 0, "squeeze.lua runs with tol=1e-7", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 tol=2")
  T.check(code == 1 and text:find("tol must be in (0, 1)", 1, true) ~= nil,
          "squeeze.lua with tol=2 exits 1 naming tol", text)
  -- a removed engine option is no parameter of the script
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 dt_growth=eased")
  T.check(code == 1 and text:find("dt_growth", 1, true) ~= nil, "squeeze.lua with dt_growth=eased exits 1 naming dt_growth", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 dt_max=-1")
  T.check(code == 1 and text:find("dt_max must be a number >= 0", 1, true) ~= nil and not text:find("traceback", 1, true),
          "squeeze.lua with dt_max=-1 exits 1 naming dt_max, no traceback", text)
  text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.005 visc_tol=1e-7")
  T.check(code == 1 and text:find("visc_tol", 1, true) ~= nil, "squeeze.lua with visc_tol=1e-7 exits 1 naming visc_tol", text)
end)

-- A stiff yield stress: the density correction makes much of the particles' motion (the
-- square at Bn = 1000 to t = 0.01: 0.38 at dx = 1/20, 0.18 at 1/40); the script says so, and
-- that a finer dx lowers it (a shorter step does not: a Bingham film at dt_max = 1e-5 has
-- 0.27 against 0.22 at the engine's step).
T.case("headline squeeze script warns when the velocity does not carry the flow", function()
  local text, code = run("mode=velocity Re=0.05 Bn=1000 M=800 dx=0.05 t_end=0.01 frames=0 plots=0")
  T.check(code == 0, "squeeze.lua runs the square at Bn = 1000", text)
  T.check(text:find("warning: the density correction made", 1, true) ~= nil and text:find("a finer dx lowers it", 1, true) ~= nil,
          "it warns that the density correction made the motion, and that a finer dx lowers it", text)
end)

-- Early endings say why, with a status that is not 0 (issue 27 D): h_stop before t_end
-- stops with status 2 and the gap; a gap under 3 particles across is refused (status 1).
T.case("headline squeeze script, stopped at h_stop before t_end", function()
  local text, code = run("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=1 h_stop=0.9")
  T.check(code == 2, "squeeze.lua exits 2 when h_stop ends the run before t_end", text)
  T.check(text:find("stopped at t = 0.1", 1, true) ~= nil and text:find("<= h_stop = 0.9, before t_end = 1", 1, true) ~= nil,
          "it says where and why it stopped", text)
  T.check(not text:find("done:", 1, true), "it does not call the run done", text)
  T.check(lines(dir .. "/series.csv") > 2, "the series up to the stop is written", tostring(lines(dir .. "/series.csv")))
end)

T.case("headline squeeze script, a gap too thin for the particles", function()
  local text, code = run("mode=load F=-1.3e8 Re=1 Bn=0 dx=0.05 t_end=0.01 h_stop=0.05")
  T.check(code == 1 and text:find("h_stop = 0.05 is 1.0 particles across (dx = 0.05): the gap must stay at least 3", 1, true) ~= nil,
          "h_stop = dx is refused with status 1 and the reason", text)
  T.check(not text:find("done:", 1, true), "no run is reported as done", text)
  text, code = run("mode=velocity Re=1 Bn=0 width=1.6 height=0.1 dx=0.05 t_end=0.001")
  T.check(code == 1 and text:find("height = 0.1 is 2.0 particles across", 1, true) ~= nil,
          "a sample 2 particles high is refused", text)
  text, code = run("mode=velocity Re=1 Bn=0 dx=0.05 t_end=0.001 h_stop=0.15")
  T.check(code == 0, "h_stop = 3 dx runs", text)
end)

-- SIGINT / SIGTERM (src/main.c, lsph.c): the step ends, w:run raises "interrupted", the
-- script writes its series, plots and a state, says how to go on and exits 128 + signal;
-- restarted from the state with the same arguments it ends as the uninterrupted run, series
-- bit for bit.
local function file_size(f)
  local g = io.open(f, "rb")
  if not g then return nil end
  local n = g:seek("end")
  g:close()
  return n
end

for _, sig in ipairs{ { "INT", 130, "SIGINT" }, { "TERM", 143, "SIGTERM" } } do
  T.case("headline squeeze script, interrupted by SIG" .. sig[1], function()
    local d = dir .. "/int_" .. sig[1]
    -- outputs about 20 steps apart: the state falls inside an interval, whose force the
    -- restart's first row gives as the mean over the whole of it (state.bin.last)
    local args = "mode=velocity V=0.2 Re=10 Bn=0.5 M=100 dx=0.05 t_end=1.5 every=0.05 plots=1 threads=1"
    os.execute("mkdir -p '" .. d .. "'")
    -- in the background; killed once its series has 20 rows
    local cmd = string.format("%s %s/scripts/squeeze.lua %s out=%s >%s/log 2>&1 & pid=$!; i=0; "
      .. "while [ \"$(cat %s/series.csv 2>/dev/null | wc -l)\" -lt 20 ] && [ $i -lt 600 ]; do sleep 0.02; i=$((i+1)); done; "
      .. "kill -%s $pid; wait $pid; echo \"exit=$?\"", sph_bin, top, args, d, d, d, sig[1])
    local p = assert(io.popen(cmd))
    local res = p:read("a")
    p:close()
    local lf = io.open(d .. "/log")
    local log = lf and lf:read("a") or ""
    if lf then lf:close() end
    T.check(tonumber(res:match("exit=(%d+)")) == sig[2], "squeeze.lua exits " .. sig[2] .. " on SIG" .. sig[1], res .. log)
    T.check(log:find("interrupted (" .. sig[3] .. ") at t=", 1, true) ~= nil, "it says it was interrupted, and when", log)
    T.check(log:find("restart=" .. d .. "/state.bin", 1, true) ~= nil, "it says how to continue", log)
    T.check((file_size(d .. "/h.png") or 0) > 0 and (file_size(d .. "/force.png") or 0) > 0, "the plots are written", log)
    local rows = lines(d .. "/series.csv")
    T.check(rows >= 20 and rows < 32, "the series holds the rows so far", rows)
    local sph = require "sph"
    local ok, w = pcall(sph.load, d .. "/state.bin")
    T.check(ok and w.t > 0 and w.t < 1.5, "sph.load reads the state it saved", w)
    if not ok then return end
    -- the last output's clock, impulse and gap, exact, for the restart's first mean force
    local lf2 = io.open(d .. "/state.bin.last")
    local lt, li, lh = (lf2 and lf2:read("l") or ""):match("^(%S+) (%S+) (%S+)$")
    if lf2 then lf2:close() end
    local got = series(d .. "/series.csv")
    local row = got[#got] or {}
    T.check(tonumber(lt) and tonumber(li) and row[1] and math.abs(tonumber(lt) - row[1]) <= 1e-7
            and math.abs(tonumber(lh) - row[2]) <= 1e-7 and tonumber(lt) <= w.t,
            "state.bin.last holds the last row's time and gap (and the impulse then)", tostring(lt) .. " " .. tostring(row[1]))
    w:close()
    if sig[1] ~= "INT" then return end
    -- continued to the end, against the run never interrupted
    local pr = assert(io.popen(string.format("%s %s/scripts/squeeze.lua %s out=%s restart=%s/state.bin 2>&1; echo \"exit=$?\"",
      sph_bin, top, args, d, d)))
    local text = pr:read("a")
    pr:close()
    local code = tonumber(text:match("exit=(%d+)"))
    T.check(code == 0 and text:find("restart: ", 1, true) ~= nil, "the restart runs to the end", text)
    local ref = dir .. "/int_ref"
    local p2 = assert(io.popen(string.format("%s %s/scripts/squeeze.lua %s out=%s 2>&1", sph_bin, top, args, ref)))
    p2:read("a")
    p2:close()
    local function read(f)
      local g = io.open(f, "rb")
      local t = g and g:read("a") or ""
      if g then g:close() end
      return t
    end
    local a, b = read(d .. "/series.csv"), read(ref .. "/series.csv")
    T.check(#a > 0 and a == b, "the restarted run's series is the uninterrupted one's, bit for bit",
      #a .. " vs " .. #b .. " bytes")
  end)
end

os.execute("rm -rf '" .. dir .. "'")

-- Case parameters are checked: a misspelt name or a value of the wrong type stops the run
-- with status 1 and a message naming the parameter (it used to run the default case).
T.case("headline squeeze script, bad parameters are refused by name", function()
  local text, code = run("viscocity=explicit t_end=0.001 dx=0.05")
  T.check(code == 1 and text:find("unknown parameter 'viscocity' (did you mean viscosity?)", 1, true) ~= nil,
          "a misspelt parameter exits 1 and suggests the right name", text)
  T.check(text:find("the parameters are: mode, units, Re, Bn", 1, true) ~= nil, "the message lists the parameters", text)
  text, code = run("Bn=abc t_end=0.001 dx=0.05")
  T.check(code == 1 and text:find('Bn must be a number, got "abc"', 1, true) ~= nil, "Bn=abc exits 1 naming Bn", text)
  text, code = run("mode=lod t_end=0.001 dx=0.05")
  T.check(code == 1 and text:find("mode must be one of velocity, load", 1, true) ~= nil, "mode=lod names mode", text)
  text, code = run("frames=2.5 t_end=0.001 dx=0.05")
  T.check(code == 1 and text:find("frames must be an integer", 1, true) ~= nil, "frames=2.5 names frames", text)
end)

-- The output folder is made without a shell: a quote in its name is a name like any other.
T.case("headline squeeze script, an output folder with a quote in its name", function()
  local odir = dir .. "/it's here/deeper"
  local cmd = string.format("%s %s/scripts/squeeze.lua \"out=%s\" threads=1 dx=0.05 t_end=0.005 2>&1; echo \"exit=$?\"",
    sph_bin, top, odir)
  local p = assert(io.popen(cmd))
  local text = p:read("a")
  p:close()
  T.check(tonumber(text:match("exit=(%d+)")) == 0, "squeeze.lua runs with out= holding a quote", text)
  T.check(lines(odir .. "/series.csv") > 1, "its series is in that folder", text)
end)

-- The same script and arguments under a stock lua5.4 (where it is installed) with the
-- module and helpers on its paths.
T.case("headline squeeze script under lua5.4", function()
  local ok = os.execute("command -v lua5.4 >/dev/null 2>&1")
  if not ok then
    print("# lua5.4 not installed: skipped")
    return
  end
  -- the module next to the host that runs this test (build/ or make check's build-san/)
  local sodir = sph_bin:match("^(.*)/[^/]*$") or "."
  local env = string.format("%s LUA_CPATH='%s/?.so;;' LUA_PATH='%s/lua/?.lua;;'", os.getenv("SPH_LUA_PRELOAD") or "",
    sodir, top)
  local cmd = string.format("%s lua5.4 %s/scripts/squeeze.lua mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.01 out=%s/l54 threads=1 2>&1; echo \"exit=$?\"",
    env, top, dir)
  local p = assert(io.popen(cmd))
  local text = p:read("a")
  p:close()
  T.check(tonumber(text:match("exit=(%d+)")) == 0 and text:find("done: t=0.01", 1, true) ~= nil,
          "lua5.4 runs the script with its arguments", text)
  cmd = string.format("%s lua5.4 %s/scripts/squeeze.lua Bn=abc 2>&1; echo \"exit=$?\"", env, top)
  p = assert(io.popen(cmd))
  text = p:read("a")
  p:close()
  T.check(tonumber(text:match("exit=(%d+)")) == 1 and text:find("Bn must be a number", 1, true) ~= nil,
          "lua5.4 refuses Bn=abc by name", text)
end)


-- units=SI: a case in physical units equals its dimensionless twin: H = 0.01 m, U = 0.01 m/s,
-- rho = 1000, mu = 0.1 Pa s, tau0 = 0.2 Pa, m = 100 s give Re = 1, Bn = 2, M = 100, and the
-- series in s, m, m/s and N/m are the twin's times the scales (1 s, 0.01 m, 0.01 m/s,
-- 1e-3 N/m). Under a load the speed scale is the load's viscous speed |F| / mu: F = -0.01 N/m
-- gives U = 0.1 m/s, Re = 10, Bn = 0.2, M = 1000 and the twin's load -1.
local function twins(si_args, dl_args, sc, name)
  local sdir, ddir = dir .. "/si_" .. name, dir .. "/dl_" .. name
  local cmd = "%s %s/scripts/squeeze.lua %s frames=0 plots=0 threads=1 out=%s 2>&1; echo \"exit=$?\""
  local p = assert(io.popen(string.format(cmd, sph_bin, top, si_args, sdir)))
  local t1 = p:read("a")
  p:close()
  p = assert(io.popen(string.format(cmd, sph_bin, top, dl_args, ddir)))
  local t2 = p:read("a")
  p:close()
  T.check(t1:find("exit=0", 1, true) and t2:find("exit=0", 1, true), name .. ": both runs exit 0", t1 .. t2)
  local a, b = series(sdir .. "/series.csv"), series(ddir .. "/series.csv")
  T.check(#a == #b and #a > 5, name .. ": the same number of rows", #a .. " vs " .. #b)
  local worst = 0
  for i = 1, math.min(#a, #b) do
    for c, k in ipairs{ sc.T, sc.H, sc.U, sc.F } do
      if a[i][c] and b[i][c] then
        local d = math.abs(a[i][c] / k - b[i][c]) / math.max(1e-12, math.abs(b[i][c]))
        if d > worst then worst = d end
      end
    end
  end
  print(string.format("# %s: largest relative difference of the rescaled series %.2e", name, worst))
  T.below(worst, 1e-6, name .. ": the SI series is the dimensionless one times the scales")
  return t1
end

T.case("headline squeeze script, units=SI equals its dimensionless twin", function()
  local text = twins("units=SI height=0.01 V=0.01 rho=1000 mu=0.1 tau0=0.2 m=100 dx=0.0005 t_end=0.03 every=0.005",
    "Re=1 Bn=2 M=100 dx=0.05 t_end=0.03 every=0.005", { T = 1, H = 0.01, U = 0.01, F = 1e-3 }, "velocity")
  T.check(text:find("Re=1 Bn=2 M=100", 1, true) ~= nil, "it prints Re, Bn and M", text)
  twins("units=SI mode=load F=-0.01 height=0.01 rho=1000 mu=0.1 tau0=0.2 m=100 dx=0.0005 t_end=0.003 every=0.0005",
    "mode=load F=-1 Re=10 Bn=0.2 M=1000 dx=0.05 t_end=0.03 every=0.005", { T = 0.1, H = 0.01, U = 0.1, F = 0.01 }, "load")
  local t, code = run("units=SI height=0.01 V=0.01 rho=1000 mu=0.1 Re=2 dx=0.0005 t_end=0.001")
  T.check(code == 1 and t:find("Re is not a parameter with units=SI", 1, true) ~= nil, "Re with units=SI is refused", t)
  t, code = run("mu=0.1 dx=0.05 t_end=0.001")
  T.check(code == 1 and t:find("mu is a parameter of units=SI", 1, true) ~= nil, "mu without units=SI is refused", t)
  t, code = run("units=SI height=0.01 V=0.01 rho=1000 t_end=0.001 dx=0.0005")
  T.check(code == 1 and t:find("units=SI needs mu", 1, true) ~= nil, "a missing material parameter is named", t)
end)

T.done()
