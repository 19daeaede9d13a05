-- The pictures from Lua: w:render, sph.plot, sph.animate. Images are read back with Pillow
-- (through /usr/bin/python3, as the C animate test does); a view centred on a point puts
-- that point at the image centre whatever the margins, so colours are checked there.
local sph = require "sph"
local T = require "sph.test"

local base = os.tmpname() -- a fresh name; our files are base .. "_*.png"
os.remove(base)
local made = {}
local function tmp(name)
  local f = base .. "_" .. name
  made[#made + 1] = f
  return f
end

-- Pillow helper: modes "pix FILE x y ...", "count FILE r g b tol", "line FILE r g b tol",
-- "anim FILE"; prints numbers separated by spaces (single quotes are not allowed in it).
local PY = [==[
import sys
from PIL import Image, ImageChops
mode, f, a = sys.argv[1], sys.argv[2], [float(v) for v in sys.argv[3:]]
im = Image.open(f)
out = [im.size[0], im.size[1]]
if mode == "anim":
    out += [im.n_frames, im.info.get("loop", -1)]
    for i in range(im.n_frames):
        im.seek(i)
        out.append(im.info["duration"])
else:
    rgb = im.convert("RGB")
    if mode == "pix":
        for i in range(0, len(a), 2):
            out += list(rgb.getpixel((int(a[i]), int(a[i + 1]))))
    else:
        # mask of pixels within tol of colour a[0:3] in every channel (Pillow does the loops)
        ch = [c.point([255 if abs(v - a[k]) <= a[3] else 0 for v in range(256)])
              for k, c in enumerate(rgb.split())]
        mask = ImageChops.multiply(ImageChops.multiply(ch[0], ch[1]), ch[2])
        W = im.size[0]
        pts = [(i % W, i // W) for i, m in enumerate(mask.getdata()) if m]
        out.append(len(pts))
        if mode == "line":
            n = max(len(pts), 1)
            mx = sum(p[0] for p in pts) / n; my = sum(p[1] for p in pts) / n
            sxx = sum((p[0] - mx) ** 2 for p in pts); syy = sum((p[1] - my) ** 2 for p in pts)
            sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
            out.append(sxy / (sxx * syy) ** 0.5 if sxx > 0 and syy > 0 else 0)
print(" ".join(str(v) for v in out))
]==]

local function pillow(mode, file, ...)
  local args = { ... }
  for i = 1, #args do args[i] = string.format("%.10g", args[i]) end
  local p = io.popen("/usr/bin/python3 -c '" .. PY .. "' " .. mode .. " '" .. file .. "' "
    .. table.concat(args, " ") .. " 2>&1")
  local line = p:read("a")
  p:close()
  local v = {}
  for num in line:gmatch("%S+") do v[#v + 1] = tonumber(num) end
  if #v == 0 or v[1] == nil then error("Pillow could not read " .. file .. ": " .. line) end
  return v
end

-- colour at the centre of an image (the centre of a centred view)
local function centre(file, W, H)
  local v = pillow("pix", file, W // 2, H // 2)
  return { v[3], v[4], v[5] }
end

local function near(c, want, tol)
  for k = 1, 3 do
    if math.abs(c[k] - want[k]) > tol then return false end
  end
  return true
end
local function show(c) return string.format("(%d, %d, %d)", c[1], c[2], c[3]) end

-- the renderer's colours (render.c, colormap.c), as 8-bit sRGB
local UNYIELDED = { 25.5, 51, 127.5 }
local YIELDED = { 204, 224.4, 244.8 }
local WHITE = { 255, 255, 255 }
local VIRIDIS_LO = { 68.1, 1.2, 84.0 }
local VIRIDIS_HI = { 253.3, 231.4, 36.7 }

-- a view of half-width r centred on (x, y)
local function around(x, y, r) return { x - r, y - r, x + r, y + r } end

T.case("render a known scene", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local f = tmp("known.png")
  local ok, msg = w:render{ file = f, width = 200, height = 160, view = around(0.55, 0.55, 0.5) }
  T.check(ok == true, "render returns true", msg)
  local v = pillow("pix", f, 0, 0)
  T.check(v[1] == 200 and v[2] == 160, "render honours width and height", v[1] .. "x" .. v[2])
  local c = centre(f, 200, 160)
  T.check(near(c, UNYIELDED, 3), "a particle's pixel has the unyielded colour before any step", show(c))
  w:render{ file = f, width = 200, height = 160, view = around(0.5, 0.5, 0.5) }
  c = centre(f, 200, 160)
  T.check(near(c, WHITE, 3), "between four particles (radius 0.55 dx) is background", show(c))
  w:render{ file = f, width = 200, height = 160, view = around(1.5, 0.5, 0.5) }
  c = centre(f, 200, 160)
  T.check(near(c, WHITE, 0), "outside the fluid is background", show(c))
  w:render{ file = f, width = 200, height = 200 }
  local n = pillow("count", f, YIELDED[1], YIELDED[2], YIELDED[3], 6)[3]
  local m = pillow("count", f, UNYIELDED[1], UNYIELDED[2], UNYIELDED[3], 3)[3]
  T.check(n == 0 and m > 0.4 * 200 * 200 / 4, "a fitted view shows only unyielded fluid",
    string.format("%d yielded, %d unyielded pixels", n, m))
  -- radius: 0.04 from a centre (0.06 from the next) is covered by default, empty at 0.02
  w:render{ file = f, width = 200, height = 160, view = around(0.55 + 0.04, 0.55, 0.5) }
  c = centre(f, 200, 160)
  T.check(near(c, UNYIELDED, 3), "the default radius (0.55 dx) covers 0.4 dx from a centre", show(c))
  w:render{ file = f, width = 200, height = 160, view = around(0.55 + 0.04, 0.55, 0.5), radius = 0.02 }
  c = centre(f, 200, 160)
  T.check(near(c, WHITE, 3), "radius = 0.02 leaves 0.04 from a centre empty", show(c))
end)

T.case("render yielded and unyielded", function()
  -- a plate sliding along x over part of a Bingham block: fluid under it yields, far fluid rests
  local w = sph.world{ dx = 0.1, threads = 1 } -- tiny: one thread is fastest
  w:fill{ rect = { 0, 0, 2, 1 }, material = sph.bingham{ mu = 1, tau0 = 1, m = 100 } }
  local top = w:plate{ rect = { 0, 1, 0.5, 1.3 }, axis = "x" }
  top:velocity(1)
  for _ = 1, 10 do w:step() end
  local x, y, yl, gd = w:field("x"), w:field("y"), w:field("yielded"), w:field("gammadot")
  local iy, iu = nil, nil
  for i = 1, #yl do
    if yl[i] == 1 and (not iy or gd[i] > gd[iy]) then iy = i end
    if yl[i] == 0 and (not iu or x[i] > x[iu]) then iu = i end
  end
  T.check(iy and iu, "the scene has yielded and unyielded particles")
  if not (iy and iu) then return end
  local f = tmp("bingham.png")
  w:render{ file = f, width = 120, height = 120, view = around(x[iy], y[iy], 0.3) }
  local c = centre(f, 120, 120)
  T.check(near(c, YIELDED, 3), "a yielded particle is drawn light", show(c))
  w:render{ file = f, width = 120, height = 120, view = around(x[iu], y[iu], 0.3) }
  c = centre(f, 120, 120)
  T.check(near(c, UNYIELDED, 3), "an unyielded particle is drawn dark", show(c))
  w:render{ file = f, width = 400, height = 240, label = "Re=1 Bn=1" }
  local n = pillow("count", f, YIELDED[1], YIELDED[2], YIELDED[3], 3)[3]
  local m = pillow("count", f, UNYIELDED[1], UNYIELDED[2], UNYIELDED[3], 3)[3]
  T.check(n > 500 and m > 2000, "a whole frame shows both colours",
    string.format("%d yielded, %d unyielded pixels", n, m))
  -- plates are drawn grey on top
  w:render{ file = f, width = 120, height = 120, view = around(0.25, 1.15, 0.1) }
  c = centre(f, 120, 120)
  T.check(near(c, { 114.75, 114.75, 114.75 }, 3), "a plate is drawn grey", show(c))
end)

T.case("render a field with a fixed range", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local f = tmp("field.png")
  w:render{ file = f, width = 100, height = 100, color = "x", range = { 1, 2 }, colorbar = false,
            view = around(0.55, 0.55, 0.3) }
  local c = centre(f, 100, 100)
  T.check(near(c, VIRIDIS_LO, 3), "values below the range take the low end of viridis", show(c))
  w:render{ file = f, width = 100, height = 100, color = "y", range = { -2, -1 }, colorbar = false,
            view = around(0.55, 0.55, 0.3) }
  c = centre(f, 100, 100)
  T.check(near(c, VIRIDIS_HI, 3), "values above the range take the high end of viridis", show(c))
  T.check(w:render{ file = f, color = "p", colorbar = true, label = true } == true,
    "a constant field with a colour bar renders")
end)

-- A log axis's automatic range in whole decades: data at 5e-324 would round down to
-- 10^-324 = 0 (1.7e308 up to 10^309 = inf), and the tick loop would convert log10(0) = -inf
-- to int (UBSan: signed overflow in axis_ticks). The decades stay within [1e-307, 1e308].
T.case("log axes of data at the ends of the doubles", function()
  local dir = os.tmpname()
  for _, y in ipairs{ { 5e-324, 1 }, { 1, 1.7e308 }, { 5e-324, 1.7e308 } } do
    T.check(sph.plot{ file = dir .. ".png", log = "xy", series = { { x = y, y = y } } } ~= nil,
            string.format("a log plot of data from %g to %g", y[1], y[2]))
  end
  os.remove(dir .. ".png")
  os.remove(dir)
end)

T.case("ranges of any finite width end", function()
  -- the tick search of a colour bar or an axis ends for any finite range: a span of one
  -- subnormal (its tick step underflowed to 0 and the search spun forever), the widest
  -- doubles, equal ends
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local f = tmp("ranges.png")
  local line = { x = { 0, 1 }, y = { 0, 1 } }
  local ranges = { { 0, 5e-324 }, { 5e-324, 1e-323 }, { 1, 1 }, { -1.7976931348623157e308, 1.7976931348623157e308 },
                   { 1e17, 1e17 + 16 } }
  for _, r in ipairs(ranges) do
    local what = string.format("{%g, %g}", r[1], r[2])
    T.check(w:render{ file = f, width = 120, height = 80, color = "p", range = r } == true,
            "render with range " .. what .. " ends")
    if r[1] < r[2] then
      T.check(sph.plot{ file = f, width = 160, height = 120, xrange = r, yrange = r, series = { line } } == true,
              "plot with xrange and yrange " .. what .. " ends")
    end
  end
  T.check(sph.plot{ file = f, width = 160, height = 120, series = { { x = { 0, 5e-324 }, y = { 0, 5e-324 } } } } == true,
          "plot of data a subnormal apart (automatic range) ends")
end)

T.case("render mirror and label", function()
  local w = sph.world{ dx = 0.1, symmetry = { x = 0 } }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local f = tmp("mirror.png")
  w:render{ file = f, width = 100, height = 100, view = around(-0.55, 0.55, 0.3) }
  local c = centre(f, 100, 100)
  T.check(near(c, UNYIELDED, 3), "a symmetry plane at x = 0 draws the mirrored half by default", show(c))
  w:render{ file = f, width = 100, height = 100, view = around(-0.55, 0.55, 0.3), mirror = false }
  c = centre(f, 100, 100)
  T.check(near(c, WHITE, 0), "mirror = false leaves the other half empty", show(c))
  -- the label goes in a band above the picture: dark text there only when asked for
  local view = { -3, -1, 3, 2 }
  w:render{ file = f, width = 300, height = 150, view = view, label = "Re=1 Bn=5" }
  local with = pillow("count", f, 0, 0, 0, 100)[3]
  w:render{ file = f, width = 300, height = 150, view = view, label = false }
  local without = pillow("count", f, 0, 0, 0, 100)[3]
  T.check(with > 30 and without == 0, "label = string draws text, label = false none",
    string.format("%d dark pixels with, %d without", with, without))
end)

T.case("animate rendered frames", function()
  local w = sph.world{ dx = 0.1, threads = 1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local frames = {}
  for k = 1, 3 do
    frames[k] = tmp(string.format("f_%04d.png", k))
    assert(w:render{ file = frames[k], width = 160, height = 100, label = true })
    w:step()
  end
  local out = tmp("anim.png")
  local ok, msg = sph.animate{ frames = frames, file = out, fps = 10, loop = 2 }
  T.check(ok == true, "animate returns true", msg)
  local v = pillow("anim", out)
  T.check(v[1] == 160 and v[2] == 100, "the animation has the frames' size", v[1] .. "x" .. v[2])
  T.check(v[3] == 3, "three frames decode", tostring(v[3]))
  T.check(v[4] == 2, "loop = 2 is stored", tostring(v[4]))
  T.check(v[5] == 100 and v[6] == 100 and v[7] == 100, "fps = 10 gives 100 ms per frame",
    table.concat(v, " ", 5))
  ok = sph.animate{ frames = frames, file = out }
  T.check(ok and pillow("anim", out)[5] == 40, "fps defaults to 25 (40 ms)")
  local odd = tmp("odd.png")
  w:render{ file = odd, width = 100, height = 100 }
  local r, m = sph.animate{ frames = { frames[1], odd, frames[2] }, file = out }
  T.check(r == nil and type(m) == "string" and m:find("same size", 1, true),
    "frames of different sizes: nil and a message", tostring(m))
  r, m = sph.animate{ frames = { frames[1], base .. "_missing.png" }, file = out }
  T.check(r == nil and m:find("missing.png", 1, true), "a missing frame: nil and a message naming it", tostring(m))
end)

T.case("plot a known line", function()
  local xs, up, down = {}, {}, {}
  for i = 0, 50 do
    xs[#xs + 1] = i / 50
    up[#up + 1] = i / 50
    down[#down + 1] = 1 - i / 50
  end
  local BLUE = { 0, 114, 178 } -- the first series' colour (Okabe & Ito)
  local f = tmp("plot.png")
  local ok, msg = sph.plot{ file = f, width = 320, height = 240, xlabel = "t", ylabel = "h",
                            series = { { x = xs, y = up } } }
  T.check(ok == true, "plot returns true", msg)
  local v = pillow("line", f, BLUE[1], BLUE[2], BLUE[3], 40)
  T.check(v[1] == 320 and v[2] == 240, "plot honours width and height", v[1] .. "x" .. v[2])
  T.check(v[3] > 100 and v[4] < -0.99, "y = x is a rising straight line (pixel rows fall with columns)",
    string.format("%d pixels, correlation %.4f", v[3], v[4]))
  sph.plot{ file = f, width = 320, height = 240, series = { { x = xs, y = down, style = "both" } } }
  v = pillow("line", f, BLUE[1], BLUE[2], BLUE[3], 40)
  T.check(v[3] > 100 and v[4] > 0.99, "y = 1 - x is a falling straight line",
    string.format("%d pixels, correlation %.4f", v[3], v[4]))
  local pos = { 1, 10, 100 }
  T.check(sph.plot{ file = f, log = "xy", title = "log", xrange = { 0.5, 200 },
                    series = { { x = pos, y = pos, label = "a", style = "markers" },
                               { x = pos, y = { 1, 0 / 0, 3 }, label = "b" } } } == true,
    "log axes, ranges, labels and a NaN gap plot")
end)

T.case("failed writes", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local bad = "/nonexistent-sph-dir/x.png"
  local r, m = w:render{ file = bad }
  T.check(r == nil and type(m) == "string" and m:find(bad, 1, true), "render to a bad path: nil and message", tostring(m))
  r, m = sph.plot{ file = bad, series = { { x = { 0, 1 }, y = { 0, 1 } } } }
  T.check(r == nil and type(m) == "string" and m:find(bad, 1, true), "plot to a bad path: nil and message", tostring(m))
  local f = tmp("one.png")
  w:render{ file = f, width = 50, height = 50 }
  r, m = sph.animate{ frames = { f }, file = bad }
  T.check(r == nil and type(m) == "string" and m:find(bad, 1, true), "animate to a bad path: nil and message", tostring(m))
end)

-- A picture replaces its file whole (src/atomic.c): a write that fails (here for real: a
-- child sph under a 1 KB file size limit, SIGXFSZ ignored) leaves the old file byte for
-- byte and no temporary file.
T.case("a failed picture write leaves the old file", function()
  local names = { render = tmp("old_render.png"), plot = tmp("old_plot.png"), animate = tmp("old_anim.png") }
  local frame = tmp("old_frame.png")
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  w:render{ file = frame, width = 300, height = 200 }
  local old = "old bytes\n"
  for _, f in pairs(names) do
    local g = assert(io.open(f, "wb")); g:write(old); g:close()
  end
  local script = tmp("old.lua")
  local g = assert(io.open(script, "w"))
  g:write(string.format([[
local sph = require "sph"
local w = sph.world{ dx = 0.1, threads = 1 }
w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
print("render", w:render{ file = %q, width = 300, height = 200 })
print("plot", sph.plot{ file = %q, series = { { x = { 0, 1 }, y = { 0, 1 } } } })
print("animate", sph.animate{ frames = { %q, %q }, file = %q })
]], names.render, names.plot, frame, frame, names.animate))
  g:close()
  local p = io.popen("sh -c \"trap '' XFSZ; ulimit -f 2; exec '" .. arg[-1] .. "' '" .. script .. "'\" 2>&1")
  local out = p:read("a")
  p:close()
  for what, f in pairs(names) do
    local line = out:match(what .. "\t([^\n]*)") or "(no line)"
    T.check(line:find("nil", 1, true) and line:find(f, 1, true), what .. " under a 1 KB file limit fails, naming the file",
            line)
    local h = io.open(f, "rb")
    local now = h and h:read("a")
    if h then h:close() end
    T.check(now == old, what .. ": the old file keeps its bytes after the failed write", now and #now .. " bytes")
  end
  local left = io.popen("ls '" .. base .. "'_old*.tmp.* 2>/dev/null | wc -l"):read("a")
  T.check(tonumber(left) == 0, "no temporary file left behind", left)
end)

T.case("argument errors", function()
  local w = sph.world{ dx = 0.1 }
  w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
  local f = tmp("err.png")
  T.checkerror("file: string expected", "render without file", w.render, w, {})
  T.checkerror("table expected", "render needs a table", w.render, w, "x.png")
  T.checkerror("unknown option 'colour'; options are file", "render with a misspelt option", w.render, w,
    { file = f, colour = "p" })
  T.checkerror("unknown field 'pressure'; fields are yield, x, y", "render color lists the fields", w.render, w,
    { file = f, color = "pressure" })
  T.checkerror("width: integer in 8..16384", "render width too small", w.render, w, { file = f, width = 3 })
  T.checkerror("height: integer", "render height not an integer", w.render, w, { file = f, height = 10.5 })
  T.checkerror("view: table {x0, y0, x1, y1}", "render view too short", w.render, w, { file = f, view = { 0, 0, 1 } })
  T.checkerror("view: need x0 < x1", "render view inverted", w.render, w, { file = f, view = { 1, 0, 0, 1 } })
  T.checkerror("range: need vmin <= vmax", "render range inverted", w.render, w, { file = f, color = "x", range = { 2, 1 } })
  T.checkerror("range[2]: finite number", "render range with NaN", w.render, w, { file = f, range = { 0, 0 / 0 } })
  T.checkerror("label: boolean or string", "render label a number", w.render, w, { file = f, label = 3 })
  T.checkerror("mirror: boolean expected", "render mirror a string", w.render, w, { file = f, mirror = "yes" })
  T.checkerror("radius: positive number", "render negative radius", w.render, w, { file = f, radius = -1 })
  T.checkerror("colormap: unknown colour map 'jet'", "render unknown colour map", w.render, w,
    { file = f, color = "x", colormap = "jet" })
  T.checkerror("too small for its label", "render too small for its label", w.render, w,
    { file = f, width = 8, height = 8, label = true })
  local render = w.render
  w:close()
  T.checkerror("closed sph.world", "render on a closed world", render, w, { file = f })

  local line = { x = { 0, 1 }, y = { 0, 1 } }
  T.checkerror("file: string expected", "plot without file", sph.plot, { series = { line } })
  T.checkerror("series: table of series expected", "plot without series", sph.plot, { file = f })
  T.checkerror("at least one series", "plot with no series", sph.plot, { file = f, series = {} })
  T.checkerror("series[2]: table", "plot with a bad series", sph.plot, { file = f, series = { line, 3 } })
  T.checkerror("series[1].y: table of numbers", "plot series without y", sph.plot, { file = f, series = { { x = { 1 } } } })
  T.checkerror("series[1].x[2]: number expected", "plot series with a string value", sph.plot,
    { file = f, series = { { x = { 1, "a" }, y = { 1, 2 } } } })
  T.checkerror("x has 2 values but y has 3", "plot series of unequal lengths", sph.plot,
    { file = f, series = { { x = { 1, 2 }, y = { 1, 2, 3 } } } })
  T.checkerror("series[1].style", "plot series with a bad style", sph.plot,
    { file = f, series = { { x = { 1 }, y = { 1 }, style = "dots" } } })
  T.checkerror("unknown option 'colour'", "plot series with a stray key", sph.plot,
    { file = f, series = { { x = { 1 }, y = { 1 }, colour = "red" } } })
  T.checkerror("log: \"\", \"x\", \"y\" or \"xy\"", "plot with a bad log", sph.plot, { file = f, log = "z", series = { line } })
  T.checkerror("unknown option 'xlog'", "plot with a misspelt option", sph.plot, { file = f, xlog = true, series = { line } })
  T.checkerror("x range", "plot with an inverted xrange", sph.plot, { file = f, xrange = { 1, 0 }, series = { line } })
  T.checkerror("width: integer in 64..16384", "plot too narrow", sph.plot, { file = f, width = 10, series = { line } })

  T.checkerror("frames: table of file names", "animate without frames", sph.animate, { file = f })
  T.checkerror("at least one frame", "animate with no frames", sph.animate, { file = f, frames = {} })
  T.checkerror("frames[2]: string expected", "animate with a bad frame", sph.animate, { file = f, frames = { "a.png", 2 } })
  T.checkerror("file: string expected", "animate without file", sph.animate, { frames = { "a.png" } })
  T.checkerror("fps: fps must be a positive number", "animate with fps = 0", sph.animate,
    { file = f, frames = { "a.png" }, fps = 0 })
  T.checkerror("loop: integer", "animate with a negative loop", sph.animate, { file = f, frames = { "a.png" }, loop = -1 })
  T.checkerror("unknown option 'delay'", "animate with a misspelt option", sph.animate,
    { file = f, frames = { "a.png" }, delay = 3 })
end)

for _, f in ipairs(made) do os.remove(f) end
-- End by returning (or raising) rather than T.done(): os.exit skips the host's release of
-- the font caches, which the leak checker of `make check` would report.
if T.failed() > 0 then error(T.failed() .. " pictures checks failed", 0) end
