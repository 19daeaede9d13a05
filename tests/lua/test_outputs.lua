-- Outputs a user takes elsewhere: VTK XML particles (w:write_vtu) and their time series
-- (sph.pvd_write) read back by a reader written here from the format's rules (Python's
-- XML parser, base64 and struct: not our writer's code), one set of field names in every
-- file, the yield legend, the label's time, failed writes, and the headline script's
-- default outputs.
local sph = require "sph"
local T = require "sph.test"

local base = os.tmpname()
os.remove(base)
local made = {}
local function tmp(name)
  local f = base .. "_" .. name
  made[#made + 1] = f
  return f
end

-- The reader: "vtu FILE" prints "points N CELLS VERSION HEADER", "time T" and one line
-- "array NAME PARENT COMPONENTS COUNT v1 v2 ..." per data array (values as Python's repr,
-- exact); "pvd FILE" prints "dataset T FILE" per entry; "box FILE x0 y0 x1 y1 r g b tol"
-- counts the pixels of a colour in a box (Pillow). A broken rule prints "error ..." and
-- exits 1. (No single quote in it: it goes through sh -c '...'.)
local PY = [==[
import sys, base64, struct
import xml.etree.ElementTree as ET
mode, f = sys.argv[1], sys.argv[2]
def fail(msg):
    print("error " + msg)
    sys.exit(1)
if mode == "box":
    from PIL import Image
    a = [float(v) for v in sys.argv[3:]]
    im = Image.open(f).convert("RGB")
    n = 0
    for y in range(int(a[1]), int(a[3])):
        for x in range(int(a[0]), int(a[2])):
            p = im.getpixel((x, y))
            if all(abs(p[k] - a[4 + k]) <= a[7] for k in range(3)):
                n += 1
    print(im.size[0], im.size[1], n)
    sys.exit(0)
raw = open(f, "rb").read()
if mode == "pvd":
    root = ET.fromstring(raw)
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        fail("not a VTKFile of type Collection")
    sets = root.findall("Collection/DataSet")
    if len(sets) != len(list(root.iter("DataSet"))):
        fail("a DataSet outside Collection")
    for d in sets:
        print("dataset", repr(float(d.get("timestep"))), d.get("file"))
    sys.exit(0)
# appended raw data is the one part that is not XML text: cut it out, parse the rest
app = None
i = raw.find(b"<AppendedData")
xml = raw
if i >= 0:
    j = raw.index(b">", i) + 1
    if b"encoding=\"raw\"" not in raw[i:j]:
        fail("appended data not raw")
    u = raw.index(b"_", j)
    if raw[j:u].strip():
        fail("text before the underscore of the appended data")
    end = raw.rindex(b"</AppendedData>")
    app = raw[u + 1:end]
    xml = raw[:j] + raw[end:]
root = ET.fromstring(xml)
if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
    fail("not a VTKFile of type UnstructuredGrid")
if root.get("byte_order") != "LittleEndian":
    fail("byte_order " + str(root.get("byte_order")))
ht = root.get("header_type", "UInt32")
if ht == "UInt64" and root.get("version") != "1.0":
    fail("header_type UInt64 needs version 1.0")
hfmt = {"UInt32": "<I", "UInt64": "<Q"}[ht]
hsz = struct.calcsize(hfmt)
codes = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B", "Int8": "b",
         "UInt32": "I", "UInt64": "Q", "Int16": "h", "UInt16": "H"}
pieces = root.findall("UnstructuredGrid/Piece")
if len(pieces) != 1:
    fail("%d pieces" % len(pieces))
piece = pieces[0]
npts, ncells = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
print("points", npts, ncells, root.get("version"), ht)
tv = root.find("UnstructuredGrid/FieldData/DataArray[@Name=\"TimeValue\"]")
if tv is not None:
    print("time", repr(float(tv.text)))
spans = []
for parent in ("Points", "Cells", "PointData"):
    for da in piece.findall(parent + "/DataArray"):
        nc = int(da.get("NumberOfComponents", "1"))
        code = codes[da.get("type")]
        word = struct.calcsize("<" + code)
        form = da.get("format")
        if form == "binary":
            blob = base64.b64decode("".join(da.text.split()), validate=True)
        elif form == "appended":
            if app is None:
                fail("format appended without AppendedData")
            off = int(da.get("offset"))
            blob = app[off:]
        else:
            fail("format " + str(form))
        nbytes = struct.unpack(hfmt, blob[:hsz])[0]
        data = blob[hsz:hsz + nbytes]
        if len(data) != nbytes:
            fail(da.get("Name") + ": header says %d bytes, %d there" % (nbytes, len(data)))
        if form == "binary" and len(blob) != hsz + nbytes:
            fail(da.get("Name") + ": decoded %d bytes, header and data %d" % (len(blob), hsz + nbytes))
        if form == "appended":
            spans.append((off, off + hsz + nbytes))
        if nbytes % word:
            fail(da.get("Name") + ": not a whole number of values")
        vals = struct.unpack("<%d%s" % (nbytes // word, code), data)
        want = {"Points": npts * nc, "Cells": ncells}.get(parent, npts * nc)
        if len(vals) != want:
            fail(da.get("Name") + ": %d values, %d expected" % (len(vals), want))
        print("array", da.get("Name"), parent, nc, len(vals), " ".join(repr(v) for v in vals))
if app is not None:  # the arrays tile the appended block, and nothing follows but blanks
    spans.sort()
    at = 0
    for a, b in spans:
        if a != at:
            fail("appended arrays do not follow each other at %d" % a)
        at = b
    if app[at:].strip():
        fail("bytes after the last appended array")
]==]

local function reader(mode, file, ...)
  local args = { ... }
  for i = 1, #args do args[i] = string.format("%.10g", args[i]) end
  local p = io.popen("/usr/bin/python3 -c '" .. PY .. "' " .. mode .. " '" .. file .. "' " .. table.concat(args, " ") .. " 2>&1")
  local text = p:read("a")
  p:close()
  return text
end

-- the reader's view of a .vtu: { points =, cells =, version =, header =, time =, arrays = {name = {parent =, nc =, v = {...}}} }
local function read_vtu(file)
  local text = reader("vtu", file)
  local r = { arrays = {}, text = text }
  for line in text:gmatch("[^\n]+") do
    local word = line:match("^(%S+)")
    if word == "error" or word == "Traceback" then r.error = text end
    if word == "points" then
      local n, c, v, h = line:match("^points (%d+) (%d+) (%S+) (%S+)")
      r.points, r.cells, r.version, r.header = tonumber(n), tonumber(c), v, h
    elseif word == "time" then
      r.time = tonumber(line:match("^time (%S+)"))
    elseif word == "array" then
      local name, parent, nc, count, rest = line:match("^array (%S+) (%S+) (%d+) (%d+) ?(.*)$")
      local v = {}
      for x in rest:gmatch("%S+") do v[#v + 1] = tonumber(x) end
      r.arrays[name] = { parent = parent, nc = tonumber(nc), count = tonumber(count), v = v }
    end
  end
  if not r.points and not r.error then r.error = text end
  return r
end

-- a Bingham half sample a few steps on, mirror plane at x = 0, plates
local function squeeze_world(opts)
  opts = opts or {}
  local w = sph.world{ dx = 0.1, threads = 1, shifting = 20, symmetry = opts.symmetry ~= false and { x = 0 } or nil }
  w:fill{ rect = { opts.symmetry == false and -0.5 or 0, 0, 0.5, 1 }, material = sph.bingham{ mu = 1, tau0 = 0.5, m = 100 } }
  w:plate{ rect = { -1, -0.3, 1, 0 } }
  local top = w:plate{ rect = { -1, 1, 1, 1.3 }, axis = "y" }
  top:velocity(-1)
  for _ = 1, 4 do w:step() end
  return w
end

local FIELDS = { "id", "kind", "u", "v", "p", "rho", "eta", "gammadot", "stress", "yielded", "surface", "material" }

-- the file's fluid points (kind 0) of the first copy against w:field, value for value
local function check_fields(w, r, what)
  local kind = r.arrays.kind and r.arrays.kind.v or {}
  local pts = r.arrays.Points and r.arrays.Points.v or {}
  local nall = w:stats().particles
  local fluid = {}
  for i = 1, nall do
    if kind[i] == 0 then fluid[#fluid + 1] = i end
  end
  T.check(#fluid == w:stats().fluid, what .. ": the fluid particles are there, kind 0",
    #fluid .. " vs " .. w:stats().fluid)
  local bad = {}
  local function same(name, got)
    local want = w:field(name)
    for k = 1, #want do
      if got(fluid[k]) ~= want[k] then
        bad[#bad + 1] = string.format("%s[%d] = %s, w:field %s", name, k, tostring(got(fluid[k])), tostring(want[k]))
        return
      end
    end
  end
  same("x", function(i) return pts[3 * i - 2] end)
  same("y", function(i) return pts[3 * i - 1] end)
  for _, name in ipairs(FIELDS) do
    if name ~= "kind" then
      local a = r.arrays[name]
      if not a then bad[#bad + 1] = "no array " .. name
      else same(name, function(i) return a.v[i] end) end
    end
  end
  local vel = r.arrays.velocity and r.arrays.velocity.v or {}
  same("u", function(i) return vel[3 * i - 2] end)
  same("v", function(i) return vel[3 * i - 1] end)
  T.check(#bad == 0, what .. ": points and every array match w:field, value for value (x y id u v p rho eta gammadot stress yielded surface material, velocity)",
    table.concat(bad, "; "))
end

T.case("w:write_vtu: base64, UInt64 header, the mirrored half", function()
  local w = squeeze_world()
  local f = tmp("a.vtu")
  local ok, msg = w:write_vtu(f)
  T.check(ok == true, "write_vtu returns true", msg)
  local r = read_vtu(f)
  T.check(not r.error, "the reader parses it: XML well-formed, every array decodes", r.error)
  if r.error then return end
  local nall = w:stats().particles
  T.check(r.version == "1.0" and r.header == "UInt64", "version 1.0, header_type UInt64 by default", r.version .. " " .. r.header)
  T.check(r.points == 2 * nall and r.cells == 2 * nall, "with a symmetry plane the mirrored half is in by default: twice the particles",
    string.format("%d points, %d cells, %d particles", r.points, r.cells, nall))
  T.check(r.time == w.t, "TimeValue is w.t", tostring(r.time))
  local conn, offs, types = r.arrays.connectivity.v, r.arrays.offsets.v, r.arrays.types.v
  local cells_ok = #conn == r.points and #offs == r.points and #types == r.points
  for i = 1, r.points do
    if conn[i] ~= i - 1 or offs[i] ~= i or types[i] ~= 1 then cells_ok = false end
  end
  T.check(cells_ok, "one vertex cell (type 1) a point: connectivity 0..N-1, offsets 1..N")
  check_fields(w, r, "base64")
  -- the mirror half: point i + n is point i reflected in x = 0, u negated, the rest kept
  local pts, id = r.arrays.Points.v, r.arrays.id.v
  local u, v, p, vel = r.arrays.u.v, r.arrays.v.v, r.arrays.p.v, r.arrays.velocity.v
  local bad, seen, dup, maxid = nil, {}, false, 0
  for i = 1, nall do maxid = math.max(maxid, id[i]) end
  for i = 1, nall do
    local j = i + nall
    if pts[3 * j - 2] ~= -pts[3 * i - 2] or pts[3 * j - 1] ~= pts[3 * i - 1] or u[j] ~= -u[i] or v[j] ~= v[i]
       or p[j] ~= p[i] or vel[3 * j - 2] ~= -vel[3 * i - 2] or vel[3 * j - 1] ~= vel[3 * i - 1] or id[j] <= maxid then
      bad = bad or string.format("point %d: (%g, %g) u %g v %g id %d against (%g, %g) u %g v %g id %d", j, pts[3 * j - 2],
        pts[3 * j - 1], u[j], v[j], id[j], pts[3 * i - 2], pts[3 * i - 1], u[i], v[i], id[i])
    end
  end
  for i = 1, 2 * nall do
    if seen[id[i]] then dup = true end
    seen[id[i]] = true
  end
  T.check(not bad, "the mirrored half: x reflected, u negated, y, v and p kept, ids after the originals'", bad)
  T.check(not dup, "every id in the file is distinct")
  T.check(w:write_vtu(f, { mirror = false }) == true, "mirror = false writes")
  r = read_vtu(f)
  T.check(r.points == nall, "mirror = false: the simulated half only", tostring(r.points))
end)

T.case("w:write_vtu: raw appended data, UInt32 header", function()
  local w = squeeze_world()
  local f = tmp("b.vtu")
  T.check(w:write_vtu(f, { encoding = "raw", header_type = "UInt32" }) == true, "write_vtu with encoding raw, header_type UInt32")
  local r = read_vtu(f)
  T.check(not r.error, "the reader parses it: the XML around the data well-formed, the arrays tile the appended block", r.error)
  if r.error then return end
  T.check(r.header == "UInt32" and r.points == 2 * w:stats().particles, "UInt32 headers, both halves", r.header .. " " .. r.points)
  check_fields(w, r, "raw appended")
  T.check(w:write_vtu(f, { encoding = "raw", mirror = false }) == true and read_vtu(f).points == w:stats().particles,
    "raw, UInt64, no mirror")
end)

T.case("w:write_vtu: no symmetry plane, nothing mirrored", function()
  local w = squeeze_world{ symmetry = false }
  local f = tmp("c.vtu")
  T.check(w:write_vtu(f) == true, "write_vtu without a symmetry plane")
  local r = read_vtu(f)
  T.check(not r.error and r.points == w:stats().particles, "the particles once", r.error or tostring(r.points))
  if not r.error then check_fields(w, r, "no symmetry") end
  -- before any step: the fields are the initial ones, still readable
  local w0 = sph.world{ dx = 0.25 }
  w0:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  T.check(w0:write_vtu(f) == true and read_vtu(f).points == 16, "a world before its first step: 16 particles")
  local e = sph.world{ dx = 0.25 }
  T.check(e:write_vtu(f) == true, "an empty world writes")
  r = read_vtu(f)
  T.check(not r.error and r.points == 0, "an empty world: 0 points, arrays of 0 values", r.error or tostring(r.points))
end)

T.case("w:write_vtu: argument errors", function()
  local w = squeeze_world()
  local f = tmp("err.vtu")
  T.checkerror("unknown option 'mirrored'; options are encoding, header_type, mirror", "a misspelt option",
    w.write_vtu, w, f, { mirrored = false })
  T.checkerror("encoding: \"base64\" or \"raw\" expected, got ascii", "encoding ascii", w.write_vtu, w, f, { encoding = "ascii" })
  T.checkerror("header_type: \"UInt64\" or \"UInt32\" expected", "header_type Int32", w.write_vtu, w, f, { header_type = "Int32" })
  T.checkerror("mirror: boolean expected", "mirror = 1", w.write_vtu, w, f, { mirror = 1 })
  T.checkerror("string expected", "no file", w.write_vtu, w)
end)

T.case("sph.pvd_write: the time series", function()
  local f = tmp("s.pvd")
  local list = { { t = 0, file = "p_0001.vtu" }, { t = 0.025, file = "vtu/p_0002.vtu" }, { t = 1 / 3, file = "a&b <\"c\">.vtu" } }
  T.check(sph.pvd_write(f, list) == true, "pvd_write returns true")
  local text = reader("pvd", f)
  local got = {}
  for t, file in text:gmatch("dataset (%S+) ([^\n]+)") do got[#got + 1] = { t = tonumber(t), file = file } end
  local ok = #got == #list
  for k = 1, #list do ok = ok and got[k] and got[k].t == list[k].t and got[k].file == list[k].file end
  T.check(ok, "the .pvd lists the files with their times, in order, exactly (names with & < \" > too)", text)
  T.check(sph.pvd_write(f, {}) == true and not reader("pvd", f):find("error", 1, true), "an empty series is a valid collection")
  T.checkerror("entry 2: t: finite number expected", "a NaN time", sph.pvd_write, f, { { t = 0, file = "a" }, { t = 0 / 0, file = "b" } })
  T.checkerror("entry 1: file: string expected", "no file", sph.pvd_write, f, { { t = 0 } })
  T.checkerror("unknown option 'time'", "a misspelt key", sph.pvd_write, f, { { time = 0, file = "a" } })
  local r, m = sph.pvd_write(f, { { t = 0, file = "a\1b" } })
  T.check(r == nil and m:find("control character", 1, true), "a control character in a name: nil and a message", tostring(m))
end)

T.case("one set of field names in every output", function()
  local w = squeeze_world()
  local csv, vtk = tmp("n.csv"), tmp("n.vtk")
  assert(w:write_csv(csv))
  assert(w:write_vtk(vtk))
  local h = io.open(csv):read("l")
  T.check(h == "id,kind,x,y,u,v,p,rho,eta,gammadot,stress,yielded,surface,material", "the CSV header", h)
  local names = {}
  for name in io.open(vtk):read("a"):gmatch("\nSCALARS (%S+)") do names[#names + 1] = name end
  T.check(table.concat(names, " ") == table.concat(FIELDS, " "), "the legacy VTK's scalars are the w:field names",
    table.concat(names, " "))
  local f = tmp("n.vtu")
  assert(w:write_vtu(f))
  local r = read_vtu(f)
  local missing = {}
  for _, n in ipairs(FIELDS) do
    if not r.arrays[n] then missing[#missing + 1] = n end
    local ok = pcall(w.field, w, n)
    if n ~= "kind" and not ok then missing[#missing + 1] = n .. " (not a w:field name)" end
  end
  T.check(#missing == 0, "the .vtu's point data are the w:field names (and kind), velocity the one vector",
    table.concat(missing, " "))
end)

-- A failed write (here for real: a child sph under a 1 KB file size limit) leaves the old
-- file byte for byte and no temporary file; an unwritable folder gives nil and a message.
T.case("failed writes of .vtu and .pvd", function()
  local w = squeeze_world()
  for _, call in ipairs{ { "write_vtu", function(f) return w:write_vtu(f) end },
                         { "pvd_write", function(f) return sph.pvd_write(f, { { t = 0, file = "x.vtu" } }) end } } do
    local bad = "/nonexistent-sph-dir/x.out"
    local r, m = call[2](bad)
    T.check(r == nil and type(m) == "string" and m:find(bad, 1, true) and m:find("No such file", 1, true),
      call[1] .. " into a missing folder: nil and a message naming the file and why", tostring(m))
  end
  local ro = tmp("readonly")
  os.execute("mkdir -p '" .. ro .. "' && chmod 555 '" .. ro .. "'")
  local r, m = w:write_vtu(ro .. "/a.vtu")
  -- (root writes anywhere: then only the clean-up is checked)
  T.check(r == true or (r == nil and m:find(ro, 1, true)), "write_vtu into a read-only folder: nil and a message (or, as root, written)", tostring(m))
  os.execute("chmod 755 '" .. ro .. "'; rm -rf '" .. ro .. "'")
  local vtu, pvd = tmp("old.vtu"), tmp("old.pvd")
  local old = "old bytes\n"
  for _, f in ipairs{ vtu, pvd } do
    local g = assert(io.open(f, "wb")); g:write(old); g:close()
  end
  local script = tmp("old.lua")
  local g = assert(io.open(script, "w"))
  g:write(string.format([[
local sph = require "sph"
local w = sph.world{ dx = 0.05, threads = 1, symmetry = { x = 0 } }
w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
print("vtu", w:write_vtu(%q))
local list = {}
for k = 1, 200 do list[k] = { t = k, file = string.rep("f", 40) .. k .. ".vtu" } end
print("pvd", sph.pvd_write(%q, list))
]], vtu, pvd))
  g:close()
  local p = io.popen("sh -c \"trap '' XFSZ; ulimit -f 2; exec '" .. arg[-1] .. "' '" .. script .. "'\" 2>&1")
  local out = p:read("a")
  p:close()
  for what, f in pairs{ vtu = vtu, pvd = pvd } do
    local line = out:match(what .. "\t([^\n]*)") or "(no line)"
    T.check(line:find("nil", 1, true) and line:find(f, 1, true) and line:find("File too large", 1, true),
      what .. " under a 1 KB file limit fails, naming the file and why", line)
    local h = io.open(f, "rb")
    local now = h and h:read("a")
    if h then h:close() end
    T.check(now == old, what .. ": the old file keeps its bytes after the failed write", now and #now .. " bytes")
  end
  local left = io.popen("ls '" .. base .. "'_old.*.tmp.* 2>/dev/null | wc -l"):read("a")
  T.check(tonumber(left) == 0, "no temporary file left behind", left)
end)

-- the renderer's yield colours (render.c) as 8-bit sRGB
local UNYIELDED = { 25.5, 51, 127.5 }
local YIELDED = { 204, 224.4, 244.8 }

T.case("the yield legend", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 2, 1 }, material = sph.bingham{ mu = 1, tau0 = 1, m = 100 } }
  local f = tmp("legend.png")
  local W, H = 400, 200
  -- the band above the picture (the label's line): 1.6 font sizes, the font min(W, H) / 28
  -- clamped to 9..18 px; the legend sits at its right
  local band = math.ceil(1.6 * math.max(9, math.min(18, math.min(W, H) / 28)))
  local function count(file, c) return tonumber(reader("box", file, W / 2, 0, W, band, c[1], c[2], c[3], 3):match("%d+ %d+ (%d+)")) end
  assert(w:render{ file = f, width = W, height = H, colorbar = true })
  local ny, nu = count(f, YIELDED), count(f, UNYIELDED)
  T.check(ny >= 25 and nu >= 25, "colorbar = true on a yield frame: swatches of both colours in the band at the top right",
    string.format("%d yielded, %d unyielded pixels", ny, nu))
  assert(w:render{ file = f, width = W, height = H, colorbar = true, label = "Re=1" })
  ny, nu = count(f, YIELDED), count(f, UNYIELDED)
  T.check(ny >= 25 and nu >= 25, "with a label the legend shares its line", string.format("%d yielded, %d unyielded pixels", ny, nu))
  assert(w:render{ file = f, width = W, height = H, label = "Re=1" })
  ny, nu = count(f, YIELDED), count(f, UNYIELDED)
  T.check(ny == 0 and nu == 0, "no legend by default on a yield frame", string.format("%d yielded, %d unyielded pixels", ny, nu))
end)

T.case("label shows the time once", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  w:step()
  local a, b = tmp("la.png"), tmp("lb.png")
  local function bytes(file)
    local g = io.open(file, "rb")
    local d = g:read("a")
    g:close()
    return d
  end
  local t = string.format("%.4g", w.t)
  assert(w:render{ file = a, width = 300, height = 150, label = true })
  assert(w:render{ file = b, width = 300, height = 150, label = "t = " .. t })
  T.check(bytes(a) == bytes(b), "label = true draws \"t = <time>\"")
  assert(w:render{ file = a, width = 300, height = 150, label = "Re=1 Bn=5" })
  assert(w:render{ file = b, width = 300, height = 150, label = "t = " .. t .. "   Re=1 Bn=5" })
  T.check(bytes(a) == bytes(b), "label = string draws \"t = <time>   string\"")
  assert(w:render{ file = a, width = 300, height = 150, label = string.format("t = %.3f  mine", w.t) })
  assert(w:render{ file = b, width = 300, height = 150, label = string.format("t = %s   t = %.3f  mine", t, w.t) })
  T.check(bytes(a) ~= bytes(b), "a label that shows its own time is drawn as given, without a second time")
end)

-- The headline script's defaults: frames, the animation, h.png and force.png besides the
-- series; frames=0 plots=0 the series alone; vtu=N the ParaView files and their series.
T.case("the headline script's default outputs", function()
  local dir = tmp("squeeze")
  local function run(args, out)
    return T.script("squeeze.lua", ("mode=velocity Re=10 Bn=0.5 M=100 dx=0.05 t_end=0.4 every=0.01 threads=1 out=%s %s"):format(out, args))
  end
  local function exists(f)
    local g = io.open(f, "rb")
    if g then g:close() end
    return g ~= nil
  end
  local text, code = run("vtu=3", dir)
  T.check(code == 0, "squeeze.lua runs", text)
  local nf = 0
  for k = 1, 100 do
    if exists(string.format("%s/frames/f_%04d.png", dir, k)) then nf = k end
  end
  T.check(nf == 40, "40 yield-state frames by default", tostring(nf))
  T.check(exists(dir .. "/squeeze.png") and exists(dir .. "/h.png") and exists(dir .. "/force.png"),
    "the animation squeeze.png, h.png and force.png by default", text)
  local g = io.open(dir .. "/series.csv")
  g:read("l")
  local first, second = g:read("l"), g:read("l")
  g:close()
  T.check(first and first:match("^0,1,%-1,,"), "the series' first row is t = 0, its force cell empty (none computed before a step)", first)
  T.check(second and second:match("^0%.01,[^,]+,[^,]+,%d"), "the next row has its force", second)
  local list = reader("pvd", dir .. "/squeeze.pvd")
  local n, files_ok = 0, true
  for t, file in list:gmatch("dataset (%S+) ([^\n]+)") do
    n = n + 1
    local r = read_vtu(dir .. "/" .. file)
    files_ok = files_ok and not r.error and math.abs(r.time - tonumber(t)) < 1e-12
  end
  T.check(n == 3 and files_ok, "vtu=3: three .vtu files listed in squeeze.pvd with their times", list)
  local dir0 = tmp("squeeze0")
  text, code = run("frames=0 plots=0 t_end=0.02", dir0)
  T.check(code == 0 and exists(dir0 .. "/series.csv") and not exists(dir0 .. "/frames") and not exists(dir0 .. "/squeeze.png")
    and not exists(dir0 .. "/h.png") and not exists(dir0 .. "/force.png"), "frames=0 plots=0: the series alone", text)
  os.execute("rm -rf '" .. dir .. "' '" .. dir0 .. "'")
end)

for _, f in ipairs(made) do os.remove(f) end
if T.failed() > 0 then error(T.failed() .. " output checks failed", 0) end
