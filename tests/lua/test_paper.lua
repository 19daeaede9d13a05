-- scripts/paper.lua (make paper) parses its parameters and refuses bad ones, without running
-- a case: check=1 prints the plan and exits 0; a bad value or an unknown name exits 1 with a
-- message naming it. (The runs themselves take half a minute and more: make paper quick=1.)
local T = require "sph.test"

local function run(args) return T.script("paper.lua", args) end

T.case("paper.lua parameters", function()
  local text, code = run("check=1")
  T.check(code == 0 and text:find("full pass, dx = 1/20, 1/40", 1, true), "check=1: the full pass at 1/20 and 1/40", text)
  text, code = run("check=1 quick=1")
  T.check(code == 0 and text:find("quick pass, dx = 1/20,", 1, true), "check=1 quick=1: the quick pass at 1/20", text)
  text, code = run("check=1 n=40,80 only=6,7 threads=2")
  T.check(code == 0 and text:find("dx = 1/40, 1/80, figures 6,7, 2 threads", 1, true), "n, only and threads reach the plan", text)
  for _, c in ipairs{
    { "check=1 quick=2", "quick must be 0 or 1" },
    { "check=1 n=20,abc", "n must be integers 10..160" },
    { "check=1 n=5", "n must be integers 10..160" },
    { "check=1 only=2,3", "only must be integers 3..7" },
    { "check=1 threads=0", "threads must be 1..256" },
    { "check=1 quik=1", "unknown parameter 'quik' (did you mean quick?)" },
  } do
    text, code = run(c[1])
    T.check(code == 1 and text:find(c[2], 1, true) ~= nil, ("paper.lua %s exits 1: %s"):format(c[1], c[2]), text)
  end
end)
