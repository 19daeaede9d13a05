-- A Newtonian film started thin (half sample 1.6 wide, 0.2 high: a/h = 8.4 at the start,
-- Re = 1, V = 1, dx = 1/40, 8 particle rows across), squeezed to h = 0.17 (a/h = 11), with
-- the thin-film scheme (thin_film = true: the density correction by GMRES, the difference
-- gradient; pressure.c). Measured (one thread): peak max density error 0.80 % over 627 steps (1.6 s),
-- plate force / lubrication (F = mu V A^3 / h^6, A = 0.64) 0.86-0.88 at h = 0.175-0.17;
-- with GMRES alone the error peaks at 0.96 %, with the difference gradient alone at 7.8 %.
-- At dx = 1/80 (16 rows) the defaults' plate force runs away at h = 0.191 (a pressure mode
-- alternating from step to step); with both options the film reaches h = 0.17 with the
-- error under 0.8 % (582 steps). The limit is the stability suite's own (1 %); the force's
-- error against lubrication, 0.12-0.14, is bounded at 0.23 (the force is noisy step to
-- step: 0.82-0.94 between h = 0.185 and 0.17).
local squeeze = require "sph.squeeze"
local T = require "sph.test"
local o = ... or {}

T.case("film started thin, dx = 1/40, thin-film scheme, to h = 0.17", function()
  local a0, h0 = 1.6, 0.2
  local w, top = squeeze.build{ dx = 1 / 40, Re = 1, Bn = 0, mode = "velocity", width = a0, height = h0, h_min = 0.17,
                                world = { threads = o.threads or 1, thin_film = true } }
  local A, peak, sum, n = 2 * a0 * h0, 0, 0, 0
  local ok, err = pcall(function()
    while top.position > 0.17 do
      w:step()
      peak = math.max(peak, w:stats().max_density_error)
      local h = top.position
      if h <= 0.175 then sum, n = sum + top.force * h ^ 6 / A ^ 3, n + 1 end
    end
  end)
  local ratio = n > 0 and sum / n or 0
  print(string.format("# film started thin: h = %.4f after %d steps (%.1f s), peak density error %.4f, mean F / lubrication over h in [0.17, 0.175] %.3f",
    top.position, w.steps, w:stats().wall_time, peak, ratio))
  T.check(ok, "film started thin: runs to h = 0.17 without an engine error", tostring(err))
  T.below(peak, 0.01, "film started thin: max density error under 1 % at every step")
  T.below(math.abs(ratio - 1), 0.23, "film started thin: plate force within 0.23 of lubrication over h in [0.17, 0.175]")
end)

-- The density passes' first direction (density.c): a step's first pass moves along the
-- symmetric gradient's direction until one falls short (step length under 1); that pass
-- moves along the difference form's direction of the same potential where that one lowers
-- the squared error more, and the winner is where the next first pass starts. Measured
-- (300 steps, one thread): 299 of the 300 first passes moved along the difference
-- direction; the max density error after a step averaged 0.542 %, 221 steps above
-- density_tol (0.5 %); with the symmetric form alone (an option of earlier versions)
-- 0.592 % and 229 steps. The checks: the switch acts on this film, and the mean error
-- stays under the symmetric form's (the gap, 9 %, is well over the round-off spread).
T.case("film started thin: the first density pass takes the better direction", function()
  local w = squeeze.build{ dx = 1 / 40, Re = 1, Bn = 0, mode = "velocity", width = 1.6, height = 0.2, h_min = 0.17,
                           world = { threads = o.threads or 1 } }
  local sum, above = 0, 0
  for _ = 1, 300 do
    w:step()
    local e = w:stats().max_density_error
    sum = sum + e
    if e > 0.005 then above = above + 1 end
  end
  local s = w:stats()
  print(string.format("# film started thin, 300 steps: %d first passes moved along the difference direction; mean max density error %.5f, steps above density_tol %d",
    s.density_switches, sum / 300, above))
  T.check(s.density_switches > 0, "first passes move along the difference direction on this film", s.density_switches)
  T.below(sum / 300, 0.00592, "the film's mean max density error stays under the symmetric form's (0.592 %)")
end)

-- make validate's film a/h = 10 (section 2), short: the half sample 10 wide and 1 high at
-- V = -1, Re = 0.05, 16 and 32 rows across the gap (sph.squeeze_validation.film, the
-- defaults), the plate force over t in (0.005, 0.02) against REFERENCES.md section 2's FE fit
-- for the rectangle of the current gap and contact half-width (the no-slip plates hold the
-- contact while the sides bulge: 10.100 / 10.049 at 16 / 32 rows at t = 0.02, the area's
-- 10.20). The force moves by about 1 % each time particles of the bulge reach the rows next
-- to the plates (every 0.003-0.005), so the window spans several such events. Measured:
-- 0.9787 / 0.9978 (errors 0.0213 / 0.0022, order 3.3); against the area's rectangle 0.9534 /
-- 0.9669. Bounds: REFERENCES.md's 3 % at 16 rows (the accuracy issue's), 0.01 at 32 rows, an
-- order of at least 1.
T.case("film a/h = 10 against FE at 16 and 32 rows", function()
  local sv = require "sph.squeeze_validation"
  local errs = {}
  for k, rows in ipairs{ 16, 32 } do
    local r = sv.film(10, rows, { world = { threads = o.threads or 1 } })
    errs[k] = math.abs(r.ratio_c - 1)
    print(string.format("# film a/h = 10, %d rows: F / F_FE %.4f at the contact half-width %.4f (%.4f at the area's %.4f), %d steps",
                        rows, r.ratio_c, r.a_c, r.ratio, r.a_area, r.steps))
  end
  T.below(errs[1], 0.03, "film a/h = 10, 16 rows: the plate force within 3 % of FE")
  T.below(errs[2], 0.01, "film a/h = 10, 32 rows: the plate force within 1 % of FE")
  local order = math.log(errs[1] / errs[2]) / math.log(2)
  print(string.format("# film a/h = 10: observed order %.2f from 16 to 32 rows", order))
  T.check(order >= 1, "film a/h = 10: observed order at least 1 from 16 to 32 rows", string.format("order %.2f", order))
end)

T.done()
