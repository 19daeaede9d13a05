-- A parameter sweep: a grid of case parameters expanded into runs of a case script, run in
-- parallel on this machine, gathered into one CSV and a plot; and a Slurm job-array script
-- for a cluster from the same grid.
--   build/sph scripts/sweep.lua Bn=1,2 F=-5,-10 mode=load Re=1 t_end=1 workers=2 out=out/sweep
-- A parameter whose value holds commas is an axis of the grid (Bn=1,2 F=-5,-10: four runs);
-- the others are passed to every run as they are. The sweep's own parameters:
--   script   the case script (default scripts/squeeze.lua, beside this one)
--   workers  runs at a time here (default: the cores); 0 writes the job files only
--   out      the sweep's folder (default out/sweep): run_0001/ ... (each run's out=),
--            jobs.txt (one shell command a run), slurm.sh, summary.csv, summary.png
-- Runs of the squeeze script get frames=0 plots=0 unless given (one summary plot instead).
-- Runs go through GNU parallel when it is installed, else `xargs -P`. Each run's folder gets
-- log.txt (what it printed) and status (its exit status). summary.csv: one row a run, the
-- axes' values, the status, and the last row of the run's series.csv (t, h, velocity,
-- force); summary.png: h at the end against the first axis, one line per value of the
-- second. On a cluster: `sbatch out/sweep/slurm.sh` runs jobs.txt as an array, one run a
-- task; then `build/sph scripts/sweep.lua <the same arguments> workers=0 gather=1`
-- gathers.
local sph = require "sph"
local ok, o = pcall(require("sph.params").raw, ...)
if not ok then io.stderr:write("sweep: ", tostring(o), "\n"); os.exit(1) end

local here = (arg and arg[0] or "scripts/sweep.lua"):match("^(.*)/[^/]*$") or "."
local script = o.script or (here .. "/squeeze.lua")
local out = o.out or "out/sweep"
local workers = o.workers ~= nil and tonumber(o.workers) or sph.cores
local gather_only = o.gather == 1 or o.gather == "1"
if not workers or workers < 0 or workers ~= math.floor(workers) then
  io.stderr:write("sweep: workers must be an integer >= 0, got ", tostring(o.workers), "\n")
  os.exit(1)
end
local host = arg and arg[-1] or "sph"
if not host:find("sph", 1, true) then host = "sph" end -- under lua5.4: the host on PATH

-- axes (values with commas) and fixed parameters, in a stable order
local OWN = { script = true, workers = true, out = true, gather = true }
local axes, fixed = {}, {}
local names = {}
for k in pairs(o) do if not OWN[k] then names[#names + 1] = k end end
table.sort(names)
for _, k in ipairs(names) do
  local v = o[k]
  if type(v) == "string" and v:find(",", 1, true) then
    local vals = {}
    for x in v:gmatch("[^,]+") do vals[#vals + 1] = x end
    axes[#axes + 1] = { name = k, values = vals }
  else
    fixed[#fixed + 1] = { k, tostring(v) }
  end
end
-- the squeeze script makes frames and plots by default: a sweep's runs do not, unless asked
if script:match("squeeze%.lua$") then
  for _, k in ipairs{ "frames", "plots" } do
    if o[k] == nil then fixed[#fixed + 1] = { k, "0" } end
  end
end
if #axes == 0 then
  io.stderr:write("sweep: no axis (give a parameter a list of values: Bn=1,2,5)\n")
  os.exit(1)
end

-- the runs: the cartesian product, the first axis varying slowest
local runs = { { values = {} } }
for _, ax in ipairs(axes) do
  local nxt = {}
  for _, r in ipairs(runs) do
    for _, v in ipairs(ax.values) do
      local c = { values = {} }
      for k2, v2 in pairs(r.values or {}) do c.values[k2] = v2 end
      c.values[ax.name] = v
      nxt[#nxt + 1] = c
    end
  end
  runs = nxt
end

local function q(s) return "'" .. tostring(s):gsub("'", "'\\''") .. "'" end

local made, why = sph.mkdir(out)
if not made then io.stderr:write("sweep: ", why, "\n"); os.exit(1) end

local function write_file(path, text)
  local tmp = path .. ".tmp"
  local f, err = io.open(tmp, "w")
  if not f then io.stderr:write("sweep: ", err, "\n"); os.exit(1) end
  local ok, werr = f:write(text)
  local cok, cerr = f:close()
  if not ok or not cok then
    os.remove(tmp)
    io.stderr:write("sweep: cannot write ", path, ": ", tostring(werr or cerr), "\n")
    os.exit(1)
  end
  assert(os.rename(tmp, path))
end

-- jobs.txt: one command a run, its output and status in its folder
local jobs = {}
for i, r in ipairs(runs) do
  local dir = string.format("%s/run_%04d", out, i)
  assert(sph.mkdir(dir))
  local args = {}
  for _, f in ipairs(fixed) do args[#args + 1] = q(f[1] .. "=" .. f[2]) end
  for _, ax in ipairs(axes) do args[#args + 1] = q(ax.name .. "=" .. r.values[ax.name]) end
  args[#args + 1] = q("out=" .. dir)
  jobs[i] = string.format("%s %s %s > %s 2>&1; echo $? > %s", q(host), q(script), table.concat(args, " "),
    q(dir .. "/log.txt"), q(dir .. "/status"))
  r.dir = dir
end
write_file(out .. "/jobs.txt", table.concat(jobs, "\n") .. "\n")

-- slurm.sh: a job array, task k runs line k of jobs.txt
local abs_out = out:sub(1, 1) == "/" and out or (os.getenv("PWD") or ".") .. "/" .. out
write_file(out .. "/slurm.sh", table.concat({
  "#!/bin/sh",
  "#SBATCH --job-name=sph-sweep",
  string.format("#SBATCH --array=1-%d", #runs),
  "#SBATCH --ntasks=1",
  "#SBATCH --cpus-per-task=1",
  string.format("#SBATCH --output=%s/slurm_%%a.out", abs_out),
  "# one run a task: line SLURM_ARRAY_TASK_ID of jobs.txt (its output goes to that run's folder)",
  string.format("cd %s || exit 1", q(os.getenv("PWD") or ".")),
  "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}",
  string.format("sed -n \"${SLURM_ARRAY_TASK_ID}p\" %s | sh", q(abs_out .. "/jobs.txt")),
  "",
}, "\n"))

if workers > 0 and not gather_only then
  local has_parallel = os.execute("command -v parallel >/dev/null 2>&1")
  -- each run on one thread: the workers share the cores
  local cmd
  if has_parallel then
    cmd = string.format("OMP_NUM_THREADS=1 parallel --will-cite -j %d < %s", workers, q(out .. "/jobs.txt"))
  else
    cmd = string.format("tr '\\n' '\\0' < %s | OMP_NUM_THREADS=1 xargs -0 -P %d -n 1 sh -c", q(out .. "/jobs.txt"), workers)
  end
  io.write(string.format("sweep: %d runs on %d workers (%s)\n", #runs, workers, has_parallel and "GNU parallel" or "xargs -P"))
  io.flush()
  os.execute(cmd)
elseif not gather_only then
  io.write(string.format("sweep: %d runs written to %s/jobs.txt and %s/slurm.sh\n", #runs, out, out))
  return
end

-- gather: one row a run
local header = {}
for _, ax in ipairs(axes) do header[#header + 1] = ax.name end
for _, c in ipairs{ "status", "t", "h", "velocity", "force" } do header[#header + 1] = c end
local rows, failed = { table.concat(header, ",") }, 0
for _, r in ipairs(runs) do
  local st = "missing"
  local f = io.open(r.dir .. "/status")
  if f then st = f:read("l") or "missing"; f:close() end
  local last
  f = io.open(r.dir .. "/series.csv")
  if f then
    f:read("l")
    for line in f:lines() do last = line end
    f:close()
  end
  local t, h, v, F = "", "", "", ""
  if last then t, h, v, F = last:match("^([^,]*),([^,]*),([^,]*),([^,]*)") end
  if st ~= "0" and st ~= "2" then failed = failed + 1 end
  r.result = { t = tonumber(t), h = tonumber(h), force = tonumber(F), status = st }
  local row = {}
  for _, ax in ipairs(axes) do row[#row + 1] = r.values[ax.name] end
  for _, c in ipairs{ st, t or "", h or "", v or "", F or "" } do row[#row + 1] = c end
  rows[#rows + 1] = table.concat(row, ",")
end
write_file(out .. "/summary.csv", table.concat(rows, "\n") .. "\n")

-- summary.png: h at the end against the first axis, a line per value of the second
local xs_axis, line_axis = axes[1], axes[2]
local series, by = {}, {}
for _, r in ipairs(runs) do
  local key = line_axis and (line_axis.name .. " = " .. r.values[line_axis.name]) or "h"
  if not by[key] then
    by[key] = { x = {}, y = {}, label = key }
    series[#series + 1] = by[key]
  end
  local x = tonumber(r.values[xs_axis.name])
  if x and r.result.h then
    local s = by[key]
    s.x[#s.x + 1], s.y[#s.y + 1] = x, r.result.h
  end
end
local plotted = {}
for _, s in ipairs(series) do if #s.x > 0 then plotted[#plotted + 1] = s end end
if #plotted > 0 and tonumber(xs_axis.values[1]) then
  local ok, err = sph.plot{ file = out .. "/summary.png", xlabel = xs_axis.name, ylabel = "h at the end",
    series = plotted }
  if not ok then io.stderr:write("sweep: summary.png: ", tostring(err), "\n") end
end
io.write(string.format("sweep: %d runs, %d failed; %s/summary.csv\n", #runs, failed, out))
if failed > 0 then os.exit(1) end
