-- scripts/sweep.lua run as a user runs it: a 4-point grid (Bn x F) of short loaded
-- squeezes on 2 workers; the summary CSV has a row per run with the axes and the last
-- series row, the plot exists, and the Slurm script is an array of 4 tasks, one line of
-- jobs.txt each. A run that fails is counted and makes the sweep exit 1.
local T = require "sph.test"
local dir = os.tmpname()
os.remove(dir)

local function run(args) return T.script("sweep.lua", args) end

local function read(file)
  local f = io.open(file)
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

T.case("a 4-point sweep on 2 workers", function()
  local out = dir .. "/sweep"
  local text, code = run("Bn=1,2 F=-5,-10 mode=load Re=1 dx=0.05 t_end=0.01 workers=2 out=" .. out)
  T.check(code == 0, "sweep.lua exits 0", text)
  T.check(text:find("4 runs on 2 workers", 1, true) ~= nil, "it says 4 runs on 2 workers", text)
  local csv = read(out .. "/summary.csv") or ""
  local rows = {}
  for line in csv:gmatch("[^\n]+") do rows[#rows + 1] = line end
  T.check(rows[1] == "Bn,F,status,t,h,velocity,force", "summary.csv's header", rows[1])
  T.check(#rows == 5, "summary.csv has a row per run", csv)
  local seen = {}
  for k = 2, #rows do
    local bn, f, st, t, h = rows[k]:match("^([^,]*),([^,]*),([^,]*),([^,]*),([^,]*)")
    seen[bn .. "/" .. f] = true
    T.check(st == "0" and tonumber(t) and math.abs(tonumber(t) - 0.01) < 1e-9 and tonumber(h) and tonumber(h) < 1,
            "run " .. (k - 1) .. " ended at t_end with the gap closing", rows[k])
  end
  T.check(seen["1/-5"] and seen["1/-10"] and seen["2/-5"] and seen["2/-10"], "every grid point ran once", csv)
  T.check(read(out .. "/summary.png") ~= nil, "summary.png written")
  local slurm = read(out .. "/slurm.sh") or ""
  T.check(slurm:find("#SBATCH --array=1-4", 1, true) ~= nil, "slurm.sh is an array of 4 tasks", slurm)
  T.check(slurm:find("SLURM_ARRAY_TASK_ID", 1, true) ~= nil and slurm:find("jobs.txt", 1, true) ~= nil,
          "each task runs its line of jobs.txt", slurm)
  local jobs = read(out .. "/jobs.txt") or ""
  local n = 0
  for line in jobs:gmatch("[^\n]+") do
    n = n + 1
    T.check(line:find(string.format("out=%s/run_%04d", out, n), 1, true) ~= nil, "job " .. n .. " writes to its own folder", line)
  end
  T.check(n == 4, "jobs.txt has one line per run", jobs)
end)

T.case("a failing run is counted", function()
  local out = dir .. "/bad"
  local text, code = run("Bn=1,abc mode=load Re=1 dx=0.05 t_end=0.005 workers=2 out=" .. out)
  T.check(code == 1 and text:find("2 runs, 1 failed", 1, true) ~= nil, "one bad run: exit 1, counted", text)
  local log = read(out .. "/run_0002/log.txt") or ""
  T.check(log:find("Bn must be a number", 1, true) ~= nil, "its log says why", log)
end)

T.case("workers=0 writes the job files only", function()
  local out = dir .. "/jobsonly"
  local text, code = run("Bn=1,2,3 mode=load dx=0.05 t_end=0.005 workers=0 out=" .. out)
  T.check(code == 0 and text:find("3 runs written", 1, true) ~= nil, "3 runs written, none run", text)
  T.check(read(out .. "/run_0001/status") == nil, "no run ran")
end)

os.execute("rm -rf '" .. dir .. "'")
T.done()
