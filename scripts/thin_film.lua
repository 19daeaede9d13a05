-- Study (not a test): the Newtonian square-sample squeeze (Re = 1, V = 1, half sample with a
-- symmetry plane) run into a thin film, the plate force against lubrication theory
-- (F = mu V / h^6 for the whole sample of area 1) as a function of a / h = 1 / (2 h^2),
-- with the defaults and with the thin-film scheme (thin_film = true). Each run goes to
-- h = h_stop or until the engine stops it (the message is printed; exit status 1 then). h_stop under 3 dx is refused. Writes
-- OUT/thin_film.csv (run, h, a/h, F h^6, max density error) and OUT/thin_film.png.
--   build/sph scripts/thin_film.lua [dx=0.025] [runs=defaults,thin] [h_stop=0.15] [out=out/bench]
--                                   [threads=1]
local sph = require "sph"
local squeeze = require "sph.squeeze"
local o = ... or {}
local dx, h_stop, outdir = o.dx or 1 / 40, o.h_stop or 0.15, o.out or "out/bench"
if not (h_stop >= 3 * dx * (1 - 1e-9)) then -- a film a particle or two across resolves no flow
  io.stderr:write(string.format("thin_film: h_stop = %g is %.1f particles across (dx = %g): at least 3 "
    .. "(h_stop >= %g); lower dx or raise h_stop\n", h_stop, h_stop / dx, dx, 3 * dx))
  os.exit(1)
end
local stopped = 0 -- runs the engine stopped before h_stop (status 1 at the end)
local OPTIONS = { defaults = {}, thin = { thin_film = true } }
local runs = {}
for k in tostring(o.runs or "defaults,thin"):gmatch("[%a_]+") do
  if not OPTIONS[k] then
    io.stderr:write(string.format("thin_film: runs: '%s' is neither defaults nor thin\n", k))
    os.exit(1)
  end
  runs[#runs + 1] = k
end
assert(sph.mkdir(outdir))
local csv = assert(io.open(outdir .. "/thin_film.csv", "w"))
csv:write("run,h,a_over_h,F_h6,max_density_error\n")
local series = {}
for _, run in ipairs(runs) do
  local world = { threads = o.threads or 1 }
  for k, v in pairs(OPTIONS[run]) do world[k] = v end
  local w, top = squeeze.build{ dx = dx, Re = 1, Bn = 0, mode = "velocity", h_min = h_stop, world = world }
  local xs, ys, next_h = {}, {}, 0.5
  local ok, err = pcall(function()
    while top.position > h_stop do
      w:step()
      local h = top.position
      if h <= next_h then
        local s = w:stats()
        local r = top.force * h ^ 6
        csv:write(string.format("%s,%.5f,%.3f,%.4f,%.5f\n", run, h, 1 / (2 * h * h), r, s.max_density_error))
        xs[#xs + 1], ys[#ys + 1] = 1 / (2 * h * h), r
        next_h = h - 0.005
      end
    end
  end)
  local s = w:stats()
  print(string.format("%s: %s at h = %.4f after %d steps (%.1f s), peak density error %.4f",
                      run, ok and "reached" or "stopped", top.position, w.steps, s.wall_time, s.peak_density_error))
  if not ok then
    print("  " .. tostring(err))
    stopped = stopped + 1
  end
  series[#series + 1] = { x = xs, y = ys, label = run, style = "both" }
end
csv:close()
assert(sph.plot{ file = outdir .. "/thin_film.png", xlabel = "a / h", ylabel = "F h^6 / (mu V)  (lubrication: 1)",
                 series = series, title = string.format("Newtonian squeeze into a thin film, dx = %g", dx) })
print("wrote " .. outdir .. "/thin_film.csv and thin_film.png")
if stopped > 0 then
  io.stderr:write(string.format("thin_film: %d of %d runs stopped before h = %g (exit status 1)\n", stopped, #runs,
    h_stop))
  os.exit(1)
end
