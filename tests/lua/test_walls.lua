-- No-slip walls in a thin channel: steady plane Poiseuille driven by a body force g = 1
-- (rho = mu = 1) between fixed plates H = 0.175 apart, periodic in x, run to t = 1 (the
-- viscous time H^2 / nu is 0.03): the flux per unit depth against g H^3 / (12 nu).
-- Measured (one thread; the same at -O1): with the linear (Morris) wall extrapolation
-- 1.0557 at 7 rows (dx = 0.025) and 1.0186 at 14, 1.0092 at 28 (first order: an effective
-- slip of about 0.065 dx; observed order 1.58 from 7 to 14 rows). Bounds: the error
-- |flux / exact - 1| at most 0.005 above the measured one (the runs are 36-46 steps of a
-- steady flow, the same figures with either build), the order at least 1.
local sph = require "sph"
local T = require "sph.test"
local o = ... or {}

local function channel_flux(dx)
  local H, Lx = 0.175, 10 * dx
  local w = sph.world{ dx = dx, rho = 1, gravity = { 1, 0 }, periodic = { x = { 0, Lx } }, threads = o.threads or 1 }
  w:fill{ rect = { 0, 0, Lx, H }, material = sph.newtonian{ mu = 1 } }
  w:plate{ rect = { 0, -3 * dx, Lx, 0 } }
  w:plate{ rect = { 0, H, Lx, H + 3 * dx } }
  w:run{ until_t = 1 }
  local s = 0
  for _, u in ipairs(w:field("u")) do s = s + u end
  local ratio = s * dx * dx / Lx / (H ^ 3 / 12)
  print(string.format("# channel of %d rows: flux / exact %.4f (%d steps)", math.floor(H / dx + 0.5), ratio, w.steps))
  return ratio
end

T.case("thin channel: flux against the exact Poiseuille flux", function()
  local lin7, lin14 = channel_flux(0.025), channel_flux(0.0125)
  local e7, e14 = math.abs(lin7 - 1), math.abs(lin14 - 1)
  T.below(e7, 0.0607, "linear walls, 7 rows: flux within 0.0607 of exact (first-order wall error)")
  T.below(e14, 0.0236, "linear walls, 14 rows: flux within 0.0236 of exact")
  local order = math.log(e7 / e14) / math.log(2)
  print(string.format("# channel: observed order %.2f from 7 to 14 rows", order))
  T.check(order >= 1, "linear walls: observed order at least 1 from 7 to 14 rows", string.format("order %.2f", order))
end)
-- A drop of 3 x 3 particles (all on the free surface, p = 0) falls onto a plate under
-- g = 10 with mu = 1e-3: the pressure holds none of its particles off the wall (plates.c,
-- sph_plate_contact). Measured: without the contact it goes through the plate at step 39
-- (t = 0.188); with it, it lands and rests 0.1 dx above the face (69 steps to t = 0.5,
-- 231 contacts).
T.case("a drop of free-surface particles lands on a plate instead of going through it", function()
  local dx = 0.025
  local w = sph.world{ dx = dx, rho = 1, gravity = { 0, -10 }, threads = o.threads or 1 }
  w:fill{ rect = { -1.5 * dx, 0.1, 1.5 * dx, 0.1 + 3 * dx }, material = sph.newtonian{ mu = 1e-3 } }
  w:plate{ rect = { -0.3, -4 * dx, 0.3, 0 } }
  local ok, err = pcall(function() w:run{ until_t = 0.5 } end)
  T.check(ok, "the drop runs to t = 0.5 without an engine error", err)
  local lo = math.huge
  for _, y in ipairs(w:field("y")) do lo = math.min(lo, y) end
  print(string.format("# drop: %d steps, lowest particle %.3f dx above the face, %d contacts", w.steps, lo / dx,
                      w:stats().wall_contacts))
  T.check(lo >= 0.1 * dx * (1 - 1e-9), "no particle of the drop closer than 0.1 dx to the face", lo / dx .. " dx")
  T.check(w:stats().wall_contacts > 0, "the contact held the drop", "no contact counted")
end)

T.done()
