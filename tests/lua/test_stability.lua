-- The stability suite's reduced versions (issue 3): every hard case of lua/sph/stability.lua
-- to a tenth of its end time (`make stability` runs them to the end). Each must run without
-- an engine error (NaN, particle through a plate, diverging solver), keep the max density
-- error under 1 % at every step, keep a loaded plate from moving back up by more than dx,
-- and flag the free surface where the sample's outline is (no false surface inside, no
-- edge particle missed away from the contact line).
-- Measured max density errors (dx = 1/40): Bn=100 load 0.75 %, M=1e4 0.55 %, Re=0.01 0.65 %,
-- Re=1000 0.80 %, thin film 0.55 %, paper case 0.74 %; no surface flag wrong in any.
-- The limit is the suite's own (1 %), not a tolerance fitted to these figures.
local stability = require "sph.stability"
local T = require "sph.test"
local o = ... or {}

for _, c in ipairs(stability.cases) do
  T.case(c.name .. " (to t = " .. c.t_end / 10 .. ")", function()
    local dx = 1 / 40
    local r = stability.run(c, c.t_end / 10, { dx = dx, threads = o.threads })
    print(string.format("# %s: t = %.4g, %d steps, %.1f s, max density error %.4f, h = %.4f, plate back up %.2g, " ..
      "surface inside %d missing %d", c.name, r.t, r.steps, r.wall, r.emax, r.h, r.backup, r.inside, r.missing))
    T.check(r.ok, c.name .. ": runs without an engine error", r.err)
    T.below(r.emax, 0.01, c.name .. ": max density error under 1 % at every step")
    if c.mode == "load" then T.below(r.backup, dx, c.name .. ": loaded plate never moves back up by more than dx") end
    T.check(r.inside == 0, c.name .. ": no particle inside the sample taken for free surface", r.inside .. " of them")
    T.check(r.missing == 0, c.name .. ": no edge particle missed by the free-surface flags", r.missing .. " of them")
  end)
end
-- A stretched sample has no surface inside it. The thin film's square sample squeezed from
-- rest stands in columns up to 1.55 dx apart (rows 0.65 dx), where the kernel sum's normal
-- is noise (|n| h 0.001-0.014) and a cone along a row can find nothing within 1.5 dx. Every
-- step to step 3000 (h = 0.28), no flag may lie more than 3 dx inside the outermost
-- particle of its row and the rows beside it, away from the plates (3 dx). Measured: none;
-- without the empty-cone test's |n| h >= 0.03 (src/surface.c, SURFACE_NORMAL_MIN) such flags
-- come one at a time in 33 of the 3000 steps on one thread, 197 on two.
T.case("thin film: no surface flags inside the stretched sample (steps 1-3000)", function()
  local squeeze = require "sph.squeeze"
  local c = stability.find("thin film h=0.15")
  local dx = 1 / 40
  local w, top = squeeze.build{ dx = dx, Re = c.Re, Bn = c.Bn, M = c.M, mode = c.mode, h_min = c.h_min,
                                world = { threads = o.threads } }
  local total, worst, at = 0, 0, 0
  for s = 1, 3000 do
    w:step()
    local deep = stability.flags_inside(w, dx, 0, top.position)
    total = total + deep
    if deep > worst then worst, at = deep, s end
  end
  print(string.format("# stretched sample to h = %.4f: %d flags inside in all, at most %d (step %d)", top.position,
                      total, worst, at))
  T.check(total == 0, "thin film: no surface flag inside the stretched sample, steps 1-3000",
          total .. " in all, " .. worst .. " at step " .. at)
  -- On to h = 0.225: from h = 0.24 the film's front is a tongue whose rows next to the
  -- free surface gather a density error the passes cannot take out (their step length 0);
  -- the density descent (density.c) keeps it at the density limit (0.8 %). Measured max
  -- density error (one thread): 0.80 % with the descent, 1.0 % at h = 0.2376 and 5.2 % by
  -- h = 0.226 without it. The limit is the suite's 1 %.
  -- From here on the suite's surface check every 10 steps as well (its criterion: no flag
  -- inside the sample, no exposed edge particle missed; stability.surface_check). Measured:
  -- 0 and 0 with -O2 on one and two threads and with make check's -O1 build. Round-off
  -- does not decide borderline flags: the engine's cone reaches further (2 dx, 1.7 dx to
  -- walls) than the check looks (1.6 dx), the check's enclosure is a 60-degree opening
  -- test, and its edge test looks further (2.1 dx) than the engine's cone (src/surface.c,
  -- lua/sph/stability.lua).
  local emax, inside, missing = 0, 0, 0
  local function surface()
    if w.steps % 10 == 0 then
      local a, b = stability.surface_check(w, dx, 0, top.position)
      inside, missing = inside + a, missing + b
    end
  end
  while top.position > 0.225 do
    w:step()
    emax = math.max(emax, w:stats().max_density_error)
    surface()
  end
  print(string.format("# thin film steps 3001-%d to h = %.4f: max density error %.4f, %d descent moves", w.steps,
                      top.position, emax, w:stats().density_descents))
  T.below(emax, 0.01, "thin film: max density error under 1 % down to h = 0.225")
  -- And on to the suite's h = 0.15: below h ~ 0.17 the symmetric gradient's term in p_i
  -- itself makes the film's pressure alternate step to step and grow unless the pressure
  -- matrix has it (pressure.c, SELF_TERM). Measured: to h = 0.15 at 0.80 % on one and two
  -- threads (9357 and 9382 steps).
  local ok, err = pcall(function()
    while top.position > 0.15 do
      w:step()
      emax = math.max(emax, w:stats().max_density_error)
      surface()
    end
  end)
  print(string.format("# thin film to h = %.4f in %d steps: max density error %.4f; surface flags counted inside %d, " ..
                      "edge particles missed %d (checks every 10 steps from step 3001)", top.position, w.steps, emax,
                      inside, missing))
  T.check(ok, "thin film: runs to h = 0.15 without an engine error", err)
  T.check(inside == 0, "thin film to h = 0.15: no particle inside the sample taken for free surface", inside)
  T.check(missing == 0, "thin film to h = 0.15: no edge particle missed by the free-surface flags", missing)
  T.below(emax, 0.01, "thin film: max density error under 1 % down to h = 0.15")
end)
-- Walls the fluid does not reach are no unknowns (src/pressure.c, mark_unknowns). A block
-- held 4 dx above a plate: the plate's walls in the 3 x 3 cells around the fluid are
-- active, but those beyond the kernel's support (3 dx) of every fluid particle are
-- coupled only among themselves: as unknowns they would be a singular block. And the case
-- that needs it: Re = 1000 with the difference-form gradient, where such walls (18 under
-- the sheet thrown off the contact line, near t = 0.27) make the multigrid cycle indefinite
-- and the pressure solve fail (measured with them left out: to t = 0.4, 1910 steps).
T.case("walls out of the fluid's reach are left out of the pressure system", function()
  local sph = require "sph"
  local dx = 1 / 20
  local w = sph.world{ dx = dx, rho = 1, threads = o.threads }
  w:fill{ rect = { 0, 4 * dx, 0.5, 0.5 }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { -0.2, -3 * dx, 0.7, 0 } }
  w:step()
  local s = w:stats()
  print(string.format("# block 4 dx above a plate: %d floating walls left out, %d unknowns", s.floating_walls,
                      s.unknowns))
  T.check(s.floating_walls > 0, "the plate's walls beyond the fluid's support are left out", s.floating_walls)
  local squeeze = require "sph.squeeze"
  local w2 = squeeze.build{ dx = 1 / 40, Re = 1, Bn = 0, mode = "velocity", world = { threads = o.threads } }
  w2:step()
  T.check(w2:stats().floating_walls == 0, "a squeeze's plates touching the sample: none left out",
          w2:stats().floating_walls)
  local c = stability.find("Re=1000")
  local r = stability.run(c, 0.3, { threads = o.threads, world = { thin_film = true } })
  print(string.format("# Re = 1000, thin-film scheme: t = %.4g, %d steps", r.t, r.steps))
  T.check(r.ok, "Re = 1000 with the thin-film scheme runs to t = 0.3", r.err)
end)
T.done()
