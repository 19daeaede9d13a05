-- Case parameters given as name=value, checked against a list of the parameters a script
-- takes: an unknown name (a misspelling) or a value of the wrong type is an error that
-- names the parameter, instead of a silent default.
--   local params = require "sph.params"
--   local o = params.parse("squeeze", SPEC, ...)
-- SPEC is a list of { name, kind, default, help }; kind is "number", "integer", "string",
-- "flag" (0 or 1) or a list of the allowed strings. The arguments (...) are either the
-- table build/sph passes (values already numbers where they read as numbers) or, under a
-- stock lua5.4, the strings "name=value" of the command line.
local P = {}

local function kind_name(kind)
  if type(kind) == "table" then return "one of " .. table.concat(kind, ", ") end
  if kind == "flag" then return "0 or 1" end
  if kind == "integer" then return "an integer" end
  return "a " .. kind
end

-- Levenshtein distance, for "did you mean"
local function distance(a, b)
  local prev = {}
  for j = 0, #b do prev[j] = j end
  for i = 1, #a do
    local cur = { [0] = i }
    for j = 1, #b do
      local cost = a:sub(i, i):lower() == b:sub(j, j):lower() and 0 or 1
      cur[j] = math.min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost)
    end
    prev = cur
  end
  return prev[#b]
end

local function convert(name, kind, v)
  if type(kind) == "table" then
    for _, k in ipairs(kind) do if v == k then return v end end
    return nil, string.format("%s must be %s, got %q", name, kind_name(kind), tostring(v))
  end
  if kind == "string" then
    if type(v) == "number" then return tostring(v) end
    if type(v) ~= "string" then return nil, string.format("%s must be a string, got %s", name, type(v)) end
    return v
  end
  local x = tonumber(v)
  if x == nil or x ~= x or x == math.huge or x == -math.huge then
    return nil, string.format("%s must be %s, got %q", name, kind_name(kind), tostring(v))
  end
  if kind == "integer" or kind == "flag" then
    if x ~= math.floor(x) then return nil, string.format("%s must be %s, got %s", name, kind_name(kind), tostring(v)) end
    x = math.tointeger(x) or x
    if kind == "flag" and x ~= 0 and x ~= 1 then
      return nil, string.format("%s must be 0 or 1, got %s", name, tostring(v))
    end
  end
  return x
end

-- The raw name -> value table from the script's arguments (the host's table as it is, a
-- stock lua5.4's "name=value" strings split, values left as strings), unchecked: for a
-- script whose parameters are open-ended, such as a sweep's.
function P.raw(...)
  local first = ...
  if type(first) == "table" then return first end
  local t = {}
  for k = 1, select("#", ...) do
    local a = select(k, ...)
    if type(a) ~= "string" then error(string.format("argument %d: name=value expected, got a %s", k, type(a)), 0) end
    local name, value = a:match("^([^=]+)=(.*)$")
    if not name then error(string.format("argument '%s': name=value expected", a), 0) end
    t[name] = value
  end
  return t
end

-- Checks the arguments; returns the table of every parameter (defaults filled in) or
-- raises an error "<script>: ..." naming the first bad parameter.
function P.parse(script, spec, ...)
  local by = {}
  for _, s in ipairs(spec) do by[s[1]] = s end
  local ok, given = pcall(P.raw, ...)
  if not ok then error(script .. ": " .. given, 0) end
  local names = {}
  for k in pairs(given) do names[#names + 1] = k end
  table.sort(names, function(a, b) return tostring(a) < tostring(b) end)
  local o = {}
  for _, k in ipairs(names) do
    local s = by[k]
    if not s then
      local best, bd = nil, math.huge
      for _, c in ipairs(spec) do
        local d = distance(tostring(k), c[1])
        if d < bd then best, bd = c[1], d end
      end
      local hint = (best and bd <= math.max(2, #tostring(k) // 3)) and string.format(" (did you mean %s?)", best) or ""
      local valid = {}
      for _, c in ipairs(spec) do valid[#valid + 1] = c[1] end
      error(string.format("%s: unknown parameter '%s'%s; the parameters are: %s", script, tostring(k), hint,
        table.concat(valid, ", ")), 0)
    end
    local v, why = convert(k, s[2], given[k])
    if v == nil then error(script .. ": " .. why, 0) end
    o[k] = v
  end
  for _, s in ipairs(spec) do
    if o[s[1]] == nil then o[s[1]] = s[3] end
  end
  return o
end

-- As parse, for a script's own arguments: a bad parameter is reported on stderr
-- ("script: ...") and ends the script with status 1.
function P.args(script, spec, ...)
  local ok, o = pcall(P.parse, script, spec, ...)
  if not ok then
    io.stderr:write(tostring(o), "\n")
    os.exit(1)
  end
  return o
end

-- A script's refusal of its parameters: "script: msg" on stderr, status 1.
function P.refuse(script, msg)
  io.stderr:write(script, ": ", msg, "\n")
  os.exit(1)
end

-- The numbers of a comma-separated list s, each in lo..hi (integers unless real); a bad or
-- empty list is refused (P.refuse) naming the parameter.
function P.list(script, name, s, lo, hi, real)
  local t = {}
  for v in tostring(s):gmatch("[^,]+") do
    local x = tonumber(v)
    if not real then x = math.tointeger(x) end
    if not x or x < lo or x > hi then
      P.refuse(script, ("%s must be %s %g..%g separated by commas, got %q"):format(name, real and "numbers" or "integers", lo,
        hi, tostring(s)))
    end
    t[#t + 1] = x
  end
  if #t == 0 then P.refuse(script, ("%s is empty"):format(name)) end
  return t
end

-- The parameters as lines "name  default  help", for a script's usage message.
function P.usage(spec)
  local lines = {}
  for _, s in ipairs(spec) do
    local d = s[3] == nil and "-" or tostring(s[3])
    lines[#lines + 1] = string.format("  %-20s %-10s %s", s[1], d, s[4] or "")
  end
  return table.concat(lines, "\n")
end

return P
