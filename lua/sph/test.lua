-- Test helpers for sph's Lua tests: every check prints "ok - name" or
-- "not ok - name: why", the lines tests/run.sh counts.
local T = {}
local failed = 0

local function report(ok, name, why)
  if ok then
    print("ok - " .. name)
  else
    failed = failed + 1
    print("not ok - " .. name .. ": " .. tostring(why))
  end
  io.stdout:flush()
  return ok
end

function T.check(cond, name, why) return report(cond and true or false, name, why or "condition false") end

-- |a - b| <= tol
function T.close(a, b, tol, name)
  local ok = type(a) == "number" and type(b) == "number" and math.abs(a - b) <= tol
  return report(ok, name, string.format("%.10g vs %.10g (|diff| %.3g > %.3g)", a, b, math.abs(a - b), tol))
end

-- a <= limit
function T.below(a, limit, name)
  return report(type(a) == "number" and a <= limit, name, string.format("%.6g > %.6g", a, limit))
end

-- f(...) raises an error whose message contains msg (plain text)
function T.checkerror(msg, name, f, ...)
  local ok, err = pcall(f, ...)
  if ok then return report(false, name, "no error raised") end
  return report(string.find(tostring(err), msg, 1, true) ~= nil, name,
    string.format("error %q does not mention %q", tostring(err), msg))
end

-- A test body that raises counts as one failure instead of ending the file unseen.
function T.case(name, f)
  local ok, err = xpcall(f, debug.traceback)
  if not ok then report(false, name, err) end
end

-- Relative L2 norm of a - b over b.
function T.rel_l2(a, b)
  local num, den = 0, 0
  for i = 1, #a do
    num = num + (a[i] - b[i]) ^ 2
    den = den + b[i] ^ 2
  end
  return math.sqrt(num / den)
end

-- Least-squares slope of log y against log x.
function T.loglog_slope(xs, ys)
  local n, sx, sy, sxx, sxy = #xs, 0, 0, 0, 0
  for i = 1, n do
    local x, y = math.log(xs[i]), math.log(ys[i])
    sx, sy, sxx, sxy = sx + x, sy + y, sxx + x * x, sxy + x * y
  end
  return (n * sxy - sx * sy) / (n * sxx - sx * sx)
end

-- Runs a shell command: its stdout and stderr together, and its exit status.
function T.sh(cmd)
  local p = assert(io.popen(cmd .. " 2>&1; echo \"exit=$?\""))
  local text = p:read("a")
  p:close()
  return text, tonumber(text:match("exit=(%d+)%s*$"))
end

-- Runs scripts/<name> with the sph host running this test (arg[-1]), from the checkout
-- this test file is in: T.sh's text and status.
function T.script(name, args)
  local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
  return T.sh(("%s %s/scripts/%s %s"):format(arg[-1], top, name, args))
end

function T.failed() return failed end

-- Exit status for the end of a test file.
function T.done() os.exit(failed == 0 and 0 or 1) end

return T
