-- scripts/validate.lua (make validate) refuses bad parameters with a message naming them, and
-- its two-process run (jobs = 2, the default) puts validation.md together from both processes
-- in section order, with every section's plot and no part file left. The run here is the
-- coarsest there is (sections 2 and 4 at one resolution, about 10 s); the full one takes
-- about 17 minutes (make validate).
local T = require "sph.test"

local function run(args) return T.script("validate.lua", args) end

T.case("validate.lua parameters", function()
  local text, code = run("check=1")
  T.check(code == 0 and text:find("sections 1,2,3,4, 2 at a time, 1 thread a world", 1, true),
    "check=1: the four sections, two at a time", text)
  text, code = run("check=1 only=3,1 jobs=1 threads=2")
  T.check(code == 0 and text:find("sections 1,3, 1 at a time, 2 threads a world", 1, true), "only, jobs and threads reach the plan",
    text)
  for _, c in ipairs{
    { "check=1 jobs=0", "jobs must be 1..4" },
    { "check=1 jobs=1.5", "jobs must be an integer" },
    { "check=1 only=5", "only must be integers 1..4" },
    { "check=1 n=20,x", "n must be integers 4..320" },
    { "check=1 ar=0.1", "ar must be numbers 0.5..50" },
    { "check=1 threads=0", "threads must be 1..256" },
    { "check=1 job=2", "unknown parameter 'job' (did you mean jobs?)" },
  } do
    text, code = run(c[1])
    T.check(code == 1 and text:find(c[2], 1, true) ~= nil, ("validate.lua %s exits 1: %s"):format(c[1], c[2]), text)
  end
end)

local dir = os.tmpname()
os.remove(dir)

T.case("validate.lua in two processes", function()
  local text, code = run(("out='%s' only=4,2 rows=16 ar=2 flow_n=20 cavity_n=20"):format(dir))
  T.check(code == 0, "the run exits 0", text)
  T.check(text:find("section 2 in a process of its own", 1, true) and text:find("section 4 in a process of its own", 1, true),
    "each section in a process of its own", text)
  local f = io.open(dir .. "/validation.md")
  T.check(f ~= nil, "validation.md written")
  if not f then return end
  local md = f:read("a")
  f:close()
  local a, b = md:find("## Thin films (section 2)", 1, true), md:find("## Exact and 1D flows (section 4)", 1, true)
  local c = md:find("## Cost", 1, true)
  T.check(a and b and c and a < b and b < c, "validation.md: section 2, then 4, then the cost", md:sub(1, 400))
  T.check(md:find("2 sections at a time", 1, true) ~= nil, "the cost says two sections ran at a time")
  T.check(md:find("| a/h = 2 | 16 (1/16) |", 1, true) ~= nil, "section 2's row, from its process")
  T.check(md:find("| t | u(0.5) reference | 1/20 (error) | tau_w reference |", 1, true) ~= nil,
    "section 4's Couette table, from its process")
  for _, p in ipairs{ "validation_film.png", "validation_flows.png" } do
    local g = io.open(dir .. "/" .. p, "rb")
    T.check(g ~= nil and g:read(8) == "\137PNG\r\n\26\n", p .. " written by its section's process")
    if g then g:close() end
  end
  local left = io.popen("ls '" .. dir .. "' | grep -c part"):read("a")
  T.check(tonumber(left) == 0, "no part file left", left)
end)

os.execute("rm -rf '" .. dir .. "'")
T.done()
