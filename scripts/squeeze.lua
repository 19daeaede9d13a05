-- The headline case: the squeeze-flow test of a Bingham (or Newtonian) sample.
--   build/sph scripts/squeeze.lua mode=velocity Re=10 Bn=0.5 M=100 dx=0.025 t_end=0.4 out=out/sq
--   build/sph scripts/squeeze.lua mode=load F=-10 Re=1 Bn=5 t_end=2 out=out/load
-- Parameters (paper's scaling, H = U = mu = 1): mode (velocity | load), Re, Bn, M, dx,
-- t_end, F (load on the whole sample per unit depth, in units of mu U: the paper's
-- F* = F Bn; negative compresses), V (plate speed), every (output interval), h_min (the
-- thinnest gap the plates are sized for: the sample spread to it still lies on them;
-- default min(0.25, 0.8 height)), h_stop (end the run at an output time when the gap is
-- thinner; default h_min), viscosity, shifting, threads, out (folder); width and
-- height (the half sample's, default 0.5 and 1: a film started thin is width=1.6
-- height=0.2), thin_film=1 (the engine's thin-film scheme, for a film of a few
-- particle rows; README, Thin films), tol (the
-- relative residual of the pressure and viscous solves; docs/performance.md).
-- Writes out/series.csv: t, h, plate velocity, plate force, solver iterations, max
-- density error, and the lubrication reference (Newtonian: mu V / h^6 or h(t) under load).
-- The force is its mean since the last output (the plate's impulse over the interval, as a
-- load cell reads it: one step's force can jump when a particle at the plate's edge joins
-- or leaves the free surface, docs/limitations.md), and a force reference is the mean of
-- the reference over the same interval.
-- Its first row is the start, t = 0, before any step: no force is computed there yet, so
-- its force cell is empty (and force.png starts at the first output's mean).
-- Exit status: 0 the run reached t_end; 1 an error (bad arguments, a gap under 3 particles
-- across asked for, an engine error: the message says which); 2 it reached h_stop before
-- t_end ("stopped at t = ..., h = ... <= h_stop"); 130 / 143 interrupted.
-- By default it also writes 40 yield-state frames evenly over the run into
-- out/frames/f_0001.png ... (yielded light, unyielded dark, with their legend), the
-- animation out/squeeze.png (fps, default 10; frame_width, default 800) and the plots
-- out/h.png and out/force.png: frames=N for N frames, frames=0 plots=0 for the series alone.
-- vtu=N (default 0): N ParaView files out/vtu/p_0001.vtu ... evenly over the run (the
-- whole sample: the mirrored half included) and out/squeeze.pvd, their time series.
-- SIGINT / SIGTERM (Ctrl-C, kill) end the run after the current step: the series, the
-- frames so far, the plots and the animation are written, the state goes to
-- out/state.bin, and the script says how to continue (the same arguments and
-- restart=out/state.bin: sph.load of the state, the series and frames picked up); it exits
-- 130 (SIGINT) or 143 (SIGTERM). A second signal kills at once.
local sph = require "sph"
local squeeze = require "sph.squeeze"
local params = require "sph.params"

-- every parameter: name, kind, default (nil: the engine's or a derived one), meaning
local SPEC = {
  { "mode", { "velocity", "load" }, "velocity", "constant plate velocity or constant load" },
  { "units", { "dimensionless", "SI" }, "dimensionless", "SI: the lengths, times, V, F and the material in SI (or any consistent units)" },
  { "Re", "number", nil, "Reynolds number (rho; 10)" },
  { "Bn", "number", nil, "Bingham number (tau0; 0.5); 0: Newtonian" },
  { "M", "number", nil, "Papanastasiou exponent (m; 800)" },
  { "rho", "number", nil, "units=SI: density" },
  { "mu", "number", nil, "units=SI: plastic (or Newtonian) viscosity" },
  { "tau0", "number", nil, "units=SI: yield stress (0)" },
  { "m", "number", nil, "units=SI: Papanastasiou regularisation time (with tau0 > 0)" },
  { "dx", "number", nil, "particle spacing (1/40 of the height)" },
  { "t_end", "number", 0.5, "end time" },
  { "every", "number", nil, "output interval (0.005 in the engine's units)" },
  { "F", "number", nil, "load on the whole sample per unit depth (mode=load; negative compresses; -10)" },
  { "V", "number", nil, "plate speed (mode=velocity; 1)" },
  { "width", "number", nil, "the half sample's width (half the height)" },
  { "height", "number", nil, "the sample's height (1)" },
  { "h_min", "number", nil, "thinnest gap the plates are sized for (min(0.25, 0.8 height))" },
  { "h_stop", "number", nil, "end the run when the gap is thinner (h_min)" },
  { "out", "string", "out/squeeze", "output folder" },
  { "frames", "integer", 40, "yield-state frames over the run and the animation squeeze.png (0: none)" },
  { "fps", "number", 10, "the animation's frames per second" },
  { "frame_width", "integer", 800, "frame width in pixels" },
  { "plots", "flag", 1, "h.png and force.png (0: none)" },
  { "vtu", "integer", 0, "ParaView files vtu/p_*.vtu over the run and squeeze.pvd (0: none)" },
  { "restart", "string", nil, "a saved state to continue (out/state.bin)" },
  { "threads", "integer", nil, "threads (all cores)" },
  { "viscosity", { "implicit", "explicit" }, nil, "the viscous step" },
  { "shifting", "number", nil, "particle shifting coefficient (20)" },
  { "thin_film", "flag", 0, "1: the engine's thin-film scheme (docs/api.md)" },
  { "tol", "number", nil, "the pressure and viscous solves' relative residual" },
  { "dt_max", "number", nil, "the longest time step (none: the engine's own limits)" },
}
local o = params.args("squeeze", SPEC, ...) -- a bad parameter: named, exit 1

local mode = o.mode
local function fail(msg)
  io.stderr:write("squeeze: ", msg, "\n")
  os.exit(1)
end
-- units=SI: the case in physical units, run in the engine's scaling (sph.units: lengths in
-- the height H, velocities in the plate speed U, or under a load the load's viscous speed),
-- the outputs turned back; S holds the scales (1 when dimensionless)
local S = { T = 1, H = 1, U = 1, F = 1 }
if o.units == "SI" then
  for _, k in ipairs{ "Re", "Bn", "M" } do
    if o[k] ~= nil then fail(k .. " is not a parameter with units=SI: give rho, mu, tau0 and m (the groups follow)") end
  end
  for _, k in ipairs{ "height", "rho", "mu", "dx" } do
    if o[k] == nil then fail("units=SI needs " .. k) end
  end
  local units = require "sph.units"
  local okU, sc = pcall(units.scales, { H = o.height, rho = o.rho, mu = o.mu, tau0 = o.tau0, m = o.m,
    U = mode == "velocity" and (o.V or fail("units=SI, mode=velocity needs V (the plate speed)")) or nil,
    F = mode == "load" and (o.F or fail("units=SI, mode=load needs F (the load per unit depth)")) or nil })
  if not okU then fail(tostring(sc):gsub("^units: ", "")) end
  S = { T = sc.T, H = sc.H, U = sc.U, F = sc.Fs }
  o.Re, o.Bn, o.M = sc.Re, sc.Bn, sc.M or 800
  o.dx = o.dx / sc.H
  o.t_end = o.t_end / sc.T
  o.every = o.every and o.every / sc.T
  o.dt_max = o.dt_max and o.dt_max / sc.T
  o.width = o.width and o.width / sc.H
  o.height = 1
  o.h_min = o.h_min and o.h_min / sc.H
  o.h_stop = o.h_stop and o.h_stop / sc.H
  if mode == "velocity" then o.V = 1 else o.F = o.F / sc.Fs end
  print(string.format("squeeze: units=SI: Re=%.6g Bn=%.6g M=%.6g; scales: length %g, time %g, velocity %g, force %g (per unit depth)",
    o.Re, o.Bn, o.M, S.H, S.T, S.U, S.F))
else
  for _, k in ipairs{ "rho", "mu", "tau0", "m" } do
    if o[k] ~= nil then fail(k .. " is a parameter of units=SI; dimensionless cases take Re, Bn and M") end
  end
end
o.Re, o.Bn, o.M = o.Re or 10, o.Bn or 0.5, o.M or 800
o.dx, o.F, o.V = o.dx or 1 / 40, o.F or -10, o.V or 1
o.every = o.every or 0.005
local Re, Bn, M, dx = o.Re, o.Bn, o.M, o.dx
local t_end, every = o.t_end, o.every
local out = o.out

local world_opts = { threads = o.threads, viscosity = o.viscosity, shifting = o.shifting,
                     thin_film = o.thin_film == 1, tol = o.tol, dt_max = o.dt_max }
local height = o.height or 1
local width = o.width or 0.5 * height
-- the plates are sized for the sample spread to the gap h_min; the run ends at h_stop, by
-- default h_min (thinner, the sample would flow off the plates' ends)
local h_min = o.h_min or math.min(0.25, 0.8 * height)
local h_stop = o.h_stop or h_min
-- a gap a particle or two across is no flow the method resolves (a force of 1.3e8 at
-- h_stop = dx was reported as done): refused before the run
local MIN_ACROSS = 3
for _, g in ipairs{ { "height", height }, { "h_stop", h_stop }, { "h_min", h_min } } do
  if not (g[2] >= MIN_ACROSS * dx * (1 - 1e-9)) then
    io.stderr:write(string.format("squeeze: %s = %g is %.1f particles across (dx = %g): the gap must stay at least "
      .. "%d particles across (%s >= %g); lower dx or raise %s\n", g[1], g[2], g[2] / dx, dx, MIN_ACROSS, g[1],
      MIN_ACROSS * dx, g[1]))
    os.exit(1)
  end
end
local area = 2 * width * height -- the whole sample's, per unit depth
-- an engine option out of range (tol=-1, dt_max=-1): its message and exit 1, not a traceback
local okb, w, top, bottom = pcall(squeeze.build, { dx = dx, Re = Re, Bn = Bn, M = M, mode = mode, F = o.F or -10,
                              V = o.V or 1, h_min = h_min, width = width,
                              height = height, world = world_opts })
if not okb then
  io.stderr:write("squeeze: " .. tostring(w):gsub("^.-bad argument to 'world' %((.*)%)$", "%1") .. "\n")
  os.exit(1)
end
-- restart=FILE: the run saved there (an interrupted one) goes on; the other arguments must
-- be the saved run's (they give the outputs, the references and the end)
local restart = o.restart
local view_rects = { bottom.rect, top.rect } -- the frames' view: the plates as built
if restart then
  w:close()
  w = sph.load(restart)
  bottom, top = w:plate(1), w:plate(2)
end

do
  local made, why = sph.mkdir(out)
  if not made then
    io.stderr:write("squeeze: ", why, "\n")
    os.exit(1)
  end
end
-- a restart keeps the series' rows up to the state's time (their plot data too)
local old_rows = {}
if restart then
  local f = io.open(out .. "/series.csv")
  if f then
    f:read("l")
    for line in f:lines() do
      local t = tonumber(line:match("^([^,]+),"))
      if t and t <= w.t * S.T * (1 + 1e-12) then old_rows[#old_rows + 1] = line end
    end
    f:close()
  end
end
local series = assert(io.open(out .. "/series.csv", "w"))
series:write(o.units == "SI" and "t [s],h [m],velocity [m/s],force [N/m],solver_iterations,max_density_error,reference\n"
  or "t,h,velocity,force,solver_iterations,max_density_error,reference\n")
for _, line in ipairs(old_rows) do series:write(line, "\n") end
local function ref(h, t)
  if Bn > 0 then return 0 / 0 end
  if mode == "velocity" then return squeeze.newtonian_force(h, o.V or 1) * area ^ 3 end
  if area ~= 1 then return 0 / 0 end -- the h(t) law below is for the unit sample
  return squeeze.newtonian_height(t, -(o.F or -10))
end
-- frames: N renders evenly over [0, t_end], at the first output at or after each time
local nframes = math.floor(o.frames or 0)
local frames = {}
local frame_opts
if nframes > 0 then
  assert(sph.mkdir(out .. "/frames"))
  local b, t = view_rects[1], view_rects[2] -- a fixed view: the plates' width, the initial gap
  local pad = 0.02 * (t[4] - b[2])
  local view = { b[1], b[2] - pad, b[3], t[4] + pad }
  local fw = math.floor(o.frame_width or 800)
  local fh = math.max(120, math.floor(fw * (view[4] - view[2]) / (view[3] - view[1])) + 40)
  -- the legend (yielded / unyielded) on the right, the time and the case above
  frame_opts = { width = fw, height = fh, view = view, color = "yield", colorbar = true,
                 label = string.format("Re=%g Bn=%g", Re, Bn) }
end
-- the k-th of n outputs spread evenly over [0, t_end] (k from 0) is due at time t
local function due(n, k, t)
  local tk = n > 1 and t_end * k / (n - 1) or 0
  return t >= tk - 1e-9 * t_end
end
local frame_t = -math.huge -- the time of the last frame
local function frame(w)
  if nframes == 0 or #frames >= nframes or not due(nframes, #frames, w.t) then return end
  frame_opts.file = string.format("%s/frames/f_%04d.png", out, #frames + 1)
  assert(w:render(frame_opts))
  frames[#frames + 1], frame_t = frame_opts.file, w.t
end
-- vtu=N: N ParaView files spread like the frames, and the time series squeeze.pvd listing
-- them, written again after each file (an interrupted run leaves a series ParaView opens)
local nvtu = math.floor(o.vtu or 0)
local vtus = {} -- { t = , file = } with file relative to out (where the .pvd is)
if nvtu > 0 then assert(sph.mkdir(out .. "/vtu")) end
local function vtu(w, last)
  if nvtu == 0 or #vtus >= nvtu or not (last or due(nvtu, #vtus, w.t)) then return end
  local name = string.format("vtu/p_%04d.vtu", #vtus + 1)
  assert(w:write_vtu(out .. "/" .. name))
  vtus[#vtus + 1] = { t = w.t, file = name }
  assert(sph.pvd_write(out .. "/squeeze.pvd", vtus))
end
if restart and nvtu > 0 then -- the files listed before the interrupt, none past the state
  local f = io.open(out .. "/squeeze.pvd")
  local text = f and f:read("a") or ""
  if f then f:close() end
  for t, file in text:gmatch('timestep="([^"]+)"[^>]-file="([^"]+)"') do
    if tonumber(t) <= w.t * (1 + 1e-12) and #vtus < nvtu then vtus[#vtus + 1] = { t = tonumber(t), file = file } end
  end
end
local ts, hs, fs, refs = {}, {}, {}, {}
local stopped_h -- the gap at which record stopped the run (h < h_stop)
for _, line in ipairs(old_rows) do
  local t, h, _, f = line:match("^([^,]+),([^,]+),([^,]*),([^,]*),")
  t, h = tonumber(t), tonumber(h)
  local r = ref(h / S.H, t / S.T) * (mode == "velocity" and S.F or S.H)
  ts[#ts + 1], hs[#hs + 1], fs[#fs + 1], refs[#refs + 1] = t, h, tonumber(f) or 0 / 0, r
end
-- and the frames made before the interrupt (f_0001.png ... in order, none past the state)
if restart and nframes > 0 then
  while #frames < nframes do
    local file = string.format("%s/frames/f_%04d.png", out, #frames + 1)
    local tk = nframes > 1 and t_end * #frames / (nframes - 1) or 0
    local f = io.open(file, "rb")
    if not f or tk > w.t + 1e-9 * t_end then
      if f then f:close() end
      break
    end
    f:close()
    frames[#frames + 1], frame_t = file, tk
  end
end
-- a film a few particles thick is where the defaults fail (README, Thin films): say so once
local thin_noted = o.thin_film == 1
local thin_options = "thin_film=1"
-- a progress line on a terminal (stderr): the time, the gap and the time left, rewritten
-- at each output and cleared before anything else is printed
local progress_on = os.execute("test -t 2") == true and os.getenv("TERM") ~= "dumb"
local progress_shown = false
local function clear_progress()
  if progress_shown then
    io.stderr:write("\r\27[K")
    progress_shown = false
  end
end
local function progress(w, el)
  if not progress_on or w.t <= 0 then return end
  local f = math.min(1, w.t / t_end)
  local left = f > 0 and el * (1 - f) / f or 0
  local function hms(x)
    x = math.floor(x + 0.5)
    return x >= 3600 and string.format("%dh%02dm", x // 3600, x % 3600 // 60)
      or x >= 60 and string.format("%dm%02ds", x // 60, x % 60) or string.format("%ds", x)
  end
  io.stderr:write(string.format("\r\27[Kt=%.4g of %.4g (%.0f %%)  h=%.4f  %d steps  %s left", w.t * S.T, t_end * S.T,
    100 * f, top.position * S.H, w.steps, hms(left)))
  io.stderr:flush()
  progress_shown = true
end
local last_wall = 0 -- the wall time at the last output (for the progress line)
-- the clock, the plate's impulse and gap at the last output: each row's force is the mean
-- over the interval since. An interrupted run writes them next to its state (FILE.last,
-- exact hexadecimal numbers), so that its restart's first row is the uninterrupted one's;
-- without that file, the start of this run.
local last = { t = w.t, impulse = top.impulse, h = top.position }
if restart then
  local f = io.open(restart .. ".last")
  local lt, li, lh
  if f then
    lt, li, lh = (f:read("l") or ""):match("^(%S+) (%S+) (%S+)$")
    f:close()
  end
  lt, li, lh = tonumber(lt), tonumber(li), tonumber(lh)
  if lt and li and lh and lt <= w.t then last = { t = lt, impulse = li, h = lh } end
end
local function record(w)
  local s = w:stats()
  last_wall = s.wall_time
  local h = top.position
  if not thin_noted and h < 12 * dx then
    thin_noted = true
    clear_progress()
    print(string.format("note: t=%.4g, the gap h=%.4f is %.1f particles across; the defaults fail in thin films "
      .. "(README, Thin films): %s", w.t, h, h / dx, thin_options))
  end
  -- before the first step (the t = 0 row) the plate has no force computed yet: the cell
  -- is empty and the force plot leaves it out. Later rows: the mean since the last output
  local span = w.t - last.t
  local force = w.steps > 0 and span > 0 and (top.impulse - last.impulse) / span or nil
  -- the reference is a force at constant velocity (its mean over the same interval:
  -- Simpson's rule, the gap linear in t) or a gap under a load
  local r
  if mode == "velocity" and span > 0 then
    r = (ref(last.h, last.t) + 4 * ref(0.5 * (last.h + h), w.t - 0.5 * span) + ref(h, w.t)) / 6 * S.F
  else
    r = ref(h, w.t) * (mode == "velocity" and S.F or S.H)
  end
  last.t, last.impulse, last.h = w.t, top.impulse, h
  series:write(string.format("%.8g,%.8g,%.8g,%s,%d,%.4e,%s\n", w.t * S.T, h * S.H, top:velocity() * S.U,
    force and string.format("%.8g", force * S.F) or "", s.solver_iterations, s.max_density_error,
    r == r and string.format("%.8g", r) or ""))
  series:flush()
  ts[#ts + 1], hs[#hs + 1], fs[#fs + 1], refs[#refs + 1] = w.t * S.T, h * S.H, force and force * S.F or 0 / 0, r
  frame(w)
  vtu(w)
  if h < h_stop then
    stopped_h = h
    return false
  end
end

print(string.format("squeeze: mode=%s Re=%g Bn=%g M=%g dx=%g: %d fluid particles (half sample), t_end=%g",
  mode, Re, Bn, M, dx, w:stats().fluid, t_end))
if restart then
  -- the outputs on the first run's grid (t0 = 0): the steps are that run's, bit for bit
  print(string.format("restart: %s at t=%.6g, step %d", restart, w.t * S.T, w.steps))
end
-- w:run calls record at t = 0 too (the series' first row) but not at the start of a
-- restart (t0 = 0 lies before it). An engine error (a particle through a plate, a NaN, a
-- collapsed time step) ends the run with its message; what was computed up to then is
-- still written (series, frames, plots)
local ok, run_err = pcall(w.run, w, { until_t = t_end, every = every, t0 = 0, each = function(w)
  local r = record(w)
  progress(w, last_wall)
  return r
end })
clear_progress()
series:close()
local sig, signame = sph.interrupted()
if not ok then
  io.stderr:write("squeeze: the run stopped early: " .. tostring(run_err) .. "\n")
  -- the engine speaks its own units: with units=SI, say how they convert
  if o.units == "SI" then
    io.stderr:write(string.format("squeeze: (that message is in the engine's units: its unit of time is %g, of length %g, "
      .. "of velocity %g, of force per unit depth %g, in the units given)\n", S.T, S.H, S.U, S.F))
  end
end
-- the run ended early, or had fewer outputs than frames: show its end (once)
if nframes > 0 and #frames < nframes and not sig and w.t > frame_t + 1e-9 * t_end then
  nframes = #frames + 1
  frame_opts.file = string.format("%s/frames/f_%04d.png", out, #frames + 1)
  assert(w:render(frame_opts))
  frames[#frames + 1] = frame_opts.file
end
if nvtu > 0 and #vtus < nvtu and not sig and (#vtus == 0 or vtus[#vtus].t < w.t) then vtu(w, true) end
local s = w:stats()
-- the force as the series' last row gives it (its mean over the last output interval, as a
-- load cell reads it): one step's force carries the step's noise (a particle coming to the
-- free surface moves it by several per cent for that step)
local force_end = fs[#fs]
if not (force_end and force_end == force_end) or ts[#ts] ~= w.t * S.T then force_end = top.force * S.F end
print(string.format((sig and "interrupted" or (ok and not stopped_h) and "done" or "stopped") .. ": t=%.4g h=%.4f force=%.5g  %d steps in %.1f s (%.0f steps/s, %.2f us per particle-step)  "
  .. "mean pressure iterations %.1f  max density error %.2e",
  w.t * S.T, top.position * S.H, force_end, w.steps, s.wall_time, w.steps / s.wall_time,
  1e6 * s.wall_time / (w.steps * s.particles), s.solver_iterations_total / w.steps, s.max_density_error))
print("wrote " .. out .. "/series.csv")
-- The velocity should carry the flow; where the density correction moves the particles as
-- much as their velocity does, the velocity field, and so the stresses, forces and yield
-- zones computed from it, are not the flow's. The share falls as dx is refined (the square at
-- Bn = 1000: 0.24 / 0.16 / 0.11 at dx = 1/20, 1/40, 1/80; the Bingham film of the README,
-- 8 rows thick: 0.22, and 0.06 at 16 rows), not with a shorter step (that film at
-- dt_max = 1e-5: 0.27)
if s.correction_share > 0.1 then
  print(string.format("warning: the density correction made %.0f %% of the particles' motion (stats correction_share; "
    .. "under 5 %% where the velocity carries the flow): the velocity field, the stresses and the forces are not to be "
    .. "trusted; a finer dx lowers it (docs/limitations.md)", 100 * s.correction_share))
end
if s.peak_density_error > 0.01 then
  print(string.format("warning: the density error reached %.2f %% during the run (above 1 %%): "
    .. "forces near that time carry errors of that order; see max_density_error in series.csv",
    100 * s.peak_density_error))
end

if #frames > 0 then
  assert(sph.animate{ frames = frames, file = out .. "/squeeze.png", fps = o.fps or 10 })
  print(string.format("wrote %d frames %s/frames/f_*.png and %s/squeeze.png", #frames, out, out))
end
if #vtus > 0 then
  print(string.format("wrote %d ParaView files %s/vtu/p_*.vtu and their series %s/squeeze.pvd", #vtus, out, out))
end
if o.plots ~= 0 then
  -- the lubrication reference where it is finite: a force at constant velocity, a gap under load
  local rt, rv = {}, {}
  for i = 1, #ts do
    if refs[i] == refs[i] and math.abs(refs[i]) < math.huge then rt[#rt + 1], rv[#rv + 1] = ts[i], refs[i] end
  end
  local title = string.format("%s: Re=%g Bn=%g M=%g dx=%g", mode, Re, Bn, M, dx)
  local hser = { { x = ts, y = hs, label = "SPH" } }
  local ft, fv = {}, {} -- the computed forces only (none at t = 0, before the first step)
  for i = 1, #ts do
    if fs[i] == fs[i] then ft[#ft + 1], fv[#fv + 1] = ts[i], fs[i] end
  end
  local fser = { { x = ft, y = fv, label = "SPH" } }
  if #rt > 0 then
    table.insert(mode == "load" and hser or fser, { x = rt, y = rv, label = "lubrication" })
  end
  local si = o.units == "SI"
  assert(sph.plot{ file = out .. "/h.png", xlabel = si and "t [s]" or "t", ylabel = si and "h [m]" or "h", title = title,
    series = hser })
  assert(sph.plot{ file = out .. "/force.png", xlabel = si and "t [s]" or "t",
    ylabel = si and "plate force [N/m]" or "plate force", title = title, series = fser })
  print("wrote " .. out .. "/h.png and " .. out .. "/force.png")
end
if sig then
  -- the state at the interrupted step, to go on from (the step ended before the error)
  local state = out .. "/state.bin"
  local saved, why = pcall(w.save, w, state)
  if saved then
    -- without it the restart still runs: its first row's force is the mean since the restart
    local f, err = io.open(state .. ".last", "w")
    local wrote = f and f:write(string.format("%a %a %a\n", last.t, last.impulse, last.h))
    if f then wrote = f:close() and wrote end
    if not wrote then
      io.stderr:write(string.format("squeeze: cannot write %s.last (%s): a restart's first force is then the mean "
        .. "since the restart, not since the last row\n", state, tostring(err or "write failed")))
    end
  end
  if saved then
    local args = {}
    for i = 1, #arg do
      if not arg[i]:match("^restart=") then args[#args + 1] = arg[i] end
    end
    args[#args + 1] = "restart=" .. state
    print(string.format("interrupted (%s) at t=%.6g, step %d: wrote %s\n"
      .. "continue with the same arguments and restart=%s:\n  %s %s %s\n"
      .. "(or in Lua: local w = sph.load(\"%s\"))", signame, w.t * S.T, w.steps, state, state, arg[-1] or "sph",
      arg[0] or "scripts/squeeze.lua", table.concat(args, " "), state))
  else
    io.stderr:write("squeeze: interrupted, and the state could not be saved: " .. tostring(why) .. "\n")
  end
  os.exit(128 + sig)
end
if not ok then os.exit(1) end
-- the run ended before t_end without an error: it reached h_stop. Said, and status 2: the
-- series ends before the time asked for
if stopped_h and w.t < t_end * (1 - 1e-9) then
  print(string.format("stopped at t = %.6g, h = %.6g <= h_stop = %g, before t_end = %g (exit status 2)", w.t,
    stopped_h, h_stop, t_end))
  os.exit(2)
end
